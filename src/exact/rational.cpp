// exact/rational.cpp — GMP bridge: exact conversions and correct rounding.
#include "exact/rational.hpp"

#include <cmath>
#include <memory>

namespace polyvol::exact {

Rational::Rational(double x) {
    mpq_init(q_);
    mpq_set_d(q_, x);  // exact for finite doubles
}

Rational::Rational(long n, unsigned long d) {
    mpq_init(q_);
    mpq_set_si(q_, n, d);
    mpq_canonicalize(q_);
}

Rational::Rational(const ExactSum& s) {
    mpq_init(q_);
    ExactSum t = s;
    t.normalize();
    const int64_t* c = t.chunks();
    mpz_t z;
    mpz_init_set_si(z, static_cast<long>(c[ExactSum::kChunks - 1]));
    for (int k = ExactSum::kChunks - 2; k >= 0; --k) {
        mpz_mul_2exp(z, z, 32);
        mpz_add_ui(z, z, static_cast<unsigned long>(c[k]));
    }
    mpq_set_z(q_, z);
    mpq_div_2exp(q_, q_, static_cast<mp_bitcnt_t>(-ExactSum::kUnitExponent));  // canonical
    mpz_clear(z);
}

std::string Rational::str() const {
    std::unique_ptr<char, void (*)(void*)> s(mpq_get_str(nullptr, 10, q_), [](void* p) {
        void (*freefunc)(void*, size_t);
        mp_get_memory_functions(nullptr, nullptr, &freefunc);
        freefunc(p, std::char_traits<char>::length(static_cast<char*>(p)) + 1);
    });
    return std::string(s.get());
}

double Rational::to_double() const { return round_to_double(q_); }

Rational operator+(const Rational& a, const Rational& b) {
    Rational r;
    mpq_add(r.q_, a.q_, b.q_);
    return r;
}
Rational operator-(const Rational& a, const Rational& b) {
    Rational r;
    mpq_sub(r.q_, a.q_, b.q_);
    return r;
}
Rational operator*(const Rational& a, const Rational& b) {
    Rational r;
    mpq_mul(r.q_, a.q_, b.q_);
    return r;
}
Rational operator/(const Rational& a, const Rational& b) {
    Rational r;
    mpq_div(r.q_, a.q_, b.q_);
    return r;
}
Rational operator-(const Rational& a) {
    Rational r;
    mpq_neg(r.q_, a.q_);
    return r;
}

double round_to_double(mpq_srcptr q) {
    const int sgn = mpq_sgn(q);
    if (sgn == 0) return 0.0;
    mpz_t num, den, quo, rem;
    mpz_init(num);
    mpz_init_set(den, mpq_denref(q));
    mpz_init(quo);
    mpz_init(rem);
    mpz_abs(num, mpq_numref(q));
    // Choose a scale 2^e so that quo = floor(|q| / 2^e) has 66 or 67 bits:
    // then the result's ulp (>= 2^(e+13)) is far above quo's unit, and the
    // remainder only says "a little more" (a sticky bit).
    const long bn = static_cast<long>(mpz_sizeinbase(num, 2));
    const long bd = static_cast<long>(mpz_sizeinbase(den, 2));
    const long e = bn - bd - 66;
    if (e >= 0) {
        mpz_mul_2exp(den, den, static_cast<mp_bitcnt_t>(e));
    } else {
        mpz_mul_2exp(num, num, static_cast<mp_bitcnt_t>(-e));
    }
    mpz_tdiv_qr(quo, rem, num, den);
    const bool sticky = mpz_sgn(rem) != 0;
    uint64_t digits[3] = {};
    for (int i = 0; i < 3; ++i) {
        digits[i] = mpz_get_ui(quo) & 0xFFFFFFFFu;  // quo < 2^67
        mpz_tdiv_q_2exp(quo, quo, 32);
    }
    double r;
    if (e > 2000) {
        r = sgn < 0 ? -HUGE_VAL : HUGE_VAL;
    } else if (e < -2000) {
        r = sgn < 0 ? -0.0 : 0.0;
    } else {
        r = round_digits(digits, 3, static_cast<int>(e), sticky, sgn < 0);
    }
    mpz_clear(num);
    mpz_clear(den);
    mpz_clear(quo);
    mpz_clear(rem);
    return r;
}

}  // namespace polyvol::exact
