// scale_mass_properties: the figures of a mesh whose every coordinate is
// multiplied by L (a change of unit, or --scale). A quantity of degree k in
// length (edge length 1, area 2, volume 3, first moments 4, second moments
// and inertia 5, centroid 1) is multiplied by L^k, computed in double:
// k - 1 roundings for L^k, one for the product, and k times L's own
// relative error ε against the factor meant (0.001 for mm to m is not a
// double), so each relative error grows by at most (k + 1) u + k ε, and the
// density-scaled ones (mass, moments, inertia) by the density's ε_ρ too.
// A power-of-two L with ε = 0 scales exactly: every guarantee of a length's
// quantity stays, and of a density-scaled one when ε_ρ = 0 too.
#include <cmath>
#include <limits>

#include "polyvol/measure.hpp"
#include "polyvol/units.hpp"

namespace polyvol {
namespace {

constexpr double kRoundUp = 1 + 0x1p-20;  // covers the rounding of the bounds themselves

}  // namespace

void scale_mass_properties(MassProperties& m, double length_factor, double length_error, double density_error) {
    const double L = length_factor;
    const double u = 0x1p-53;
    // Exact for a power of two within 2^±64 (no quantity of degree 5 leaves
    // the normal range for a mesh of sane size; the results are checked below):
    // the lengths' quantities (volume, area, edge length) whatever
    // the density, the others (moments, inertia and the centroid, one bound) with
    // an exact density too.
    const bool lengths_exact = is_power_of_two(L) && std::fabs(std::log2(L)) <= 64 && length_error == 0;
    const bool exact = lengths_exact && density_error == 0;
    const auto power = [&](int k) {
        double f = 1;
        for (int i = 0; i < k; ++i) f *= L;
        return f;
    };
    // The added relative error of a quantity of degree k (density-scaled or not).
    const auto added = [&](int k, bool density) {
        if (density ? exact : lengths_exact) return 0.0;
        return (k + 1) * u + k * length_error + (density ? density_error : 0.0);
    };
    const double L1 = L, L2 = power(2), L3 = power(3), L4 = power(4), L5 = power(5);

    // Volume: an absolute bound (the volume's own, scaled, plus the scaling's).
    const double volume_rounding =
        m.volume_correctly_rounded ? (lengths_exact ? 0.0 : u * std::fabs(m.volume)) : m.volume_error_bound;
    m.volume *= L3;
    if (!lengths_exact) {
        m.volume_error_bound = (volume_rounding * L3 + std::fabs(m.volume) * added(3, false)) * kRoundUp;
        m.volume_correctly_rounded = false;
    } else if (!m.volume_correctly_rounded) {
        m.volume_error_bound *= L3;
    }
    m.mass *= L3;
    m.area *= L2;
    m.area_relative_error = (m.area_relative_error + added(2, false)) * kRoundUp;
    m.edge_length *= L1;
    m.edge_length_relative_error = (m.edge_length_relative_error + added(1, false)) * kRoundUp;
    for (double& x : m.first_moments) x *= L4;
    for (double& x : m.centroid) x *= L1;
    for (double& x : m.second_moments) x *= L5;
    for (double& x : m.inertia_origin) x *= L5;
    for (double& x : m.inertia_centroid) x *= L5;
    // A result pushed out of the normal range (or a huge L) has no guarantee left.
    const auto normal = [](double x) { return x == 0 || std::isnormal(x) || std::isnan(x); };
    bool in_range = normal(m.volume) && normal(m.area) && normal(m.mass);
    for (const auto* a : {&m.second_moments, &m.inertia_origin, &m.inertia_centroid})
        for (double x : *a) in_range = in_range && normal(x);
    for (double x : m.first_moments) in_range = in_range && normal(x);
    if (!in_range) {
        const double inf = std::numeric_limits<double>::infinity();
        m.volume_correctly_rounded = m.moments_correctly_rounded = false;
        m.volume_error_bound = m.area_relative_error = m.edge_length_relative_error = m.moments_relative_error = inf;
        return;
    }
    if (!exact) {
        // One bound for every moment array, relative to its largest entry: the worst degree (5).
        const double r0 = m.moments_correctly_rounded ? u : m.moments_relative_error;
        m.moments_relative_error = (r0 + added(5, true)) * kRoundUp;
        m.moments_correctly_rounded = false;
    }
}

}  // namespace polyvol
