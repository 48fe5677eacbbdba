"""polyvol.grid: closed forms per cell (boxes), the union and intersection of
overlapping bodies, blocks with the whole grid's bits, and the writers."""

import json
import subprocess

import numpy as np
import pytest

import polyvol
from conftest import CLI, box, require_opencl_device, uv_sphere


def overlap_volume(lo, hi, edges):
    """Volume of the box [lo, hi] in every cell (closed form)."""
    parts = [np.clip(np.minimum(e[1:], h) - np.maximum(e[:-1], l), 0, None) for e, l, h in zip(edges, lo, hi)]
    return parts[0][:, None, None] * parts[1][None, :, None] * parts[2][None, None, :]


def test_a_box_in_every_cell():
    lo, hi = (0.3, -0.25, 0.1), (2.2, 1.6, 0.95)
    g = polyvol.grid(box(lo, hi), dims=(7, 6, 5), bounds=(0, -0.5, 0, 2.5, 2, 1))
    assert g.volumes.shape == (7, 6, 5) and g.shape == (7, 6, 5)
    assert np.allclose(g.volumes, overlap_volume(lo, hi, g.edges), rtol=0, atol=1e-15)
    assert np.allclose(g.fractions, g.volumes / g.cell_volumes)
    assert g.union is g.volumes
    assert g.summary["body_volumes"][0] == pytest.approx(1.9 * 1.85 * 0.85, rel=1e-15)
    assert [len(e) for e in g.edges] == [8, 7, 6]


def test_grid_choices_and_moments_and_surface():
    v, f = uv_sphere(16, 32)
    g = polyvol.grid((v, f), cells=10, moments=True, surface=True)
    assert max(g.shape) == 10
    assert g.volumes.sum() == pytest.approx(polyvol.volume(v, f), rel=1e-14)
    c = g.first_moments.sum(axis=(0, 1, 2)) / g.volumes.sum()
    assert np.allclose(c, polyvol.mass_properties(v, f).centroid, atol=1e-14)
    assert g.wetted_area.sum() == pytest.approx(polyvol.mass_properties(v, f).area, rel=1e-13)
    assert g.surface_normal.shape == g.shape + (3,)
    h = polyvol.grid((v, f), cell_size=0.5)
    assert np.allclose(np.diff(h.edges[0]), 0.5)
    with pytest.raises(ValueError):
        polyvol.grid((v, f), cells=10, dims=(3, 3, 3))


def test_two_overlapping_boxes_union_and_intersection():
    a, b = ((0, 0, 0), (2, 2, 2)), ((1.25, 0.5, 0.75), (3, 2.5, 2.5))
    edges = [np.linspace(-0.5, 3.5, 9), np.linspace(-0.5, 3, 8), np.linspace(-0.25, 3, 6)]
    g = polyvol.grid([box(*a), box(*b)], edges=edges, intersection=True)
    va, vb = overlap_volume(*a, g.edges), overlap_volume(*b, g.edges)
    common = overlap_volume((1.25, 0.5, 0.75), (2, 2, 2), g.edges)
    assert g.volumes.shape == (2, 8, 7, 5)
    assert np.allclose(g.volumes, [va, vb], atol=1e-15, rtol=0)
    assert np.allclose(g.union, va + vb - common, atol=1e-15, rtol=0)
    assert np.allclose(g.intersection, common, atol=1e-15, rtol=0)
    assert g.summary["union_volume"] == pytest.approx(8 + 1.75 * 2 * 1.75 - common.sum(), rel=1e-15)
    assert set(np.unique(g.cell_class)) <= {0, 1, 2, 3} and (g.cell_class == 3).any()
    assert g.summary["contact_cells"] == int((g.cell_class == 3).sum())


def test_an_inside_out_body_is_turned_outward_unless_signed():
    v, f = box()
    inside_out = (v + 0.5, f[:, ::-1].copy())
    with pytest.warns(UserWarning, match="turned outward"):
        g = polyvol.grid([(v, f), inside_out], dims=(3, 3, 3), bounds=(-1, -1, -1, 2, 2, 2))
    assert g.volumes[1].sum() == 1.0 and g.summary["union_volume"] == 2 - 0.125
    with pytest.warns(UserWarning, match="union"):
        g = polyvol.grid([(v, f), inside_out], dims=(3, 3, 3), bounds=(-1, -1, -1, 2, 2, 2), signed=True)
    assert g.union is None and "inside out" in g.union_error
    assert g.volumes[1].sum() == -1.0
    with pytest.raises(ValueError):
        polyvol.grid([(v, f), inside_out], dims=(3, 3, 3), union=True, signed=True)


