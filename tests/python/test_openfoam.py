"""`polyvol cells` against OpenFOAM itself (Debian's openfoam, v1912):
blockMesh builds the cases from tests/data/openfoam, polyvol writes
0/alpha.water, and OpenFOAM's postProcess integrates it (a volFieldValue
volIntegrate, ../shared/OPENFOAM.md) and writes its own cell volumes."""

import json
import math
import os
import pathlib
import re
import shutil
import subprocess
from fractions import Fraction

import numpy as np
import pytest

from conftest import CLI, box, uv_sphere

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "openfoam"
BASHRC = pathlib.Path("/usr/share/openfoam/etc/bashrc")

if not BASHRC.exists():
    if os.environ.get("CI"):
        raise RuntimeError("OpenFOAM is not installed (apt-get install openfoam): the README's setup installs it")
    pytest.skip("OpenFOAM is not installed (apt-get install openfoam)", allow_module_level=True)


def foam(case, command):
    out = subprocess.run(["bash", "-c", f"source {BASHRC} >/dev/null 2>&1; cd '{case}' && {command}"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    return out.stdout


def make_case(tmp_path, dictionary):
    case = tmp_path / dictionary
    (case / "system").mkdir(parents=True)
    for f in (DATA / "system").iterdir():
        shutil.copy(f, case / "system")
    shutil.copy(DATA / dictionary / "system" / "blockMeshDict", case / "system")
    foam(case, "blockMesh")
    return case


def off_file(path, v, f):
    path.write_text(f"OFF\n{len(v)} {len(f)} 0\n" + "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    return path


def cells(*args):
    out = subprocess.run([CLI, "cells", *map(str, args), "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def vol_integrate(case):
    text = foam(case, 'postProcess -dict system/volAlpha -time 0 -fields "(alpha.water)"')
    return float(re.search(r"volIntegrate\(region0\) of alpha.water = (\S+)", text).group(1))


def internal_field(path):
    text = path.read_text()
    body = text.split("internalField", 1)[1]
    n = int(re.search(r"List<scalar>\s*(\d+)", body).group(1))
    values = body.split("(", 1)[1].split(")", 1)[0].split()
    assert len(values) == n
    return np.array([float(v) for v in values])


def test_openfoam_integrates_the_field_to_polyvols_total_on_planar_cells(tmp_path):
    case = make_case(tmp_path, "graded_box")
    # A box inside the mesh: the total is its volume, correctly rounded.
    inside = off_file(tmp_path / "inside.off", *box((0.05, 0.03, 0.02), (0.21, 0.17, 0.1)))
    total = cells(case, inside, "--field", "alpha.water")["bodies"][0]["inside_mesh"]
    assert total == float((Fraction(0.21) - Fraction(0.05)) * (Fraction(0.17) - Fraction(0.03)) *
                          (Fraction(0.1) - Fraction(0.02)))
    assert math.isclose(vol_integrate(case), total, rel_tol=1e-12)
    # A box sticking out at the top (where blockMesh's points are not quite
    # one plane): OpenFOAM's integral of the fractions is polyvol's total.
    out = off_file(tmp_path / "out.off", *box((0.05, 0.03, 0.02), (0.21, 0.17, 0.2)))
    total = cells(case, out, "--field", "alpha.water")["bodies"][0]["inside_mesh"]
    assert math.isclose(total, 0.16 * 0.14 * 0.11, rel_tol=1e-14)
    assert math.isclose(vol_integrate(case), total, rel_tol=1e-12)


def test_openfoam_reads_the_fractions_on_warped_cells(tmp_path):
    case = make_case(tmp_path, "warped_ascii")
    body = off_file(tmp_path / "sphere.off", *uv_sphere(16, 32, 0.7, (1.55, 1.05, 1.1)))
    r = cells(case, body, "--field", "alpha.water")
    alpha = internal_field(case / "0" / "alpha.water")
    assert len(alpha) == r["mesh"]["cells"] and alpha.min() >= 0 and alpha.max() <= 1
    foam(case, "postProcess -func writeCellVolumes -time 0")
    v = internal_field(case / "0" / "V")
    # OpenFOAM read our fractions exactly: its integral is Σ α V with its own cell volumes.
    assert math.isclose(vol_integrate(case), math.fsum(alpha * v), rel_tol=1e-12)
    # Its volumes come from face-centre decompositions, ours from the fan
    # rule (docs/cells.md): on these warped faces they differ, a little.
    assert math.isclose(math.fsum(v), r["mesh"]["volume"], rel_tol=1e-2)
    assert math.isclose(r["bodies"][0]["inside_mesh"], r["bodies"][0]["volume"], rel_tol=0)  # inside the mesh


def test_an_existing_fields_boundary_conditions_are_kept(tmp_path):
    case = make_case(tmp_path, "graded_box")
    (case / "0").mkdir()
    (case / "0" / "alpha.water").write_text(
        "FoamFile { version 2.0; format ascii; class volScalarField; object alpha.water; }\n"
        "dimensions [0 0 0 0 0 0 0];\ninternalField uniform 0;\n"
        "boundaryField\n{\n    walls\n    {\n        type fixedValue;\n        value uniform 0.25;\n    }\n}\n")
    body = off_file(tmp_path / "box.off", *box((0.05, 0.03, 0.02), (0.21, 0.17, 0.2)))
    cells(case, body, "--field", "alpha.water")
    text = (case / "0" / "alpha.water").read_text()
    assert "type fixedValue;" in text and "value uniform 0.25;" in text
    assert math.isclose(vol_integrate(case), 0.002464, rel_tol=1e-12)


def test_a_decomposed_case_gives_the_whole_cases_bits_one_processor_a_dask_task(tmp_path):
    import polyvol
    import polyvol.dask
    case = make_case(tmp_path, "warped_ascii")  # warped faces, split by the rule of positions
    foam(case, "decomposePar")
    assert len(list(case.glob("processor*"))) == 3
    sphere = off_file(tmp_path / "sphere.off", *uv_sphere(12, 24, 0.7, (1.55, 1.05, 1.1)))
    body = polyvol.load(sphere)
    whole = polyvol.cells(case, body, units="m")
    parts = polyvol.dask.cells(case, body, units="m")
    assert np.array_equal(parts.cell_volumes, whole.cell_volumes)
    assert np.array_equal(parts.volumes, whole.volumes) and np.array_equal(parts.cell_class, whole.cell_class)
    assert parts.cells_sum == whole.cells_sum and parts.body_volumes == whole.body_volumes
    assert whole.cut_cells[0] > 10 and parts.cut_cells == whole.cut_cells
    with pytest.raises(ValueError, match="not a decomposed OpenFOAM case"):
        polyvol.dask.cells(tmp_path, body, units="m")


def test_a_decomposed_case_is_read_whole_and_its_fields_are_written_per_processor_for_openfoam(tmp_path):
    import polyvol
    case = make_case(tmp_path, "warped_ascii")
    foam(case, "decomposePar")
    # The processors alone (no constant/polyMesh of the case's own): the whole mesh from its pieces.
    alone = tmp_path / "alone"
    shutil.copytree(case / "system", alone / "system")
    for p in case.glob("processor*"):
        shutil.copytree(p, alone / p.name)
    whole, pieces = polyvol.load_cells(case), polyvol.load_cells(alone)
    for field in ("points", "face_offsets", "face_points", "owner", "neighbour"):
        assert np.array_equal(getattr(whole, field), getattr(pieces, field)), field
    sphere = off_file(tmp_path / "sphere.off", *uv_sphere(12, 24, 0.7, (1.55, 1.05, 1.1)))
    a = cells(case, sphere, "--units", "m", "--field", "alpha.water")
    b = cells(alone, sphere, "--units", "m", "--field", "alpha.water")
    assert a["bodies"] == b["bodies"] and a["mesh"]["volume"] == b["mesh"]["volume"]
    # OpenFOAM puts the processors' fields together again: the whole case's field, value for value.
    for p in alone.glob("processor*"):
        shutil.copytree(p / "0", case / p.name / "0")
    expected = internal_field(case / "0" / "alpha.water")
    shutil.rmtree(case / "0")
    foam(case, "reconstructPar -withZero -fields '(alpha.water)'")
    assert np.array_equal(internal_field(case / "0" / "alpha.water"), expected)


def test_a_cell_zone_limits_the_cells_and_openfoam_integrates_the_zones_field(tmp_path):
    import polyvol
    case = make_case(tmp_path, "graded_box")
    foam(case, "topoSet")
    whole, zone = polyvol.load_cells(case), polyvol.load_cells(case, cell_zone="inner")
    assert 0 < zone.cell_count < whole.cell_count and zone.case_cells == whole.cell_count
    body = off_file(tmp_path / "box.off", *box((0.05, 0.03, 0.02), (0.21, 0.17, 0.1)))
    a = polyvol.cells(whole, polyvol.load(body), units="m")
    z = polyvol.cells(zone, polyvol.load(body), units="m")
    assert np.array_equal(z.volumes[0], a.volumes[0][zone.case_index])  # each cell the same double
    j = cells(case, body, "--cell-zone", "inner", "--field", "alpha.water")
    assert j["mesh"]["cells"] == zone.cell_count and j["mesh"]["cell_zone"] == "inner"
    assert j["bodies"][0]["inside_mesh"] == z.inside_mesh[0]
    alpha = internal_field(case / "0" / "alpha.water")
    outside = np.ones(whole.cell_count, dtype=bool)
    outside[zone.case_index] = False
    assert len(alpha) == whole.cell_count and np.all(alpha[outside] == 0)
    assert math.isclose(vol_integrate(case), z.inside_mesh[0], rel_tol=1e-12)
    with pytest.raises(polyvol.ReadError, match="no cellZone outer .the zones: inner"):
        polyvol.load_cells(case, cell_zone="outer")
