// measure/prism.cpp — Allgower–Schmidt's prism rule (2.2) in 3D.
//
// Source: E. L. Allgower, P. H. Schmidt, "Computing volumes of polyhedra",
// Math. Comp. 46 (1986), formula (2.2) with n = 3:
//   V = (-1)^(n-1) Σ_σ (mean of the z of σ's vertices) · det[[1 1 1],[w_a w_b w_c]] / (n-1)!
// where w is a vertex without its z. For a fan triangle (a, b, c):
//   det[[1 1 1],[w_a w_b w_c]] = (b_x-a_x)(c_y-a_y) - (b_y-a_y)(c_x-a_x) = ((b-a)×(c-a))_z,
// so  V = Σ (z_a+z_b+z_c)/3 · ((b-a)×(c-a))_z / 2 = (1/6) Σ (z_a+z_b+z_c) ((b-a)×(c-a))_z.
// Each term is the signed volume of the prism between the triangle and the
// plane z = 0 (the divergence theorem with F = (0, 0, z): ∫ z n_z dA, exact
// for a triangle because z is linear on it). Sign: for outward (counter-
// clockwise seen from outside) faces ((b-a)×(c-a))/2 is the outward area
// vector, so a solid gives V > 0 — checked on boxes in methods_test.cpp.
//
// The sum is over the fan triangles of the given doubles as they are (no
// shift of origin): x and y enter only through differences, so translating
// in x, y changes nothing; translating by h in z adds h · Σ (projected area),
// which is 0 exactly for a closed surface and not otherwise.
//
// Error bound (u = 2^-53, γ_k = k u / (1 - k u), exact quantities starred).
// Per triangle the computed differences are exact ones times (1+δ), so
//   p = fl(dx1 dy2) = p*(1+θ3),  q = fl(dy1 dx2) = q*(1+θ3),
//   A2 = fl(p - q):   |A2 - A2*| <= γ4 (|p*| + |q*|)      =: γ4 P*
//   Z  = fl((z_a+z_b)+z_c): |Z - Z*| <= γ2 (|z_a|+|z_b|+|z_c|) =: γ2 Zabs
//   t  = fl(Z A2):    |t - Z* A2*| <= ((1+γ2)(1+γ4)(1+u) - 1) Zabs P* <= γ7 Zabs P*.
// The per-term bound e = γ7 · Zabs · (|p| + |q|) is evaluated from the
// computed magnitudes; finish() covers the roundings of that evaluation, the
// summation and the final division by 6 (see the block below).
// Underflow: an underflowing product adds <= 2^-1075 absolutely; in a term it
// is multiplied by at most |Z| <= Zabs (1+γ2), so the allowance
// 2^-1060 · (1 + max Zabs) per term covers it with room.
//
// Correctly rounded (prism_volume_correctly_rounded): the exact sum of the
// terms τ = Z* A* on the given doubles, divided by 6 and rounded once.
// With every coordinate the fan triangles read in cone.hpp's safe range
// ({0} ∪ [2^-160, 2^190]; NaN when one is not finite),
// every value below is a multiple of 2^-1060 under 2^1000: the error-free
// transformations are exact and no rounding underflows.
//   Filter, per fan triangle, in double-double (ux + ux' = b_x - a_x exactly
//   by two_sum, likewise uy, wx, wy for c - a; X = |ux wy| + |uy wx|;
//   Zabs = |z_a| + |z_b| + |z_c|):
//     p1 + p1' = ux wy, p2 + p2' = uy wx                 (two_prod, exact)
//     c1 = fl(fl(ux wy') + fl(ux' wy)), c2 likewise: with the dropped ux' wy'
//       (<= u² |ux wy|), |Ux Wy - (p1 + p1' + c1)| <= 5.01 u² |ux wy|
//     s + s' = p1 - p2                                   (two_sum, exact)
//     A_lo = fl(s' + fl(fl(p1' - p2') + fl(c1 - c2))): three roundings of
//       values <= 4.05 u X:  |A* - (s + A_lo)| <= 17.3 u² X, |A_lo| <= 4.1 u X
//     z1 + z1' = z_a + z_b, Z + z2' = z1 + z_c            (two_sum, exact)
//     Z_lo = fl(z1' + z2'):  |Z* - (Z + Z_lo)| <= 2.02 u² Zabs, |Z_lo| <= 2.02 u Zabs
//     t + t' = Z s                                        (two_prod, exact)
//     T_lo = fl(fl(t' + fl(Z A_lo)) + fl(Z_lo s))
//   |τ - (t + T_lo)| <= (17.4 [Z times A's error] + 2.03 [Z's error times A*]
//     + 8.3 [the dropped Z_lo A_lo] + 6.14 [the two products] + 14.4 [the two
//     sums]) u² Zabs X < 48.3 u² Zabs X.
//   t and T_lo go into a superaccumulator (exact), fl(Zabs fl(|p1| + |p2|))
//   into another; the bound used is 64 u² (1 + 2^-10) Σ Zabs X (64 covers 48.3
//   and the roundings of the magnitudes; 1 + 2^-10 the rounding of their sum).
//   The result is decided when Σ ± bound, divided by 6, round to the same
//   double.
//   Exact, when the filter cannot decide (e.g. an exact zero): A* expands
//   without differences, A* = b_x c_y - b_x a_y - a_x c_y - b_y c_x + b_y a_x
//   + a_y c_x (a_x a_y cancels); each product by two_prod, each of the 12
//   parts times each of z_a, z_b, z_c by two_prod: 72 doubles per triangle
//   whose exact sum is τ, into the superaccumulator.
//   Outside the safe range (finite): GMP rationals, triangle by triangle.
//   The range is checked in the filter's pass, on the coordinates it reads.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "exact/rational.hpp"
#include "measure/certified_sum.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure {
namespace {

using namespace certified;
using exact::ExactSum;
using exact::two_prod;
using exact::two_sum;

// cone.hpp's Range, of the coordinates the fan triangles read (vertices no
// face uses do not matter, as for the cone rule).
struct UsedRange {
    bool unsafe = false, nonfinite = false;
    void merge(const UsedRange& o) {
        unsafe = unsafe || o.unsafe;
        nonfinite = nonfinite || o.nonfinite;
    }
};

void check_range(const double* p, UsedRange& r) {
    for (int k = 0; k < 3; ++k) {
        r.nonfinite = r.nonfinite || !std::isfinite(p[k]);
        r.unsafe = r.unsafe || !exact::in_safe_range(p[k]);
    }
}

// The filter's sums (see the top of this file), and the range of the
// coordinates they read (the sums mean something only when it is safe).
struct FilterSums {
    ExactSum sum;        // Σ (t + T_lo)
    ExactSum magnitude;  // Σ Zabs X
    UsedRange range;
    void merge(const FilterSums& o) {
        sum.merge(o.sum);
        magnitude.merge(o.magnitude);
        range.merge(o.range);
    }
};

void add_filtered_term(const double* a, const double* b, const double* c, FilterSums& acc) {
    check_range(a, acc.range);
    check_range(b, acc.range);
    check_range(c, acc.range);
    double ux, ux_, uy, uy_, wx, wx_, wy, wy_;
    two_sum(b[0], -a[0], ux, ux_);
    two_sum(b[1], -a[1], uy, uy_);
    two_sum(c[0], -a[0], wx, wx_);
    two_sum(c[1], -a[1], wy, wy_);
    double p1, p1_, p2, p2_;
    two_prod(ux, wy, p1, p1_);
    two_prod(uy, wx, p2, p2_);
    const double c1 = ux * wy_ + ux_ * wy, c2 = uy * wx_ + uy_ * wx;
    double s, s_;
    two_sum(p1, -p2, s, s_);
    const double a_lo = s_ + ((p1_ - p2_) + (c1 - c2));
    double z1, z1_, z, z2_;
    two_sum(a[2], b[2], z1, z1_);
    two_sum(z1, c[2], z, z2_);
    const double z_lo = z1_ + z2_;
    double t, t_;
    two_prod(z, s, t, t_);
    acc.sum.add(t);
    acc.sum.add((t_ + z * a_lo) + z_lo * s);
    const double zabs = (std::fabs(a[2]) + std::fabs(b[2])) + std::fabs(c[2]);
    acc.magnitude.add(zabs * (std::fabs(p1) + std::fabs(p2)));
}

// τ exactly (see the top of this file), into acc.
void add_exact_term(const double* a, const double* b, const double* c, ExactSum& acc) {
    double part[12];
    two_prod(b[0], c[1], part[0], part[1]);
    two_prod(-b[0], a[1], part[2], part[3]);
    two_prod(-a[0], c[1], part[4], part[5]);
    two_prod(-b[1], c[0], part[6], part[7]);
    two_prod(b[1], a[0], part[8], part[9]);
    two_prod(a[1], c[0], part[10], part[11]);
    for (const double z : {a[2], b[2], c[2]})
        for (const double x : part) {
            double p, e;
            two_prod(z, x, p, e);
            acc.add(p);
            acc.add(e);
        }
}

struct ExactAcc {
    ExactSum sum;
    void merge(const ExactAcc& o) { sum.merge(o.sum); }
};

// Σ τ / 6 in rationals, for coordinates outside the safe range.
double rational_prism(const MeshView& mesh) {
    using exact::Rational;
    Rational total;
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) continue;
        const uint32_t* v = mesh.indices.data() + mesh.face_begin(f);
        auto coord = [&](uint32_t i, int j) { return Rational(mesh.positions[3 * std::size_t{i} + j]); };
        const Rational ax = coord(v[0], 0), ay = coord(v[0], 1), az = coord(v[0], 2);
        for (std::size_t i = 1; i + 1 < k; ++i) {
            const Rational ux = coord(v[i], 0) - ax, uy = coord(v[i], 1) - ay;
            const Rational wx = coord(v[i + 1], 0) - ax, wy = coord(v[i + 1], 1) - ay;
            total = total + (az + coord(v[i], 2) + coord(v[i + 1], 2)) * (ux * wy - uy * wx);
        }
    }
    return (total / Rational(6L)).to_double();
}

}  // namespace

