// measure/area.cpp — the fan area Σ |(b-a)×(c-a)|/2 and the welded edge
// length Σ |b-a| over undirected polygon edges.
//
// Conventions (mesh.hpp, measure.hpp): the area is that of the fan triangles
// (a concave polygon's fan counts its overlapping triangles, as the corpus
// does); the edge length counts each undirected edge of the polygon faces
// (consecutive vertices of faces with >= 3 vertices, with the closing edge)
// once, after welding vertices with bit-identical coordinates (-0.0 == +0.0,
// weld_vertices in mesh.hpp); edges whose ends weld together are skipped.
//
// Error bounds (u = 2^-53, γ_k = k u/(1 - k u), exact quantities starred):
//   norm3() returns |v| with relative error <= γ5 (squares of components,
//   two additions, a square root; scaled by an exact power of two when the
//   largest component is outside [2^-500, 2^500], so neither overflow nor
//   underflow of the squares matters).
//   Area, per fan triangle: n = fl(d1 × d2) from rounded differences, each
//   component off by <= γ4 (|p*| + |q*|) (its two products), so
//   |n - n*|_2 <= |n - n*|_1 <= γ4 X*, X = Σ |products|; t = norm3(n):
//   |t - |n*|| <= γ5 |n| + γ4 X* <= γ5 t/(1-γ5) + γ4 X*   -> e = γ5 t + γ4 X.
//   Length, per edge: d = fl(b - a) = d*(1+δ) per component, so
//   t = norm3(d) = |d*|(1+θ6):  |t - |d*|| <= γ6 t/(1-γ6)   -> e = γ6 t.
// finish() (below) adds the summation error (terms summed with two_sum), the
// rounding of these per-term expressions and the final halving of the area;
// underflowing products add <= 6 · 2^-1075 per triangle, covered by the
// allowance of 2^-1060 per term.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include "exact/eft.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure {
namespace {

// ---- Certified summation. The same block is in prism.cpp, pyramid.cpp,
// vtnb.cpp and area.cpp (each file is owned separately for now; keep them
// identical, or move the block into a private header). ----
//
// Model: fl(a op b) = (a op b)(1+δ), |δ| <= u = 2^-53 (round to nearest, no
// FMA contraction: the build passes -ffp-contract=off), plus an absolute error
// <= 2^-1075 when a product or quotient underflows (sums never do).
//
// A kernel calls add(t_i, e_i) for every computed term t_i, where e_i is its
// bound on |t_i - τ_i| (τ_i the exact term on the given doubles), evaluated
// in floating point from computed, non-negative magnitudes with upper-bounded
// constants (gam()). Such an expression of sums, products and quotients of
// positive numbers, each operand within a factor (1+θ_j) of its exact value,
// is itself within (1+θ_J) of its exact value with J <= 256 for every kernel
// here (Higham, Accuracy and Stability, Lemma 3.3; the longest, vtnb's, needs
// about 100), so
//   Σ exact e_i <= (1 + γ_{2J}) · (1 + γ_N) · err <= (1 + γ_{N+512}) err.
// Underflow while evaluating e_i loses at most a few 2^-1075 absolutely,
// covered by the allowance below.
// Terms are added with Knuth's two_sum (Sum2 of Ogita, Rump & Oishi 2005, also
// across the parallel merges): s + Σ(errors) == Σ t_i exactly, and with
// N = 3n + 2 >= the number of additions on any path from a term to the result
// (n leaf two_sums, at most n - 1 merges with two additions each),
//   |fl(s + c) - Σ t_i| <= (u |fl(s+c)| + (1+u) γ_N² Σ|t_i|) / (1 - u),
//   Σ|t_i| <= (1 + γ_N) · abs     (abs: plain sum of |t_i|, any order).
// Then value = fl(±σ / d):  |value - (±σ/d)| <= u |value| / (1-u) + 2^-1075.
// Everything in the bound itself is computed with up() after every
// operation, which gives an upper bound of the exact expression.

constexpr double kU = 0x1p-53;
constexpr double kOnePlus2U = 1 + 0x1p-52;  // >= 1 + u, representable

double up(double x) { return std::nextafter(x, std::numeric_limits<double>::infinity()); }
// An upper bound of γ_k (rigorous; k u < 1/2).
double gamma_up(double k) { return up(up(k * kU) / std::nextafter(1.0 - k * kU, 0.0)); }
// γ_k <= k u (1 + 2 k u) for k u <= 1/2: for per-term expressions (within J).
constexpr double gam(double k) { return k * kU * (1 + 2 * k * kU); }

struct Acc {
    double s = 0;      // running two_sum sum
    double c = 0;      // sum of two_sum errors
    double abs = 0;    // Σ |t_i|
    double err = 0;    // Σ e_i
    double aux = 0;    // max per-term magnitude (underflow allowance)
    uint64_t n = 0;    // terms added
    uint64_t units = 0;  // underflow units (kernel-specific count)

