// core/portable_math: atan2 within a few ulps of the C library's, with its
// quadrants and signed zeros; asin_upper_bound above asin (x87's asinl, 64
// bits) and within 2^-38 of it.
#include "core/portable_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace {

using polyvol::core::asin_upper_bound;
using polyvol::core::portable_atan2;

TEST(PortableMath, Atan2IsWithinFourUlpsOfTheLibrarys) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::uniform_int_distribution<int> exponent(-60, 60);
    for (int i = 0; i < 200000; ++i) {
        const double y = std::ldexp(unit(rng), exponent(rng)), x = std::ldexp(unit(rng), exponent(rng));
        const double a = portable_atan2(y, x), b = std::atan2(y, x);
        ASSERT_LE(std::fabs(a - b), 4 * std::numeric_limits<double>::epsilon() * std::fabs(b) + 0x1p-1074) << y << ", " << x;
    }
}

TEST(PortableMath, Atan2KeepsTheQuadrantsAndSignedZeros) {
    const double inf = std::numeric_limits<double>::infinity(), pi = std::numbers::pi;
    for (const double y : {0.0, -0.0, 1.0, -1.0, 1e-300, -1e300, inf, -inf})
        for (const double x : {0.0, -0.0, 1.0, -1.0, 1e-300, -1e300, inf, -inf}) {
            if (std::isinf(x) && std::isinf(y)) continue;  // ±π/4, ±3π/4: not needed
            const double a = portable_atan2(y, x), b = std::atan2(y, x);
            EXPECT_EQ(std::signbit(a), std::signbit(b)) << y << ", " << x;
            EXPECT_NEAR(a, b, 4e-16 * pi) << y << ", " << x;
        }
    EXPECT_TRUE(std::isnan(portable_atan2(std::nan(""), 1.0)));
    EXPECT_EQ(portable_atan2(0.0, -1.0), pi);
    EXPECT_EQ(portable_atan2(1.0, 0.0), pi / 2);
}

TEST(PortableMath, AsinUpperBoundIsAboveAsinAndTight) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int i = 0; i < 100000; ++i) {
        const double s = i % 2 ? unit(rng) : std::ldexp(unit(rng), -static_cast<int>(rng() % 1000));
        if (!(s < 1)) continue;
        const double bound = asin_upper_bound(s);
        const long double exact = std::asin(static_cast<long double>(s));
        ASSERT_GE(static_cast<long double>(bound), exact) << s;
        ASSERT_LE(static_cast<long double>(bound), exact * (1 + 0x1p-38L) + 0x1p-1074L) << s;
    }
    EXPECT_EQ(asin_upper_bound(0.0), 0.0);
    EXPECT_GE(asin_upper_bound(0.5), std::asin(0.5L));
    EXPECT_GE(static_cast<long double>(asin_upper_bound(std::nextafter(1.0, 0.0))), std::asin(static_cast<long double>(std::nextafter(1.0, 0.0))));
}

}  // namespace
