"""polyvol.dask on a local cluster of two worker processes: the corpus as a
dataframe equals polyvol.measure_file file by file (bad files included, as
rows), and a grid cut into blocks equals the single-machine grid bit for
bit, also written to zarr."""

import math

import numpy as np
import pandas as pd
import pytest

import polyvol
import polyvol.dask as pvd
from conftest import CORPUS, box, manifest, require_opencl_device, uv_sphere

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as c:
        with distributed.Client(c) as cl:
            yield cl


def missing(x):
    return x is None or x is pd.NA or (isinstance(x, float) and math.isnan(x))


def same(got, want):
    """A cell of the dataframe against the JSON value (None: the key is absent or null)."""
    if missing(want):
        return missing(got)
    return got == want


def test_measure_files_over_the_corpus_equals_the_plain_loop(client):
    paths = [str(CORPUS / e["path"]) for e in manifest()]
    frame = pvd.measure_files(paths, files_per_partition=8).compute()
    assert list(frame["file"]) == paths
    for path, (_, row) in zip(paths, frame.iterrows()):
        want = polyvol.measure_file(path)
        assert set(want) <= set(pvd.COLUMNS), set(want) - set(pvd.COLUMNS)
        for key in pvd.COLUMNS:
            got = row[key]
            assert same(got, want.get(key)), (path, key, got, want.get(key))
    assert (frame["exit_code"] == 2).sum() >= 5  # the unreadable files are rows, with their errors
    assert frame.loc[frame["exit_code"] == 2, "error"].str.len().min() > 0
    assert frame["volume"].dtype == np.float64 and str(frame["triangles"].dtype) == "Int64"
    lazy = pvd.measure_files(paths[:20], files_per_partition=8)
    assert lazy["volume"].dtype == np.float64  # the meta's types: numeric operations work lazily
    assert lazy[lazy.exit_code == 0]["volume"].sum().compute() == pytest.approx(
        sum(polyvol.measure_file(p).get("volume") or 0 for p in paths[:20]), rel=1e-12)


def test_grid_blocks_on_workers_equal_the_whole_grid(client, tmp_path):
    s = uv_sphere(24, 48, 1.0, (0.02, -0.01, 0.03))
    whole = polyvol.grid(s, dims=(37, 29, 31), moments=True)
    a = pvd.grid(s, dims=(37, 29, 31), chunks=(16, 10, 8))
    assert a.shape == (37, 29, 31) and a.chunks[0] == (16, 16, 5)
    assert np.array_equal(a.compute(), whole.volumes)
    m = pvd.grid(s, dims=(37, 29, 31), chunks=(16, 10, 8), what="first_moments").compute()
    assert np.array_equal(m, whole.first_moments)
    f = pvd.grid(s, dims=(37, 29, 31), chunks=(16, 10, 8), what="fractions").compute()
    assert np.array_equal(f, whole.fractions) and f.min() >= 0 and f.max() <= 1
    a.to_zarr(str(tmp_path / "g.zarr"))
    import zarr
    assert np.array_equal(zarr.open(str(tmp_path / "g.zarr"))[:], whole.volumes)


def test_grid_blocks_on_an_opencl_device_equal_the_cpus(client):
    require_opencl_device()
    s = uv_sphere(16, 32, 1.0, (0.02, -0.01, 0.03))
    whole = polyvol.grid(s, dims=(21, 19, 17), device="cpu")
    a = pvd.grid(s, dims=(21, 19, 17), chunks=(8, 10, 8), device="opencl").compute()
    assert a.tobytes() == whole.volumes.tobytes()
    with pytest.raises(polyvol.DeviceError, match="no OpenCL device 99"):  # the blocks take the device asked for
        pvd.grid(s, dims=(21, 19, 17), chunks=(8, 10, 8), device="opencl:99").compute()


def test_grid_from_a_path_and_of_several_bodies(client, tmp_path):
    v, f = box((0.1, 0.2, 0.3), (0.9, 1.7, 1.1))
    path = tmp_path / "box.off"
    path.write_text("OFF\n8 12 0\n" + "".join(f"{a!r} {b!r} {c!r}\n" for a, b, c in v)
                    + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    whole = polyvol.grid(polyvol.load(path), dims=(9, 11, 7))
    assert np.array_equal(pvd.grid(str(path), dims=(9, 11, 7), chunks=(4, 4, 4)).compute(), whole.volumes)
    t = uv_sphere(12, 24, 0.6, (0.8, 1.0, 0.9))
    both = polyvol.grid([(v, f), t], dims=(9, 11, 7), intersection=True)
    got = pvd.grid([(v, f), t], dims=(9, 11, 7), chunks=(5, 4, 3), what="volumes").compute()
    assert got.shape == (2, 9, 11, 7) and np.array_equal(got, both.volumes)
    for what in ("union", "intersection"):
        got = pvd.grid([(v, f), t], dims=(9, 11, 7), chunks=(5, 4, 3), what=what, intersection=True).compute()
        assert np.array_equal(got, getattr(both, what)), what
