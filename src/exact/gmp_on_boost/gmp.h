// exact/gmp_on_boost/gmp.h — the part of GMP's C interface polyvol uses, over
// Boost.Multiprecision's header-only cpp_int, for targets without a GMP build
// (WebAssembly: Debian has no wasm GMP). Chosen with -DPOLYVOL_BIGINT=boost;
// the default build uses GMP itself and never sees this file.
//
// Every function keeps GMP's documented semantics, which are not always
// Boost's (docs/web.md, "GMP on the web"):
//   - mpz_get_d, mpz_get_d_2exp and mpq_get_d truncate toward zero (Boost's
//     conversions round through long double);
//   - mpz_set_d truncates and mpq_set_d is exact, both without long double;
//   - mpz_tdiv_q_2exp shifts the magnitude (Boost's >> floors negatives);
//   - mpz_sizeinbase(0, 2) is 1 (Boost's msb(0) throws);
//   - limbs are 64 bits on every target, `long` arguments never carry more
//     than the callers' 32-bit-safe values (wasm32's long is 32 bits).
// GMP's <gmp.h> makes mpz_sgn, mpq_sgn, mpq_numref and mpq_denref macros, so
// they are declared and called as (name)(...): the parity test includes both.
// Conventions: a number is a plain cpp_int in a struct, so mpz_t is an array
// of one struct as in GMP; mpz_init and mpz_clear only reset it (the
// destructor frees); a rational is kept canonical (den > 0, gcd 1) by every
// operation but mpq_set_si and the two-argument constructors, as in GMP.
#pragma once

#include <boost/multiprecision/cpp_int.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

