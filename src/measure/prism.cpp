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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "exact/eft.hpp"
#include "measure/certified_sum.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure {
namespace {

using namespace certified;

}  // namespace

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
