"""The GIL is released while polyvol computes: another Python thread runs
meanwhile, and two threads measuring at once get the results of one."""

import sys
import threading

import pytest

import numpy as np

import polyvol
from conftest import uv_sphere


@pytest.mark.parametrize("call", ["grid", "mass_properties", "check", "load"])
def test_another_python_thread_runs_while_polyvol_computes(call, tmp_path):
    """The main thread starts a long call; a second thread, woken just
    before it, records whether the call had returned when it got to run.
    With the switch interval set to 10 s, a call that held the GIL would
    keep the second thread out until it returned."""
    v, f = uv_sphere(200, 400)
    path = tmp_path / "s.off"
    if call == "load":
        path.write_text(f"OFF\n{len(v)} {len(f)} 0\n" + "".join(f"{a} {b} {c}\n" for a, b, c in v)
                        + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    work = {
        "grid": lambda: polyvol.grid((v, f), dims=(200, 200, 200)),
        "mass_properties": lambda: [polyvol.mass_properties(v, f) for _ in range(20)],
        "check": lambda: polyvol.check(v, f),
        "load": lambda: [polyvol.load(path) for _ in range(5)],
    }[call]
    go, seen = threading.Event(), []
    returned = False

    def watcher():
        go.wait()
        seen.append(returned)

    t = threading.Thread(target=watcher)
    t.start()
    interval = sys.getswitchinterval()
    sys.setswitchinterval(10.0)
    try:
        go.set()
        work()
        returned = True
    finally:
        sys.setswitchinterval(interval)
    t.join()
    assert seen == [False], "the other thread ran only after the call returned"


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
