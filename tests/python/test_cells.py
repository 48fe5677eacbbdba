"""polyvol.cells, load_cells, cell_volumes and write_foam_field against
`polyvol cells` (the same bits), closed forms and the one solid policy."""
import json
import math
import pathlib
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
    with pytest.warns(UserWarning, match="states no unit: taken to be in m, the mesh's"):
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


def vtk_meshes(tmp_path):
    """VTK's own writer, every encoding: a 3^3 hexahedral grid (jittered
    inside) cut into tetrahedra, voxels, and a wedge and a pyramid."""
    vtk = pytest.importorskip("vtkmodules.all")
    rng = np.random.default_rng(5)
    pts = vtk.vtkPoints()
    pts.SetDataTypeToDouble()
    n = 3
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                p = np.array([i, j, k], dtype=float) / n * 2 - 1
                if 0 < i < n and 0 < j < n and 0 < k < n:
                    p += rng.uniform(-0.1, 0.1, 3)
                pts.InsertNextPoint(*p)
    hexes = vtk.vtkUnstructuredGrid()
    hexes.SetPoints(pts)
    pid = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)
    for k in range(n):
        for j in range(n):
            for i in range(n):
                hexes.InsertNextCell(vtk.VTK_HEXAHEDRON, 8, [pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k),
                                                            pid(i, j + 1, k), pid(i, j, k + 1), pid(i + 1, j, k + 1),
                                                            pid(i + 1, j + 1, k + 1), pid(i, j + 1, k + 1)])
    tets = vtk.vtkDataSetTriangleFilter()
    tets.SetInputData(hexes)
    tets.Update()
    grid = vtk.vtkRectilinearGrid()
    grid.SetDimensions(3, 2, 2)
    for axis, values in zip("XYZ", ([0, 0.5, 1.25], [0, 1], [-1, 0.5])):
        a = vtk.vtkDoubleArray()
        for v in values:
            a.InsertNextValue(v)
        getattr(grid, f"Set{axis}Coordinates")(a)
    voxels = vtk.vtkAppendFilter()
    voxels.AddInputData(grid)
    voxels.Update()
    shapes = vtk.vtkUnstructuredGrid()
    sp = vtk.vtkPoints()
    sp.SetDataTypeToDouble()
    for p in [(0, 0, 0), (0, 1, 0), (1, 0, 0), (0, 0, 2), (0, 1, 2), (1, 0, 2),  # a wedge (VTK's winding)
              (3, 0, 0), (5, 0, 0), (5, 2, 0), (3, 2, 0), (4, 1, 3)]:          # a pyramid
        sp.InsertNextPoint(*p)
    shapes.SetPoints(sp)
    shapes.InsertNextCell(vtk.VTK_WEDGE, 6, [0, 1, 2, 3, 4, 5])
    shapes.InsertNextCell(vtk.VTK_PYRAMID, 5, [6, 7, 8, 9, 10])
    files = {}
    for name, data in (("tets", tets.GetOutput()), ("voxels", voxels.GetOutput()), ("shapes", shapes)):
        for mode, zlib, b64, header in (("Ascii", 0, 0, 32), ("Binary", 0, 0, 32), ("Binary", 1, 0, 64),
                                        ("Appended", 0, 0, 32), ("Appended", 1, 0, 32), ("Appended", 0, 1, 64),
                                        ("Appended", 1, 1, 64)):
            path = tmp_path / f"{name}_{mode}_{zlib}{b64}{header}.vtu"
            w = vtk.vtkXMLUnstructuredGridWriter()
            w.SetInputData(data)
            w.SetFileName(str(path))
            getattr(w, f"SetDataModeTo{mode}")()
            w.SetCompressorTypeToZLib() if zlib else w.SetCompressorTypeToNone()
            w.SetEncodeAppendedData(b64)
            w.SetHeaderTypeToUInt64() if header == 64 else w.SetHeaderTypeToUInt32()
            w.Write()
            files.setdefault(name, []).append(path)
    return vtk, files, {"tets": tets.GetOutput(), "voxels": voxels.GetOutput(), "shapes": shapes}


