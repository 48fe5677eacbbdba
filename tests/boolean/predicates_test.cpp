// The boolean module's exact predicates and filters against rational
// arithmetic: orient3d_sign on exactly coplanar points (where only the
// exact path can answer 0), on points one ulp off a plane, and on
// coordinates of mixed magnitudes (whose differences are not doubles, the
// four-determinant path); the float boxes rounded outward.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <random>

#include "boolean/operand.hpp"
#include "boolean/predicates.hpp"

namespace polyvol::boolean {
namespace {

// orient(a, b, c, d) = det(b - a, c - a, d - a), in rationals.
int rational_orient(const double* a, const double* b, const double* c, const double* d) {
    mpq_class u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = mpq_class(b[k]) - mpq_class(a[k]);
        v[k] = mpq_class(c[k]) - mpq_class(a[k]);
        w[k] = mpq_class(d[k]) - mpq_class(a[k]);
    }
    const mpq_class det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                          u[2] * (v[0] * w[1] - v[1] * w[0]);
    return sgn(det);
}

TEST(Predicates, Orient3dIsExactOnPlanesAndNearThem) {
    std::mt19937_64 rng(36);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<int> magnitude(-150, 170);
    int zeros = 0, positive = 0, negative = 0;
    for (int trial = 0; trial < 6000; ++trial) {
        const double scale = std::ldexp(1.0, magnitude(rng) / 4);
        double p[4][3];
        for (int i = 0; i < 3; ++i)
            for (double& x : p[i]) x = unit(rng) * scale;
        if (trial % 2 == 0) {
            // Four points on the plane z = h: orient is exactly 0 (or, one
            // ulp off it, as small as it gets).
            for (int i = 0; i < 3; ++i) p[i][2] = p[0][2];
            p[3][0] = unit(rng) * scale;
            p[3][1] = unit(rng) * scale;
            p[3][2] = trial % 4 == 0 ? p[0][2] : std::nextafter(p[0][2], INFINITY);
        } else {
            // d = a + s (b - a) + t (c - a) rounded: within rounding of a
            // tilted plane, where the filter cannot decide.
            const double s = unit(rng), t = unit(rng);
            for (int k = 0; k < 3; ++k) p[3][k] = p[0][k] + s * (p[1][k] - p[0][k]) + t * (p[2][k] - p[0][k]);
        }
        // Some trials: a coordinate of another magnitude, so that the
        // differences are not doubles (the four-determinant path).
        if (trial % 5 == 2) {
            const double y = unit(rng) * std::ldexp(1.0, magnitude(rng));
            for (auto& q : p) q[1] += y;  // every point moved alike: the same orient, rounded differently
        }
        const int expected = rational_orient(p[0], p[1], p[2], p[3]);
        EXPECT_EQ(orient3d_sign(p[0], p[1], p[2], p[3]), expected) << "trial " << trial;
        (expected == 0 ? zeros : expected > 0 ? positive : negative) += 1;
    }
    EXPECT_GT(zeros, 500);  // every outcome was exercised
    EXPECT_GT(positive, 500);
    EXPECT_GT(negative, 500);
}

TEST(Predicates, FloatBoxesHoldTheirDoublesAndAreTheNearestFloats) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<int> exponent(-160, 180);
    const double special[] = {0.0, -0.0, 1.0, -1.0, 0.1, -0.1, double(FLT_MAX), -double(FLT_MAX), 0x1p128, -0x1p128,
                              0x1p180, -0x1p180, 0x1p-160, -0x1p-160, double(FLT_TRUE_MIN), 0x1p-150, -0x1p-150};
    auto check = [](double x) {
        const float lo = box_below(x), hi = box_above(x);
        EXPECT_LE(double(lo), x) << x;
        EXPECT_GE(double(hi), x) << x;
        // Nearest: the next float up from lo (down from hi) is past x.
        EXPECT_GT(double(std::nextafter(lo, INFINITY)), x) << x;
        EXPECT_LT(double(std::nextafter(hi, -INFINITY)), x) << x;
    };
    for (const double x : special) check(x);
    for (int i = 0; i < 100000; ++i) check(unit(rng) * std::ldexp(1.0, exponent(rng)));
}

}  // namespace
}  // namespace polyvol::boolean
