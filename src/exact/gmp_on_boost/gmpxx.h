// exact/gmp_on_boost/gmpxx.h — the part of gmpxx's mpz_class and mpq_class polyvol
// uses, over the cpp_int of gmp_on_boost/gmp.h (-DPOLYVOL_BIGINT=boost only).
// Values, not expression templates: the same results, more temporaries. As in
// gmpxx, `/` and `%` on integers truncate toward zero, `>>` floors (Boost's
// does not), the
// rational's (num, den) constructor does not canonicalize, and every other
// rational operation does. A double mixed with a rational is converted exactly,
// as gmpxx does; mixed with an integer it is refused at compile time (gmpxx
// would truncate it, and nothing here needs that).
#pragma once

#include "gmp.h"

#include <cctype>
#include <concepts>
#include <cstdlib>
#include <ios>
#include <ostream>
#include <string>

namespace polyvol::gmp_on_boost {

namespace detail {
// x in base 10 or 16 (lower-case digits), with a leading '-' when negative.
inline std::string text(const Int& x, int base) {
    if (base != 10 && base != 16) std::abort();
    const Int m = boost::multiprecision::abs(x);
    std::string s = base == 10 ? m.str() : m.str(0, std::ios::hex);
    for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return x.sign() < 0 ? "-" + s : s;
}
}  // namespace detail

class mpz_class {
public:
    mpz_class() = default;
    template <std::integral T>
    mpz_class(T x) {  // NOLINT: implicit, as gmpxx
        z_.v = x;
    }
    explicit mpz_class(double d) { mpz_set_d(&z_, d); }
    explicit mpz_class(mpz_srcptr z) : z_(*z) {}
    explicit mpz_class(Int v) { z_.v = std::move(v); }

    mpz_ptr get_mpz_t() { return &z_; }
    mpz_srcptr get_mpz_t() const { return &z_; }
    const Int& value() const { return z_.v; }
    double get_d() const { return mpz_get_d(&z_); }
    std::string get_str(int base = 10) const { return detail::text(z_.v, base); }
    void swap(mpz_class& o) noexcept { z_.v.swap(o.z_.v); }

    mpz_class& operator+=(const mpz_class& b) { return z_.v += b.z_.v, *this; }
    mpz_class& operator-=(const mpz_class& b) { return z_.v -= b.z_.v, *this; }
    mpz_class& operator*=(const mpz_class& b) { return z_.v *= b.z_.v, *this; }
    mpz_class& operator/=(const mpz_class& b) { return z_.v /= b.z_.v, *this; }
    mpz_class& operator%=(const mpz_class& b) { return z_.v %= b.z_.v, *this; }
    mpz_class& operator<<=(unsigned long k) { return z_.v <<= k, *this; }
    mpz_class& operator>>=(unsigned long k) { return z_.v = detail::floor_shift(z_.v, k), *this; }
    mpz_class& operator++() { return ++z_.v, *this; }
    mpz_class& operator--() { return --z_.v, *this; }

    friend mpz_class operator-(const mpz_class& a) { return mpz_class(Int(-a.z_.v)); }
    friend mpz_class operator+(const mpz_class& a, const mpz_class& b) { return mpz_class(Int(a.z_.v + b.z_.v)); }
    friend mpz_class operator-(const mpz_class& a, const mpz_class& b) { return mpz_class(Int(a.z_.v - b.z_.v)); }
    friend mpz_class operator*(const mpz_class& a, const mpz_class& b) { return mpz_class(Int(a.z_.v * b.z_.v)); }
    friend mpz_class operator/(const mpz_class& a, const mpz_class& b) { return mpz_class(Int(a.z_.v / b.z_.v)); }
    friend mpz_class operator%(const mpz_class& a, const mpz_class& b) { return mpz_class(Int(a.z_.v % b.z_.v)); }
    friend mpz_class operator<<(const mpz_class& a, unsigned long k) { return mpz_class(Int(a.z_.v << k)); }
    friend mpz_class operator>>(const mpz_class& a, unsigned long k) { return mpz_class(detail::floor_shift(a.z_.v, k)); }
    friend bool operator==(const mpz_class& a, const mpz_class& b) { return a.z_.v == b.z_.v; }
    friend auto operator<=>(const mpz_class& a, const mpz_class& b) { return a.z_.v.compare(b.z_.v) <=> 0; }
    template <std::floating_point T>
    friend bool operator==(const mpz_class&, T) = delete;
    template <std::floating_point T>
    friend auto operator<=>(const mpz_class&, T) = delete;

