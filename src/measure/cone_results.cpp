// measure/cone_results.cpp — measure/cone_results.hpp: the results as
// rational intervals from the sums' intervals.
#include "measure/cone_results.hpp"
#include "core/bit_cast.hpp"

#include <cmath>
#include <limits>

namespace polyvol::measure::cone {
namespace {

Interval operator+(const Interval& a, const Interval& b) {
    return {a.lo + b.lo, a.hi + b.hi, a.bounded && b.bounded};
}
Interval operator-(const Interval& a, const Interval& b) {
    return {a.lo - b.hi, a.hi - b.lo, a.bounded && b.bounded};
}
Interval operator-(const Interval& a) { return {-a.hi, -a.lo, a.bounded}; }
Interval operator*(const Interval& a, const Interval& b) {
    const Rational p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    Interval r{p[0], p[0], a.bounded && b.bounded};
    for (const Rational& x : p) {
        if (x < r.lo) r.lo = x;
        if (r.hi < x) r.hi = x;
    }
    return r;
}
Interval operator/(const Interval& a, const Interval& b) {
    if (b.lo.sign() <= 0 && b.hi.sign() >= 0) return {Rational(), Rational(), false};
    const Rational one(1L);
    return a * Interval{one / b.hi, one / b.lo, b.bounded};
}
Interval operator*(const Interval& a, const Rational& c) { return a * point(c); }


}  // namespace

Interval interval(const exact::ExactSum& sum, double bound) {
    const Rational c(sum);
    if (!(bound > 0)) return point(c);
    const Rational e(bound);
    return {c - e, c + e, true};
}

// The results as intervals from the sums' intervals (count == 1: volume and
// mass only). density: a finite density (mass, moments and inertia scale).
std::vector<Result> evaluate(const std::array<Interval, kSumCount>& s, int count, const Rational& density) {
    std::vector<Result> r(static_cast<std::size_t>(result_count(count)));
    const Rational sixth(1L, 6), r24(1L, 24), r120(1L, 120);
    r[kVolume] = {s[kV] * sixth, bit(kV)};
    r[kMass] = {s[kV] * sixth * density, bit(kV)};
    if (count == 1) return r;
    const bool v_zero = s[kV].lo.sign() == 0 && s[kV].hi.sign() == 0;
    const Interval four_v = s[kV] * Rational(4L);
    const Interval v96 = s[kV] * Rational(96L);
    for (int i = 0; i < 3; ++i) {
        r[kFirst + i] = {s[kMx + i] * r24 * density, bit(kMx + i)};
        if (v_zero) {
            r[kCentroid + i] = {point(Rational()), bit(kV), true};
        } else {
            r[kCentroid + i] = {s[kMx + i] / four_v, bit(kMx + i) | bit(kV)};
        }
    }
    if (count == kSxx) return r;
    Interval second[6];
    for (int k = 0; k < 6; ++k) {
        second[k] = s[kSxx + k] * r120;
        r[kSecond + k] = {second[k] * density, bit(kSxx + k)};
    }
    // Inertia from second moments {xx,yy,zz,xy,yz,zx}.
    constexpr int A[3] = {1, 0, 0}, B[3] = {2, 2, 1};
    for (int k = 0; k < 3; ++k) {
        r[kInertiaOrigin + k] = {(second[A[k]] + second[B[k]]) * density, bit(kSxx + A[k]) | bit(kSxx + B[k])};
        r[kInertiaOrigin + 3 + k] = {-second[3 + k] * density, bit(kSxx + 3 + k)};
    }
    // Central second moments c_ij = S_ij/120 - M_i M_j / (96 ΣV).
    constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
    Interval central[6];
    uint32_t central_deps[6];
    for (int k = 0; k < 6; ++k) {
        const int i = I[k], j = J[k];
        if (!v_zero) central[k] = second[k] - (s[kMx + i] * s[kMx + j]) / v96;
        central_deps[k] = bit(kSxx + k) | bit(kMx + i) | bit(kMx + j) | bit(kV);
    }
    for (int k = 0; k < 3; ++k) {
        if (v_zero) {
            r[kInertiaCentroid + k] = {point(Rational()), bit(kV), true};
            r[kInertiaCentroid + 3 + k] = {point(Rational()), bit(kV), true};
            continue;
        }
        r[kInertiaCentroid + k] = {(central[A[k]] + central[B[k]]) * density, central_deps[A[k]] | central_deps[B[k]]};
        r[kInertiaCentroid + 3 + k] = {-central[3 + k] * density, central_deps[3 + k]};
    }
    return r;
}

// The nearest double to a result, when both ends of its interval agree.
std::optional<double> decided(const Result& r) {
    if (r.nan) return std::numeric_limits<double>::quiet_NaN();
    if (!r.iv.bounded) return std::nullopt;
    const double lo = r.iv.lo.to_double();
    const double hi = r.iv.hi.to_double();
    if (core::bit_cast<uint64_t>(lo) != core::bit_cast<uint64_t>(hi)) return std::nullopt;
    return lo;
}

// An upper bound (a double) on max(|x - lo|, |hi - x|).
double error_bound(const Result& r, double x) {
    if (r.nan) return 0;
    if (!r.iv.bounded || !std::isfinite(x)) return std::numeric_limits<double>::infinity();
    const Rational rx(x);
    const Rational d1 = rx - r.iv.lo, d2 = r.iv.hi - rx;
    const Rational& d = d1 < d2 ? d2 : d1;
    double e = d.to_double();
    if (Rational(e) < d) e = std::nextafter(e, std::numeric_limits<double>::infinity());
    return e;
}


double relative_to(double error, double magnitude) {
    if (error == 0) return 0;
    if (!(magnitude > 0)) return std::numeric_limits<double>::infinity();
    return std::nextafter(error / magnitude, std::numeric_limits<double>::infinity());
}

uint32_t undecided_sums(const std::vector<Result>& results) {
    uint32_t need = 0;
    for (const Result& r : results)
        if (!decided(r)) need |= r.deps;
    return need;
}

}  // namespace polyvol::measure::cone
