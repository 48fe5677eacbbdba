"""The library measures a file (polyvol/report.hpp, #35): Python's
measure_file is the library's report under the keys report_json declares,
the same dict `polyvol measure --json` prints (no JSON text in between), its
keys also attributes; densities with units as the CLI takes them; and the
package's namespace holds only its API."""
import json
import pathlib
import subprocess

import pytest

import polyvol
from conftest import CLI

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"
FILES = [DATA / "units" / "tetra_inch.3mf", DATA / "weld" / "box.obj"]


def cli_report(*args):
    out = subprocess.run([CLI, "measure", "--json", *map(str, args)], capture_output=True, text=True)
    return json.loads(out.stdout)[0]


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_measure_file_is_the_cli_report_key_for_key(path):
    r = polyvol.measure_file(path)
    assert isinstance(r, dict) and isinstance(r, polyvol.FileReport)
    cli = cli_report(path)
    assert r.keys() == cli.keys()
    for key in cli:
        assert r[key] == cli[key], key
    assert r.volume == r["volume"] and r.exit_code == 0
    with pytest.raises(AttributeError):
        r.no_such_key


def test_density_with_a_unit_and_mass_unit():
    box = DATA / "weld" / "box.obj"  # [0, 0.3]^3
    r = polyvol.measure_file(box, units="mm", density="1.24g/cm3", to="mm", mass_unit="g")
    cli = cli_report(box, "--units", "mm", "--density", "1.24g/cm3", "--to", "mm", "--mass-unit", "g")
    assert (r.unit, r.mass_unit) == ("mm", "g")
    assert r.mass == cli["mass"] == pytest.approx(0.027 * 1.24e-3, rel=1e-14)
    with pytest.raises(ValueError, match="needs a density with a unit"):
        polyvol.measure_file(box, mass_unit="g")
    with pytest.raises(ValueError, match="kg/m3 or g/cm3"):
        polyvol.measure_file(box, density="3 stone")


def test_errors_are_fields():
    r = polyvol.measure_file(DATA / "no_such_file.stl")
    assert r.exit_code == 2 and "no_such_file" in r.error


def test_the_namespace_holds_only_the_api():
    public = {n for n in dir(polyvol) if not n.startswith("_")}
    assert not public & {"np", "os", "math", "warnings", "json"}, public & {"np", "os", "math", "warnings"}
