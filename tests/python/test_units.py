"""Units in Python (#33 items 9 and 10), as the command line takes them:
densities with units ('2700kg/m3', '1.24g/cm3') and mass_unit, units=/to=
on mass_properties, volume, overlap and grid, a Mesh's declared unit, and
the principal axes and bounds on MassProperties. Each converted figure
carries a bound that holds; the figures agree with `polyvol measure --json`."""
import json
import pathlib
import subprocess
import warnings

import numpy as np
import pytest

import polyvol
from conftest import CLI

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "units"
INCH_3MF = DATA / "tetra_inch.3mf"    # corner tetrahedron of side 2, unit="inch": 4/3 in³
METER_AMF = DATA / "tetra_meter.amf"  # the same, unit="meter"


def box(size, lo=(0.0, 0.0, 0.0)):
    """An axis-aligned box as vertices and outward triangles."""
    (a, b, c), (x, y, z) = size, lo
    v = np.array([(x + a * (i & 1), y + b * ((i >> 1) & 1), z + c * ((i >> 2) & 1)) for i in range(8)], float)
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = np.array([t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))], np.uint32)
    return v, f


def test_density_with_a_unit_gives_kilograms_grams_pounds():
    v, f = box((20.0, 20.0, 20.0))  # 20 mm cube: 8e-6 m³
    kg = polyvol.mass_properties(v, f, density="2700kg/m3", units="mm")
    assert (kg.unit, kg.mass_unit) == ("m", "kg")
    assert abs(kg.volume - 8e-6) <= kg.volume_error_bound
    assert kg.mass == pytest.approx(0.0216, rel=1e-14)
    g = polyvol.mass_properties(v, f, density="1.24g/cm3", units="mm", to="mm", mass_unit="g")
    assert (g.unit, g.mass_unit) == ("mm", "g")
    assert g.mass == pytest.approx(9.92, rel=1e-14)  # 8 cm³ of PLA
    assert g.volume == 8000
    lb = polyvol.mass_properties(v, f, density="2700kg/m3", units="mm", mass_unit="lb")
    assert lb.mass == pytest.approx(0.0216 / 0.45359237, rel=1e-14)
    plain = polyvol.mass_properties(v, f, density=2.0)  # mass per unit³: no unit known or needed
    assert (plain.unit, plain.mass_unit, plain.mass) == (None, None, 16000.0)


