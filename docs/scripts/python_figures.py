#!/usr/bin/env python3
"""The two figures of docs/python.md, made through the Python package.

* docs/python_grid_slice.png: the union's volume fraction per cell in the
  slice z = 0 of two overlapping spheres, exact in every cell (contact cells
  included), next to the cells' classes;
* docs/python_implicit_convergence.png: the error of the unit ball's volume
  against the lattice spacing h, for the PL volume V(h), the Richardson
  extrapolation and its error estimate (F a Python function called on many
  points at once).

    PYTHONPATH=build/python /usr/bin/python3 docs/scripts/python_figures.py

Needs python3-matplotlib and python3-numpy (Debian).
"""
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import polyvol  # noqa: E402

DOCS = pathlib.Path(__file__).resolve().parents[1]


def uv_sphere(rings, segments, r, centre):
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                     np.repeat(np.cos(theta)[:, None], segments, axis=1)], axis=-1).reshape(-1, 3)
    v = np.vstack([[0, 0, 1], ring, [0, 0, -1]]) * r + np.asarray(centre)
    south, f = len(v) - 1, []
    for s in range(segments):
        t = (s + 1) % segments
        f.append([0, 1 + s, 1 + t])
        for k in range(rings - 2):
            a, b = 1 + k * segments, 1 + (k + 1) * segments
            f += [[a + s, b + s, b + t], [a + s, b + t, a + t]]
        last = 1 + (rings - 2) * segments
        f.append([south, last + t, last + s])
    return v, np.array(f)


def grid_slice():
    a = uv_sphere(48, 96, 1.0, (0.0, 0.0, 0.0))
    b = uv_sphere(48, 96, 0.8, (1.1, 0.35, 0.0))
    g = polyvol.grid([a, b], dims=(48, 36, 33), bounds=(-1.2, -1.2, -1.05, 2.0, 1.2, 1.05))
    k = g.shape[2] // 2
    fraction = (g.union / g.cell_volumes)[:, :, k].T
    x, y, _ = g.edges
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    im = axes[0].pcolormesh(x, y, fraction, cmap="viridis", vmin=0, vmax=1)
    axes[0].set_title("union volume fraction, slice k = %d" % k)
    fig.colorbar(im, ax=axes[0])
    classes = g.cell_class[:, :, k].T
    cmap = matplotlib.colors.ListedColormap(["#f2f2f2", "#4c72b0", "#dd8452", "#c44e52"])
    axes[1].pcolormesh(x, y, classes, cmap=cmap, vmin=-0.5, vmax=3.5)
    axes[1].set_title("cells: empty, full, cut (one surface), contact (two)")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.savefig(DOCS / "python_grid_slice.png", dpi=90)
    exact = polyvol.overlap(a, b).union
    print(f"grid slice: union over the cells {g.summary['union_volume']!r}, overlap's exact union {exact!r}, "
          f"contact cells {g.summary['contact_cells']}")


def implicit_convergence():
    ball = 4 / 3 * math.pi
    hs, pl, extrapolated, estimate = [], [], [], []
    for cells in (8, 12, 16, 24, 32, 48, 64, 96, 128):
        h = 3.0 / cells
        r = polyvol.implicit(lambda p: (p * p).sum(axis=1) - 1.0, 3, (-1.5, 1.5), h=h)
        hs.append(h)
        pl.append(abs(r.volume_pl - ball))
        extrapolated.append(abs(r.volume - ball))
        estimate.append(r.error_estimate)
    fig, ax = plt.subplots(figsize=(6, 4.2), constrained_layout=True)
    ax.loglog(hs, pl, "o-", label="|V(h) - V|, the PL solid")
    ax.loglog(hs, extrapolated, "s-", label="|Richardson - V|")
    ax.loglog(hs, estimate, "^--", label="error_estimate")
    ax.set_xlabel("lattice spacing h")
    ax.set_ylabel("error of the unit ball's volume")
    ax.legend()
    fig.savefig(DOCS / "python_implicit_convergence.png", dpi=90)
    slope = np.polyfit(np.log(hs), np.log(pl), 1)[0]
    print(f"implicit: slope of the PL error {slope:.2f}; at h = {hs[-1]}: PL {pl[-1]:.2e}, "
          f"extrapolated {extrapolated[-1]:.2e}, estimate {estimate[-1]:.2e}")


if __name__ == "__main__":
    grid_slice()
    implicit_convergence()
