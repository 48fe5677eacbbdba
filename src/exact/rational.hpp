// exact/rational.hpp — exact rationals (GMP's mpq_t) for the few operations
// per mesh that need them: converting exact sums, forming derived
// quantities (centroid, central moments) exactly or as rigorous intervals,
// and rounding once to the nearest double.
//
// mpq_get_d truncates; to_double() below rounds to nearest, ties to even,
// with gradual underflow (results below 2^-1022 are rounded at 2^-1074) and
// overflow to ±inf, exactly as an IEEE operation with an exact intermediate
// would.
#pragma once

#include <gmp.h>

#include <cstdint>
#include <string>

#include "exact/exact_sum.hpp"

namespace polyvol::exact {

class Rational {
public:
    Rational() { mpq_init(q_); }
    explicit Rational(double x);   // exact; x must be finite
    explicit Rational(long n, unsigned long d = 1);
    explicit Rational(const ExactSum& s);  // exact; s must be finite()
    Rational(const Rational& o) {
        mpq_init(q_);
        mpq_set(q_, o.q_);
    }
    Rational(Rational&& o) noexcept {
        mpq_init(q_);
        mpq_swap(q_, o.q_);
    }
    Rational& operator=(const Rational& o) {
        if (this != &o) mpq_set(q_, o.q_);
        return *this;
    }
    Rational& operator=(Rational&& o) noexcept {
        mpq_swap(q_, o.q_);
        return *this;
    }
    ~Rational() { mpq_clear(q_); }

    mpq_srcptr get() const { return q_; }
    mpq_ptr get() { return q_; }

    int sign() const { return mpq_sgn(q_); }
    // The nearest double, ties to even.
    double to_double() const;
    std::string str() const;

    friend Rational operator+(const Rational& a, const Rational& b);
    friend Rational operator-(const Rational& a, const Rational& b);
    friend Rational operator*(const Rational& a, const Rational& b);
    friend Rational operator/(const Rational& a, const Rational& b);  // b != 0
    friend Rational operator-(const Rational& a);
    friend bool operator<(const Rational& a, const Rational& b) { return mpq_cmp(a.q_, b.q_) < 0; }
    friend bool operator==(const Rational& a, const Rational& b) { return mpq_equal(a.q_, b.q_) != 0; }

private:
    mpq_t q_;
};

// The nearest double to n / d (d != 0), ties to even.
double round_to_double(mpq_srcptr q);

}  // namespace polyvol::exact