def test_blocks_have_the_whole_grids_bits():
    s = uv_sphere(20, 40, 1.0, (0.01, -0.02, 0.03))
    t = uv_sphere(12, 24, 0.7, (0.6, 0.3, 0.2))
    whole = polyvol.grid([s, t], dims=(11, 9, 10), intersection=True, moments=True)
    for block in [((0, 4), (0, 9), (0, 10)), ((3, 8), (2, 5), (4, 7)), ((10, 11), (8, 9), (0, 1))]:
        part = polyvol.grid([s, t], edges=whole.edges, block=block, intersection=True, moments=True)
        sl = tuple(slice(*p) for p in block)
        assert part.volumes.shape == (2,) + tuple(p[1] - p[0] for p in block)
        assert np.array_equal(part.volumes, whole.volumes[(slice(None),) + sl])
        assert np.array_equal(part.first_moments, whole.first_moments[(slice(None),) + sl])
        assert np.array_equal(part.union, whole.union[sl])
        assert np.array_equal(part.intersection, whole.intersection[sl])
    with pytest.raises(ValueError):
        polyvol.grid(s, edges=whole.edges, block=((0, 12), (0, 9), (0, 10)))


def test_writers(tmp_path):
    g = polyvol.grid([box(), box((0.5, 0.5, 0.5), (1.5, 1.5, 1.5))], dims=(4, 4, 4))
    g.to_npy(tmp_path / "u.npy", "union")
    assert np.array_equal(np.load(tmp_path / "u.npy"), g.union)
    g.to_vti(tmp_path / "g.vti")
    head = (tmp_path / "g.vti").read_bytes()[:4096]
    assert b"<ImageData" in head and b'Name="union_volume"' in head and b'Name="volume_1"' in head
    edges = [np.array([0, 0.1, 0.5, 1.0]), np.linspace(0, 1, 3), np.linspace(0, 1, 3)]
    polyvol.grid(box(), edges=edges).to_vti(tmp_path / "g.vtr")
    assert b"<RectilinearGrid" in (tmp_path / "g.vtr").read_bytes()[:4096]


