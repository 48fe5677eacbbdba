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
