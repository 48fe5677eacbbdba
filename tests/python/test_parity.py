"""The Python API against the command line: every result's to_dict() has
the keys of the command's --json with the same values, file names that are
not UTF-8 work, and what the arguments cannot mean is refused clearly."""

import json
import math
import os
import pathlib
import re
import subprocess
import tracemalloc

import numpy as np
import pytest

import polyvol
import polyvol.dask as pvd
from conftest import CLI, box, uv_sphere


def cli_json(*args):
    out = subprocess.run([CLI, *map(str, args), "--json"], capture_output=True, text=True)
    return json.loads(out.stdout)


def off_file(path, v, f):
    path.write_text(f"OFF\n{len(v)} {len(f)} 0\n" + "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    return path


def same(a, b):
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    return a == b


def test_check_has_the_keys_and_values_of_polyvol_check(tmp_path):
    v, f = box((0, 0, 0), (2, 2, 2))
    w, g = box((1, 1, 1), (3, 3, 3))
    path = off_file(tmp_path / "two.off", np.vstack([v, w]), np.vstack([f, g + 8]))
    cli = cli_json("check", path)[0]
    d = polyvol.check(polyvol.load(path)).to_dict()
    file_keys = {"file", "format", "encoding", "gzip", "notes", "exit_code"}
    assert set(d) == set(cli) - file_keys, set(d) ^ (set(cli) - file_keys)
    for key in d:
        assert same(d[key], cli[key]), key


def test_overlap_has_the_keys_and_values_of_polyvol_overlap(tmp_path):
    a = off_file(tmp_path / "a.off", *box((0, 0, 0), (2, 2, 2)))
    b = off_file(tmp_path / "b.off", *uv_sphere(12, 24, 1.0, (2, 2, 2)))
    cli = cli_json("overlap", a, b)
    d = polyvol.overlap(polyvol.load(a), polyvol.load(b)).to_dict()
    assert set(d) == set(cli) - {"a", "b", "seconds"}, set(d) ^ (set(cli) - {"a", "b", "seconds"})
    for key in d:
        assert same(d[key], cli[key]), key


def test_chain_volume_has_the_keys_and_values_of_polyvol_ndim(tmp_path):
    path = tmp_path / "t.chain"
    path.write_text("3 4 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 2 1\n0 1 3\n0 3 2\n1 2 3\n")
    cli = cli_json("ndim", path)[0]  # an array of per-file objects, as every command that measures files
    d = polyvol.chain_volume(*polyvol.load_chain(path)).to_dict()
    for key in d:
        assert key in cli, key
        if key != "stats":
            assert same(d[key], cli[key]), key
    assert d["volume"] == 1 / 6


def test_implicit_has_the_keys_and_values_of_polyvol_implicit():
    cli = cli_json("implicit", "x^2+y^2+z^2-1", "--dim", 3, "--box", "-1.5:1.5", "--h", 0.1)
    d = polyvol.implicit("x^2+y^2+z^2-1", 3, (-1.5, 1.5), h=0.1).to_dict()
    assert set(d) == set(cli), set(d) ^ set(cli)
    for key in d:
        if key in ("seconds", "fine", "coarse"):
            continue
        assert same(d[key], cli[key]), key
    for key in d["fine"]:
        if key != "seconds":
            assert same(d["fine"][key], cli["fine"][key]), key


def test_file_names_that_are_not_utf8(tmp_path):
    name = os.fsencode(str(tmp_path)) + b"/caf\xe9.off"
    with open(name, "wb") as out:
        out.write(off_file(tmp_path / "plain.off", *box()).read_bytes())
    assert polyvol.volume(polyvol.load(name)) == 1.0
    text = os.fsdecode(name)
    assert polyvol.volume(polyvol.load(text)) == 1.0
    report = polyvol.measure_file(text)
    assert report["exit_code"] == 0 and report["file"] == text and report["volume"] == 1.0
    missing = os.fsencode(str(tmp_path)) + b"/gon\xe9.stl"
    with pytest.raises(polyvol.ReadError) as e:
        polyvol.load(missing)
    assert e.value.path == os.fsdecode(missing)
    rows = pvd.measure_files([text, os.fsdecode(missing)], files_per_partition=1).compute(scheduler="sync")
    assert list(rows["exit_code"]) == [0, 2]


def test_grid_arguments_that_mean_nothing_are_refused():
    mesh = box()
    for bad in ({"dims": (0, 2, 2)}, {"dims": (2, 2)}, {"dims": (-1, 2, 2)}, {"cells": 0}, {"cell_size": 0},
                {"cell_size": -1.0}, {"block": ((-1, 1), (0, 2), (0, 2)), "dims": (2, 2, 2)},
                {"block": ((1, 1), (0, 2), (0, 2)), "dims": (2, 2, 2)}):
        with pytest.raises(ValueError):
            polyvol.grid(mesh, **bad)
    with pytest.raises(ValueError):
        pvd.grid(mesh, dims=(2, 2, 2), what="volume")


def test_a_block_is_a_grid_of_its_own():
    s = uv_sphere(12, 24)
    whole = polyvol.grid(s, dims=(8, 6, 7), union=True)
    part = polyvol.grid(s, dims=(8, 6, 7), block=((2, 5), (1, 6), (3, 7)), union=True)
    assert part.shape == (3, 5, 4) and [len(e) for e in part.edges] == [4, 6, 5]
    assert np.array_equal(part.fractions, whole.fractions[2:5, 1:6, 3:7])
    assert np.array_equal(part.cell_class, whole.cell_class[2:5, 1:6, 3:7])
    assert part.to_dict()["grid"]["dims"] == [3, 5, 4] and part.to_dict()["grid"]["block"] == [[2, 5], [1, 6], [3, 7]]
    assert set(np.unique(whole.cell_class)) == {0, 1, 2}  # one body: no contact cells
    c = pvd.grid(s, dims=(8, 6, 7), chunks=(3, 3, 3), what="cell_class").compute(scheduler="sync")
    assert np.array_equal(c, whole.cell_class)


def test_faces_with_fewer_than_three_vertices_and_no_faces():
    v, f = box()
    with pytest.raises(ValueError):
        polyvol.volume(v, [list(x) for x in f] + [[3]])
    assert polyvol.volume(v, []) == 0.0
    assert polyvol.volume(v, np.zeros((0, 3), dtype=np.int64)) == 0.0


def test_numpy_inputs_cross_into_cpp_without_a_copy():
    v, f = uv_sphere(200, 400)  # 159k triangles: 1.9 MB of coordinates, 1.9 MB of faces
    for faces in (f, f.astype(np.int32)):
        tracemalloc.start()
        polyvol.volume(v, faces)
        polyvol.mass_properties(v, faces)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        assert peak < v.nbytes / 10, peak


def result_classes():
    return {name: cls for name, cls in vars(polyvol).items()
            if isinstance(cls, type) and issubclass(cls, polyvol._Result) and cls._fields}


def test_every_result_and_field_is_in_the_docs_table():
    """docs/python.md's "Results and their fields" lists each result's fields,
    exactly: a field added, renamed or dropped in one place fails here."""
    doc = (pathlib.Path(__file__).resolve().parents[2] / "docs" / "python.md").read_text()
    section = doc.split("## Results and their fields", 1)[1].split("\n## ", 1)[0]
    rows = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0].startswith("`"):
            rows[cells[0].strip("`")] = tuple(re.findall(r"`([a-z_0-9]+)`", cells[2]))
    classes = result_classes()
    assert set(rows) == set(classes), set(rows) ^ set(classes)
    for name, cls in classes.items():
        assert rows[name] == cls._fields, (name, set(rows[name]) ^ set(cls._fields))


