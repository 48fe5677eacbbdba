// principal_inertia: the principal moments and axes of a box's inertia in
// closed form, also turned by a rotation (R D R^T, the axes R's columns),
// each within its stated bound; equal moments leave their axes undetermined.
#include <gtest/gtest.h>

#include <cmath>

#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

// {xx, yy, zz, xy, yz, zx} of R diag(d) R^T.
std::array<double, 6> turned(const double r[3][3], const std::array<double, 3>& d) {
    double a[3][3] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) a[i][j] += r[i][k] * d[static_cast<std::size_t>(k)] * r[j][k];
    return {a[0][0], a[1][1], a[2][2], a[0][1], a[1][2], a[2][0]};
}

TEST(PrincipalInertia, ABoxInClosedForm) {
    // The box 1 x 2 x 3 of mass 6: I = m (b² + c²) / 12 ... = 6.5, 5, 2.5 about x, y, z.
    const PrincipalInertia p = principal_inertia({6.5, 5, 2.5, 0, 0, 0}, 0x1p-53);
    EXPECT_NEAR(p.moments[0], 2.5, p.moment_error);
    EXPECT_NEAR(p.moments[1], 5, p.moment_error);
    EXPECT_NEAR(p.moments[2], 6.5, p.moment_error);
    EXPECT_LT(p.moment_error, 1e-13);
    const std::array<double, 3> z{0, 0, 1}, y{0, 1, 0}, x{-1, 0, 0};
    EXPECT_EQ(p.axes[0], z);
    EXPECT_EQ(p.axes[1], y);
    EXPECT_EQ(p.axes[2], x);  // right-handed: z × y = -x
}

TEST(PrincipalInertia, ATurnedBoxWithinTheBounds) {
    // A rotation by the 3-4-5 triangle about z, then 5-12-13 about x.
    const double c1 = 0.6, s1 = 0.8, c2 = 5.0 / 13, s2 = 12.0 / 13;
    const double rz[3][3] = {{c1, -s1, 0}, {s1, c1, 0}, {0, 0, 1}};
    const double rx[3][3] = {{1, 0, 0}, {0, c2, -s2}, {0, s2, c2}};
    double r[3][3] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) r[i][j] += rx[i][k] * rz[k][j];
    const std::array<double, 3> d{2.5, 5, 6.5};
    const double relative = 1e-12;  // as if the tensor came with this bound
    const PrincipalInertia p = principal_inertia(turned(r, d), relative);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(p.moments[k], d[k], p.moment_error) << k;
        // The axis is R's column k, up to sign.
        double dot = 0;
        for (int i = 0; i < 3; ++i) dot += p.axes[k][static_cast<std::size_t>(i)] * r[i][k];
        EXPECT_GE(std::fabs(dot), std::cos(p.axis_angle[k]) - 1e-15) << k;
        EXPECT_LT(p.axis_angle[k], 1e-10) << k;
    }
    EXPECT_GT(p.moment_error, 3 * relative * 5);  // the tensor's own error is in it
}

TEST(PrincipalInertia, EqualMomentsLeaveTheirAxesUndetermined) {
    const PrincipalInertia p = principal_inertia({4, 4, 1, 0, 0, 0}, 0x1p-53);
    EXPECT_NEAR(p.moments[0], 1, p.moment_error);
    EXPECT_LT(p.axis_angle[0], 1e-13);     // the odd one out is determined
    EXPECT_TRUE(std::isinf(p.axis_angle[1]));
    EXPECT_TRUE(std::isinf(p.axis_angle[2]));
}

}  // namespace
}  // namespace polyvol