namespace polyvol::gmp_on_boost {

namespace detail {
using Int = boost::multiprecision::cpp_int;
}
using detail::Int;

struct mpz_struct {
    Int v;
};
struct mpq_struct {
    mpz_struct num, den{Int(1)};
};
using mpz_t = mpz_struct[1];
using mpq_t = mpq_struct[1];
using mpz_ptr = mpz_struct*;
using mpz_srcptr = const mpz_struct*;
using mpq_ptr = mpq_struct*;
using mpq_srcptr = const mpq_struct*;
using mp_bitcnt_t = unsigned long;
using mp_limb_t = uint64_t;
using mp_size_t = long;

namespace detail {

// |x| >> k, with the sign of x (GMP's truncating shift).
inline Int shift_magnitude(const Int& x, unsigned long k) {
    Int m = boost::multiprecision::abs(x) >> k;
    return x.sign() < 0 ? Int(-m) : m;
}

// floor(x / 2^k): gmpxx's >> (Boost's >> drops a negative value's sign).
inline Int floor_shift(const Int& x, unsigned long k) {
    if (x.sign() >= 0) return x >> k;
    const Int m = -x;
    return -Int((m + ((Int(1) << k) - 1)) >> k);
}

// Bits of |x|; 0 for 0.
inline unsigned long bit_length(const Int& x) {
    return x.is_zero() ? 0 : static_cast<unsigned long>(boost::multiprecision::msb(boost::multiprecision::abs(x))) + 1;
}

// The integer of a finite double truncated toward zero, exactly: d = m 2^e
// with |m| < 2^53 an integer.
inline Int from_double_truncated(double d) {
    d = std::trunc(d);
    if (d == 0) return Int(0);
    int e;
    const double f = std::frexp(d, &e);  // |f| in [0.5, 1)
    const auto m = static_cast<int64_t>(std::ldexp(f, 53));
    Int r(m);
    return e >= 53 ? Int(r << (e - 53)) : shift_magnitude(r, static_cast<unsigned long>(53 - e));
}

// |x| truncated to its top 53 bits, as m 2^e with m < 2^53 (a double exactly).
inline double top_bits(const Int& x, long& e) {
    const unsigned long n = bit_length(x);
    const unsigned long shift = n > 53 ? n - 53 : 0;
    const Int top = boost::multiprecision::abs(x) >> shift;
    e = static_cast<long>(shift);
    return static_cast<double>(top.convert_to<uint64_t>());
}

inline void canonicalize(mpq_struct& q) {
    if (q.num.v.is_zero()) {
        q.den.v = 1;
        return;
    }
    const Int g = boost::multiprecision::gcd(q.num.v, q.den.v);
    if (g != 1) {
        q.num.v /= g;
        q.den.v /= g;
    }
    if (q.den.v.sign() < 0) {
        q.num.v = -q.num.v;
        q.den.v = -q.den.v;
    }
}

}  // namespace detail

// ---- integers ------------------------------------------------------------------------------
inline void mpz_init(mpz_ptr z) { z->v = 0; }
inline void mpz_clear(mpz_ptr z) { z->v = Int(); }
inline void mpz_init_set(mpz_ptr z, mpz_srcptr a) { z->v = a->v; }
inline void mpz_init_set_si(mpz_ptr z, long a) { z->v = a; }
inline void mpz_set(mpz_ptr z, mpz_srcptr a) { z->v = a->v; }
inline void mpz_set_si(mpz_ptr z, long a) { z->v = a; }
inline void mpz_set_ui(mpz_ptr z, unsigned long a) { z->v = a; }
inline void mpz_set_d(mpz_ptr z, double d) { z->v = detail::from_double_truncated(d); }
inline void mpz_swap(mpz_ptr a, mpz_ptr b) { a->v.swap(b->v); }
inline int (mpz_sgn)(mpz_srcptr a) { return a->v.sign(); }
inline void mpz_neg(mpz_ptr r, mpz_srcptr a) { r->v = -a->v; }
inline void mpz_abs(mpz_ptr r, mpz_srcptr a) { r->v = boost::multiprecision::abs(a->v); }
inline void mpz_add(mpz_ptr r, mpz_srcptr a, mpz_srcptr b) { r->v = a->v + b->v; }
inline void mpz_add_ui(mpz_ptr r, mpz_srcptr a, unsigned long b) { r->v = a->v + b; }
inline void mpz_sub(mpz_ptr r, mpz_srcptr a, mpz_srcptr b) { r->v = a->v - b->v; }
inline void mpz_mul(mpz_ptr r, mpz_srcptr a, mpz_srcptr b) { r->v = a->v * b->v; }
inline void mpz_addmul(mpz_ptr r, mpz_srcptr a, mpz_srcptr b) { r->v += a->v * b->v; }
inline void mpz_submul(mpz_ptr r, mpz_srcptr a, mpz_srcptr b) { r->v -= a->v * b->v; }
inline void mpz_mul_2exp(mpz_ptr r, mpz_srcptr a, mp_bitcnt_t k) { r->v = a->v << k; }
inline void mpz_tdiv_q_2exp(mpz_ptr r, mpz_srcptr a, mp_bitcnt_t k) { r->v = detail::shift_magnitude(a->v, k); }
inline void mpz_tdiv_q(mpz_ptr q, mpz_srcptr n, mpz_srcptr d) { q->v = n->v / d->v; }  // cpp_int truncates
inline void mpz_tdiv_qr(mpz_ptr q, mpz_ptr r, mpz_srcptr n, mpz_srcptr d) {
    Int qq, rr;
    boost::multiprecision::divide_qr(n->v, d->v, qq, rr);
    q->v = std::move(qq);
    r->v = std::move(rr);
}
// floor(n / d): the truncated quotient, one less when the signs differ and the division is not exact.
inline void mpz_fdiv_q(mpz_ptr q, mpz_srcptr n, mpz_srcptr d) {
    Int qq, rr;
    boost::multiprecision::divide_qr(n->v, d->v, qq, rr);
    if (!rr.is_zero() && (rr.sign() < 0) != (d->v.sign() < 0)) --qq;
    q->v = std::move(qq);
}
inline void mpz_divexact(mpz_ptr q, mpz_srcptr n, mpz_srcptr d) { q->v = n->v / d->v; }
inline void mpz_ui_pow_ui(mpz_ptr r, unsigned long b, unsigned long e) {
    r->v = boost::multiprecision::pow(Int(b), static_cast<unsigned>(e));
}
inline size_t mpz_sizeinbase(mpz_srcptr a, int base) {
    if (base != 2) std::abort();  // only base 2 is used
    return a->v.is_zero() ? 1 : detail::bit_length(a->v);
}
inline size_t mpz_size(mpz_srcptr a) { return (detail::bit_length(a->v) + 63) / 64; }
inline mp_limb_t mpz_getlimbn(mpz_srcptr a, mp_size_t n) {
    const Int w = boost::multiprecision::abs(a->v) >> (64 * static_cast<unsigned long>(n));
    return static_cast<mp_limb_t>(w & Int(UINT64_MAX));
}
// The low bits of |a| that fit an unsigned long, as GMP.
inline unsigned long mpz_get_ui(mpz_srcptr a) {
    return static_cast<unsigned long>(static_cast<uint64_t>(boost::multiprecision::abs(a->v) & Int(UINT64_MAX)));
}
// a truncated toward zero to a double (±inf beyond the range).
inline double mpz_get_d(mpz_srcptr a) {
    long e;
    const double m = detail::top_bits(a->v, e);
    const double r = e > 2000 ? HUGE_VAL : std::ldexp(m, static_cast<int>(e));
    return a->v.sign() < 0 ? -r : r;
}
// a = d 2^exp with 0.5 <= |d| < 1, d truncated toward zero; 0 gives 0 and exp 0.
inline double mpz_get_d_2exp(long* exp, mpz_srcptr a) {
    if (a->v.is_zero()) {
        *exp = 0;
        return 0.0;
    }
    long e;
    const double m = detail::top_bits(a->v, e);
    const long n = static_cast<long>(detail::bit_length(a->v));
    *exp = n;
    const double d = std::ldexp(m, static_cast<int>(e - n));
    return a->v.sign() < 0 ? -d : d;
}

// ---- rationals -----------------------------------------------------------------------------
inline mpz_ptr (mpq_numref)(mpq_ptr q) { return &q->num; }
inline mpz_ptr (mpq_denref)(mpq_ptr q) { return &q->den; }
inline mpz_srcptr (mpq_numref)(mpq_srcptr q) { return &q->num; }
inline mpz_srcptr (mpq_denref)(mpq_srcptr q) { return &q->den; }
inline void mpq_init(mpq_ptr q) {
    q->num.v = 0;
    q->den.v = 1;
}
inline void mpq_clear(mpq_ptr q) {
    q->num.v = Int();
    q->den.v = Int();
}
inline void mpq_set(mpq_ptr r, mpq_srcptr a) { *r = *a; }
inline void mpq_swap(mpq_ptr a, mpq_ptr b) {
    a->num.v.swap(b->num.v);
    a->den.v.swap(b->den.v);
}
inline void mpq_set_z(mpq_ptr r, mpz_srcptr a) {
    r->num.v = a->v;
    r->den.v = 1;
}
inline void mpq_set_si(mpq_ptr r, long n, unsigned long d) {
    r->num.v = n;
    r->den.v = d;
}
inline void mpq_canonicalize(mpq_ptr q) { detail::canonicalize(*q); }
// Exact: a finite double is m 2^e with an integer m of at most 53 bits.
inline void mpq_set_d(mpq_ptr r, double d) {
    int e;
    const double f = std::frexp(d, &e);
    r->num.v = static_cast<int64_t>(std::ldexp(f, 53));
    r->den.v = 1;
    e -= 53;
    if (e >= 0) {
        r->num.v <<= static_cast<unsigned>(e);
    } else {
        r->den.v <<= static_cast<unsigned>(-e);
        detail::canonicalize(*r);
    }
}
inline int (mpq_sgn)(mpq_srcptr q) { return q->num.v.sign(); }
inline int mpq_cmp(mpq_srcptr a, mpq_srcptr b) { return Int(a->num.v * b->den.v).compare(Int(b->num.v * a->den.v)); }
inline int mpq_equal(mpq_srcptr a, mpq_srcptr b) { return a->num.v == b->num.v && a->den.v == b->den.v; }
inline void mpq_neg(mpq_ptr r, mpq_srcptr a) {
    r->num.v = -a->num.v;
    r->den.v = a->den.v;
}
inline void mpq_add(mpq_ptr r, mpq_srcptr a, mpq_srcptr b) {
    Int n = a->num.v * b->den.v + b->num.v * a->den.v;
    r->den.v = a->den.v * b->den.v;
    r->num.v = std::move(n);
    detail::canonicalize(*r);
}
inline void mpq_sub(mpq_ptr r, mpq_srcptr a, mpq_srcptr b) {
    Int n = a->num.v * b->den.v - b->num.v * a->den.v;
    r->den.v = a->den.v * b->den.v;
    r->num.v = std::move(n);
    detail::canonicalize(*r);
}
inline void mpq_mul(mpq_ptr r, mpq_srcptr a, mpq_srcptr b) {
    Int n = a->num.v * b->num.v;
    r->den.v = a->den.v * b->den.v;
    r->num.v = std::move(n);
    detail::canonicalize(*r);
}
inline void mpq_div(mpq_ptr r, mpq_srcptr a, mpq_srcptr b) {  // b != 0
    Int n = a->num.v * b->den.v;
    r->den.v = a->den.v * b->num.v;
    r->num.v = std::move(n);
    detail::canonicalize(*r);
}
// r = a 2^k or a / 2^k, kept canonical by moving the common powers of two.
inline void mpq_mul_2exp(mpq_ptr r, mpq_srcptr a, mp_bitcnt_t k) {
    *r = *a;
    if (r->num.v.is_zero()) return;
    const unsigned long t = std::min<unsigned long>(k, boost::multiprecision::lsb(r->den.v));
    r->den.v >>= t;
    r->num.v <<= (k - t);
}
inline void mpq_div_2exp(mpq_ptr r, mpq_srcptr a, mp_bitcnt_t k) {
    *r = *a;
    if (r->num.v.is_zero()) return;
    const unsigned long t =
        std::min<unsigned long>(k, boost::multiprecision::lsb(boost::multiprecision::abs(r->num.v)));
    r->num.v = detail::shift_magnitude(r->num.v, t);
    r->den.v <<= (k - t);
}
// n / d truncated toward zero to a double: the quotient scaled to at least 54 bits
// and truncated, so both truncations are one.
inline double mpq_get_d(mpq_srcptr q) {
    if (q->num.v.is_zero()) return 0.0;
    const long bn = static_cast<long>(detail::bit_length(q->num.v));
    const long bd = static_cast<long>(detail::bit_length(q->den.v));
    const long s = 55 - (bn - bd);  // quotient of 54 or 55 bits
    Int n = boost::multiprecision::abs(q->num.v), d = q->den.v;
    if (s > 0) n <<= static_cast<unsigned long>(s);
    else d <<= static_cast<unsigned long>(-s);
    const Int quo = n / d;
    long e;
    double m = detail::top_bits(quo, e);
    long x = e - s;  // |q| truncated = m 2^x, m < 2^53 an integer
    double r;
    if (x > 2000) {
        r = HUGE_VAL;
    } else if (x < -1200) {
        r = 0.0;
    } else {
        if (x < -1074) {  // a subnormal: drop the bits below 2^-1074 (exact: m / 2^k stays normal)
            m = std::trunc(std::ldexp(m, static_cast<int>(x + 1074)));
            x = -1074;
        }
        r = std::ldexp(m, static_cast<int>(x));
    }
    return q->num.v.sign() < 0 ? -r : r;
}
inline char* mpq_get_str(char* buffer, int base, mpq_srcptr q) {
    if (base != 10 || buffer != nullptr) std::abort();  // only the allocating base-10 form is used
    std::string s = q->num.v.str();
    if (q->den.v != 1) s += "/" + q->den.v.str();
    char* out = static_cast<char*>(std::malloc(s.size() + 1));
    std::memcpy(out, s.c_str(), s.size() + 1);
    return out;
}
inline void mp_get_memory_functions(void* (**alloc)(size_t), void* (**realloc)(void*, size_t, size_t),
                                    void (**freefunc)(void*, size_t)) {
    (void)alloc;
    (void)realloc;
    if (freefunc) *freefunc = [](void* p, size_t) { std::free(p); };
}

}  // namespace polyvol::gmp_on_boost