double prism_volume_correctly_rounded(const MeshView& mesh) {
    const FilterSums f = reduce_fan<FilterSums>(
        mesh, [](const double* a, const double* b, const double* c, FilterSums& acc) { add_filtered_term(a, b, c, acc); });
    if (f.range.nonfinite) return std::numeric_limits<double>::quiet_NaN();
    if (f.range.unsafe) return rational_prism(mesh);
    const double bound = up(64 * kU * kU * up(f.magnitude.round() * (1 + 0x1p-10)));
    if (const auto v = exact::decided_round_div(f.sum, bound, 6)) return *v;
    const ExactAcc e = reduce_fan<ExactAcc>(
        mesh, [](const double* a, const double* b, const double* c, ExactAcc& acc) { add_exact_term(a, b, c, acc.sum); });
    return e.sum.round_div(6);
}

SumWithBound prism_volume(const MeshView& mesh) {
    constexpr double g7 = gam(7);
    const Acc acc = reduce_fan<Acc>(mesh, [&](const double* pa, const double* pb, const double* pc, Acc& a) {
        const double dx1 = pb[0] - pa[0], dy1 = pb[1] - pa[1];
        const double dx2 = pc[0] - pa[0], dy2 = pc[1] - pa[1];
        const double p = dx1 * dy2, q = dy1 * dx2;
        const double area2 = p - q;                  // ((b-a)×(c-a))_z
        const double zsum = (pa[2] + pb[2]) + pc[2];  // 3 · mean z
        const double zabs = (std::fabs(pa[2]) + std::fabs(pb[2])) + std::fabs(pc[2]);
        a.add(zsum * area2, g7 * (zabs * (std::fabs(p) + std::fabs(q))));
        a.aux = std::max(a.aux, zabs);
        ++a.units;
    });
    return finish(acc, 6.0, 1);
}

}  // namespace polyvol::measure