def test_vtu_files_in_every_encoding_give_the_same_cells_and_vtks_volumes(tmp_path):
    vtk, files, data = vtk_meshes(tmp_path)
    from vtkmodules.util.numpy_support import vtk_to_numpy
    for name, paths in files.items():
        sizes = vtk.vtkCellSizeFilter()
        sizes.SetInputData(data[name])
        sizes.Update()
        vtk_volumes = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
        first = None
        for path in paths:
            m = polyvol.load_cells(path)
            assert m.format == "vtu" and m.cell_count == data[name].GetNumberOfCells(), path.name
            v, total = polyvol.cell_volumes(m)
            assert np.allclose(v, vtk_volumes, rtol=1e-12, atol=0), path.name
            if first is None:
                first = (m.points.copy(), v, total)
            assert np.array_equal(m.points, first[0]) and np.array_equal(v, first[1]) and total == first[2], path.name
    # The closed forms: the wedge's and the pyramid's volumes.
    v, _ = polyvol.cell_volumes(polyvol.load_cells(files["shapes"][0]))
    assert v[0] == 1.0 and v[1] == 4.0


def test_a_body_in_tetrahedra_from_a_vtu_adds_up_to_its_volume(tmp_path):
    _, files, _ = vtk_meshes(tmp_path)
    s = polyvol.Mesh(*uv_sphere(12, 24, 0.6, (0.05, -0.1, 0.2)))
    r = polyvol.cells(files["tets"][2], s, units="m")
    assert r.inside_mesh[0] == polyvol.volume(s)
    assert math.isclose(r.volumes.sum(), r.inside_mesh[0], rel_tol=1e-13)