def test_bad_units_are_refused_with_the_fix():
    v, f = box((1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="its length unit is not known.*units= gives it"):
        polyvol.mass_properties(v, f, density="2700kg/m3")
    with pytest.raises(ValueError, match="needs a density with a unit"):
        polyvol.mass_properties(v, f, mass_unit="g")
    with pytest.raises(ValueError, match="positive number, optionally with kg/m3"):
        polyvol.mass_properties(v, f, density="7850kg/l")
    with pytest.raises(ValueError, match="unknown unit furlong"):
        polyvol.volume(v, f, units="furlong")


def test_volume_in_another_unit_has_a_true_bound():
    v, f = box((0.3, 0.3, 0.3))
    cm = polyvol.mass_properties(v, f, units="mm", to="cm")
    assert cm.accuracy == "error-bound" and cm.length_factor == 0.1
    assert abs(cm.volume - 0.027e-3) <= cm.volume_error_bound < 1e-18
    assert polyvol.volume(v, f, units="mm", to="cm") == cm.volume
    same = polyvol.mass_properties(v, f, units="mm")  # nothing to convert
    assert same.accuracy == "correctly-rounded" and same.unit == "mm"


def test_declared_unit_of_a_file_and_agreement_with_the_cli():
    mesh = polyvol.load(INCH_3MF)
    assert mesh.unit == "in" and mesh.coordinate_error == 0
    mm = polyvol.mass_properties(mesh, to="mm")
    exact = 4 / 3 * 16387.064
    assert mm.unit == "mm" and abs(mm.volume - exact) <= mm.volume_error_bound * (1 + 1e-9) + 1e-12
    cli = json.loads(subprocess.run([CLI, "measure", "--json", "--to", "mm", str(INCH_3MF)], capture_output=True,
                                    text=True, check=True).stdout)[0]
    for key in ("volume", "volume_error_bound", "area", "length_factor"):
        assert getattr(mm, key) == cli[key], key
    assert list(mm.centroid) == cli["centroid"]
    assert list(mm.bounds) == cli["bounds"]
    assert np.array_equal(mm.principal_moments, cli["principal_moments"])
    assert np.array_equal(mm.principal_axes, cli["principal_axes"])
    assert mm.principal_moment_error == cli["principal_moment_error"]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        polyvol.volume(mesh, units="mm")
    assert any("declares its unit as in; mm is used instead" in str(w.message) for w in caught)


def test_principal_axes_and_bounds_of_a_box():
    v, f = box((1.0, 2.0, 3.0), lo=(1.0, 1.0, 1.0))  # mass 6 at density 1
    p = polyvol.mass_properties(v, f)
    # moments m (b² + c²)/12 about the centroid, increasing: about z, y, x
    assert p.principal_moments == pytest.approx([6 * 5 / 12, 6 * 10 / 12, 6 * 13 / 12], rel=1e-15)
    assert np.abs(p.principal_axes) == pytest.approx(np.array([[0, 0, 1], [0, 1, 0], [1, 0, 0]]), abs=1e-15)
    assert np.linalg.det(p.principal_axes) == pytest.approx(1.0)  # right-handed
    exact = np.array([6 * 5 / 12, 6 * 10 / 12, 6 * 13 / 12])
    assert np.all(np.abs(p.principal_moments - exact) <= p.principal_moment_error)
    assert p.principal_moment_error < 1e-14 * exact.max()
    assert all(a < 1e-13 for a in p.principal_axis_angle_bound)
    assert list(p.bounds) == [1.0, 1.0, 1.0, 2.0, 3.0, 4.0]
    cube = polyvol.mass_properties(*box((1.0, 1.0, 1.0)))
    assert all(a == np.inf for a in cube.principal_axis_angle_bound)  # equal moments: no axis is determined


def test_overlap_in_one_unit():
    a, b = polyvol.load(METER_AMF), polyvol.load(INCH_3MF)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = polyvol.overlap(a, b)  # B converted from in to m
    assert any("converted from in to m" in str(w.message) for w in caught)
    assert r.unit == "m" and r.volume_a == 4 / 3
    inside = 4 / 3 * 0.0254 ** 3
    assert abs(r.volume_b - inside) <= r.volume_error_bound and abs(r.intersection - inside) <= r.volume_error_bound
    mm = polyvol.overlap(b, b, to="mm")
    assert mm.unit == "mm" and mm.accuracy == "error-bound"
    assert abs(mm.union - 4 / 3 * 16387.064) <= mm.volume_error_bound * (1 + 1e-9) + 1e-12
    cli = json.loads(subprocess.run([CLI, "overlap", "--json", "--to", "mm", str(INCH_3MF), str(INCH_3MF)],
                                    capture_output=True, text=True, check=True).stdout)
    for key in ("volume_a", "intersection", "union", "volume_error_bound", "area_a", "area_error_bound"):
        assert getattr(mm, key) == cli[key], key
    v, f = box((1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="A: its length unit is not known"):
        polyvol.overlap((v, f), (v, f), to="mm")
    assert polyvol.overlap((v, f), (v, f), units="cm", to="mm").union == pytest.approx(1000.0, rel=1e-15)


def test_grid_in_one_unit():
    mesh = polyvol.load(INCH_3MF)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        g = polyvol.grid(mesh, cells=4, to="mm")
    assert any("converted from in to mm" in str(w.message) for w in caught)
    assert g.summary["unit"] == "mm"
    assert g.summary["body_volumes"][0] == pytest.approx(4 / 3 * 16387.064, rel=1e-14)
    cli = json.loads(subprocess.run([CLI, "grid", "--json", "--cells", "4", "--to", "mm", str(INCH_3MF)],
                                    capture_output=True, text=True, check=True).stdout)
    assert g.summary["body_volumes"] == cli["body_volumes"]  # the same conversion, the same bits
    assert g.summary["grid"]["bounds"] == cli["grid"]["bounds"]
    assert polyvol.grid(mesh, cells=4).summary["unit"] == "in"
    v, f = box((1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="its length unit is not known"):
        polyvol.grid((v, f), cells=4, to="mm")


def test_dask_grid_in_one_unit_has_the_grids_bits():
    dask_grid = pytest.importorskip("polyvol.dask").grid
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the conversion's note, said by both
        whole = polyvol.grid(polyvol.load(INCH_3MF), cells=8, to="mm")
        blocks = dask_grid(str(INCH_3MF), cells=8, to="mm", chunks=(3, 3, 3)).compute(scheduler="synchronous")
    assert np.array_equal(blocks, whole.volumes)
    assert whole.summary["unit"] == "mm"
