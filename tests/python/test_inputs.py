"""Meshes in and out of the Python API: zero-copy views of what was read,
numpy inputs of every dtype and layout (converted exactly, or refused with
TypeError), objects shaped like a trimesh mesh, and the errors."""

import gzip

import pathlib
import subprocess

import numpy as np
import pytest

import polyvol
from polyvol import _arrays
from conftest import CLI, box, uv_sphere

OBJ = b"""v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
"""


def test_loaded_arrays_are_read_only_views_of_the_mesh():
    m = polyvol.load_bytes(OBJ, "tet.obj")
    v = m.vertices
    assert v.shape == (4, 3) and v.dtype == np.float64
    assert not v.flags.writeable
    assert v.base is not None and np.shares_memory(v, m.vertices)  # the same memory every time
    assert m.faces.dtype == np.uint32 and m.faces.shape == (4, 3)
    assert np.shares_memory(m.faces, m.face_indices)
    with pytest.raises(ValueError):
        v[0, 0] = 1.0
    del m  # the view keeps the mesh alive
    assert v[1].tolist() == [1.0, 0.0, 0.0]


def test_a_tetrahedron_has_its_closed_form_properties():
    m = polyvol.load_bytes(OBJ, "tet.obj")
    p = polyvol.mass_properties(m, density=3.0)
    assert p.volume == 1 / 6 and p.mass == 0.5
    assert p.centroid.tolist() == [0.25, 0.25, 0.25]
    # ∫x² over the unit simplex = 1/60, ∫xy = 1/120
    assert p.second_moments[0, 0] == 3 / 60 and p.second_moments[0, 1] == 3 / 120
    assert p.inertia_origin[0, 0] == 3 * 2 / 60 and p.inertia_origin[0, 1] == -3 / 120
    assert p.volume_correctly_rounded and p.moments_correctly_rounded
    assert polyvol.volume(m) == 1 / 6
    assert polyvol.check(m).closed


def test_every_format_and_gzip(tmp_path):
    v, f = box((0, 0, 0), (2, 3, 4))
    off = "OFF\n8 12 0\n" + "".join(f"{a} {b} {c}\n" for a, b, c in v) + "".join(f"3 {a} {b} {c}\n" for a, b, c in f)
    stl = "solid s\n" + "".join(
        "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in v[t]) + "endloop\nendfacet\n"
        for t in f) + "endsolid s\n"
    (tmp_path / "b.off").write_text(off)
    (tmp_path / "b.stl.gz").write_bytes(gzip.compress(stl.encode()))
    a, b = polyvol.load(tmp_path / "b.off"), polyvol.load(tmp_path / "b.stl.gz")
    assert (a.format, b.format, b.gzip, b.vertices_in_file) == ("off", "stl", True, 36)
    assert polyvol.volume(a) == polyvol.volume(b) == 24.0


