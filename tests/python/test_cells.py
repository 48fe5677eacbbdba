"""polyvol.cells, load_cells, cell_volumes and write_foam_field against
`polyvol cells` (the same bits), closed forms and the one solid policy."""
import json
import math
import subprocess
from fractions import Fraction

import numpy as np
import pytest

import polyvol
from conftest import CLI, box, uv_sphere, write_polymesh


def off_file(path, v, f):
    path.write_text(f"OFF\n{len(v)} {len(f)} 0\n" + "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    return path


@pytest.fixture()
def case(tmp_path):
    return write_polymesh(tmp_path / "case", -1.0, 1.0, 4)


def test_the_cells_of_a_mesh(case):
    m = polyvol.load_cells(case)
    assert (m.cell_count, m.face_count, m.unit, m.format) == (64, 4 * 4 * 5 * 3, "m", "openfoam")
    assert m.points.shape == (125, 3) and (m.neighbour == -1).sum() == 6 * 16
    v, total = polyvol.cell_volumes(m)
    assert np.all(v == 0.125) and total == 8.0


def test_cells_gives_the_commands_bits_and_a_boxs_closed_form(case, tmp_path):
    lo, hi = (-0.7, -0.3, 0.1), (0.45, 0.9, 1.6)  # sticks out of the mesh at the top
    body = off_file(tmp_path / "box.off", *box(lo, hi))
    r = polyvol.cells(polyvol.load_cells(case), polyvol.load(body), units="m")
    out = subprocess.run([CLI, "cells", case, body, "--units", "m", "-o", tmp_path / "v.npy", "--json"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert np.array_equal(np.load(tmp_path / "v.npy"), r.volumes[0])
    assert j["bodies"][0]["inside_mesh"] == r.inside_mesh[0] and j["mesh"]["volume"] == r.total
    exact = math.prod(Fraction(min(h, 1.0)) - Fraction(max(l, -1.0)) for l, h in zip(lo, hi))
    assert r.inside_mesh[0] == float(exact)
    assert r.cut_cells[0] + r.full_cells[0] + r.empty_cells[0] == 64
    assert r.fractions.min() >= 0 and r.fractions.max() <= 1 and r.cell_class.shape == (1, 64)


def test_a_sphere_inside_the_mesh_adds_up_to_its_volume(case):
    s = polyvol.Mesh(*uv_sphere(16, 32, 0.8, (0.1, 0.05, 0.0)))
    with pytest.warns(UserWarning, match="no unit stated"):
        r = polyvol.cells(case, s)
    assert r.inside_mesh[0] == polyvol.volume(s) == r.body_volumes[0]
    assert math.isclose(r.volumes.sum(), r.inside_mesh[0], rel_tol=1e-14)


def test_bodies_are_their_solids_or_refused(case):
    v, f = box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    inside_out = polyvol.Mesh(v, f[:, ::-1].copy())
    with pytest.warns(UserWarning, match="turned outward"):
        r = polyvol.cells(case, inside_out, units="m")
    assert r.inside_mesh[0] == 1.0
    with pytest.raises(polyvol.NotASolidError, match="not a closed surface"):
        polyvol.cells(case, polyvol.Mesh(v, f[:-1].copy()), units="m")
    with pytest.raises(polyvol.ReadError):
        polyvol.load_cells(case / "nothing")


def test_the_field_is_written_for_openfoam(case):
    m = polyvol.load_cells(case)
    path = polyvol.write_foam_field(m, "alpha.water", np.linspace(0, 1, 64))
    text = open(path).read()
    assert "class       volScalarField;" in text and "internalField   nonuniform List<scalar>\n64\n(" in text
    assert "walls" in text and "zeroGradient" in text
    with pytest.raises(ValueError, match="one value per cell"):
        polyvol.write_foam_field(m, "alpha.water", np.zeros(3))


def test_vtk_opens_the_vtu_with_the_cells_and_their_values(case, tmp_path):
    vtk = pytest.importorskip("vtkmodules.all")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    body = off_file(tmp_path / "sphere.off", *uv_sphere(12, 24, 0.7, (0.1, 0.0, -0.2)))
    out = subprocess.run([CLI, "cells", case, body, "--units", "m", "-o", tmp_path / "c.vtu"], capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stderr
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(tmp_path / "c.vtu"))
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfCells() == 64 and grid.GetNumberOfPoints() == 125
    assert grid.GetCellType(0) == vtk.VTK_POLYHEDRON and grid.GetCell(0).GetNumberOfFaces() == 6
    r = polyvol.cells(polyvol.load_cells(case), polyvol.load(body), units="m")
    data = grid.GetCellData()
    assert np.array_equal(vtk_to_numpy(data.GetArray("volume")), r.volumes[0])
    assert np.array_equal(vtk_to_numpy(data.GetArray("fraction")), r.fractions[0])
    assert np.array_equal(vtk_to_numpy(data.GetArray("cell_class")), r.cell_class[0])
    # VTK's own cell volumes agree with the cells' (planar faces).
    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(grid)
    sizes.Update()
    vtk_volumes = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
    assert np.allclose(vtk_volumes, vtk_to_numpy(data.GetArray("cell_volume")), rtol=1e-12, atol=0)


def test_the_command_refuses_an_open_cell_and_an_unreadable_mesh(case, tmp_path):
    mesh = case / "constant" / "polyMesh"
    for name in ("faces", "owner"):  # the last boundary face gone: its cell is open
        text = (mesh / name).read_text()
        head, body = text.split("\n(\n", 1)
        items = body.split("\n)")[0].split("\n")[:-1]
        (mesh / name).write_text(head.rsplit("\n", 1)[0] + f"\n{len(items)}\n(\n" + "\n".join(items) + "\n)\n")
    out = subprocess.run([CLI, "cells", case], capture_output=True, text=True)
    assert out.returncode == 3 and "cell 63's faces do not close" in out.stderr, out.stderr
    (mesh / "points").write_text("FoamFile { format ascii; class vectorField; }\n3\n(\n(0 0 0)\n(1 0 0)\n)\n")
    out = subprocess.run([CLI, "cells", case], capture_output=True, text=True)
    assert out.returncode == 2 and "points:3: the list claims 3 points" in out.stderr, out.stderr
