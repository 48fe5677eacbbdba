// core/portable_math.hpp — functions whose results are the same bits on every
// platform: the native build's libm (glibc) and the WebAssembly build's
// (musl) round atan2 and asin differently in the last bit, and a figure
// printed from them would differ. These use only +, −, ×, ÷ and sqrt, each
// correctly rounded by IEEE 754, in a fixed order (no contraction).
#pragma once

#include <cmath>
#include <numbers>

namespace polyvol::core {

// atan t for 0 <= t <= 1. Two halvings, atan t = 2 atan(t / (1 + √(1 + t²))),
// leave u <= tan(π/16) < 0.2, where Σ (−1)^n u^(2n+1) / (2n + 1) to n = 11
// is within u^25 / 25 < 2^-60 u of atan u.
inline double portable_atan_unit(double t) {
    double u = t;
    for (int i = 0; i < 2; ++i) u = u / (1 + std::sqrt(1 + u * u));
    const double u2 = u * u;
    double s = 0;
    for (int n = 11; n >= 0; --n) s = (n % 2 ? -1.0 : 1.0) / (2 * n + 1) + u2 * s;
    return 4 * (u * s);
}

// atan2(y, x) with the standard's quadrants and signed zeros (NaN for NaN),
// within a few ulps of the exact angle.
inline double portable_atan2(double y, double x) {
    constexpr double pi = std::numbers::pi;
    if (std::isnan(x) || std::isnan(y)) return x + y;
    const double ay = std::fabs(y), ax = std::fabs(x);
    double r;
    if (ay == 0) {
        r = std::signbit(x) ? pi : 0.0;
    } else if (ax == 0) {
        r = pi / 2;
    } else {
        // atan(|y| / |x|), through 1 / t above 1: atan t = π/2 − atan(1/t).
        r = ay <= ax ? portable_atan_unit(ay / ax) : pi / 2 - portable_atan_unit(ax / ay);
        if (std::signbit(x)) r = pi - r;
    }
    return std::signbit(y) ? -r : r;
}

// An upper bound on asin s (0 <= s < 1), the same bits in every build (a
// libm's asin is not): asin s = atan(s / √(1 − s²)), computed within a few
// ulps (about 10 roundings of relative u, the series within 2^-60), then
// raised by 2^-40. Below 2^-400, asin s − s = s³/6 + ... < 2^-1074.
inline double asin_upper_bound(double s) {
    if (s == 0) return 0;
    if (s < 0x1p-400) return std::nextafter(s, 1.0);
    return portable_atan2(s, std::sqrt((1 - s) * (1 + s))) * (1 + 0x1p-40);
}

}  // namespace polyvol::core
