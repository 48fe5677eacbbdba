// measure/principal.cpp — principal moments and axes of an inertia tensor
// (measure.hpp, principal_inertia): Eigen's symmetric eigensolver, then
// bounds from the residuals (an eigenvalue lies within |A v - λ v| of λ for
// a unit v), Weyl's inequality for the tensor's own error, and Davis–Kahan's
// sin θ theorem for the axes.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/portable_math.hpp"
#include "polyvol/measure.hpp"

namespace polyvol {
PrincipalInertia principal_inertia(const std::array<double, 6>& t, double relative_error) {
    Eigen::Matrix3d a;
    a << t[0], t[3], t[5],  //
        t[3], t[1], t[4],   //
        t[5], t[4], t[2];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(a);
    PrincipalInertia p;
    const double inf = std::numeric_limits<double>::infinity();
    if (solver.info() != Eigen::Success) {
        p.moment_error = inf;
        p.axis_angle = {inf, inf, inf};
        return p;
    }
    // Signs: the first two axes point along their largest component, the
    // third completes a right-handed frame (an exact cross product would be
    // nicer; this one is within a few u, covered by the residuals below).
    Eigen::Matrix3d v = solver.eigenvectors();
    for (int k = 0; k < 2; ++k) {
        Eigen::Index at = 0;
        v.col(k).cwiseAbs().maxCoeff(&at);
        if (v(at, k) < 0) v.col(k) = -v.col(k);
    }
    v.col(2) = v.col(0).cross(v.col(1)).normalized();
    double largest = 0;
    for (double x : t) largest = std::max(largest, std::fabs(x));
    constexpr double u = 0x1p-53;
    // The residuals, computed in double: each within about 8 u |A| |v| of the exact one.
    double residual = 0;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d col = v.col(k).normalized();
        residual = std::max(residual, (a * col - solver.eigenvalues()(k) * col).norm());
    }
    // Matching the k-th computed moment with the k-th eigenvalue takes the
    // residual matrix's norm, at most √3 times the largest column's (Kahan).
    const double tensor_error = 3 * relative_error * largest;  // |E|_F for entries within relative_error max|A|
    p.moment_error = (std::sqrt(3.0) * residual + 16 * u * 3 * largest + tensor_error) * (1 + 0x1p-40);
    if (std::isnan(p.moment_error)) p.moment_error = inf;
    for (int k = 0; k < 3; ++k) {
        p.moments[static_cast<std::size_t>(k)] = solver.eigenvalues()(k);
        for (int i = 0; i < 3; ++i) p.axes[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)] = v(i, k) + 0.0;  // no -0
    }
    for (std::size_t k = 0; k < 3; ++k) {
        double gap = inf;
        for (std::size_t j = 0; j < 3; ++j)
            if (j != k) gap = std::min(gap, std::fabs(p.moments[k] - p.moments[j]));
        gap -= 2 * p.moment_error;  // between the exact moments
        const double s = gap > 0 ? p.moment_error / gap : inf;
        p.axis_angle[k] = s < 1 ? core::asin_upper_bound(s) : inf;
    }
    return p;
}

PrincipalInertia principal_inertia(const MassProperties& m) {
    return principal_inertia(m.inertia_centroid, m.moments_correctly_rounded ? 0x1p-53 : m.moments_relative_error);
}

double moments_error_bound(const MassProperties& m, std::span<const double> entries) {
    if (m.moments_correctly_rounded) return 0;
    double largest = 0;
    for (double e : entries) largest = std::max(largest, std::fabs(e));
    return m.moments_relative_error * largest;
}

}  // namespace polyvol