def test_mass_properties_has_the_keys_and_values_of_polyvol_measure(tmp_path):
    v, f = box((0, 0, 0), (2, 2, 2))
    w, g = box((1, 1, 1), (3, 3, 3))
    files = [off_file(tmp_path / "two.off", np.vstack([v, w]), np.vstack([f, g + 8])),
             off_file(tmp_path / "sphere.off", *uv_sphere(12, 24, 1.5, (0.25, 0.5, 0.75)))]
    for path in files:
        cli = cli_json("measure", path, "--density", "2.5")[0]
        d = polyvol.mass_properties(polyvol.load(path), density=2.5).to_dict()
        assert set(d) <= set(cli), set(d) - set(cli)
        for key in d:
            assert same(d[key], cli[key]), (path.name, key)
    assert polyvol.mass_properties(polyvol.load(files[0])).volume == 15.0


def test_polygon_area_has_the_keys_and_values_of_polyvol_area(tmp_path):
    path = tmp_path / "square_with_hole.txt"
    path.write_text("0 0 4 0 4 4 0 4\n1 1 1 2 2 2 2 1\n")
    cli = cli_json("area", path)[0]
    d = polyvol.polygon_area(polyvol.load_polygons(path)).to_dict()
    assert set(d) <= set(cli), set(d) - set(cli)
    for key in d:
        assert same(d[key], cli[key]), key
    assert d["area"] == 15.0
