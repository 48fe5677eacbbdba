"""polyvol.grid: closed forms per cell (boxes), the union and intersection of
overlapping bodies, blocks with the whole grid's bits, and the writers."""

import json
import subprocess

import numpy as np
import pytest

import polyvol
from conftest import CLI, box, uv_sphere


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


def test_an_inside_out_body_gives_the_bodies_and_says_why_there_is_no_union():
    v, f = box()
    inside_out = (v + 0.5, f[:, ::-1].copy())
    with pytest.warns(UserWarning, match="union"):
        g = polyvol.grid([(v, f), inside_out], dims=(3, 3, 3), bounds=(-1, -1, -1, 2, 2, 2))
    assert g.union is None and "inside out" in g.union_error
    assert g.volumes[1].sum() == -1.0
    with pytest.raises(ValueError):
        polyvol.grid([(v, f), inside_out], dims=(3, 3, 3), union=True)


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
    text = (tmp_path / "g.vti").read_text()
    assert "<ImageData" in text and 'Name="union_volume"' in text and 'Name="volume_1"' in text
    edges = [np.array([0, 0.1, 0.5, 1.0]), np.linspace(0, 1, 3), np.linspace(0, 1, 3)]
    polyvol.grid(box(), edges=edges).to_vti(tmp_path / "g.vtr")
    assert "<RectilinearGrid" in (tmp_path / "g.vtr").read_text()


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