def test_our_vtu_reads_back_as_the_same_cells(case, tmp_path):
    body = off_file(tmp_path / "sphere.off", *uv_sphere(12, 24, 0.7, (0.1, 0.0, -0.2)))
    out = subprocess.run([CLI, "cells", case, body, "--units", "m", "-o", tmp_path / "c.vtu"], capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stderr
    a, b = polyvol.load_cells(case), polyvol.load_cells(tmp_path / "c.vtu")
    assert np.array_equal(polyvol.cell_volumes(a)[0], polyvol.cell_volumes(b)[0])
    assert np.array_equal(polyvol.cells(a, polyvol.load(body), units="m").volumes,
                          polyvol.cells(b, polyvol.load(body), units="m").volumes)


def test_bad_vtu_files_are_refused_with_the_reason(tmp_path):
    head = ('<VTKFile type="UnstructuredGrid" byte_order="LittleEndian"><UnstructuredGrid>'
            '<Piece NumberOfPoints="3" NumberOfCells="1"><Points><DataArray type="Float64" NumberOfComponents="3" '
            'format="ascii">0 0 0 1 0 0 0 1 0</DataArray></Points><Cells>'
            '<DataArray type="Int64" Name="connectivity" format="ascii">0 1 2</DataArray>'
            '<DataArray type="Int64" Name="offsets" format="ascii">3</DataArray>')
    polygon = tmp_path / "polygon.vtu"
    polygon.write_text(head + '<DataArray type="UInt8" Name="types" format="ascii">5</DataArray>'
                       '</Cells></Piece></UnstructuredGrid></VTKFile>')
    with pytest.raises(polyvol.ReadError, match="VTK cell type 5 is not read"):
        polyvol.load_cells(polygon)
    broken = tmp_path / "broken.vtu"
    broken.write_text(head + '<DataArray type="UInt8" Name="types" format="binary">AgAA$$$</DataArray>'
                      '</Cells></Piece></UnstructuredGrid></VTKFile>')
    with pytest.raises(polyvol.ReadError, match="not base64"):
        polyvol.load_cells(broken)
    cut = tmp_path / "cut.vtu"
    cut.write_text(head.replace("</Points>", "").replace('format="ascii">0 0 0 1 0 0 0 1 0</DataArray>',
                                                          'format="appended" offset="0"/></Points>')
                   + '<DataArray type="UInt8" Name="types" format="ascii">10</DataArray></Cells></Piece>'
                   '</UnstructuredGrid><AppendedData encoding="raw">_\x48\x00\x00\x00</AppendedData></VTKFile>')
    with pytest.raises(polyvol.ReadError, match="more bytes than there are"):
        polyvol.load_cells(cut)


def test_a_vtu_that_claims_to_expand_to_gigabytes_is_refused_before_allocating(tmp_path):
    import base64
    import struct
    head = struct.pack("<IIII", 1, 0xFFFFFF00, 0xFFFFFF00, 10)  # one block of almost 4 GiB
    bomb = tmp_path / "bomb.vtu"
    bomb.write_text('<VTKFile type="UnstructuredGrid" byte_order="LittleEndian" compressor="vtkZLibDataCompressor">'
                    '<UnstructuredGrid><Piece NumberOfPoints="1" NumberOfCells="0"><Points><DataArray type="Float64" '
                    'NumberOfComponents="3" format="binary">' + base64.b64encode(head).decode()
                    + base64.b64encode(b"x" * 10).decode() + "</DataArray></Points></Piece></UnstructuredGrid></VTKFile>")
    with pytest.raises(polyvol.ReadError, match="claims to expand to more than"):
        polyvol.load_cells(bomb)


def grdecl_file(path, nx, ny, nz, actnum, throw=0.0, lean=0.0, skew=0.0):
    """A corner-point grid of 10 × 20 × 5 m cells (depth down), columns i >= 2
    thrown down by `throw`, pillars leaning apart by `lean` per column and
    by `skew` in x per row (pillars then not parallel: faces warped)."""
    coord = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            coord += [10.0 * i, 20.0 * j, 1000.0, 10.0 * i + lean * i + skew * j, 20.0 * j, 1100.0]
    z = []
    for k in range(nz):
        for c in range(2):
            for j in range(ny):
                for b in range(2):
                    for i in range(nx):
                        z += [1000.0 + 5.0 * (k + c) + (throw if i >= 2 else 0.0)] * 2
    path.write_text("METRIC\nSPECGRID\n%d %d %d 1 F /\nCOORD\n%s /\nZCORN\n%s /\nACTNUM\n%s /\n" % (
        nx, ny, nz, " ".join(map(repr, coord)), " ".join(map(repr, z)), " ".join(map(str, actnum))))
    return path


def read_keyword(path):
    """A GRDECL keyword file's values, repeats expanded."""
    words = [w for line in path.read_text().splitlines() if not line.startswith("--") for w in line.split()]
    values = []
    for w in words[1:words.index("/")]:
        n, _, v = w.rpartition("*")
        values += [float(v)] * (int(n) if n else 1)
    return words[0], np.array(values)


def test_a_corner_point_grid_gives_the_commands_bits_and_its_keyword_file(tmp_path):
    grid = grdecl_file(tmp_path / "grid.grdecl", 4, 3, 2, [1] * 5 + [0] + [1] * 18, throw=2.0)
    lo, hi = (5.0, 3.0, 1001.0), (33.0, 51.0, 1012.5)
    body = off_file(tmp_path / "box.off", *box(lo, hi))
    m = polyvol.load_cells(grid)
    assert (m.format, m.unit, m.grid_dims, m.cell_count, m.cells_tile) == ("grdecl", "m", (4, 3, 2), 23, True)
    assert m.fault_faces == 3 * 2 - 1  # between columns 1 and 2, one beside the inactive cell
    r = polyvol.cells(m, polyvol.load(body), units="m")
    out = subprocess.run([CLI, "cells", grid, body, "--units", "m", "-o", tmp_path / "frac.grdecl", "--fractions",
                          "--keyword", "SATBODY", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert j["mesh"]["grid"] == {"dims": [4, 3, 2], "active_cells": 23, "fault_faces": 5}
    assert j["bodies"][0]["inside_mesh"] == r.inside_mesh[0]
    keyword, values = read_keyword(tmp_path / "frac.grdecl")
    assert keyword == "SATBODY" and len(values) == 24 and values[5] == 0
    assert np.array_equal(values[m.grid_index], r.fractions[0])  # the same doubles, through the text
    # Vertical pillars: the thrown cells still tile; each cell is the box's overlap, exactly.
    exact = Fraction(0)
    for c, g in enumerate(m.grid_index):
        i, jj, k = g % 4, g // 4 % 3, g // 12
        t = 2.0 if i >= 2 else 0.0
        cell = [(10.0 * i, 10.0 * i + 10), (20.0 * jj, 20.0 * jj + 20), (1000 + 5.0 * k + t, 1005 + 5.0 * k + t)]
        v = math.prod(max(Fraction(0), Fraction(min(h, b)) - Fraction(max(l, a)))
                      for (a, b), l, h in zip(cell, lo, hi))
        assert r.volumes[0][c] == float(v)
        exact += v
    assert r.inside_mesh[0] == float(exact)


def test_a_faulted_grid_on_leaning_pillars_counts_the_covered_region_once(tmp_path):
    grid = grdecl_file(tmp_path / "grid.grdecl", 3, 2, 2, [1] * 12, throw=3.0, lean=4.0, skew=3.0)
    body = off_file(tmp_path / "box.off", *box((12.0, 3.0, 1001.0), (27.0, 30.0, 1012.0)))
    r = polyvol.cells(grid, polyvol.load(body), units="m")
    assert r.cells_tile is False
    # The cells overlap at the fault: they add up to more than they cover,
    # and the body in the overlaps counts in the cells' sum more than once.
    assert r.covered_volume < r.total and r.total - r.covered_volume > 1.0
    assert r.in_overlaps[0] == r.cells_sum[0] - r.inside_mesh[0] and r.in_overlaps[0] > 0.01
    assert r.cells_sum[0] == math.fsum(r.volumes[0])
    out = subprocess.run([CLI, "cells", grid, body, "--units", "m", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert j["cells_tile"] is False and j["mesh"]["covered_volume"] == r.covered_volume
    assert (j["bodies"][0]["inside_mesh"], j["bodies"][0]["in_overlaps"]) == (r.inside_mesh[0], r.in_overlaps[0])
    out = subprocess.run([CLI, "cells", grid, body, "--units", "m"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "faults: 4 faces" in out.stdout and "may overlap or leave gaps" in out.stdout
    assert "counted more than once where cells overlap" in out.stdout


def test_bad_grdecl_files_are_refused_with_the_line(tmp_path):
    grid = grdecl_file(tmp_path / "grid.grdecl", 2, 2, 1, [1] * 4)
    grid.write_text(grid.read_text().replace("ZCORN\n1000.0", "ZCORN\nx1000.0"))
    out = subprocess.run([CLI, "cells", grid], capture_output=True, text=True)
    assert out.returncode == 2 and "grid.grdecl:7: ZCORN: 'x1000.0' is not a number" in out.stderr, out.stderr
    with pytest.raises(polyvol.ReadError, match="is not a number"):
        polyvol.load_cells(grid)
    out = subprocess.run([CLI, "cells", grid, grid, "-o", tmp_path / "o.grdecl", "--keyword", "x"],
                         capture_output=True, text=True)
    assert out.returncode == 2  # the mesh is unreadable before the keyword is looked at
    good = grdecl_file(tmp_path / "good.grdecl", 2, 2, 1, [1] * 4)
    out = subprocess.run([CLI, "cells", good, "-o", tmp_path / "o.grdecl"], capture_output=True, text=True)
    assert out.returncode == 1 and "needs exactly one body" in out.stderr


def test_two_bodies_union_and_intersection_give_the_commands_bits_and_the_boxes_closed_forms(case, tmp_path):
    a, b = ((-0.7, -0.3, -0.2), (0.45, 0.6, 0.5)), ((-0.1, -0.6, 0.1), (0.8, 0.2, 0.9))
    files = [off_file(tmp_path / f"{n}.off", *box(*ab)) for n, ab in (("a", a), ("b", b))]
    r = polyvol.cells(case, [polyvol.load(f) for f in files], units="m", union=True, intersection=True)
    out = subprocess.run([CLI, "cells", case, *files, "--units", "m", "--union", tmp_path / "u.npy",
                          "--intersection", tmp_path / "i.npy", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert np.array_equal(np.load(tmp_path / "u.npy"), r.union_volumes)
    assert np.array_equal(np.load(tmp_path / "i.npy"), r.intersection_volumes)
    assert j["union"]["inside_mesh"] == r.union_inside_mesh and j["intersection"]["inside_mesh"] == r.intersection_inside_mesh
    # Closed forms: the union by inclusion-exclusion of boxes, exactly; the intersection box.
    size = lambda lo, hi: math.prod(max(Fraction(0), Fraction(h) - Fraction(l)) for l, h in zip(lo, hi))
    meet = (tuple(map(max, a[0], b[0])), tuple(map(min, a[1], b[1])))
    assert r.union_inside_mesh == float(size(*a) + size(*b) - size(*meet))
    assert abs(Fraction(r.intersection_inside_mesh) - size(*meet)) <= 2 * math.ulp(r.union_inside_mesh)
    assert np.all(r.intersection_volumes <= np.minimum(r.volumes[0], r.volumes[1]))
    with pytest.raises(ValueError, match="two bodies"):
        polyvol.cells(case, polyvol.load(files[0]), units="m", union=True)
    assert polyvol.cells(case, polyvol.load(files[0]), units="m").union_volumes is None


def test_the_wetted_area_and_normal_give_the_commands_bits_and_add_up_to_the_surface(case, tmp_path):
    s = polyvol.Mesh(*uv_sphere(16, 32, 0.6, (0.1, 0.05, 0.0)))
    body = off_file(tmp_path / "s.off", np.asarray(s.vertices), np.asarray(s.faces))
    r = polyvol.cells(case, polyvol.load(body), units="m", surface=True)
    out = subprocess.run([CLI, "cells", case, body, "--units", "m", "--surface", tmp_path / "s.npy",
                          "-o", tmp_path / "c.vtu", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    written = np.load(tmp_path / "s.npy")
    assert written.shape == (64, 4)
    assert np.array_equal(written[:, 0], r.wetted_area[0]) and np.array_equal(written[:, 1:], r.surface_normal[0])
    # The cells add up to the sphere's area, and its closed surface's normals to nothing, within the bounds.
    bound = r.surface_bound[0].sum()
    assert abs(j["bodies"][0]["wetted_area"] - polyvol.mass_properties(s).area) <= j["bodies"][0]["wetted_area_bound"] + 1e-15
    assert np.all(np.abs(r.surface_normal[0].sum(axis=0)) <= bound)
    assert np.all((r.wetted_area[0] > 0) == (r.cell_class[0] == 2))
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(tmp_path / "c.vtu"))
    reader.Update()
    data = reader.GetOutput().GetCellData()
    assert np.array_equal(vtk_to_numpy(data.GetArray("wetted_area")), r.wetted_area[0])
    assert np.array_equal(vtk_to_numpy(data.GetArray("surface_normal")), r.surface_normal[0])


def test_a_rectilinear_mesh_as_polymesh_or_vtu_gives_the_grids_numbers(tmp_path):
    # The same 8^3 cells as an OpenFOAM case, as the .vtu polyvol writes of
    # it, and as polyvol.grid's planes: cells correctly rounded, the grid
    # within 3.5e-16 of a cell's volume (docs/grid.md), so they agree within both.
    n = 8
    case = write_polymesh(tmp_path / "case", -1.0, 1.0, n)
    sphere = polyvol.Mesh(*uv_sphere(24, 48, 0.83, (0.1, -0.05, 0.02)))
    r = polyvol.cells(case, sphere, units="m")
    vtu = tmp_path / "cells.vtu"
    out = subprocess.run([CLI, "cells", case, "-o", vtu], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    from_vtu = polyvol.cells(polyvol.load_cells(vtu), sphere, units="m", mesh_units="m")
    assert np.array_equal(from_vtu.volumes, r.volumes) and from_vtu.inside_mesh == r.inside_mesh
    edges = [np.linspace(-1.0, 1.0, n + 1)] * 3
    g = polyvol.grid(sphere, edges=edges)
    cells = r.volumes[0].reshape(n, n, n).transpose(2, 1, 0)  # cell i + n (j + n k) -> [i, j, k]
    own = r.cell_volumes.reshape(n, n, n).transpose(2, 1, 0)
    assert np.array_equal(own, g.cell_volumes)
    bound = 3.5e-16 * own + np.spacing(own)
    assert np.all(np.abs(cells - g.volumes) <= bound)
    assert 0 < r.cut_cells[0] < n ** 3 and np.count_nonzero((cells > 0) & (cells < own)) == r.cut_cells[0]


def test_a_bodys_declared_unit_is_converted_or_overridden_by_units_as_grid_does(tmp_path):
    # A corner tetrahedron of side 2 in a 3MF that says inch (4/3 in³),
    # inside a case in metres: converted from its unit, or, with --units,
    # taken in the unit given (the file's unit overridden, with a warning).
    body = pathlib.Path(__file__).resolve().parents[1] / "data" / "units" / "tetra_inch.3mf"
    case = write_polymesh(tmp_path / "case", -1.0, 3.0, 2)
    out = subprocess.run([CLI, "cells", case, body, "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "converted from in to m" in out.stderr
    inside = json.loads(out.stdout)["bodies"][0]["inside_mesh"]
    assert math.isclose(inside, 4 / 3 * 0.0254 ** 3, rel_tol=1e-15)
    out = subprocess.run([CLI, "cells", case, body, "--units", "m", "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "declares its unit as in; m is used instead" in out.stderr
    b = json.loads(out.stdout)["bodies"][0]
    assert b["inside_mesh"] == b["volume"] == float(Fraction(4, 3))
