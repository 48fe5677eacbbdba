#!/usr/bin/env python3
"""The Python package against its peers, in paired rounds (docs/benchmarks.md,
"Python"):

* polyvol.volume and polyvol.mass_properties on a numpy mesh of about 1M
  triangles (a UV sphere, float64, uint32 faces) against the numpy einsum
  formula trimesh uses (trimesh.triangles.mass_properties: cross products of
  the edges dotted with the corners, summed; trimesh is not installable
  here, so its formula is written out below);
* polyvol.dask.measure_files over the shared corpus on a LocalCluster of 2
  worker processes against a plain loop of polyvol.measure_file.

Each round runs every contender once, in rotating order; medians and the
per-round ratios' medians are printed, with the CPU and its vector ISA.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py [--rounds 7] [--corpus ../shared/corpus]
"""
import argparse
import json
import pathlib
import statistics
import time

import numpy as np

import polyvol
import polyvol.dask


def cpu():
    info = pathlib.Path("/proc/cpuinfo").read_text()
    name = next((l.split(":", 1)[1].strip() for l in info.splitlines() if l.startswith("model name")), "?")
    flags = next((l.split(":", 1)[1].split() for l in info.splitlines() if l.startswith("flags")), [])
    isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "SSE"
    return f"{name}, {isa}, {len([l for l in info.splitlines() if l.startswith('processor')])} cores"


def sphere(rings, segments):
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                     np.repeat(np.cos(theta)[:, None], segments, axis=1)], axis=-1).reshape(-1, 3)
    v = np.vstack([[0, 0, 1], ring, [0, 0, -1]])
    s = np.arange(segments)
    t = (s + 1) % segments
    faces = [np.stack([np.zeros(segments, int), 1 + s, 1 + t], axis=1)]
    for k in range(rings - 2):
        a, b = 1 + k * segments, 1 + (k + 1) * segments
        faces.append(np.stack([a + s, b + s, b + t], axis=1))
        faces.append(np.stack([a + s, b + t, a + t], axis=1))
    last = 1 + (rings - 2) * segments
    faces.append(np.stack([np.full(segments, len(v) - 1), last + t, last + s], axis=1))
    return v, np.vstack(faces).astype(np.uint32)


def einsum_volume(v, f):
    """trimesh's formula: Σ (p0 · (p1 - p0) × (p2 - p0)) / 6, in numpy."""
    t = v[f]
    cross = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    return np.einsum("ij,ij->", cross, t[:, 0]) / 6.0


def einsum_mass_properties(v, f):
    """trimesh.triangles.mass_properties' integrals (volume, first and second
    moments) written out in numpy, as trimesh computes them."""
    t = v[f]
    p0, p1, p2 = t[:, 0], t[:, 1], t[:, 2]
    cross = np.cross(p1 - p0, p2 - p0)
    f1 = p0 + p1 + p2
    f2 = p0 * p0 + p1 * p1 + p0 * p1 + p2 * f1
    f3 = p0 * p0 * p0 + p0 * p0 * p1 + p0 * p1 * p1 + p1 * p1 * p1 + p2 * f2
    g0, g1, g2 = f2 + p0 * (f1 + p0), f2 + p1 * (f1 + p1), f2 + p2 * (f1 + p2)
    integral = np.zeros((10, len(f)))
    integral[0] = cross[:, 0] * f1[:, 0]
    integral[1:4] = (cross * f2).T
    integral[4:7] = (cross * f3).T
    for i in range(3):
        j = (i + 1) % 3
        integral[i + 7] = cross[:, i] * (p0[:, j] * g0[:, i] + p1[:, j] * g1[:, i] + p2[:, j] * g2[:, i])
    s = integral.sum(axis=1) * np.array([1 / 6, 1 / 24, 1 / 24, 1 / 24, 1 / 60, 1 / 60, 1 / 60, 1 / 120, 1 / 120, 1 / 120])
    volume = s[0]
    centroid = s[1:4] / volume
    return volume, centroid


def rounds(contenders, n):
    times = {name: [] for name in contenders}
    names = list(contenders)
    for r in range(n):
        order = names[r % len(names):] + names[:r % len(names)]
        for name in order:
            t0 = time.perf_counter()
            contenders[name]()
            times[name].append(time.perf_counter() - t0)
    return times


def report(times, base):
    for name, ts in times.items():
        ratio = statistics.median(b / t for b, t in zip(times[base], ts)) if name != base else 1.0
        print(f"  {name:34s} median {statistics.median(ts) * 1e3:9.1f} ms   {base} / this, median per round: {ratio:5.2f}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--corpus", default=str(pathlib.Path(__file__).resolve().parents[2] / "shared" / "corpus"))
    a = ap.parse_args()
    print("CPU:", cpu())

    v, f = sphere(708, 708)
    print(f"numpy mesh: {len(v)} vertices, {len(f)} triangles")
    exact, plain = polyvol.volume(v, f), einsum_volume(v, f)
    print(f"volume: polyvol {exact!r} (correctly rounded), einsum {plain!r} (relative difference {abs(plain - exact) / exact:.1e})")
    times = rounds({
        "numpy einsum volume (trimesh)": lambda: einsum_volume(v, f),
        "polyvol.volume": lambda: polyvol.volume(v, f),
        "polyvol.volume, accuracy=fast": lambda: polyvol.volume(v, f, accuracy="fast"),
    }, a.rounds)
    report(times, "numpy einsum volume (trimesh)")
    times = rounds({
        "numpy mass properties (trimesh)": lambda: einsum_mass_properties(v, f),
        "polyvol.mass_properties": lambda: polyvol.mass_properties(v, f, edge_length=False),
    }, a.rounds)
    report(times, "numpy mass properties (trimesh)")


    from dask.distributed import Client, LocalCluster
    corpus = pathlib.Path(a.corpus)
    paths = [str(corpus / e["path"]) for e in json.loads((corpus / "manifest.json").read_text())]
    print(f"corpus: {len(paths)} files")
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster):
        polyvol.dask.measure_files(paths[:4]).compute()  # workers warm
        times = rounds({
            "plain loop of measure_file": lambda: [polyvol.measure_file(p) for p in paths],
            "dask.measure_files, 2 workers": lambda: polyvol.dask.measure_files(paths, files_per_partition=4).compute(),
        }, max(3, a.rounds // 2))
    report(times, "plain loop of measure_file")


if __name__ == "__main__":
    main()
