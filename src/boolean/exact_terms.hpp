// boolean/exact_terms.hpp — private: the pieces' volume as exact parts, and
// its correct rounding without one giant rational.
//
// Coordinates are x = X 2^e0 with integers X (e0: the lowest set bit over
// every coordinate used). Crossing points and their contributions are then
// exact integer ratios. 6 × a volume of pieces is held as
//   whole      exact double expansions (ExactSum, real units)
//   integer    an integer in units of 2^(3 e0)
//   fractions  N / D, D > 0, in units of 2^(3 e0)
// and rounded by intervals: each fraction as floor(N 2^k / D) 2^-k, so the
// truth lies within n 2^-k above the sum; k grows until the rounding is
// decided, and exact rationals settle what no interval can (a result that is
// exactly a double or a tie).
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::boolean {

using IntPoint = std::array<mpz_class, 3>;

struct Scale {
    int e0 = 0;
    mpz_class of(double x) const { return mpz_class(std::ldexp(x, -e0)); }
    IntPoint of(const double* p) const { return {of(p[0]), of(p[1]), of(p[2])}; }
    // of(p) into existing integers (no allocation once they are large enough).
    void set(IntPoint& out, const double* p) const {
        for (int k = 0; k < 3; ++k) mpz_set_d(out[k].get_mpz_t(), std::ldexp(p[k], -e0));
    }
};

// The exponent of the lowest set bit of x != 0.
int lowest_bit_exponent(double x);

// A coordinate the exact predicates and the integer scaling take: the
// expansions' safe range (exact/eft.hpp) and at most 2^180 in magnitude.
inline bool in_predicate_range(double x) { return exact::in_safe_range(x) && std::fabs(x) <= 0x1p180; }

// a · (b × c)
mpz_class det3(const IntPoint& a, const IntPoint& b, const IntPoint& c);

// The integers det3_into and orient_into use, kept from call to call by one thread:
// GMP then allocates only while they grow (most terms of a boolean reuse them).
struct DetScratch {
    IntPoint u, v, w;
    mpz_class t;
};
// out = det3(a, b, c); out must not be t.
void det3_into(mpz_class& out, const IntPoint& a, const IntPoint& b, const IntPoint& c, mpz_class& t);
// out = orient(s0, s1, s2, x) = det(s1 - s0, s2 - s0, x - s0).
void orient_into(mpz_class& out, const IntPoint& s0, const IntPoint& s1, const IntPoint& s2, const IntPoint& x,
                 DetScratch& scratch);

// Where segment p -> q crosses the plane with orient values D_p, D_q
// (opposite signs, or one zero): num / den = (D_p q - D_q p) / (D_p - D_q)
// with den > 0; exactly p (or q), den = 1, when D_p (or D_q) is 0.
struct ExactPoint {
    IntPoint num;
    mpz_class den;
};
ExactPoint plane_crossing(const IntPoint& p, const IntPoint& q, const mpz_class& dp, const mpz_class& dq);
// The same into x (whose integers are reused).
void plane_crossing_into(ExactPoint& x, const IntPoint& p, const IntPoint& q, const mpz_class& dp, const mpz_class& dq);

// n / d 2^e in double (relative error below 2^-51), without overflow on the way.
double approx_ratio(const mpz_class& n, const mpz_class& d, int e);

double norm3(const double* v);

// A triangle's normal N = (b - a) × (c - a) in double, |N|, and a bound on
// |N|'s error: 16u |b - a| |c - a|.
struct Geometry {
    double normal_length;
    double normal_error;
    double n[3];
};
Geometry triangle_geometry(const double* a, const double* b, const double* c);

// 2 × an area: terms summed exactly, with the sum of their error bounds.
struct AreaSum {
    exact::ExactSum sum;
    double bound = 0;
    void add(double value, double error) {
        sum.add(value);
        bound += error;
    }
    void merge(const AreaSum& other) {
        sum.merge(other.sum);
        bound += other.bound;
    }
};

// 2 × the vector area ∫ n dA of pieces of triangles: each term is a signed
// area term s (an AreaSum term, error e) of one triangle, times the
// triangle's unit normal N/|N|, summed exactly per component. Bound, per
// component: e + 4u|s| + 2 × the normal's error (|s| <= |N|, so the unit
// normal's error, 2 × normal_error / |N|, costs at most that).
struct VectorAreaSum {
    exact::ExactSum sum[3];
    double bound = 0;
    void add(double s, double e, const Geometry& g) {
        bound += e + 4 * 0x1p-53 * std::fabs(s) + 2 * g.normal_error;
        if (!(g.normal_length > 0)) return;
        for (int k = 0; k < 3; ++k) sum[k].add(s * (g.n[k] / g.normal_length));
    }
    void merge(const VectorAreaSum& other) {
        for (int k = 0; k < 3; ++k) sum[k].merge(other.sum[k]);
        bound += other.bound;
    }
};

// The part of B's surface inside A, as intersection_given_windings can give
// it: 2 × its area and 2 × its vector area, with their bounds.
struct SurfaceInside {
    AreaSum area;
    VectorAreaSum normal;
};

// 6 × the volume of some pieces, in three exact parts (see the top).
struct PieceSum {
    exact::ExactSum whole;
    double whole_bound = 0;  // |whole - its exact value| <= whole_bound (0: exact)
    mpz_class integer;
    std::vector<std::pair<mpz_class, mpz_class>> fractions;

    void add_fraction(mpz_class n, mpz_class d);  // any signs; d != 0
};

// 6 × the volume of a triangle mesh's cone sum: measure's double-double sum
// with its bound, or (exactly) the exact sum with bound 0. Coordinates in
// the exact kernels' safe range.
struct VolumeSum {
    exact::ExactSum sum;
    double bound = 0;
};
VolumeSum cone_volume_sum(const MeshView& triangles, bool exactly);

// Adds the integer z 2^exponent to sum exactly (2^exponent >= 2^-1074).
void add_integer(exact::ExactSum& sum, const mpz_class& z, int exponent);

// One result to round: (base + sign × pieces) / divisor.
struct Combination {
    const exact::ExactSum* base;  // nullptr: 0
    int sign;                     // +1 or -1
    double base_bound = 0;        // |base - its exact value| <= base_bound
};

// Each combination's exact value over `divisor`, rounded once to the
// nearest double; the pieces' integers and fractions are in units of
// 2^(degree e0) (3 for volumes, 4 for first moments, 5 for second).
// refinements: the interval rounds it took (-1: exact rationals). Empty
// when a bound on the whole part or a base is not 0 and the intervals leave
// the rounding undecided: the caller then computes those exactly and asks again.
std::vector<double> round_combinations(const PieceSum& pieces, int e0, std::span<const Combination> results,
                                       int& refinements, int degree = 3, uint32_t divisor = 6);

}  // namespace polyvol::boolean
