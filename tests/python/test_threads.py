"""The GIL is released while polyvol computes: another Python thread runs
meanwhile, and two threads measuring at once get the results of one."""

import threading

import numpy as np

import polyvol
from conftest import uv_sphere


def test_other_python_threads_run_while_polyvol_computes():
    v, f = uv_sphere(60, 120)
    started, done = threading.Event(), threading.Event()
    result = {}

    def work():
        started.set()
        result["grid"] = polyvol.grid((v, f), dims=(160, 160, 160))
        done.set()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    # With the GIL held by the computation this loop could not run until it ends.
    steps = 0
    while not done.is_set():
        steps += 1
    t.join()
    assert result["grid"].volumes.shape == (160, 160, 160)
    assert steps > 1000


def test_two_threads_measuring_at_once_agree_with_one():
    meshes = [uv_sphere(40, 80, r) for r in (1.0, 2.0)]
    alone = [polyvol.mass_properties(*m) for m in meshes]
    out = [None, None]

    def work(k):
        for _ in range(5):
            out[k] = polyvol.mass_properties(*meshes[k])

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, out):
        assert a.volume == b.volume and np.array_equal(a.inertia, b.inertia)
