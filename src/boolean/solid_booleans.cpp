// boolean/solid_booleans.cpp — |A ∩ B| and the rest where an operand's
// shells overlap or cross themselves: each operand is its solid
// (winding number >= 1), and the results are exact combinations of three
// solids' sums, rounded once each.
//
// With W_A, W_B >= 0 everywhere (outward shells, cavities inside them),
// A ∪ B = {W_A >= 1} ∪ {W_B >= 1} = {W_A + W_B >= 1}: the solid of both
// meshes together. Then
//   |A ∩ B| = |A| + |B| - |A ∪ B|,  |A - B| = |A ∪ B| - |B|,  |B - A| = |A ∪ B| - |A|,
// each formed from the exact sums (solid_sums.hpp) before any rounding.
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "boolean/solid_sums.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol {
namespace boolean {
namespace {

// 6 × the volume of Σ sign_i × solid_i as one PieceSum in units of 2^(3 e0):
// the exact whole parts added, integers and numerators scaled from each
// solid's e0_i to the least e0.
PieceSum combine(std::span<const std::pair<const SolidSums*, int>> terms, int e0) {
    PieceSum out;
    for (const auto& [s, sign] : terms) {
        const PieceSum& p = s->pieces[0];
        if (sign > 0)
            out.whole.merge(p.whole);
        else
            out.whole.subtract(p.whole);
        mpz_class scale;
        mpz_ui_pow_ui(scale.get_mpz_t(), 2, static_cast<unsigned long>(3 * (s->e0 - e0)));
        out.integer += sign * p.integer * scale;
        for (const auto& [n, d] : p.fractions) out.add_fraction(sign * n * scale, d);
    }
    return out;
}

}  // namespace
}  // namespace boolean

BooleanVolumes solid_boolean_volumes(const MeshView& a, const MeshView& b, bool within_shells) {
    using namespace boolean;
    BooleanVolumes r;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.area_a = r.area_b = r.area_intersection = r.area_union = r.area_a_minus_b = r.area_b_minus_a = nan;
    r.area_error_bound = nan;  // until the solids are summed
    auto fail = [&](BooleanStatus s) {
        r.status = s;
        r.volume_a = r.volume_b = r.intersection = r.union_volume = r.a_minus_b = r.b_minus_a = nan;
        return r;
    };
    SolidSums sa, sb, su;
    const SolidWants wants{.area = true, .within_shells = within_shells};
    const SolidVolume ra = solid_sums(a, wants, sa);
    if (ra.status != BooleanStatus::ok) return fail(ra.status);
    const SolidVolume rb = solid_sums(b, wants, sb);
    if (rb.status != BooleanStatus::ok)
        return fail(rb.status == BooleanStatus::a_not_closed ? BooleanStatus::b_not_closed : rb.status);
    Mesh ab = to_mesh(a);  // both meshes' faces, B's vertices after A's
    ab.append(to_mesh(b));
    const SolidVolume ru = solid_sums(ab.view(), wants, su);
    if (ru.status != BooleanStatus::ok) return fail(ru.status);
    // Each solid's whole triangles, summed exactly once (solid_sums leaves them).
    for (SolidSums* s : {&sa, &sb, &su}) {
        s->pieces[0].whole = cone_volume_sum(s->whole.view(), true).sum;
        s->pieces[0].whole_bound = 0;
    }
    r.triangles_a = a.triangle_count();
    r.triangles_b = b.triangle_count();
    r.crossing_pairs = ru.crossing_pairs;
    const int e0 = std::min({sa.e0, sb.e0, su.e0});
    using Term = std::pair<const SolidSums*, int>;
    const std::array<Term, 1> just_a{Term{&sa, +1}}, just_b{Term{&sb, +1}}, just_u{Term{&su, +1}};
    const std::array<Term, 3> inter{Term{&sa, +1}, Term{&sb, +1}, Term{&su, -1}};
    const std::array<Term, 2> a_minus_b{Term{&su, +1}, Term{&sb, -1}}, b_minus_a{Term{&su, +1}, Term{&sa, -1}};
    const Combination one[1] = {{nullptr, +1}};
    int refinements = 0;
    auto volume = [&](std::span<const Term> terms) {
        const PieceSum sum = combine(terms, e0);
        r.rational_terms = std::max(r.rational_terms, sum.fractions.size());
        const double v = round_combinations(sum, e0, one, refinements)[0];
        r.refinements = std::max(r.refinements, refinements);
        return v;
    };
    r.volume_a = volume(just_a);
    r.volume_b = volume(just_b);
    r.union_volume = volume(just_u);
    r.intersection = volume(inter);
    r.a_minus_b = volume(a_minus_b);
    r.b_minus_a = volume(b_minus_a);
    // Areas: each solid's boundary; ∂(A ∩ B) and ∂(A ∪ B) split ∂A and ∂B
    // between them (in the perturbed limit), so |∂(A ∩ B)| = |∂A| + |∂B| - |∂(A ∪ B)|.
    // A − B and B − A need the parts of ∂A inside B: not formed here (NaN).
    exact::ExactSum inter_area = sa.area.sum;
    inter_area.merge(sb.area.sum);
    inter_area.subtract(su.area.sum);
    r.area_a = sa.area.sum.round_div(2);
    r.area_b = sb.area.sum.round_div(2);
    r.area_union = su.area.sum.round_div(2);
    r.area_intersection = inter_area.round_div(2);
    const double largest = std::max({r.area_a + r.area_b, std::fabs(r.area_union), std::fabs(r.area_intersection)});
    r.area_error_bound = ((sa.area.bound + sb.area.bound + su.area.bound) / 2 + 0x1p-53 * largest) * (1 + 0x1p-40);
    return r;
}

}  // namespace polyvol