def _vtk_cells(reader, path):
    """The cell arrays VTK's own reader finds in a file, as (nx, ny, nz) arrays in polyvol's order."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader.SetFileName(str(path))
    reader.Update()
    out = reader.GetOutput()
    dims = [d - 1 for d in out.GetDimensions()]
    cells = out.GetCellData()
    arrays = {}
    for i in range(cells.GetNumberOfArrays()):
        a = cells.GetArray(i)
        v = vtk_to_numpy(a)
        # VTK has x fastest: reshape (nz, ny, nx[, c]) and put x first
        v = v.reshape(dims[::-1] + ([a.GetNumberOfComponents()] if a.GetNumberOfComponents() > 1 else []))
        arrays[a.GetName()] = np.moveaxis(v, [0, 1, 2], [2, 1, 0])
    return arrays


def test_vtk_reads_the_vti_and_vtr_files(tmp_path):
    vtk_xml = pytest.importorskip("vtkmodules.vtkIOXML")  # python3-vtk9 (README's setup)
    g = polyvol.grid([box(), box((0.5, 0.5, 0.5), (1.5, 1.5, 1.5))], dims=(4, 5, 6))
    g.to_vti(tmp_path / "g.vti")
    cells = _vtk_cells(vtk_xml.vtkXMLImageDataReader(), tmp_path / "g.vti")
    assert np.array_equal(cells["union_volume"], g.union)
    assert np.array_equal(cells["volume_0"], g.volumes[0])
    assert cells["cell_class"].dtype == np.uint8 and np.array_equal(cells["cell_class"], g.cell_class)
    edges = [np.array([0, 0.1, 0.5, 1.0]), np.linspace(0, 1, 3), np.linspace(0, 1, 4)]
    r = polyvol.grid(box(), edges=edges)
    r.to_vti(tmp_path / "g.vtr")
    cells = _vtk_cells(vtk_xml.vtkXMLRectilinearGridReader(), tmp_path / "g.vtr")
    assert np.array_equal(cells["volume"], r.volumes)


def test_vtk_reads_the_png_slice(tmp_path):
    vtk_io = pytest.importorskip("vtkmodules.vtkIOImage")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    mesh = tmp_path / "box.off"
    v, f = box((0, 0, 0), (2, 1, 1))
    mesh.write_text(f"OFF\n{len(v)} {len(f)} 0\n" + "".join(f"{a} {b} {c}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    png = tmp_path / "slice.png"
    out = subprocess.run([CLI, "grid", str(mesh), "--dims", "12", "6", "4", "--bounds", "-0.5", "-0.25", "-0.5", "2.5",
                          "1.25", "1.5", "--png", str(png)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    reader = vtk_io.vtkPNGReader()
    reader.SetFileName(str(png))
    reader.Update()
    w, h, _ = reader.GetOutput().GetDimensions()
    assert (w, h) == (640 + 90 + 120, 320 + 44 + 64)  # the box's 2:1 aspect kept, with margins
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).reshape(h, w, -1)
    # inside the box the fraction is 1: viridis' yellow; the margins are white; the labels black
    assert tuple(pixels[h - 1 - (44 + 160), 90 + 320][:3]) == (253, 231, 37)
    assert tuple(pixels[h - 1 - 5, 5][:3]) == (255, 255, 255)
    assert (pixels[..., :3] == 0).all(axis=-1).sum() > 500


def test_summary_has_the_cli_keys_and_numbers(tmp_path):
    v, f = uv_sphere(16, 32)
    path = tmp_path / "s.off"
    path.write_text("OFF\n%d %d 0\n" % (len(v), len(f)) + "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    cli = json.loads(subprocess.run([CLI, "grid", "--dims", "6", "7", "8", "--json", str(path)],
                                    capture_output=True, text=True, check=True).stdout)
    g = polyvol.grid(polyvol.load(path), dims=(6, 7, 8)).to_dict()
    for key in ("body_volumes", "union_volume", "full_cells", "empty_cells", "cut_cells", "contact_cells"):
        assert g[key] == cli[key], key
    for key in ("dims", "bounds", "cells", "uniform", "spacing"):
        assert g["grid"][key] == cli["grid"][key], key
    for key in ("volume", "triangles", "pieces", "full_cells", "empty_cells", "cut_cells"):
        assert g["bodies"][0][key] == cli["bodies"][0][key], key


def test_fractions_are_clamped_and_a_grid_beyond_max_memory_says_so():
    v, f = box((0.1, 0.2, 0.3), (0.9, 0.7, 0.8))
    g = polyvol.grid((v, f), dims=(4, 4, 4))
    assert g.fractions.min() >= 0 and g.fractions.max() <= 1
    assert np.array_equal(g.fractions, np.clip(g.volumes / g.cell_volumes, 0, 1))
    inside_out = (v, f[:, ::-1].copy())
    assert polyvol.grid(inside_out, dims=(4, 4, 4), signed=True).fractions.min() < 0  # signed: not clamped
    with pytest.raises(MemoryError, match=r"64 cells need about .* GiB.*more than max_memory.*polyvol.dask.grid"):
        polyvol.grid((v, f), dims=(4, 4, 4), max_memory=100)


def test_devices_lists_pocl_as_the_cli_does():
    require_opencl_device()
    listed = polyvol.devices()
    assert listed["opencl_runtime"] is True
    cli = json.loads(subprocess.run([CLI, "devices", "--json"], capture_output=True, check=True, text=True).stdout)
    assert [d["name"] for d in listed["devices"]] == [d["name"] for d in cli["devices"]]
    assert any(d["type"] == "cpu" and d["fp64"] and d["usable"] for d in listed["devices"])


def test_opencl_gives_the_cpus_bits_by_keyword_and_by_environment(monkeypatch):
    require_opencl_device()
    v, f = uv_sphere(20, 40)
    cpu = polyvol.grid((v, f), cells=24, moments=True, surface=True, device="cpu")
    gpu = polyvol.grid((v, f), cells=24, moments=True, surface=True, device="opencl")
    assert cpu.summary["device"] == "cpu"
    assert gpu.summary["device"].startswith("opencl: ")
    for name in ("volumes", "first_moments", "wetted_area", "surface_normal"):
        assert getattr(cpu, name).tobytes() == getattr(gpu, name).tobytes(), name
    assert cpu.summary["body_volumes"] == gpu.summary["body_volumes"]
    monkeypatch.setenv("POLYVOL_DEVICE", "opencl:0")
    env = polyvol.grid((v, f), cells=24)
    assert env.summary["device"].startswith("opencl: ")
    assert env.volumes.tobytes() == cpu.volumes.tobytes()


def test_a_device_that_cannot_be_had_raises_device_error():
    require_opencl_device()
    v, f = uv_sphere(8, 16)
    with pytest.raises(polyvol.DeviceError, match="no OpenCL device 99"):
        polyvol.grid((v, f), cells=8, device="opencl:99")
    with pytest.raises(ValueError, match="device must be auto, cpu, opencl"):
        polyvol.grid((v, f), cells=8, device="gpu")
