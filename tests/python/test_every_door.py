"""One answer from every door: the same file gives the same solid through
`polyvol volume`, `measure`, `check`, `overlap` (as A and as B), `grid` (one
body, and with --union; on the CPU and an OpenCL device), `cells` (an OpenFOAM mesh around it) and Python's mass_properties, volume, overlap, grid,
check and measure_file — or every door refuses it for the same reason
(polyvol/solid.hpp, the one policy). A new entry point is added here, to
DOORS."""
import json
import pathlib
import struct
import subprocess
import warnings
import zipfile

import pytest

import polyvol
from conftest import CLI, write_polymesh

ROOT = pathlib.Path(__file__).resolve().parents[2]

# A cube [x, x+s]^3 as 8 vertices and 6 outward quads (OBJ numbering from 0).
QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def cube(lo, side):
    x, y, z = lo
    return [(x + side * (i & 1), y + side * ((i >> 1) & 1), z + side * ((i >> 2) & 1)) for i in range(8)]


def write_obj(path, cubes, flip=(), drop=(), move=None):
    """Cubes (lo, side) in one OBJ; `flip`: (cube, quad) reversed; `drop`:
    (cube, quad) left out; `move`: (cube, vertex, dx): the first quad at that
    vertex uses a copy of it moved by dx along x (a gap)."""
    lines, base = [], 0
    for c, (lo, side) in enumerate(cubes):
        points = cube(lo, side)
        if move and move[0] == c:
            p = points[move[1]]
            points.append((p[0] + move[2], p[1], p[2]))
        lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in points]
        moved = False
        for q, quad in enumerate(QUADS):
            if (c, q) in drop:
                continue
            quad = quad[::-1] if (c, q) in flip or ("all", c) in flip else quad
            if move and move[0] == c and move[1] in quad and not moved:
                quad, moved = tuple(8 if i == move[1] else i for i in quad), True
            lines.append("f " + " ".join(str(base + i + 1) for i in quad))
        base += len(points)
    path.write_text("\n".join(lines) + "\n")
    return path


def write_binary_stl(path, cubes):
    """Cubes (lo, side) as one binary STL, in triangles (float32 coordinates)."""
    records = []
    for lo, side in cubes:
        points = cube(lo, side)
        for a, b, c, d in QUADS:
            for tri in ((a, b, c), (a, c, d)):
                records.append(struct.pack("<12fH", 0, 0, 0, *(x for i in tri for x in points[i]), 0))
    path.write_bytes(bytes(80) + struct.pack("<I", len(records)) + b"".join(records))
    return path