    friend int sgn(const mpz_class& a) { return a.z_.v.sign(); }
    friend int cmp(const mpz_class& a, const mpz_class& b) { return a.z_.v.compare(b.z_.v); }
    friend mpz_class abs(const mpz_class& a) { return mpz_class(Int(boost::multiprecision::abs(a.z_.v))); }
    friend void swap(mpz_class& a, mpz_class& b) noexcept { a.swap(b); }
    friend std::ostream& operator<<(std::ostream& o, const mpz_class& a) { return o << a.z_.v; }

private:
    mpz_struct z_;
};

class mpq_class {
public:
    mpq_class() = default;
    template <std::integral T>
    mpq_class(T x) {  // NOLINT: implicit, as gmpxx
        q_.num.v = x;
    }
    mpq_class(const mpz_class& z) { q_.num.v = z.value(); }  // NOLINT: implicit, as gmpxx
    mpq_class(const mpz_class& n, const mpz_class& d) {       // not canonicalized, as gmpxx
        q_.num.v = n.value();
        q_.den.v = d.value();
    }
    mpq_class(double d) { mpq_set_d(&q_, d); }  // NOLINT: implicit and exact, as gmpxx
    explicit mpq_class(mpq_srcptr q) : q_(*q) {}

    mpq_ptr get_mpq_t() { return &q_; }
    mpq_srcptr get_mpq_t() const { return &q_; }
    mpz_class get_num() const { return mpz_class(&q_.num); }
    mpz_class get_den() const { return mpz_class(&q_.den); }
    double get_d() const { return mpq_get_d(&q_); }
    std::string get_str(int base = 10) const {
        std::string s = detail::text(q_.num.v, base);
        return q_.den.v == 1 ? s : s + "/" + detail::text(q_.den.v, base);
    }
    void canonicalize() { mpq_canonicalize(&q_); }
    void swap(mpq_class& o) noexcept { mpq_swap(&q_, &o.q_); }

    mpq_class& operator+=(const mpq_class& b) { return mpq_add(&q_, &q_, &b.q_), *this; }
    mpq_class& operator-=(const mpq_class& b) { return mpq_sub(&q_, &q_, &b.q_), *this; }
    mpq_class& operator*=(const mpq_class& b) { return mpq_mul(&q_, &q_, &b.q_), *this; }
    mpq_class& operator/=(const mpq_class& b) { return mpq_div(&q_, &q_, &b.q_), *this; }

    friend mpq_class operator-(const mpq_class& a) {
        mpq_class r;
        mpq_neg(&r.q_, &a.q_);
        return r;
    }
    friend mpq_class operator+(mpq_class a, const mpq_class& b) { return a += b; }
    friend mpq_class operator-(mpq_class a, const mpq_class& b) { return a -= b; }
    friend mpq_class operator*(mpq_class a, const mpq_class& b) { return a *= b; }
    friend mpq_class operator/(mpq_class a, const mpq_class& b) { return a /= b; }
    friend bool operator==(const mpq_class& a, const mpq_class& b) { return mpq_equal(&a.q_, &b.q_) != 0; }
    friend auto operator<=>(const mpq_class& a, const mpq_class& b) { return mpq_cmp(&a.q_, &b.q_) <=> 0; }

    friend int sgn(const mpq_class& a) { return (mpq_sgn)(&a.q_); }
    friend int cmp(const mpq_class& a, const mpq_class& b) { return mpq_cmp(&a.q_, &b.q_); }
    friend mpq_class abs(const mpq_class& a) { return sgn(a) < 0 ? -a : a; }
    friend void swap(mpq_class& a, mpq_class& b) noexcept { a.swap(b); }
    friend std::ostream& operator<<(std::ostream& o, const mpq_class& a) {
        o << a.q_.num.v;
        if (a.q_.den.v != 1) o << '/' << a.q_.den.v;
        return o;
    }

private:
    mpq_struct q_;
};

}  // namespace polyvol::gmp_on_boost

#ifndef POLYVOL_GMP_ON_BOOST_NAMESPACED
using polyvol::gmp_on_boost::mpq_class;
using polyvol::gmp_on_boost::mpz_class;
#endif
