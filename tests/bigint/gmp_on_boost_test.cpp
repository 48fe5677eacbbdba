// GMP's interface over Boost's cpp_int (src/exact/gmp_on_boost, the WebAssembly
// build's big integers) against GMP itself: every function polyvol calls, on
// edge and random operands, must give GMP's value (compared as hexadecimal
// text) or GMP's double (compared by bits).
#include <gmpxx.h>

#define POLYVOL_GMP_ON_BOOST_NAMESPACED
#include "exact/gmp_on_boost/gmpxx.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

namespace shim = polyvol::gmp_on_boost;

std::string hex(const mpz_class& z) { return z.get_str(16); }
std::string hex(const shim::Int& z) {
    if (z.is_zero()) return "0";
    std::string s = (z.sign() < 0 ? shim::Int(-z) : z).str(0, std::ios::hex);
    for (auto& c : s) c = static_cast<char>(std::tolower(c));
    return z.sign() < 0 ? "-" + s : s;
}
shim::Int to_shim(const mpz_class& z) {
    const std::string h = mpz_class(abs(z)).get_str(16);
    shim::Int v("0x" + h);
    return sgn(z) < 0 ? shim::Int(-v) : v;
}
uint64_t bits(double x) { return std::bit_cast<uint64_t>(x); }

// Integers that find the edges: 0, ±1, ±(2^k + {-1, 0, 1}) around limb and
// double boundaries, then random ones of up to 3000 bits, each sign.
std::vector<mpz_class> operands() {
    std::vector<mpz_class> out = {0, 1, -1};
    for (const unsigned k : {31u, 32u, 52u, 53u, 54u, 63u, 64u, 65u, 127u, 128u, 1023u, 1024u, 1025u, 1100u})
        for (const int d : {-1, 0, 1}) {
            mpz_class p;
            mpz_ui_pow_ui(p.get_mpz_t(), 2, k);
            p += d;
            out.push_back(p);
            out.push_back(-p);
        }
    gmp_randclass rng(gmp_randinit_default);
    rng.seed(20261129);
    for (int i = 0; i < 60; ++i) {
        mpz_class r = rng.get_z_bits(1 + (i * 53) % 3000);
        out.push_back(i % 2 ? mpz_class(-r) : r);
    }
    return out;
}

std::vector<double> doubles() {
    std::vector<double> out = {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1.5, -2.5, 0x1p52 + 0.5, 0x1p53, -0x1p53 + 1,
                               std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::min(), std::numeric_limits<double>::denorm_min(),
                               -3 * std::numeric_limits<double>::denorm_min(), 1e300, -1e-300, 123456789.987654321};
    std::mt19937_64 rng(7);
    for (int i = 0; i < 200; ++i) {
        const double x = std::bit_cast<double>(rng());
        if (std::isfinite(x)) out.push_back(x);
    }
    return out;
}

TEST(GmpOnBoost, ConversionsFromDoubles) {
    for (const double x : doubles()) {
        mpz_class g;
        mpz_set_d(g.get_mpz_t(), x);
        shim::mpz_t s;
        shim::mpz_set_d(s, x);
        EXPECT_EQ(hex(s->v), hex(g)) << x;
        mpq_class gq;
        mpq_set_d(gq.get_mpq_t(), x);
        shim::mpq_t sq;
        shim::mpq_set_d(sq, x);
        EXPECT_EQ(hex(sq->num.v), hex(gq.get_num())) << x;
        EXPECT_EQ(hex(sq->den.v), hex(gq.get_den())) << x;
        EXPECT_EQ(bits(shim::mpq_get_d(sq)), bits(x + 0.0)) << x;  // an exact double comes back (-0 as 0)
    }
}

