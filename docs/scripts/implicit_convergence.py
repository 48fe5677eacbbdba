#!/usr/bin/env python3
"""Error against h for the unit n-balls, n = 2 .. 6, from `polyvol implicit --json`.

Writes docs/implicit_convergence.png and prints a Markdown table (used in
docs/implicit.md and docs/benchmarks.md): for each n the fitted slope of the
PL volume's error against h (second order expected), of the number of
boundary simplices and of the time against 1/h (n - 1 expected: the cost
follows the surface).

Each ball is measured in one orthant, the alternating one
[0, 1.2] x [-1.2, 0] x [0, 1.2] x ... (the solid is clipped by the box; the
ball is 2^n times the orthant), which costs 2^-n of the whole ball on the same
lattice. F = |x|^2 - 1 is separable, so its PL solid is the same in every
orthant (docs/implicit.md); the alternating one's Kuhn simplices are crossed
about half as often as those of [0, 1.2]^n, whose cubes' main diagonal is
along the sphere's normal.

    /usr/bin/python3 docs/scripts/implicit_convergence.py [--polyvol build/polyvol] [--quick]

Needs python3-matplotlib and python3-numpy (Debian).
"""
import argparse
import json
import math
import pathlib
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SIDE = 1.2
# cells across the orthant's side for each n (h = SIDE / cells)
CELLS = {
    2: [8, 16, 32, 64, 128, 256],
    3: [8, 16, 32, 64, 128],
    4: [4, 6, 8, 12, 16, 24],
    5: [4, 6, 8, 10, 12],
    6: [4, 6, 8],
}
QUICK = {2: [8, 16, 32, 64], 3: [8, 16, 32], 4: [4, 6, 8, 12], 5: [4, 6], 6: [4]}


def ball(n):
    return math.pi ** (n / 2) / math.gamma(n / 2 + 1)


def box(n):
    return ",".join(f"0:{SIDE}" if k % 2 == 0 else f"-{SIDE}:0" for k in range(n))


def run(polyvol, n, cells):
    names = " + ".join(f"x{k}^2" for k in range(1, n + 1))
    out = subprocess.run(
        [polyvol, "implicit", f"{names} - 1", "--dim", str(n), f"--box={box(n)}",
         "--h", repr(SIDE / cells), "--json"],
        check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def slope(x, y):
    return float(np.polyfit(np.log(x), np.log(y), 1)[0]) if len(x) >= 2 else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--polyvol", default=str(ROOT / "build" / "polyvol"))
    ap.add_argument("--quick", action="store_true", help="fewer, coarser lattices")
    ap.add_argument("--out", default=str(ROOT / "docs" / "implicit_convergence.png"))
    args = ap.parse_args()
    cells = QUICK if args.quick else CELLS

    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    rows = []
    for n, sizes in cells.items():
        exact = ball(n)
        hs, pl, ex, est, simp, secs = [], [], [], [], [], []
        for c in sizes:
            j = run(args.polyvol, n, c)
            scale = 2 ** n
            hs.append(j["fine"]["spacing"][0])
            pl.append(abs(scale * j["volume_pl"] - exact) / exact)
            ex.append(abs(scale * j["volume"] - exact) / exact)
            est.append(scale * j["error_estimate"] / exact)
            simp.append(j["fine"]["boundary_simplices"])
            secs.append(j["fine"]["seconds"])
            print(f"n={n} cells={c} h={hs[-1]:.4g} pl_err={pl[-1]:.3e} extrap_err={ex[-1]:.3e} "
                  f"estimate={est[-1]:.3e} simplices={simp[-1]} seconds={secs[-1]:.3g}", flush=True)
        p = slope(hs, pl)
        inv = [1 / h for h in hs]
        rows.append((n, p, slope(inv, simp), slope(inv, secs) if len(secs) >= 2 else float("nan"),
                     hs[-1], pl[-1], ex[-1], est[-1]))
        line, = ax.loglog(hs, pl, "o-", label=f"n = {n}: PL volume, slope {p:.2f}")
        ax.loglog(hs, ex, "x--", color=line.get_color(), alpha=0.6)
    ax.set_xlabel("lattice spacing h")
    ax.set_ylabel("relative error in the volume of the unit n-ball")
    ax.set_title("polyvol implicit: PL volume (o, solid) and Richardson (x, dashed)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}\n")
    print("| n | error slope (PL) | boundary simplices vs 1/h | time vs 1/h | finest h | PL error | extrapolated error | estimate |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n, p, s, t, h, e, x, est in rows:
        print(f"| {n} | {p:.2f} | {s:.2f} | {t:.2f} | {h:.4g} | {e:.2e} | {x:.2e} | {est:.2e} |")


if __name__ == "__main__":
    main()