def write_3mf(path, cubes):
    """Cubes (lo, side) as one 3MF object (millimetres), in triangles."""
    vertices, triangles = [], []
    for lo, side in cubes:
        base = len(vertices)
        vertices += cube(lo, side)
        for a, b, c, d in QUADS:
            triangles += [(base + a, base + b, base + c), (base + a, base + c, base + d)]
    model = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">',
             '<resources><object id="1" type="model"><mesh><vertices>']
    model += [f'<vertex x="{x!r}" y="{y!r}" z="{z!r}"/>' for x, y, z in vertices]
    model += ["</vertices><triangles>"]
    model += [f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in triangles]
    model += ['</triangles></mesh></object></resources><build><item objectid="1"/></build></model>']
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml",
                   '<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/'
                   'package/2006/content-types"><Default Extension="rels" ContentType="application/'
                   'vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" '
                   'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
        z.writestr("_rels/.rels",
                   '<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/'
                   'package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" '
                   'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
        z.writestr("3D/3dmodel.model", "\n".join(model))
    return path


TWO = [((0.0, 0.0, 0.0), 2.0), ((1.0, 1.0, 1.0), 2.0)]  # overlapping in a unit cube: the solid is 15
ONE = [((0.0, 0.0, 0.0), 2.0)]
SELF = ROOT / "tests" / "data" / "self_crossing" / "one.obj"
SELF_VOLUME = 4.932123991149121  # `polyvol volume`: the solid of a shell crossing itself (winding sum 5.66...)

# name -> (how to make it, the solid's volume or the refusal's defect,
#          whether it is a solid as it is, the doors that cannot take it yet)
CASES = {
    "clean cube": (lambda d: write_obj(d / "cube.obj", ONE), 8.0, True, ()),
    "two cubes (OBJ)": (lambda d: write_obj(d / "two.obj", TWO), 15.0, True, ()),
    "two cubes (3MF)": (lambda d: write_3mf(d / "two.3mf", TWO), 15.0, True, ()),
    "two cubes (binary STL)": (lambda d: write_binary_stl(d / "two.stl", TWO), 15.0, True, ()),
    "inside-out cube": (lambda d: write_obj(d / "inside_out.obj", ONE, flip={("all", 0)}), 8.0, False, ()),
    "self-crossing shell": (lambda d: SELF, SELF_VOLUME, True,
                            ("grid", "grid --union", "grid --device opencl", "grid --union --device opencl",
                             "py grid", "py grid device=opencl")),
    "flipped face": (lambda d: write_obj(d / "flipped.obj", ONE, flip={(0, 1)}), "misoriented", False, ()),
    "open cube": (lambda d: write_obj(d / "open.obj", ONE, drop={(0, 1)}), "open", False, ()),
    "1e-7 gap": (lambda d: write_obj(d / "gap.obj", ONE, move=(0, 7, 1e-7)), "open", False, ()),
}

# What each refusal says, the same words through every door.
WORDS = {"open": "not a closed surface", "misoriented": "misoriented"}


def cli(*args):
    r = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def cli_volume(args, key):
    """The volume through a CLI door, or ("refused", stderr) on exit 3."""
    code, out, err = cli(*args)
    if code == 3:
        return "refused", err
    assert code == 0, err
    return key(json.loads(out)), err


def py(call):
    """The volume through a Python door, or ("refused", message)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return call(), ""
        except polyvol.NotASolidError as e:
            return "refused", f"{e.defect}: {e}"


@pytest.fixture(scope="module")
def big_box(tmp_path_factory):
    """A box containing every case: A ∩ box and box ∩ A are the solid; beside
    it, box.parent / "case", an OpenFOAM mesh of 3^3 cells over the same box."""
    d = tmp_path_factory.mktemp("box")
    write_polymesh(d / "case", -10.0, 20.0, 3)
    return write_obj(d / "box.obj", [((-10.0, -10.0, -10.0), 30.0)])


def cli_table_volume(args):
    """The volume column of the table a CLI door prints, or ("refused", stderr) on exit 3."""
    code, out, err = cli(*args)
    if code == 3:
        return "refused", err
    assert code == 0, err
    return float(out.splitlines()[1].split()[2]), err


DOORS = {
    "volume": lambda f, box, d: cli_volume(["volume", "--json", f], lambda j: j[0]["volume"]),
    "volume (table)": lambda f, box, d: cli_table_volume(["volume", f]),
    "volume --volume-only (table)": lambda f, box, d: cli_table_volume(["volume", "--volume-only", f]),
    "measure": lambda f, box, d: cli_volume(["measure", "--json", f], lambda j: j[0]["volume"]),
    "overlap A": lambda f, box, d: cli_volume(["overlap", "--json", f, box], lambda j: j["intersection"]),
    "overlap B": lambda f, box, d: cli_volume(["overlap", "--json", box, f], lambda j: j["intersection"]),
    "grid": lambda f, box, d: cli_volume(["grid", f, "--cells", 8, "--json"], lambda j: j["body_volumes"][0]),
    "grid --union": lambda f, box, d: cli_volume(["grid", f, "--cells", 8, "--json", "--union", d / "u.npy"],
                                                 lambda j: j["union_volume"]),
    "grid --device opencl": lambda f, box, d: cli_volume(["grid", f, "--cells", 8, "--json", "--device", "opencl"],
                                                         lambda j: j["body_volumes"][0]),
    "grid --union --device opencl": lambda f, box, d: cli_volume(
        ["grid", f, "--cells", 8, "--json", "--union", d / "u.npy", "--device", "opencl"], lambda j: j["union_volume"]),
    "cells": lambda f, box, d: cli_volume(["cells", box.parent / "case", f, "--mesh-units", "mm", "--json"],
                                          lambda j: j["bodies"][0]["inside_mesh"]),
    "py mass_properties": lambda f, box, d: py(lambda: polyvol.mass_properties(polyvol.load(f)).volume),
    "py volume": lambda f, box, d: py(lambda: polyvol.volume(polyvol.load(f))),
    "py overlap": lambda f, box, d: py(lambda: polyvol.overlap(polyvol.load(f), polyvol.load(box)).intersection),
    "py grid": lambda f, box, d: py(lambda: polyvol.grid(polyvol.load(f), cells=8).summary["body_volumes"][0]),
    "py grid device=opencl": lambda f, box, d: py(
        lambda: polyvol.grid(polyvol.load(f), cells=8, device="opencl").summary["body_volumes"][0]),
    "py measure_file": lambda f, box, d: (
        (lambda r: ("refused", r["error"]) if r["exit_code"] == 3 else (r["volume"], ""))(polyvol.measure_file(f))),
}


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("door", DOORS)
def test_every_door_gives_the_same_solid_or_the_same_refusal(case, door, big_box, tmp_path):
    make, want, _, not_yet = CASES[case]
    f = make(tmp_path)
    got, said = DOORS[door](f, big_box, tmp_path)
    if door in not_yet:  # a documented gap: refused, never a wrong number
        assert got == "refused", (door, got)
        return
    if isinstance(want, str):
        assert got == "refused", (door, got)
        assert WORDS[want] in said, (door, said)
    else:
        assert got == want, (door, said)


@pytest.mark.parametrize("case", CASES)
def test_check_judges_the_file_as_it_is(case, tmp_path):
    make, want, ready, _ = CASES[case]
    f = make(tmp_path)
    code, out, err = cli("check", "--json", f)
    assert code == (0 if ready else 3), err
    j = json.loads(out)[0]
    assert j["ready"] is ready and (j["repairs"] == []) is ready
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t = polyvol.check(polyvol.load(f))
    assert t.ready is ready and t.repairs == j["repairs"]
    if isinstance(want, float) and want != 8.0:  # shells that overlap: the solid's volume in both
        assert j["solid_volume"] == t.solid_volume == want
