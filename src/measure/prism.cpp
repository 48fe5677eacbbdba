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
// Error bound and the correctly rounded path's filter: docs/numerics.md,
// "The prism rule's bounds" (a per-term bound γ7 Zabs (|p| + |q|); the
// double-double filter within 64 u² Zabs X per triangle, else 72 exact
// two_prod parts, else GMP outside cone.hpp's safe range).

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