#ifndef POLYVOL_GMP_ON_BOOST_NAMESPACED
// This header stands in for <gmp.h>: its names are global, as GMP's are.
using polyvol::gmp_on_boost::mp_bitcnt_t;
using polyvol::gmp_on_boost::mp_get_memory_functions;
using polyvol::gmp_on_boost::mp_limb_t;
using polyvol::gmp_on_boost::mp_size_t;
using polyvol::gmp_on_boost::mpq_add;
using polyvol::gmp_on_boost::mpq_canonicalize;
using polyvol::gmp_on_boost::mpq_clear;
using polyvol::gmp_on_boost::mpq_cmp;
using polyvol::gmp_on_boost::mpq_denref;
using polyvol::gmp_on_boost::mpq_div;
using polyvol::gmp_on_boost::mpq_div_2exp;
using polyvol::gmp_on_boost::mpq_equal;
using polyvol::gmp_on_boost::mpq_get_d;
using polyvol::gmp_on_boost::mpq_get_str;
using polyvol::gmp_on_boost::mpq_init;
using polyvol::gmp_on_boost::mpq_mul;
using polyvol::gmp_on_boost::mpq_mul_2exp;
using polyvol::gmp_on_boost::mpq_neg;
using polyvol::gmp_on_boost::mpq_numref;
using polyvol::gmp_on_boost::mpq_ptr;
using polyvol::gmp_on_boost::mpq_set;
using polyvol::gmp_on_boost::mpq_set_d;
using polyvol::gmp_on_boost::mpq_set_si;
using polyvol::gmp_on_boost::mpq_set_z;
using polyvol::gmp_on_boost::mpq_sgn;
using polyvol::gmp_on_boost::mpq_srcptr;
using polyvol::gmp_on_boost::mpq_struct;
using polyvol::gmp_on_boost::mpq_sub;
using polyvol::gmp_on_boost::mpq_swap;
using polyvol::gmp_on_boost::mpq_t;
using polyvol::gmp_on_boost::mpz_abs;
using polyvol::gmp_on_boost::mpz_add;
using polyvol::gmp_on_boost::mpz_add_ui;
using polyvol::gmp_on_boost::mpz_addmul;
using polyvol::gmp_on_boost::mpz_clear;
using polyvol::gmp_on_boost::mpz_divexact;
using polyvol::gmp_on_boost::mpz_fdiv_q;
using polyvol::gmp_on_boost::mpz_get_d;
using polyvol::gmp_on_boost::mpz_get_d_2exp;
using polyvol::gmp_on_boost::mpz_get_ui;
using polyvol::gmp_on_boost::mpz_getlimbn;
using polyvol::gmp_on_boost::mpz_init;
using polyvol::gmp_on_boost::mpz_init_set;
using polyvol::gmp_on_boost::mpz_init_set_si;
using polyvol::gmp_on_boost::mpz_mul;
using polyvol::gmp_on_boost::mpz_mul_2exp;
using polyvol::gmp_on_boost::mpz_neg;
using polyvol::gmp_on_boost::mpz_ptr;
using polyvol::gmp_on_boost::mpz_set;
using polyvol::gmp_on_boost::mpz_set_d;
using polyvol::gmp_on_boost::mpz_set_si;
using polyvol::gmp_on_boost::mpz_set_ui;
using polyvol::gmp_on_boost::mpz_sgn;
using polyvol::gmp_on_boost::mpz_size;
using polyvol::gmp_on_boost::mpz_sizeinbase;
using polyvol::gmp_on_boost::mpz_srcptr;
using polyvol::gmp_on_boost::mpz_struct;
using polyvol::gmp_on_boost::mpz_sub;
using polyvol::gmp_on_boost::mpz_submul;
using polyvol::gmp_on_boost::mpz_swap;
using polyvol::gmp_on_boost::mpz_t;
using polyvol::gmp_on_boost::mpz_tdiv_q;
using polyvol::gmp_on_boost::mpz_tdiv_q_2exp;
using polyvol::gmp_on_boost::mpz_tdiv_qr;
using polyvol::gmp_on_boost::mpz_ui_pow_ui;
#endif
