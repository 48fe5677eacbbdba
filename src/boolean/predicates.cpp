#include "boolean/predicates.hpp"

#include <cmath>

#include "exact/eft.hpp"
#include "exact/expansion.hpp"

namespace polyvol::boolean {
namespace {

constexpr double kU = 0x1p-53;  // unit roundoff

int sign_of(double x) { return (x > 0) - (x < 0); }

// The sign of a nonoverlapping expansion with zeros eliminated: its largest
// component's (the last).
int expansion_sign(int n, const double* e) { return sign_of(e[n - 1]); }

void negate(int n, double* e) {
    for (int i = 0; i < n; ++i) e[i] = -e[i];
}

// orient(a, b, c, d) = det(b - a, c - a, d - a): one det3 expansion where
// the nine differences are doubles exactly (two_sum's error 0, as for most
// nearby coordinates); else det(b,c,d) - det(a,c,d) + det(a,b,d) - det(a,b,c)
// (the 4x4 determinant with a column of ones), each det3 an exact expansion.
// Both exact in the safe range: differences of coordinates there are
// multiples of 2^-212 below 2^191, as eft.hpp's conditions ask.
int orient3d_exact_sign(const double* a, const double* b, const double* c, const double* d) {
    double diff[3][3];
    bool exact_differences = true;
    for (int k = 0; k < 3; ++k) {
        const double* p[3] = {b, c, d};
        for (int i = 0; i < 3; ++i) {
            double err;
            exact::two_sum(p[i][k], -a[k], diff[i][k], err);
            exact_differences = exact_differences && err == 0;
        }
    }
    if (exact_differences) {
        double det[exact::kDetTerms];
        const int n = exact::det3_exact<false>(diff[0], diff[1], diff[2], det);
        return expansion_sign(n, det);
    }
    double bcd[exact::kDetTerms], acd[exact::kDetTerms], abd[exact::kDetTerms], abc[exact::kDetTerms];
    const int n1 = exact::det3_exact<false>(b, c, d, bcd);
    const int n2 = exact::det3_exact<false>(a, c, d, acd);
    const int n3 = exact::det3_exact<false>(a, b, d, abd);
    const int n4 = exact::det3_exact<false>(a, b, c, abc);
    negate(n2, acd);
    negate(n4, abc);
    double s1[2 * exact::kDetTerms] = {}, s2[2 * exact::kDetTerms] = {}, s[4 * exact::kDetTerms] = {};
    const int m1 = exact::fast_expansion_sum(n1, bcd, n2, acd, s1);
    const int m2 = exact::fast_expansion_sum(n3, abd, n4, abc, s2);
    const int m = exact::fast_expansion_sum(m1, s1, m2, s2, s);
    return expansion_sign(m, s);
}

}  // namespace

int orient3d_sign(const double* a, const double* b, const double* c, const double* d) {
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
    const double m0 = vy * wz - vz * wy, m1 = vz * wx - vx * wz, m2 = vx * wy - vy * wx;
    const double det = ux * m0 + uy * m1 + uz * m2;
    // Shewchuk's o3derrboundA for this evaluation order.
    const double permanent = std::fabs(ux) * (std::fabs(vy * wz) + std::fabs(vz * wy)) +
                             std::fabs(uy) * (std::fabs(vz * wx) + std::fabs(vx * wz)) +
                             std::fabs(uz) * (std::fabs(vx * wy) + std::fabs(vy * wx));
    if (std::fabs(det) > (7.0 + 56.0 * kU) * kU * permanent) return sign_of(det);
    return orient3d_exact_sign(a, b, c, d);
}

int cross_component_sign(const double* u, const double* v, const double* p, const double* q, int i, int j) {
    const double left = (v[i] - u[i]) * (q[j] - p[j]);
    const double right = (v[j] - u[j]) * (q[i] - p[i]);
    const double det = left - right;
    // Shewchuk's ccwerrboundA (3 + 16u)u, rounded up to 4u.
    if (std::fabs(det) > 4.0 * kU * (std::fabs(left) + std::fabs(right))) return sign_of(det);
    // v_i q_j - v_i p_j - u_i q_j + u_i p_j - v_j q_i + v_j p_i + u_j q_i - u_j p_i, exactly.
    const double terms[8][2] = {{v[i], q[j]},  {-v[i], p[j]}, {-u[i], q[j]}, {u[i], p[j]},
                                {-v[j], q[i]}, {v[j], p[i]},  {u[j], q[i]},  {-u[j], p[i]}};
    double e[17] = {0};
    int n = 1;
    for (const auto& t : terms) {
        double prod, err;
        exact::two_prod_dekker(t[0], t[1], prod, err);
        n = exact::grow_expansion(n, e, prod, e);
        n = exact::grow_expansion(n, e, err, e);
    }
    return expansion_sign(n, e);
}

int first_cross_sign(const double* u, const double* v, const double* p, const double* q) {
    if (const int s = cross_component_sign(u, v, p, q, 1, 2)) return s;
    if (const int s = cross_component_sign(u, v, p, q, 2, 0)) return s;
    return cross_component_sign(u, v, p, q, 0, 1);
}

int perturbed_side(const double* t0, const double* t1, const double* t2, const double* x, int shift) {
    if (const int s = orient3d_sign(t0, t1, t2, x)) return s;
    return shift * first_cross_sign(t0, t1, t0, t2);
}

int perturbed_orient_edges(const double* p, const double* q, const double* u, const double* v, int shift) {
    if (const int s = orient3d_sign(p, q, u, v)) return s;
    return shift * first_cross_sign(u, v, p, q);
}

}  // namespace polyvol::boolean
