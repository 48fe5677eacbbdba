#include "topology/degenerate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "exact/eft.hpp"
#include "exact/expansion.hpp"

namespace polyvol::topology {
namespace {

// Is (bu - au)(cv - av) - (bv - av)(cu - au) exactly zero? (u, v: two axes)
//   = bu cv - bu av - au cv - bv cu + bv au + av cu   (the au av terms cancel)
bool orient2d_is_zero(double au, double av, double bu, double bv, double cu, double cv) {
    const double left = (bu - au) * (cv - av);
    const double right = (bv - av) * (cu - au);
    const double det = left - right;
    constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff
    constexpr double kErrBound = (3.0 + 16.0 * kEps) * kEps;            // ccwerrboundA
    if (std::abs(det) > kErrBound * (std::abs(left) + std::abs(right))) return false;
    if (!std::isfinite(det)) {
        // Overflow or non-finite input: decided below after scaling.
        if (!(std::isfinite(au) && std::isfinite(av) && std::isfinite(bu) && std::isfinite(bv) &&
              std::isfinite(cu) && std::isfinite(cv)))
            return false;
    }
    // Scale so the largest magnitude is in [1, 2): exact, and no product overflows.
    const double big = std::max({std::abs(au), std::abs(av), std::abs(bu), std::abs(bv),
                                 std::abs(cu), std::abs(cv)});
    if (big == 0) return true;
    const int shift = -std::ilogb(big);
    au = std::ldexp(au, shift), av = std::ldexp(av, shift), bu = std::ldexp(bu, shift);
    bv = std::ldexp(bv, shift), cu = std::ldexp(cu, shift), cv = std::ldexp(cv, shift);
    // Six exact products (Dekker's two_prod: |x| < 2 here), summed exactly.
    const double terms[6][2] = {{bu, cv}, {-bu, av}, {-au, cv}, {-bv, cu}, {bv, au}, {av, cu}};
    double e[13] = {0};
    int n = 1;
    for (const auto& t : terms) {
        double p, err;
        exact::two_prod_dekker(t[0], t[1], p, err);
        n = exact::grow_expansion(n, e, p, e);
        n = exact::grow_expansion(n, e, err, e);
    }
    return std::all_of(e, e + n, [](double x) { return x == 0; });
}

}  // namespace

bool cross_product_is_zero(const double* a, const double* b, const double* c) {
    // Components z, x, y of the cross product: projections on xy, yz, zx.
    return orient2d_is_zero(a[0], a[1], b[0], b[1], c[0], c[1]) &&
           orient2d_is_zero(a[1], a[2], b[1], b[2], c[1], c[2]) &&
           orient2d_is_zero(a[2], a[0], b[2], b[0], c[2], c[0]);
}

DegenerateCounts count_degenerate_triangles(const WeldedMesh& m) {
    DegenerateCounts d;
    m.for_each_polygon([&](uint32_t, std::span<const uint32_t> c) {
        const uint32_t a = m.id[c[0]];
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            const uint32_t b = m.id[c[i]], e = m.id[c[i + 1]];
            if (a == b || b == e || a == e) {
                ++d.triangles_with_repeated_vertex;
                ++d.zero_area_triangles;
            } else if (cross_product_is_zero(m.position(a), m.position(b), m.position(e))) {
                ++d.zero_area_triangles;
            }
        }
    });
    return d;
}

}  // namespace polyvol::topology
