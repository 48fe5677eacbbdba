// measure/pyramid.cpp — Franklin's pyramid per face.
//
// Source: W. R. Franklin's note on polyhedron volume: the volume is the sum
// over faces of pyramids joining the origin to each face, face area times the
// signed distance of its plane from the origin / 3. Per polygon face
// (v0 v1 ... v_{k-1}), with the fan's vector area
//   A_f = Σ_{i=1}^{k-2} (v_i - v0) × (v_{i+1} - v0) / 2,
//   V_f = A_f · v0 / 3,        V = Σ_f V_f.
// This is exactly the sum of the fan's cone volumes Σ_i det(v0, v_i, v_{i+1}) / 6
// (Allgower–Schmidt (2.1)) — also for concave or non-planar faces, where it is
// the volume of the fan the face means (mesh.hpp) — because
//   det(v0, v_i, v_{i+1}) = v0 · (v_i × v_{i+1}) = v0 · ((v_i - v0) × (v_{i+1} - v0))
// (expand: the two extra terms v0·(v_i × v0) and v0·(v0 × v_{i+1}) vanish).
// For a planar face, A_f · v0 = |A_f| · (signed distance of the plane from 0).
// Computed on the given doubles (no shift): the result depends on the origin
// unless the surface is closed.
//
// Error bound (u = 2^-53, γ_k = k u / (1 - k u), exact quantities starred).
// For a face of k >= 3 vertices, m = k - 2 fan triangles, d_i = fl(v_i - v0):
//   c_i = fl(d_i × d_{i+1}) per component, e.g. c_x = fl(fl(dy dz') - fl(dz dy')):
//       |c_i - c_i*| <= γ4 P*_i,  P*_i = |dy dz'|* + |dz dy'|*  (per component)
//   S = Σ_i c_i (recursive, m - 1 additions), Q* = Σ_i P*_i:
//       |S - S*| <= γ_{m-1} Σ|c_i| + γ4 Q* <= γ_{k+1} Q*,  |S| <= (1+γ_{k+1}) Q*
//   t = fl(v0 · S):  |t - v0·S*| <= γ3 Σ_j |v0_j| |S_j| + Σ_j |v0_j| |S_j - S*_j|
//                                <= γ_{k+4} W*,  W* = Σ_j |v0_j| Q*_j
//   (a term is 2 A_f · v0 = 6 V_f; the sum is divided by 6 at the end).
// The per-face bound e = γ_{k+4} · W is evaluated from the computed |products|;
// finish() covers its rounding, the summation and the division by 6.
// Underflow: each of the 2 products per component per fan triangle adds
// <= 2^-1075 to S, multiplied by |v0_j| in the dot product, plus <= 3 · 2^-1075
// from the dot product: <= (k - 1) · 2^-1072 · (1 + |v0|_1) per face, covered by
// the allowance 2^-1060 · (1 + max |v0|_1) per unit with k - 1 units per face.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

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
}  // namespace

SumWithBound pyramid_volume(const MeshView& mesh) {
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    const Acc acc = reduce<Acc>(mesh.face_count(), [&](std::size_t f, Acc& a) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) return;
        const uint32_t* v = idx + mesh.face_begin(f);
        const double* p0 = pos + 3 * std::size_t{v[0]};
        const double* p1 = pos + 3 * std::size_t{v[1]};
        double d1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double S[3] = {0, 0, 0};  // 2 A_f
        double Q[3] = {0, 0, 0};  // Σ of |products| per component
        for (std::size_t i = 1; i + 1 < k; ++i) {
            const double* p2 = pos + 3 * std::size_t{v[i + 1]};
            const double d2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            const double px = d1[1] * d2[2], qx = d1[2] * d2[1];
            const double py = d1[2] * d2[0], qy = d1[0] * d2[2];
            const double pz = d1[0] * d2[1], qz = d1[1] * d2[0];
            S[0] += px - qx;
            S[1] += py - qy;
            S[2] += pz - qz;
            Q[0] += std::fabs(px) + std::fabs(qx);
            Q[1] += std::fabs(py) + std::fabs(qy);
            Q[2] += std::fabs(pz) + std::fabs(qz);
            std::copy(d2, d2 + 3, d1);
        }
        const double a0 = std::fabs(p0[0]), a1 = std::fabs(p0[1]), a2 = std::fabs(p0[2]);
        const double t = (p0[0] * S[0] + p0[1] * S[1]) + p0[2] * S[2];
        const double w = (a0 * Q[0] + a1 * Q[1]) + a2 * Q[2];
        a.add(t, gam(static_cast<double>(k + 4)) * w);
        a.aux = std::max(a.aux, (a0 + a1) + a2);
        a.units += k - 1;
    });
    return finish(acc, 6.0, 1);
}

}  // namespace polyvol::measure
