// core/charconv: the printf-based shortest text (the WebAssembly build's, where
// libc++ 13 has no floating-point std::to_chars) against std::to_chars, on
// edge values, every power of two and 300,000 random doubles; parse_double against std::from_chars.
#include "core/charconv.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using polyvol::core::Notation;

std::vector<double> samples() {
    std::vector<double> v = {0.0, -0.0, 1.0, -1.0, 0.1, 100.0, 1e15, 1e16, 1e21, 1e22, 1e23, 123456789012345680000.0,
                             9007199254740993.0, 0.0001, 0.00001, 1.5e-5, 5e-324, 2.2250738585072014e-308,
                             std::numeric_limits<double>::max(), 1.0 / 3, 2.0 / 3, 1e-7, 123.456, 1e300, 4.35, 0.3};
    for (int e = -1074; e <= 1023; ++e) v.push_back(std::ldexp(1.0, e));  // lopsided intervals
    std::mt19937_64 rng(20261129);
    for (int i = 0; i < 300000; ++i) {
        double x;
        switch (i % 4) {
            case 0: x = std::bit_cast<double>(rng()); break;                                       // any bits
            case 1: x = static_cast<double>(rng() >> (rng() % 64)); break;                        // integers
            case 2: x = std::ldexp(static_cast<double>(rng() >> 11), static_cast<int>(rng() % 120) - 100); break;
            default: x = std::round(std::bit_cast<double>(rng() & 0x3FFFFFFFFFFFFFFFull) * 1e4) / 1e4; break;
        }
        if (std::isfinite(x)) v.push_back(i % 8 < 4 ? x : -x);
    }
    return v;
}

std::string std_text(double x) {
    char b[400];
    return {b, std::to_chars(b, b + sizeof b, x).ptr};
}
std::string std_text(double x, std::chars_format f) {
    char b[400];
    return {b, std::to_chars(b, b + sizeof b, x, f).ptr};
}
std::string portable(double x) {
    char b[400];
    return {b, polyvol::core::portable_shortest_chars(b, b + sizeof b, x).ptr};
}
std::string portable(double x, Notation f) {
    char b[400];
    return {b, polyvol::core::portable_shortest_chars(b, b + sizeof b, x, f).ptr};
}

TEST(Charconv, PortableShortestIsStdToChars) {
    int failures = 0;
    for (const double x : samples()) {
        const std::string a = portable(x), b = std_text(x);
        if (a != b && ++failures < 20) ADD_FAILURE() << "plain " << b << " portable " << a;
        const std::string g = portable(x, Notation::general), h = std_text(x, std::chars_format::general);
        if (g != h && ++failures < 20) ADD_FAILURE() << "general " << h << " portable " << g;
        if (std::fabs(x) < 1e30) {
            const std::string f = portable(x, Notation::fixed), e = std_text(x, std::chars_format::fixed);
            if (f != e && ++failures < 20) ADD_FAILURE() << "fixed " << e << " portable " << f;
        }
    }
    EXPECT_EQ(failures, 0);
}

TEST(Charconv, TooSmallABufferIsAnError) {
    char b[3];
    EXPECT_EQ(polyvol::core::portable_shortest_chars(b, b + 3, 0.125).ec, std::errc::value_too_large);
}

TEST(Charconv, ParseDoubleIsStdFromChars) {
    for (const char* s : {"1", "0.1", "1e-400", "1e400", "-2.5e-3", "4.35", "abc", "+1", "0x10", "1.5kg", ".5", "inf", "nan"}) {
        const std::string t = s;
        double a = -7, b = -7;
        const auto r = polyvol::core::parse_double(t.data(), t.data() + t.size(), a);
        const auto q = std::from_chars(t.data(), t.data() + t.size(), b);
        EXPECT_EQ(r.ec == std::errc(), q.ec == std::errc()) << s;
        if (q.ec == std::errc()) {
            EXPECT_EQ(r.ptr, q.ptr) << s;
            EXPECT_EQ(std::bit_cast<uint64_t>(a), std::bit_cast<uint64_t>(b)) << s;
        }
    }
}

}  // namespace
