// boolean/symbolic.hpp — exact values as polynomials in the perturbation ε,
// for the decisions where three bodies meet.
//
// A vertex of a body moved by k δ, δ = (ε, ε², ε³), has the coordinates
// (X + k ε, Y + k ε², Z + k ε³) (X, Y, Z its integers, exact_terms.hpp). A
// predicate is the sign of a polynomial in ε with integer coefficients; for
// ε -> 0+ that is the sign of its first nonzero coefficient. The pairwise
// predicates (predicates.hpp) need only the first-order term; where a point
// defined by two bodies is tested against a third, products of such
// polynomials are needed, and EpsPoly computes them in full.
#pragma once

#include <gmpxx.h>

#include <array>
#include <vector>

#include "boolean/exact_terms.hpp"

namespace polyvol::boolean {

class EpsPoly {
public:
    EpsPoly() = default;
    EpsPoly(mpz_class constant) : c_{std::move(constant)} {}  // NOLINT: implicit, like a number
    EpsPoly(std::vector<mpz_class> coefficients) : c_(std::move(coefficients)) {}

    // The sign for ε -> 0+: of the first nonzero coefficient.
    int sign() const {
        for (const mpz_class& x : c_)
            if (x != 0) return sgn(x);
        return 0;
    }
    friend EpsPoly operator+(const EpsPoly& a, const EpsPoly& b) { return combine(a, b, +1); }
    friend EpsPoly operator-(const EpsPoly& a, const EpsPoly& b) { return combine(a, b, -1); }
    friend EpsPoly operator-(const EpsPoly& a) { return combine(EpsPoly(), a, -1); }
    friend EpsPoly operator*(const EpsPoly& a, const EpsPoly& b) {
        if (a.c_.empty() || b.c_.empty()) return EpsPoly();
        std::vector<mpz_class> r(a.c_.size() + b.c_.size() - 1);
        for (std::size_t i = 0; i < a.c_.size(); ++i)
            if (a.c_[i] != 0)
                for (std::size_t j = 0; j < b.c_.size(); ++j) r[i + j] += a.c_[i] * b.c_[j];
        return EpsPoly(std::move(r));
    }

private:
    static EpsPoly combine(const EpsPoly& a, const EpsPoly& b, int sign) {
        std::vector<mpz_class> r(std::max(a.c_.size(), b.c_.size()));
        for (std::size_t i = 0; i < a.c_.size(); ++i) r[i] = a.c_[i];
        for (std::size_t i = 0; i < b.c_.size(); ++i) r[i] += sign * b.c_[i];
        return EpsPoly(std::move(r));
    }
    std::vector<mpz_class> c_;
};

using EpsPoint = std::array<EpsPoly, 3>;

// A point's coordinates as exact rationals (the doubles as they are), for
// orient_of<mpq_class> where a point is not on the integer grid (a centroid).
using RationalPoint = std::array<mpq_class, 3>;
inline RationalPoint rational_point(const double* p) { return {mpq_class(p[0]), mpq_class(p[1]), mpq_class(p[2])}; }

// The point (X, Y, Z) of a body moved by k δ.
inline EpsPoint moved_point(const IntPoint& p, int32_t k) {
    const mpz_class m = k;
    return {EpsPoly({p[0], m}), EpsPoly({p[1], 0, m}), EpsPoly({p[2], 0, 0, m})};
}

// a · (b × c) and orient(s0, s1, s2, x) over any number type N (mpz_class or EpsPoly).
template <class N>
N det3_of(const std::array<N, 3>& a, const std::array<N, 3>& b, const std::array<N, 3>& c) {
    N r = a[0] * (b[1] * c[2] - b[2] * c[1]);
    r = r + a[1] * (b[2] * c[0] - b[0] * c[2]);
    r = r + a[2] * (b[0] * c[1] - b[1] * c[0]);
    return r;
}
template <class N>
N orient_of(const std::array<N, 3>& s0, const std::array<N, 3>& s1, const std::array<N, 3>& s2,
            const std::array<N, 3>& x) {
    const std::array<N, 3> u = {s1[0] - s0[0], s1[1] - s0[1], s1[2] - s0[2]};
    const std::array<N, 3> v = {s2[0] - s0[0], s2[1] - s0[1], s2[2] - s0[2]};
    const std::array<N, 3> w = {x[0] - s0[0], x[1] - s0[1], x[2] - s0[2]};
    return det3_of<N>(u, v, w);
}

}  // namespace polyvol::boolean