    void add(double t, double e) {
        double lo;
        exact::two_sum(s, t, s, lo);
        c += lo;
        abs += std::fabs(t);
        err += e;
        ++n;
    }
    void merge(const Acc& o) {
        double lo;
        exact::two_sum(s, o.s, s, lo);
        c = (c + o.c) + lo;
        abs += o.abs;
        err += o.err;
        aux = std::max(aux, o.aux);
        n += o.n;
        units += o.units;
    }
};

// value = sign · fl(s + c) / divisor and its bound (see above); the
// underflow allowance is units · 2^-1060 · (1 + aux)^power.
SumWithBound finish(const Acc& a, double divisor, int power, double sign = 1.0) {
    const double sigma = a.s + a.c;
    SumWithBound r;
    r.value = sign * (divisor == 1.0 ? sigma : sigma / divisor) + 0.0;  // + 0.0: no -0.0
    const double nn = 3.0 * static_cast<double>(a.n) + 2.0;
    const double gN = gamma_up(nn);
    const double sum_abs = up(a.abs * up(1 + gN));
    const double sum_err =
        up(up(up(kU * std::fabs(sigma)) + up(up(up(kOnePlus2U * gN) * gN) * sum_abs)) / (1 - kU));
    const double term_err = up(a.err * up(1 + gamma_up(nn + 512)));
    double amp = 1;
    for (int i = 0; i < power; ++i) amp = up(amp * up(1 + a.aux));
    const double allowance = up(up(static_cast<double>(a.units) * 0x1p-1060) * amp);
    double bound = up(up(sum_err + term_err) + allowance);
    if (divisor != 1.0) {
        bound = up(up(bound / divisor) + up(up(kU * std::fabs(r.value)) / (1 - kU)));
        bound = up(bound + 0x1p-1074);
    }
    if (!std::isfinite(r.value) || !std::isfinite(bound))
        bound = std::numeric_limits<double>::infinity();
    r.error_bound = bound;
    return r;
}

// Deterministic parallel reduction over 0..count-1 in fixed blocks: the
// same input gives the same bits for any number of threads.
constexpr std::size_t kGrain = 2048;
template <class A, class Body>
A reduce(std::size_t count, const Body& body) {
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, count, kGrain), A{},
        [&](const tbb::blocked_range<std::size_t>& range, A acc) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) body(i, acc);
            return acc;
        },
        [](A x, const A& y) {
            x.merge(y);
            return x;
        });
}
// ---- end of the certified-summation block ----

// |(x, y, z)| with relative error <= γ5 (as in vtnb.cpp).
double norm3(double x, double y, double z) {
    const double m = std::max(std::max(std::fabs(x), std::fabs(y)), std::fabs(z));
    if (m > 0x1p-500 && m < 0x1p500) return std::sqrt((x * x + y * y) + z * z);
    if (m == 0) return 0;
    if (!std::isfinite(m) || x != x || y != y || z != z) return std::numeric_limits<double>::quiet_NaN();
    int e = 0;
    std::frexp(m, &e);
    const double xs = std::ldexp(x, -e), ys = std::ldexp(y, -e), zs = std::ldexp(z, -e);
    return std::ldexp(std::sqrt((xs * xs + ys * ys) + zs * zs), e);
}

}  // namespace

SumWithBound fan_area(const MeshView& mesh) {
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    constexpr double g4 = gam(4), g5 = gam(5);
    const Acc acc = reduce<Acc>(mesh.face_count(), [&](std::size_t f, Acc& a) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) return;
        const uint32_t* v = idx + mesh.face_begin(f);
        const double* p0 = pos + 3 * std::size_t{v[0]};
        for (std::size_t i = 1; i + 1 < k; ++i) {
            const double* p1 = pos + 3 * std::size_t{v[i]};
            const double* p2 = pos + 3 * std::size_t{v[i + 1]};
            const double d1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
            const double d2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            const double px = d1[1] * d2[2], qx = d1[2] * d2[1];
            const double py = d1[2] * d2[0], qy = d1[0] * d2[2];
            const double pz = d1[0] * d2[1], qz = d1[1] * d2[0];
            const double t = norm3(px - qx, py - qy, pz - qz);  // |(b-a)×(c-a)|
            const double X = ((std::fabs(px) + std::fabs(qx)) + (std::fabs(py) + std::fabs(qy))) +
                             (std::fabs(pz) + std::fabs(qz));
            a.add(t, g5 * t + g4 * X);
            ++a.units;
        }
    });
    return finish(acc, 2.0, 0);
}

SumWithBound welded_edge_length(const MeshView& mesh) {
    const std::vector<uint32_t> weld = weld_vertices(mesh.positions);
    // Each undirected edge as (smaller welded id) << 32 | (larger welded id).
    std::vector<uint64_t> edges;
    edges.reserve(mesh.indices.size());
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) continue;
        const std::span<const uint32_t> v = mesh.face(f);
        for (std::size_t j = 0; j < k; ++j) {
            const uint32_t a = weld[v[j]], b = weld[v[j + 1 == k ? 0 : j + 1]];
            if (a == b) continue;
            edges.push_back(uint64_t{std::min(a, b)} << 32 | std::max(a, b));
        }
    }
    tbb::parallel_sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

    const double* pos = mesh.positions.data();
    constexpr double g6 = gam(6);
    const Acc acc = reduce<Acc>(edges.size(), [&](std::size_t i, Acc& a) {
        const double* pa = pos + 3 * (edges[i] >> 32);
        const double* pb = pos + 3 * (edges[i] & 0xFFFFFFFFu);
        const double t = norm3(pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]);
        a.add(t, g6 * t);
        ++a.units;
    });
    return finish(acc, 1.0, 0);
}

}  // namespace polyvol::measure