def test_read_errors_carry_the_position(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(polyvol.ReadError) as e:
        polyvol.load(bad)
    assert (e.value.path, e.value.line, e.value.offset) == (str(bad), 4, None)
    assert "7" in e.value.message and isinstance(e.value, ValueError)
    short = tmp_path / "short.stl"
    short.write_bytes(b"\0" * 80 + (5).to_bytes(4, "little") + b"\0" * 60)
    with pytest.raises(polyvol.ReadError) as e:
        polyvol.load(short)
    assert e.value.line is None and e.value.offset is not None
    with pytest.raises(polyvol.ReadError) as e:
        polyvol.load(tmp_path / "missing.stl")
    assert e.value.path.endswith("missing.stl")


def test_numpy_inputs_of_every_dtype_and_layout_give_the_same_bits():
    v, f = uv_sphere(12, 24)
    want = polyvol.mass_properties(v, f)
    assert want.volume_correctly_rounded
    v32 = v.astype(np.float32)
    widened = polyvol.volume(v32.astype(np.float64), f)
    cases = [
        (np.asfortranarray(v), f),                     # column-major coordinates
        (np.repeat(v, 2, axis=0)[::2], f),             # strided, non-contiguous
        (v, f.astype(np.int64)),                       # int64 faces
        (v, f.astype(np.int32)),
        (v, f.astype(np.uint16)),
        (v, np.asfortranarray(f)),
        (v.tolist(), f.tolist()),                      # plain lists
    ]
    for vv, ff in cases:
        assert polyvol.volume(vv, ff) == want.volume
        p = polyvol.mass_properties(vv, ff)
        assert np.array_equal(p.inertia, want.inertia)
    assert polyvol.volume(v32, f) == widened           # float32: widened exactly, then exact
    ints = (v * 1000).round().astype(np.int64)
    assert polyvol.volume(ints, f) == polyvol.volume(ints.astype(np.float64), f)


def test_inputs_already_right_are_not_copied():
    v, f = uv_sphere(8, 16)
    p, idx, offsets = _arrays.mesh(v, f)
    assert np.shares_memory(p, v) and np.shares_memory(idx, f) and offsets is None
    p, idx, _ = _arrays.mesh(v, f.astype(np.int32))
    assert idx.dtype == np.uint32
    f32 = f.astype(np.int32)
    _, idx, _ = _arrays.mesh(v, f32)
    assert np.shares_memory(idx, f32)


def test_what_cannot_be_converted_raises_type_error():
    v, f = box()
    with pytest.raises(TypeError):
        polyvol.volume(v.astype(np.complex128), f)
    with pytest.raises(TypeError):
        polyvol.volume(np.array([["a", "b", "c"]] * 8), f)
    with pytest.raises(TypeError):
        polyvol.volume(v, f.astype(np.float64))
    with pytest.raises(TypeError):
        polyvol.volume(np.full((8, 3), 2**60, dtype=np.int64), f)
    with pytest.raises(TypeError):
        polyvol.volume(object())
    if np.finfo(np.longdouble).nmant > 52:
        with pytest.raises(TypeError):
            polyvol.volume(v.astype(np.longdouble) + np.longdouble(1) / 3, f)
    with pytest.raises(ValueError):
        polyvol.volume(v[:, :2], f)
    with pytest.raises(ValueError):
        polyvol.volume(v, f + 8)
    with pytest.raises(ValueError):
        polyvol.volume(v, f - 1)
    with pytest.raises(ValueError):
        polyvol.mass_properties(v, f, method="simpson")


class TrimeshLike:
    """What trimesh.Trimesh offers that polyvol reads: .vertices and .faces."""

    def __init__(self, vertices, faces):
        self.vertices, self.faces = vertices, faces


def test_objects_with_vertices_and_faces_are_meshes():
    v, f = box((0, 0, 0), (1, 2, 3))
    t = TrimeshLike(v, f.astype(np.int64))
    assert polyvol.volume(t) == 6.0
    assert polyvol.check(t).closed
    assert polyvol.grid(t, dims=(2, 2, 3), bounds=(0, 0, 0, 1, 2, 3)).volumes.sum() == 6.0
    m = polyvol.Mesh(t.vertices, t.faces)
    assert m.format == "unknown" and polyvol.volume(m) == 6.0


def test_polygon_faces():
    # the unit cube with quads, and as a ragged list (a triangle-fanned quad is two triangles)
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    quads = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
    assert polyvol.volume(v, quads) == 1.0
    ragged = [list(q) for q in quads[:5]] + [[3, 0, 4], [3, 4, 7]]
    assert polyvol.volume(v, ragged) == 1.0
    m = polyvol.Mesh(v, quads)
    assert not m.is_triangle_mesh and m.face_offsets.tolist() == [0, 4, 8, 12, 16, 20, 24]
    with pytest.raises(ValueError):
        m.faces
    assert polyvol.mass_properties(m).edge_length == 12.0


def test_open_and_misoriented_surfaces_are_reported():
    v, f = box()
    t = polyvol.check(v, f[:-1])
    assert not t.closed and t.boundary_edges == 3 and t.unbalanced_example is not None
    flipped = f.copy()
    flipped[0] = flipped[0][::-1]
    t = polyvol.check(v, flipped)
    assert t.misoriented_edges == 3 and not t.closed


def test_overlapping_shells_and_booleans():
    a, b = box((0, 0, 0), (2, 2, 2)), box((1, 1, 1), (3, 3, 3))
    both = np.vstack([a[0], b[0]]), np.vstack([a[1], b[1] + 8])
    assert polyvol.volume(*both) == 15.0  # the solid, as `polyvol volume` gives it
    assert polyvol.mass_properties(*both, solid=False).volume == 16.0  # the shells' sum
    s = polyvol.solid(*both)
    assert (s.volume, s.winding_volume, s.overlapping_shells) == (15.0, 16.0, 2)
    assert s.crossing_pairs > 0
    assert np.allclose(s.centroid, [1.5, 1.5, 1.5])
    r = polyvol.overlap(a, b)
    assert (r.intersection, r.union, r.a_minus_b, r.b_minus_a) == (1.0, 15.0, 7.0, 7.0)
    assert r.to_dict()["accuracy"] == "correctly-rounded"
    with pytest.raises(ValueError):
        polyvol.overlap((a[0], a[1][:-1]), b)
    assert polyvol.self_crossings(*both).pairs == 0


def test_a_shell_crossing_itself_is_resolved():
    # tests/data/self_crossing: two spheres joined by a tube through both (one
    # shell), and the same 2-chain as three shells: one solid.
    data = pathlib.Path(__file__).resolve().parents[1] / "data" / "self_crossing"
    one, three = polyvol.load(data / "one.obj"), polyvol.load(data / "three.obj")
    s, t = polyvol.solid(one), polyvol.solid(three)
    assert s.self_crossing_checked and s.self_crossing_pairs == 88 and s.shells_crossing_themselves == 1
    assert (s.volume, s.winding_volume) == (t.volume, t.winding_volume)
    assert s.volume < s.winding_volume
    assert np.array_equal(s.second_moments, t.second_moments)
    unresolved = polyvol.solid(one, within_shells=False)
    assert not unresolved.self_crossing_checked and unresolved.volume == unresolved.winding_volume


def test_results_print_and_convert_to_plain_dicts():
    v, f = box()
    p = polyvol.mass_properties(v, f)
    assert "volume=1.0" in repr(p)
    d = p.to_dict()
    assert d["centroid"] == [0.5, 0.5, 0.5] and isinstance(d["inertia"][0][0], float)
    assert polyvol.check(v, f).to_dict()["shells"][0]["role"] == "solid"


def test_orient_winds_flipped_faces_back_and_turns_shells_outward(tmp_path):
    v, f = uv_sphere(10, 20)
    want = polyvol.volume(v, f)
    bad = f.copy()
    bad[[3, 40, 77]] = bad[[3, 40, 77]][:, ::-1]
    assert polyvol.check(v, bad).misoriented_edges == 9
    m, o = polyvol.orient(v, bad)
    assert (o.faces_flipped, o.undecided) == (3, 0)
    assert polyvol.volume(m) == want and polyvol.check(m).closed
    m, o = polyvol.orient(v, f[:, ::-1].copy())  # inside out
    assert o.faces_flipped == len(f) and polyvol.volume(m) == want
    path = tmp_path / "flipped.off"
    path.write_text(f"OFF\n{len(v)} {len(bad)} 0\n" + "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in bad))
    assert polyvol.measure_file(path)["exit_code"] == 3
    report = polyvol.measure_file(path, orient=True)
    assert report["oriented_faces_flipped"] == 3 and report["volume"] == want


def test_measure_file_welds_within_a_tolerance():
    data = pathlib.Path(__file__).resolve().parents[1] / "data" / "weld"
    assert polyvol.measure_file(data / "near_box.obj")["exit_code"] == 3
    report = polyvol.measure_file(data / "near_box.obj", weld_tolerance=1e-12)
    assert report["welded_points_moved"] == 16
    assert report["volume"] == polyvol.measure_file(data / "box.obj")["volume"]


def test_measure_file_converts_units():
    data = pathlib.Path(__file__).resolve().parents[1] / "data" / "units"
    inch = polyvol.measure_file(data / "tetra_inch.3mf")
    assert inch["unit"] == "in" and inch["volume"] == 4 / 3
    mm = polyvol.measure_file(data / "tetra_inch.3mf", to="mm")
    assert mm["unit"] == "mm" and mm["length_factor"] == 25.4
    assert abs(mm["volume"] - 4 / 3 * 16387.064) <= mm["volume_error_bound"] + 1e-11
    with pytest.raises(ValueError):
        polyvol.measure_file(data / "tetra_inch.3mf", to="furlong")


def test_check_gives_no_origin_dependent_volume_for_an_open_shell():
    v, f = box()
    t = polyvol.check(v, f[:-1])
    assert t.shells[0].role == "open" and t.shells[0].signed_volume is None
    assert not t.ready and t.repairs[0].startswith("not closed: 3 unbalanced edges")


def test_a_directory_or_an_unknown_file_names_every_format_read(tmp_path):
    with pytest.raises(polyvol.ReadError, match=r"a directory, not a mesh file\. polyvol reads STL, .*glTF.*bzip2.*tar"):
        polyvol.load(tmp_path)
    (tmp_path / "notes.xyz").write_text("hello\n")
    with pytest.raises(polyvol.ReadError, match=r"unrecognised content .*polyvol reads STL, .*glTF"):
        polyvol.load(tmp_path / "notes.xyz")
    r = subprocess.run([CLI, "volume", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 2 and "a directory, not a mesh file" in r.stderr


def test_the_solids_area_where_shells_overlap():
    # Two boxes overlapping in [0.5, 2] x [0.25, 2] x [0.75, 2]: each loses
    # its three faces' parts inside the other, 2.1875 + 1.875 + 2.625.
    a, b = box((0, 0, 0), (2, 2, 2)), box((0.5, 0.25, 0.75), (2.5, 2.25, 2.75))
    both = np.vstack([a[0], b[0]]), np.vstack([a[1], b[1] + 8])
    p = polyvol.mass_properties(*both)
    assert p.volume == 16 - 1.5 * 1.75 * 1.25
    assert abs(p.area - 34.625) <= p.area * p.area_relative_error and p.area_relative_error < 1e-12
    assert polyvol.mass_properties(*both, solid=False).area == 48.0  # the shells' sum
    r = polyvol.overlap(both, box((-1, -1, -1), (4, 4, 4)))
    assert abs(r.area_a - 34.625) <= r.area_error_bound and abs(r.area_intersection - 34.625) <= r.area_error_bound
    assert abs(r.area_b - 150) <= r.area_error_bound and np.isnan(r.area_a_minus_b)