TEST(GmpOnBoost, ConversionsToDoubles) {
    for (const auto& z : operands()) {
        const shim::Int s = to_shim(z);
        shim::mpz_t sz;
        sz->v = s;
        EXPECT_EQ(bits(shim::mpz_get_d(sz)), bits(mpz_get_d(z.get_mpz_t()))) << hex(z);
        long ge = 0, se = 0;
        const double gd = mpz_get_d_2exp(&ge, z.get_mpz_t());
        const double sd = shim::mpz_get_d_2exp(&se, sz);
        EXPECT_EQ(bits(sd), bits(gd)) << hex(z);
        EXPECT_EQ(se, ge) << hex(z);
        EXPECT_EQ(shim::mpz_sizeinbase(sz, 2), mpz_sizeinbase(z.get_mpz_t(), 2)) << hex(z);
        EXPECT_EQ(shim::mpz_size(sz), mpz_size(z.get_mpz_t())) << hex(z);
        for (size_t i = 0; i < mpz_size(z.get_mpz_t()); ++i)
            EXPECT_EQ(shim::mpz_getlimbn(sz, static_cast<long>(i)), mpz_getlimbn(z.get_mpz_t(), static_cast<long>(i)));
        EXPECT_EQ(shim::mpz_get_ui(sz), mpz_get_ui(z.get_mpz_t())) << hex(z);
        EXPECT_EQ((shim::mpz_sgn)(sz), mpz_sgn(z.get_mpz_t()));
    }
}

