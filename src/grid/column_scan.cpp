// grid/column_scan.cpp — the reverse prefix sum down a column (docs/grid.md,
// "The method: clipping and a column scan, no flood fill").
//
// Divergence theorem on the solid's part in cell k (floor z_k, height h):
//   F = (0, 0, z - z_k):          V      = Q + h A_top
//   F = (0, 0, (x - x_i)(z - z_k)): ∫ξ dV = Qx + h Ax_top      (η likewise)
//   F = (0, 0, (z - z_k)²/2):     ∫ζ dV  = Qz + h²/2 A_top
// and on the solid's part above the plane z_{k+1} in the same column with
// F = (0, 0, 1) (resp. (0, 0, ξ)): the cross-section integrals on the top
// face are the sums of P (resp. Px) over the pieces above:
//   A_top(k) = Σ_{k' > k} P(k'),  Ax_top(k) = Σ_{k' > k} Px(k').
// A cell that no piece enters has constant winding number w inside, so its
// exact value is w × (cell volume) with w = A_top / (cell area); w is
// rounded to the nearest integer and the value set exactly. A column no
// piece reached is empty throughout.
#include "grid/column_scan.hpp"

#include <algorithm>
#include <cmath>
#include <bit>
#include <cstdint>

namespace polyvol::grid {

namespace {

// round(x) to an integer-valued double, halves away from zero (x is within
// rounding of an integer here; no libm call). |x| >= 2^52 is already integral.
double round_integer(double x) {
    if (!(std::abs(x) < 4503599627370496.0)) return x;
    const auto i = static_cast<int64_t>(std::abs(x) + 0.5);
    return x < 0 ? -static_cast<double>(i) : static_cast<double>(i);
}

}  // namespace

ColumnCounts scan_column(const TileSums& s, int ci, int cj, const ColumnGeometry& g, double* volume,
                         double* moments, uint8_t* state) {
    ColumnCounts counts;
    const std::size_t col = s.column(ci, cj);
    if (!s.touched[col]) {
        // no piece in the column or above it: every cell empty
        std::fill(volume, volume + g.nz, 0.0);
        std::fill(state, state + g.nz, static_cast<uint8_t>(kEmpty));
        if (moments) std::fill(moments, moments + 3 * g.nz, 0.0);
        counts.empty = static_cast<std::size_t>(g.nz);
        return counts;
    }
    const std::size_t base = s.index(ci, cj, 0);
    const uint64_t* bits = s.column_bits(col);
    auto has_piece = [&](int k) { return (bits[k / 64] >> (k % 64)) & 1u; };
    // the next cell at or below k with a piece, or -1
    auto next_piece = [&](int k) {
        for (int w = k / 64; w >= 0; --w) {
            uint64_t word = bits[w];
            if (w == k / 64) word &= (k % 64 == 63) ? ~uint64_t{0} : ((uint64_t{1} << (k % 64 + 1)) - 1);
            if (word != 0) return 64 * w + 63 - std::countl_zero(word);
        }
        return -1;
    };
    const double dx = g.x1 - g.x0, dy = g.y1 - g.y0;
    const double area = dx * dy;
    const double cx = 0.5 * (g.x0 + g.x1), cy = 0.5 * (g.y0 + g.y1);
    DD a, ax, ay;
    if (has_piece(g.nz)) {
        a = s.P[base + g.nz];
        if (moments) {
            ax = s.Px[base + g.nz];
            ay = s.Py[base + g.nz];
        }
    }
    // Cells k in (stop, from] have no piece: the winding number of A_top.
    auto fill_uncut = [&](int from, int stop) {
        if (from <= stop) return;
        const double w = round_integer(a.value() / area);
        const uint8_t st = w == 0 ? kEmpty : (w >= 1 ? kFull : kCut);
        const auto n = static_cast<std::size_t>(from - stop);
        (st == kEmpty ? counts.empty : st == kFull ? counts.full : counts.cut) += n;
        std::fill(state + stop + 1, state + from + 1, st);
        if (w == 0) {
            std::fill(volume + stop + 1, volume + from + 1, 0.0);
            if (moments) std::fill(moments + 3 * (stop + 1), moments + 3 * (from + 1), 0.0);
            return;
        }
        for (int k = from; k > stop; --k) {
            const double v = w * (area * (g.z[k + 1] - g.z[k]));
            volume[k] = v;
            if (moments) {
                moments[3 * k + 0] = v * cx;
                moments[3 * k + 1] = v * cy;
                moments[3 * k + 2] = v * (0.5 * (g.z[k] + g.z[k + 1]));
            }
        }
    };
    int k = g.nz - 1;
    while (k >= 0) {
        const int p = next_piece(k);
        fill_uncut(k, p);
        if (p < 0) break;
        const std::size_t c = base + p;
        if (s.interior[c]) {
            const double z0 = g.z[p], h = g.z[p + 1] - z0;
            const DD& q = s.Q[c];
            const double v = (q.hi + h * a.hi) + (q.lo + h * a.lo);
            volume[p] = v;
            state[p] = kCut;
            ++counts.cut;
            if (moments) {
                const double mx = (s.Qx[c].hi + h * ax.hi) + (s.Qx[c].lo + h * ax.lo);
                const double my = (s.Qy[c].hi + h * ay.hi) + (s.Qy[c].lo + h * ay.lo);
                const double hh = 0.5 * h * h;
                const double mz = (s.Qz[c].hi + hh * a.hi) + (s.Qz[c].lo + hh * a.lo);
                moments[3 * p + 0] = g.x0 * v + mx;
                moments[3 * p + 1] = g.y0 * v + my;
                moments[3 * p + 2] = z0 * v + mz;
            }
        } else {
            fill_uncut(p, p - 1);  // only pieces lying in its faces
        }
        a.add(s.P[c]);
        if (moments) {
            ax.add(s.Px[c]);
            ay.add(s.Py[c]);
        }
        k = p - 1;
    }
    return counts;
}

}  // namespace polyvol::grid
