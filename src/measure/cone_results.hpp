// measure/cone_results.hpp — private: the cone rule's results (volume,
// mass, first moments, centroid, second moments, inertia) from its sums
// known as intervals, in exact rational arithmetic (GMP). Every route to the
// sums — a loaded mesh (mass_properties.cpp), streamed float32 records
// (soup.cpp) — decides its results here, so they carry the same guarantee:
//   V = ΣV/6, ∫x_i = ΣM_i/24, ∫x_i x_j = ΣS_ij/120, centroid_i = ΣM_i/(4 ΣV),
//   central second moment c_ij = ΣS_ij/120 - ΣM_i ΣM_j / (96 ΣV)
//   (the parallel axis theorem, exact: no cancellation error),
//   inertia xx = c_yy + c_zz, xy = -c_xy, ...
// A result is correctly rounded when both ends of its interval round to the
// same double; otherwise the sums it depends on are recomputed exactly.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "exact/exact_sum.hpp"
#include "exact/rational.hpp"
#include "measure/cone.hpp"

namespace polyvol::measure::cone {

using exact::Rational;

// A closed interval of rationals; unbounded when it came from a division by
// an interval containing 0.
struct Interval {
    Rational lo, hi;
    bool bounded = true;
};

inline Interval point(const Rational& x) { return {x, x, true}; }

// sum ± bound (a point when bound is 0).
Interval interval(const exact::ExactSum& sum, double bound);

// One result: its interval and the sums it depends on (a bit mask).
struct Result {
    Interval iv;
    uint32_t deps = 0;
    bool nan = false;  // exactly undefined (centroid of a zero volume)
};

enum ResultIndex : int {
    kVolume = 0,
    kMass,
    kFirst,                 // 3
    kCentroid = kFirst + 3,  // 3
    kSecond = kCentroid + 3,  // 6
    kInertiaOrigin = kSecond + 6,
    kInertiaCentroid = kInertiaOrigin + 6,
    kResultCount = kInertiaCentroid + 6
};

inline constexpr uint32_t bit(int k) { return 1u << k; }

// Results from the first `count` sums: volume and mass (1), and the first
// moments and centroid (kSxx), and the rest (kSumCount).
inline constexpr int result_count(int count) { return count == 1 ? 2 : count == kSxx ? int{kSecond} : int{kResultCount}; }

// The results as intervals from the sums' intervals (count == 1: volume and
// mass only). density: a finite density (mass, moments and inertia scale).
std::vector<Result> evaluate(const std::array<Interval, kSumCount>& s, int count, const Rational& density);

// The nearest double to a result, when both ends of its interval agree.
std::optional<double> decided(const Result& r);

// An upper bound (a double) on max(|x - lo|, |hi - x|).
double error_bound(const Result& r, double x);

// error / magnitude rounded up: a bound relative to the largest magnitude
// of an array (MassProperties::moments_relative_error); 0 when the error is
// 0, infinite when no magnitude is above 0 (no relative bound carries it).
double relative_to(double error, double magnitude);

// The sums (a mask of bits 1 << k) that the undecided results depend on;
// 0 when every result is decided.
uint32_t undecided_sums(const std::vector<Result>& results);

}  // namespace polyvol::measure::cone