TEST(GmpOnBoost, IntegerArithmetic) {
    const auto ops = operands();
    for (size_t i = 0; i < ops.size(); i += 3) {
        for (size_t j = 1; j < ops.size(); j += 4) {
            const mpz_class &a = ops[i], &b = ops[j];
            shim::mpz_t sa, sb, r, r2;
            sa->v = to_shim(a);
            sb->v = to_shim(b);
            mpz_class g, g2;
            shim::mpz_add(r, sa, sb);
            EXPECT_EQ(hex(r->v), hex(mpz_class(a + b)));
            shim::mpz_sub(r, sa, sb);
            EXPECT_EQ(hex(r->v), hex(mpz_class(a - b)));
            shim::mpz_mul(r, sa, sb);
            EXPECT_EQ(hex(r->v), hex(mpz_class(a * b)));
            r->v = 7;
            g = 7;
            shim::mpz_addmul(r, sa, sb);
            mpz_addmul(g.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
            EXPECT_EQ(hex(r->v), hex(g));
            shim::mpz_submul(r, sa, sb);
            mpz_submul(g.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
            EXPECT_EQ(hex(r->v), hex(g));
            if (b == 0) continue;
            shim::mpz_tdiv_qr(r, r2, sa, sb);
            mpz_tdiv_qr(g.get_mpz_t(), g2.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
            EXPECT_EQ(hex(r->v), hex(g)) << hex(a) << " / " << hex(b);
            EXPECT_EQ(hex(r2->v), hex(g2)) << hex(a) << " % " << hex(b);
            shim::mpz_tdiv_q(r, sa, sb);
            EXPECT_EQ(hex(r->v), hex(g));
            shim::mpz_fdiv_q(r, sa, sb);
            mpz_fdiv_q(g.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
            EXPECT_EQ(hex(r->v), hex(g)) << "floor " << hex(a) << " / " << hex(b);
            const mpz_class prod = a * b;
            shim::mpz_t sp;
            sp->v = to_shim(prod);
            shim::mpz_divexact(r, sp, sb);
            EXPECT_EQ(hex(r->v), hex(a));
            // gmpxx's operators on the shim's classes
            const shim::mpz_class xa(sa), xb(sb);
            EXPECT_EQ(hex((xa / xb).value()), hex(mpz_class(a / b)));
            EXPECT_EQ(hex((xa % xb).value()), hex(mpz_class(a % b)));
            EXPECT_EQ(cmp(xa, xb), (a > b) - (a < b));
        }
    }
}

TEST(GmpOnBoost, Shifts) {
    for (const auto& z : operands()) {
        shim::mpz_t s, r;
        s->v = to_shim(z);
        for (const unsigned long k : {0ul, 1ul, 31ul, 53ul, 64ul, 65ul, 200ul, 4000ul}) {
            mpz_class g;
            shim::mpz_tdiv_q_2exp(r, s, k);
            mpz_tdiv_q_2exp(g.get_mpz_t(), z.get_mpz_t(), k);
            EXPECT_EQ(hex(r->v), hex(g)) << hex(z) << " >> " << k;
            shim::mpz_mul_2exp(r, s, k);
            mpz_mul_2exp(g.get_mpz_t(), z.get_mpz_t(), k);
            EXPECT_EQ(hex(r->v), hex(g));
            EXPECT_EQ(hex((shim::mpz_class(s) >> k).value()), hex(mpz_class(z >> k))) << "gmpxx's >> floors";
        }
    }
}

TEST(GmpOnBoost, Rationals) {
    const auto ops = operands();
    std::vector<std::pair<mpq_class, shim::mpq_class>> qs;
    for (size_t i = 0; i + 1 < ops.size(); i += 5) {
        if (ops[i + 1] == 0) continue;
        mpq_class g(ops[i], ops[i + 1]);
        g.canonicalize();
        shim::mpz_t n, d;
        n->v = to_shim(ops[i]);
        d->v = to_shim(ops[i + 1]);
        shim::mpq_class s{shim::mpz_class(n), shim::mpz_class(d)};
        s.canonicalize();
        EXPECT_EQ(hex(s.get_num().value()), hex(g.get_num()));
        EXPECT_EQ(hex(s.get_den().value()), hex(g.get_den()));
        EXPECT_EQ(bits(s.get_d()), bits(g.get_d())) << g.get_str();
        qs.emplace_back(g, s);
    }
    for (size_t i = 0; i < qs.size(); ++i)
        for (size_t j = 0; j < qs.size(); j += 3) {
            const auto& [ga, sa] = qs[i];
            const auto& [gb, sb] = qs[j];
            auto same = [&](const mpq_class& g, const shim::mpq_class& s) {
                EXPECT_EQ(hex(s.get_num().value()), hex(g.get_num())) << ga.get_str() << " , " << gb.get_str();
                EXPECT_EQ(hex(s.get_den().value()), hex(g.get_den()));
            };
            same(ga + gb, sa + sb);
            same(ga - gb, sa - sb);
            same(ga * gb, sa * sb);
            if (sgn(gb) != 0) same(ga / gb, sa / sb);
            EXPECT_EQ(cmp(sa, sb) > 0, cmp(ga, gb) > 0);
            EXPECT_EQ(cmp(sa, sb) < 0, cmp(ga, gb) < 0);  // GMP promises only the sign
            EXPECT_EQ(sa == sb, ga == gb);
        }
    for (const auto& [g, s] : qs)
        for (const unsigned long k : {0ul, 1ul, 64ul, 300ul}) {
            mpq_class gr;
            shim::mpq_class sr;
            mpq_mul_2exp(gr.get_mpq_t(), g.get_mpq_t(), k);
            shim::mpq_mul_2exp(sr.get_mpq_t(), s.get_mpq_t(), k);
            EXPECT_EQ(hex(sr.get_num().value()), hex(gr.get_num()));
            EXPECT_EQ(hex(sr.get_den().value()), hex(gr.get_den()));
            mpq_div_2exp(gr.get_mpq_t(), g.get_mpq_t(), k);
            shim::mpq_div_2exp(sr.get_mpq_t(), s.get_mpq_t(), k);
            EXPECT_EQ(hex(sr.get_num().value()), hex(gr.get_num()));
            EXPECT_EQ(hex(sr.get_den().value()), hex(gr.get_den()));
            EXPECT_EQ(bits(sr.get_d()), bits(gr.get_d())) << gr.get_str();
        }
}

TEST(GmpOnBoost, Text) {
    shim::mpq_t q;
    shim::mpq_init(q);
    q->num.v = -6;
    q->den.v = 4;
    shim::mpq_canonicalize(q);
    char* s = shim::mpq_get_str(nullptr, 10, q);
    EXPECT_STREQ(s, "-3/2");
    void (*freefunc)(void*, size_t) = nullptr;
    shim::mp_get_memory_functions(nullptr, nullptr, &freefunc);
    freefunc(s, 5);
}

}  // namespace
