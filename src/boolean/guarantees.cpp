// src/boolean/guarantees.cpp — the booleans' volumes for coordinates a
// reader computed, and in another length unit (polyvol/boolean.hpp).
#include <algorithm>
#include <cmath>

#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

constexpr double kU = 0x1p-53;
constexpr double kRoundUp = 1 + 0x1p-40;  // covers the rounding of the bounds themselves

double largest_volume(const BooleanVolumes& r) {
    double largest = 0;
    for (double v : {r.volume_a, r.volume_b, r.union_volume}) largest = std::max(largest, std::fabs(v));
    return largest;
}

}  // namespace

void widen_for_coordinate_error(BooleanVolumes& r, const MeshView& a, double a_error, const MeshView& b,
                                double b_error) {
    if (a_error <= 0 && b_error <= 0) return;
    // |V(moved) − V| ≤ swept(A) + swept(B) for every result; the volume's own
    // rounding is half an ulp of the largest (u |V|), or its bound so far.
    const double rounding = r.volume_error_bound > 0 ? r.volume_error_bound : kU * largest_volume(r);
    r.volume_error_bound = (rounding + perturbation_bounds(a, a_error, true).swept_volume +
                            perturbation_bounds(b, b_error, true).swept_volume) *
                           kRoundUp;
}

void scale_boolean_volumes(BooleanVolumes& r, const LengthFactor& f) {
    if (f.factor == 1 && f.relative_error == 0) return;
    const double L = f.factor, L2 = L * L, L3 = L2 * L;
    const bool exact = f.exact_power_of_two();
    // A quantity of degree k: k − 1 roundings for L^k, one for the product,
    // k times the factor's own error ε: (k + 1) u + k ε relative.
    const auto added = [&](int k) { return exact ? 0.0 : (k + 1) * kU + k * f.relative_error; };
    const double rounding = r.volume_error_bound > 0 ? r.volume_error_bound : exact ? 0.0 : kU * largest_volume(r);
    for (double* v : {&r.volume_a, &r.volume_b, &r.intersection, &r.union_volume, &r.a_minus_b, &r.b_minus_a})
        *v *= L3;
    if (!exact || r.volume_error_bound > 0)
        r.volume_error_bound = (rounding * L3 + largest_volume(r) * added(3)) * kRoundUp;
    double largest_area = 0;
    for (double* a : {&r.area_a, &r.area_b, &r.area_intersection, &r.area_union, &r.area_a_minus_b, &r.area_b_minus_a}) {
        *a *= L2;
        if (std::isfinite(*a)) largest_area = std::max(largest_area, std::fabs(*a));
    }
    r.area_error_bound = (r.area_error_bound * L2 + largest_area * added(2)) * kRoundUp;
}

}  // namespace polyvol
