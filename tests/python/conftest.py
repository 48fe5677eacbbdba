"""Shared fixtures of the Python tests: the corpus manifest, the CLI and
small generated meshes. ctest sets PYTHONPATH to the built package and the
POLYVOL_* variables (python/CMakeLists.txt)."""

import json
import os
import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORPUS = pathlib.Path(os.environ.get("POLYVOL_CORPUS_DIR", ROOT.parent / "shared" / "corpus"))

CLI = os.environ.get("POLYVOL_CLI", str(ROOT / "build" / "polyvol"))

def manifest():
    path = CORPUS / "manifest.json"
    if not path.exists():
        raise RuntimeError(f"the corpus is missing: {path} (set POLYVOL_CORPUS_DIR)")
    return json.loads(path.read_text())

def box(lo=(0.0, 0.0, 0.0), hi=(1.0, 1.0, 1.0)):
    """An axis-aligned box as 8 vertices and 12 outward triangles."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], dtype=np.float64)
    f = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                  [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]], dtype=np.uint32)
    return v, f

def uv_sphere(rings=32, segments=64, r=1.0, centre=(0.0, 0.0, 0.0)):
    """A closed, outward UV sphere (poles shared)."""
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                     np.repeat(np.cos(theta)[:, None], segments, axis=1)], axis=-1).reshape(-1, 3)
    v = np.vstack([[0, 0, 1], ring, [0, 0, -1]]) * r + np.asarray(centre)
    south = len(v) - 1
    f = []
    for s in range(segments):
        t = (s + 1) % segments
        f.append([0, 1 + s, 1 + t])
        for k in range(rings - 2):
            a, b = 1 + k * segments, 1 + (k + 1) * segments
            f.append([a + s, b + s, b + t])
            f.append([a + s, b + t, a + t])
        last = 1 + (rings - 2) * segments
        f.append([south, last + t, last + s])
    return v, np.array(f, dtype=np.uint32)

@pytest.fixture(scope="session")
def corpus():
    return manifest()


def write_polymesh(case, lo=-1.0, hi=1.0, n=2):
    """An OpenFOAM case (CASE/constant/polyMesh, ASCII) of n^3 cubic cells
    over [lo, hi]^3: internal faces first, each pointing out of its owner."""
    mesh = pathlib.Path(case) / "constant" / "polyMesh"
    mesh.mkdir(parents=True, exist_ok=True)
    x = [lo + (hi - lo) * i / n for i in range(n + 1)]
    p = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)
    c = lambda i, j, k: i + n * (j + n * k)
    # The face at plane `at` of `axis` through the cell (i, j, k) corner, normal +axis.
    def plus(axis, i, j, k):
        if axis == 0:
            return [p(i, j, k), p(i, j + 1, k), p(i, j + 1, k + 1), p(i, j, k + 1)]
        if axis == 1:
            return [p(i, j, k), p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j, k)]
        return [p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k)]
    faces, owner, neighbour, boundary = [], [], [], []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                for axis, (di, dj, dk) in enumerate(((1, 0, 0), (0, 1, 0), (0, 0, 1))):
                    if (i + di, j + dj, k + dk)[axis] < n:
                        faces.append(plus(axis, i + di, j + dj, k + dk))
                        owner.append(c(i, j, k))
                        neighbour.append(c(i + di, j + dj, k + dk))
                    if (i, j, k)[axis] == 0:
                        boundary.append((plus(axis, i, j, k)[::-1], c(i, j, k)))
                    if (i + di, j + dj, k + dk)[axis] == n:
                        boundary.append((plus(axis, i + di, j + dj, k + dk), c(i, j, k)))
    faces += [f for f, _ in boundary]
    owner += [o for _, o in boundary]

    def write(name, cls, items):
        (mesh / name).write_text("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class " + cls +
                                 ";\n    object " + name + ";\n}\n" + f"{len(items)}\n(\n" +
                                 "".join(f"{it}\n" for it in items) + ")\n")
    write("points", "vectorField", [f"({x[i]!r} {x[j]!r} {x[k]!r})" for k in range(n + 1) for j in range(n + 1)
                                    for i in range(n + 1)])
    write("faces", "faceList", ["4(" + " ".join(map(str, f)) + ")" for f in faces])
    write("owner", "labelList", owner)
    write("neighbour", "labelList", neighbour)
    (mesh / "boundary").write_text("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class polyBoundaryMesh;\n"
                                   "    object boundary;\n}\n1\n(\n    walls\n    {\n        type wall;\n"
                                   f"        nFaces {len(boundary)};\n        startFace {len(faces) - len(boundary)};\n"
                                   "    }\n)\n")
    return pathlib.Path(case)


def require_opencl_device():
    """Skip (POLYVOL_TEST_ALLOW_NO_DEVICE=1: the sanitizer builds) or fail
    (elsewhere: the README installs pocl) unless an OpenCL device is usable."""
    import polyvol
    listed = polyvol.devices()
    if not any(d["usable"] for d in listed["devices"]):
        if os.environ.get("POLYVOL_TEST_ALLOW_NO_DEVICE") == "1":
            pytest.skip("no usable OpenCL device")
        pytest.fail("no usable OpenCL device (install pocl-opencl-icd): " + listed["note"])
