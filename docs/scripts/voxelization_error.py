#!/usr/bin/python3
"""How a binary voxelization errs against the exact cell volumes.

For one closed mesh and a range of grid resolutions, runs
`polyvol grid MESH --cells N -o exact.npy --json` (the exact volume of the
solid in every cell) and, independently, a binary voxelization of the same
grid: a cell counts as full when its centre is inside the mesh (parity of the
crossings of a ray from the centre along +z). Prints a Markdown table and
draws docs/voxelization_error.png:

  * misclassified volume: sum over cells of |binary - exact| * cell volume,
    relative to the mesh volume (what a per-cell field gets wrong);
  * total volume error: |sum(binary) - sum(exact)| relative to the mesh volume
    (what a volume estimate gets wrong; errors of both signs partly cancel).

Needs Debian's python3-numpy and python3-matplotlib. Usage (from the repo):
  docs/scripts/voxelization_error.py [--polyvol build/polyvol]
      [--mesh ../shared/corpus/meshes/prusa-slicer/torus.stl] [--out docs/voxelization_error.png]
The mesh must be a binary STL (read here with numpy, so no polyvol code is
involved in the binary voxelization).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_binary_stl(path):
    data = open(path, "rb").read()
    n = int.from_bytes(data[80:84], "little")
    if len(data) != 84 + 50 * n:
        sys.exit(f"{path}: not a binary STL")
    rec = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), count=n)
    return rec["v"].astype(np.float64)  # (n, 3, 3)


def centre_inside(tris, x, y, z):
    """inside[i, j, k] for the cell centres (x[i], y[j], z[k]): odd number of
    triangles crossed by the ray from the centre towards +z."""
    xc = 0.5 * (x[:-1] + x[1:])
    yc = 0.5 * (y[:-1] + y[1:])
    zc = 0.5 * (z[:-1] + z[1:])
    count = np.zeros((len(xc), len(yc), len(zc)), dtype=np.int32)
    for t in tris:
        a, b, c = t
        det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if det == 0:
            continue  # vertical in projection: the ray grazes it
        lo, hi = t[:, :2].min(axis=0), t[:, :2].max(axis=0)
        i0, i1 = np.searchsorted(xc, lo[0]), np.searchsorted(xc, hi[0], side="right")
        j0, j1 = np.searchsorted(yc, lo[1]), np.searchsorted(yc, hi[1], side="right")
        if i0 >= i1 or j0 >= j1:
            continue
        px, py = np.meshgrid(xc[i0:i1], yc[j0:j1], indexing="ij")
        # barycentric coordinates of the column centre in the projected triangle
        l1 = ((px - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (py - a[1])) / det
        l2 = ((b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1])) / det
        l0 = 1 - l1 - l2
        hit = (l0 >= 0) & (l1 > 0) & (l2 > 0) | (l0 > 0) & (l1 >= 0) & (l2 > 0) | (l0 > 0) & (l1 > 0) & (l2 >= 0)
        if not hit.any():
            continue
        zh = l0 * a[2] + l1 * b[2] + l2 * c[2]
        ii, jj = np.nonzero(hit)
        above = zc[None, :] < zh[ii, jj][:, None]  # centres below the crossing
        np.add.at(count, (ii + i0, jj + j0), above.astype(np.int32))
    return (count % 2) == 1


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.dirname(os.path.dirname(here))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--polyvol", default=os.path.join(repo, "build", "polyvol"))
    ap.add_argument("--mesh", default=os.path.join(repo, "..", "shared", "corpus", "meshes", "prusa-slicer", "torus.stl"))
    ap.add_argument("--out", default=os.path.join(repo, "docs", "voxelization_error.png"))
    ap.add_argument("--cells", default="8,12,16,24,32,48,64,96,128,192,256")
    args = ap.parse_args()

    tris = read_binary_stl(args.mesh)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in [int(s) for s in args.cells.split(",")]:
            npy = os.path.join(tmp, f"exact{n}.npy")
            out = subprocess.run([args.polyvol, "grid", args.mesh, "--cells", str(n), "-o", npy, "--json"],
                                 check=True, capture_output=True, text=True).stdout
            summary = json.loads(out)
            dims, b = summary["grid"]["dims"], summary["grid"]["bounds"]
            x = np.linspace(b[0], b[3], dims[0] + 1)
            y = np.linspace(b[1], b[4], dims[1] + 1)
            z = np.linspace(b[2], b[5], dims[2] + 1)
            exact = np.load(npy)
            cell = np.diff(x)[:, None, None] * np.diff(y)[None, :, None] * np.diff(z)[None, None, :]
            binary = np.where(centre_inside(tris, x, y, z), cell, 0.0)
            volume = summary["bodies"][0]["mesh_volume"]
            h = (b[3] - b[0]) / dims[0]
            rows.append((n, h, int((exact > 0).sum() - (exact == cell).sum()),
                         np.abs(binary - exact).sum() / volume,
                         abs(binary.sum() - exact.sum()) / volume,
                         abs(exact.sum() - volume) / volume))
    print("| cells along longest side | cell size h | cut cells | misclassified volume / V | "
          "total volume error / V (binary) | total volume error / V (exact) |")
    print("|---:|---:|---:|---:|---:|---:|")
    for n, h, cut, l1, tot, ex in rows:
        print(f"| {n} | {h:.4g} | {cut} | {l1:.3e} | {tot:.3e} | {ex:.1e} |")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    hs = np.array([r[1] for r in rows])
    fig, ax = plt.subplots(figsize=(7, 4.6), dpi=110)
    ax.loglog(hs, [r[3] for r in rows], "o-", label="binary: misclassified volume (per cell, L1)")
    ax.loglog(hs, [r[4] for r in rows], "s-", label="binary: error of the total volume")
    ax.loglog(hs, [max(r[5], 1e-17) for r in rows], "^-", label="exact fractions: error of the total volume (0 drawn at 1e-17)")
    ax.loglog(hs, rows[0][3] * hs / hs[0], "k:", lw=1, label="slope 1 (proportional to h)")
    ax.set_xlabel("cell size h")
    ax.set_ylabel("error / mesh volume")
    ax.set_title(f"Centre-sampled voxelization vs exact cell volumes: {os.path.basename(args.mesh)}")
    ax.invert_xaxis()
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out)
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
