// simplicial/exact_det.cpp — Bareiss elimination over GMP integers.
//
// Source: E. H. Bareiss, "Sylvester's identity and multistep integer-preserving
// Gaussian elimination", Math. Comp. 22 (1968): after step k every entry of
// the trailing block is a (k+1)x(k+1) minor of the matrix, so the division by
// the previous pivot is exact.
#include "simplicial/exact_det.hpp"

#include <gmp.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

namespace polyvol::simplicial {

namespace {

struct Z {
    mpz_t v;
    Z() { mpz_init(v); }
    ~Z() { mpz_clear(v); }
    Z(const Z&) = delete;
    Z& operator=(const Z&) = delete;
};

}  // namespace

exact::Rational exact_det(int n, const double* const* cols) {
    // x = mant * 2^exp with |mant| < 2^53.
    long emin = LONG_MAX;
    for (int c = 0; c < n; ++c)
        for (int r = 0; r < n; ++r) {
            const double x = cols[c][r];
            if (x == 0) continue;
            int e = 0;
            std::frexp(x, &e);
            emin = std::min(emin, static_cast<long>(e) - 53);
        }
    exact::Rational out;
    if (emin == LONG_MAX) return out;  // the zero matrix
    const auto nn = static_cast<std::size_t>(n) * n;
    std::unique_ptr<Z[]> m(new Z[nn]);
    for (int c = 0; c < n; ++c)
        for (int r = 0; r < n; ++r) {
            const double x = cols[c][r];
            if (x == 0) continue;
            int e = 0;
            const double f = std::frexp(x, &e);
            // |f| 2^53 < 2^53 is an integer: set exactly from the double (a
            // long has 32 bits on wasm32).
            mpz_set_d(m[r * n + c].v, std::ldexp(f, 53));
            mpz_mul_2exp(m[r * n + c].v, m[r * n + c].v, static_cast<mp_bitcnt_t>(e - 53 - emin));
        }
    Z prev, t;
    mpz_set_ui(prev.v, 1);
    int sign = 1;
    for (int k = 0; k + 1 < n; ++k) {
        if (mpz_sgn(m[k * n + k].v) == 0) {
            int p = k + 1;
            while (p < n && mpz_sgn(m[p * n + k].v) == 0) ++p;
            if (p == n) return out;  // singular
            for (int c = 0; c < n; ++c) mpz_swap(m[k * n + c].v, m[p * n + c].v);
            sign = -sign;
        }
        for (int i = k + 1; i < n; ++i) {
            for (int j = k + 1; j < n; ++j) {
                mpz_mul(t.v, m[i * n + j].v, m[k * n + k].v);
                mpz_submul(t.v, m[i * n + k].v, m[k * n + j].v);
                mpz_divexact(m[i * n + j].v, t.v, prev.v);
            }
        }
        mpz_set(prev.v, m[k * n + k].v);
    }
    Z& d = m[nn - 1];
    if (sign < 0) mpz_neg(d.v, d.v);
    mpq_set_z(out.get(), d.v);
    const long scale = emin * n;
    if (scale >= 0) {
        mpq_mul_2exp(out.get(), out.get(), static_cast<mp_bitcnt_t>(scale));
    } else {
        mpq_div_2exp(out.get(), out.get(), static_cast<mp_bitcnt_t>(-scale));
    }
    return out;
}

}  // namespace polyvol::simplicial
