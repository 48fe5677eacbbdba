// Tests of src/exact against GMP: error-free transformations, the exact
// determinant expansion, the superaccumulator and correct rounding.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "exact/expansion.hpp"
#include "exact/rational.hpp"

using namespace polyvol::exact;

namespace {

mpq_class q(double x) {
    mpq_class r;
    mpq_set_d(r.get_mpq_t(), x);
    return r;
}

// Independent check that r is the nearest double to x, ties to even:
// compares |x - r| with the distance to both neighbours, exactly.
::testing::AssertionResult is_correctly_rounded(double r, const mpq_class& x) {
    if (std::isinf(r)) {
        // Overflow: |x| >= DBL_MAX + half an ulp (2^970).
        const mpq_class limit = q(DBL_MAX) + q(std::ldexp(1.0, 970));
        if ((r > 0 && x >= limit) || (r < 0 && x <= -limit)) return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "inf for " << x.get_d();
    }
    const mpq_class d = abs(x - q(r));
    for (double nb : {std::nextafter(r, HUGE_VAL), std::nextafter(r, -HUGE_VAL)}) {
        if (std::isinf(nb)) continue;
        const mpq_class dn = abs(x - q(nb));
        if (dn < d)
            return ::testing::AssertionFailure() << std::hexfloat << r << " is not nearest; " << nb
                                                 << " is closer to " << x.get_d();
        if (dn == d) {
            const uint64_t br = std::bit_cast<uint64_t>(r), bn = std::bit_cast<uint64_t>(nb);
            if ((br & 1u) != 0 && (bn & 1u) == 0)
                return ::testing::AssertionFailure() << std::hexfloat << "tie not to even: " << r
                                                     << " vs " << nb;
        }
    }
    return ::testing::AssertionSuccess();
}

// Doubles with random sign, mantissa and exponent in [emin, emax].
double random_double(std::mt19937_64& rng, int emin, int emax) {
    std::uniform_int_distribution<int> ed(emin, emax);
    std::uniform_real_distribution<double> md(1.0, 2.0);
    const double m = md(rng);
    const double x = std::ldexp(m, ed(rng));
    return (rng() & 1u) ? -x : x;
}

mpq_class exact_sum(const std::vector<double>& xs) {
    mpq_class s = 0;
    for (double x : xs) s += q(x);
    return s;
}

}  // namespace

TEST(Eft, TwoSumAndTwoProdAreExact) {
    std::mt19937_64 rng(1);
    for (int i = 0; i < 20000; ++i) {
        const double a = random_double(rng, -300, 300), b = random_double(rng, -300, 300);
        double s, e;
        two_sum(a, b, s, e);
        EXPECT_EQ(q(s) + q(e), q(a) + q(b));
        if (std::fabs(a) >= std::fabs(b)) {
            fast_two_sum(a, b, s, e);
            EXPECT_EQ(q(s) + q(e), q(a) + q(b));
        }
        double p, pe;
        two_prod(a, b, p, pe);
        EXPECT_EQ(q(p) + q(pe), q(a) * q(b));
        two_prod_dekker(a, b, p, pe);
        EXPECT_EQ(q(p) + q(pe), q(a) * q(b));
    }
}

TEST(Expansion, Det3MatchesGmpExactly) {
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < 5000; ++i) {
        double v[9];
        const int mode = i % 4;
        for (int k = 0; k < 9; ++k) {
            if (mode == 0) {
                v[k] = unit(rng);
            } else if (mode == 1) {  // a small triangle far from the origin
                v[k] = 1e6 * (k % 3 + 1) + unit(rng);
            } else if (mode == 2) {  // wildly different exponents
                v[k] = random_double(rng, -150, 150);
            } else {  // nearly degenerate: rows close to each other
                v[k] = std::ldexp(1.0, 40) + static_cast<double>(k % 3) + std::ldexp(unit(rng), -20);
            }
        }
        const double *a = v, *b = v + 3, *c = v + 6;
        double e[kDetTerms];
        const int n = det3_exact<true>(a, b, c, e);
        double e2[kDetTerms];
        const int n2 = det3_exact<false>(a, b, c, e2);
        mpq_class s = 0, s2 = 0;
        for (int k = 0; k < n; ++k) s += q(e[k]);
        for (int k = 0; k < n2; ++k) s2 += q(e2[k]);
        const mpq_class det = q(a[0]) * (q(b[1]) * q(c[2]) - q(b[2]) * q(c[1])) +
                              q(a[1]) * (q(b[2]) * q(c[0]) - q(b[0]) * q(c[2])) +
                              q(a[2]) * (q(b[0]) * q(c[1]) - q(b[1]) * q(c[0]));
        ASSERT_EQ(s, det) << "mode " << mode;
        ASSERT_EQ(s2, det) << "mode " << mode;
        // Compressed: the top component is the determinant to within an ulp.
        ASSERT_LE(abs(det - q(e[n - 1])), abs(q(e[n - 1])) * q(std::ldexp(1.0, -52)));
    }
    // Exactly singular: a plane through the origin.
    const double a[3] = {1e6 + 0.125, 3e6, -7.5}, b[3] = {2 * a[0], 2 * a[1], 2 * a[2]},
                 c[3] = {0.5, 0.25, 4};
    double e[kDetTerms];
    const int n = det3_exact<true>(a, b, c, e);
    EXPECT_EQ(n, 1);
    EXPECT_EQ(e[0], 0.0);
}

TEST(ExactSum, MatchesGmpOnWildExponents) {
    std::mt19937_64 rng(3);
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<double> xs;
        const int n = 1 + static_cast<int>(rng() % 300);
        const int emin = trial % 3 == 0 ? -1074 : -400, emax = trial % 3 == 0 ? 1000 : 400;
        for (int i = 0; i < n; ++i) {
            double x = random_double(rng, emin, emax);
            if (trial % 5 == 0 && (rng() & 3u) == 0) x = std::ldexp(static_cast<double>(rng() % 1000), -1074);  // subnormals
            xs.push_back(x);
            if (trial % 2 == 0) xs.push_back(-x * (1 + std::ldexp(1.0, -52)));  // cancel catastrophically
        }
        ExactSum s;
        for (double x : xs) s.add(x);
        const mpq_class ref = exact_sum(xs);
        ASSERT_EQ(mpq_class(Rational(s).get()), ref);
        const double r = s.round();
        ASSERT_TRUE(is_correctly_rounded(r, ref)) << "trial " << trial;
        ASSERT_EQ(r, Rational(s).to_double());
        for (uint32_t d : {3u, 6u, 24u, 120u, 7u}) {
            ASSERT_TRUE(is_correctly_rounded(s.round_div(d), ref / d)) << "trial " << trial << " / " << d;
        }
        ASSERT_EQ(s.sign(), sgn(ref));
    }
}

TEST(ExactSum, HugeAndTinyAndManyTerms) {
    ExactSum s;
    s.add(1e300);
    s.add(1e-300);
    s.add(-1e300);
    EXPECT_EQ(s.round(), 1e-300);
    EXPECT_EQ(mpq_class(Rational(s).get()), q(1e-300));

    // 10^6 terms: more than kAddsPerCarry between carries, all of them cancelling.
    std::mt19937_64 rng(4);
    ExactSum t;
    std::vector<double> xs;
    for (int i = 0; i < 500000; ++i) {
        const double x = random_double(rng, 900, 1000);
        t.add(x);
        xs.push_back(x);
    }
    for (int i = 0; i < 500000; ++i) t.add(-xs[static_cast<size_t>(i)]);
    t.add(std::ldexp(1.0, -1074));
    EXPECT_EQ(t.round(), std::ldexp(1.0, -1074));
    EXPECT_EQ(t.round_div(2), 0.0);  // 2^-1075: a tie between 0 and 2^-1074 -> 0 (even)

    // Large sums of the largest doubles carry into the top chunk.
    ExactSum big;
    for (int i = 0; i < 5000; ++i) big.add(DBL_MAX);
    EXPECT_EQ(big.round(), HUGE_VAL);
    EXPECT_EQ(big.round_div(5000), DBL_MAX);
    EXPECT_EQ(mpq_class(Rational(big).get()), q(DBL_MAX) * 5000);
}

TEST(ExactSum, TiesRoundToEven) {
    const double u = std::ldexp(1.0, -53);
    auto sum = [](std::initializer_list<double> xs) {
        ExactSum s;
        for (double x : xs) s.add(x);
        return s;
    };
    EXPECT_EQ(sum({1.0, u}).round(), 1.0);                           // tie, 1 is even
    EXPECT_EQ(sum({1.0, 3 * u}).round(), 1.0 + 4 * u);              // tie, up to even
    EXPECT_EQ(sum({1.0, u, std::ldexp(1.0, -200)}).round(), 1.0 + 2 * u);  // above the tie
    EXPECT_EQ(sum({1.0, u, -std::ldexp(1.0, -200)}).round(), 1.0);  // below
    EXPECT_EQ(sum({-1.0, -u}).round(), -1.0);
    EXPECT_EQ(sum({-1.0, -3 * u}).round(), -1.0 - 4 * u);
    // Subnormal ties: 3 * 2^-1075 lies halfway between 2^-1074 and 2^-1073.
    EXPECT_EQ(sum({3 * std::ldexp(1.0, -1074)}).round_div(2), std::ldexp(1.0, -1073));
    EXPECT_EQ(sum({std::ldexp(1.0, -1074)}).round_div(2), 0.0);
    // Overflow: DBL_MAX + 2^970 is halfway to 2^1024, and DBL_MAX is odd.
    EXPECT_EQ(sum({DBL_MAX, std::ldexp(1.0, 970)}).round(), HUGE_VAL);
    EXPECT_EQ(sum({DBL_MAX, std::ldexp(1.0, 969)}).round(), DBL_MAX);
    EXPECT_EQ(sum({-DBL_MAX, -std::ldexp(1.0, 970)}).round(), -HUGE_VAL);
    // Division ties: 3 * (1 + 2u) / 3 exact; (6 + 6u) / 6 = 1 + u is a tie -> 1.
    EXPECT_EQ(sum({6.0, 6 * u}).round_div(6), 1.0);
    EXPECT_EQ(sum({6.0, 18 * u}).round_div(6), 1.0 + 4 * u);
    // round(S / 6) is not round(round(S) / 6): S = 6 + 6u - tiny, S/6 just below a tie.
    ExactSum s = sum({6.0, 6 * u, -std::ldexp(1.0, -300)});
    EXPECT_EQ(s.round_div(6), 1.0);
    EXPECT_EQ(s.round() / 6, 1.0 + 2 * u);
}

TEST(ExactSum, SpecialValues) {
    ExactSum s;
    s.add(1.0);
    s.add(HUGE_VAL);
    EXPECT_EQ(s.round(), HUGE_VAL);
    EXPECT_FALSE(s.finite());
    s.add(-HUGE_VAL);
    EXPECT_TRUE(std::isnan(s.round()));
    ExactSum n;
    n.add(std::numeric_limits<double>::quiet_NaN());
    EXPECT_TRUE(std::isnan(n.round()));
    ExactSum z;
    EXPECT_EQ(z.round(), 0.0);
    EXPECT_EQ(z.sign(), 0);
}

TEST(ExactSum, MergeIsExactAndAssociative) {
    std::mt19937_64 rng(5);
    std::vector<double> xs;
    for (int i = 0; i < 30000; ++i) xs.push_back(random_double(rng, -1074, 1020));
    ExactSum parts[5];
    for (size_t i = 0; i < xs.size(); ++i) parts[rng() % 5].add(xs[i]);
    ExactSum left = parts[0];  // ((((0 1) 2) 3) 4)
    for (int i = 1; i < 5; ++i) left.merge(parts[i]);
    ExactSum right = parts[4];  // (0 (1 (2 (3 4)))) built from the other side
    for (int i = 3; i >= 0; --i) {
        ExactSum t = parts[i];
        t.merge(right);
        right = t;
    }
    ExactSum pairs = parts[0];  // ((0 1) (2 (3 4)))
    pairs.merge(parts[1]);
    ExactSum r34 = parts[3];
    r34.merge(parts[4]);
    ExactSum r234 = parts[2];
    r234.merge(r34);
    pairs.merge(r234);
    left.normalize();
    right.normalize();
    pairs.normalize();
    for (int k = 0; k < ExactSum::kChunks; ++k) {
        ASSERT_EQ(left.chunks()[k], right.chunks()[k]);
        ASSERT_EQ(left.chunks()[k], pairs.chunks()[k]);
    }
    EXPECT_EQ(mpq_class(Rational(left).get()), exact_sum(xs));
    EXPECT_TRUE(is_correctly_rounded(left.round(), exact_sum(xs)));
    ExactSum d = left;
    d.subtract(pairs);
    EXPECT_EQ(d.sign(), 0);
}

TEST(Rational, ToDoubleIsCorrectlyRounded) {
    std::mt19937_64 rng(6);
    for (int i = 0; i < 20000; ++i) {
        const long num = static_cast<long>(rng() >> 2) * ((rng() & 1u) ? 1 : -1);
        const unsigned long den = (rng() >> 3) | 1u;
        mpq_class x(num, den);
        x.canonicalize();
        const int shift = static_cast<int>(rng() % 2300) - 1150;
        if (shift >= 0) {
            mpq_mul_2exp(x.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
        } else {
            mpq_div_2exp(x.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(-shift));
        }
        const double r = round_to_double(x.get_mpq_t());
        ASSERT_TRUE(is_correctly_rounded(r, x)) << x.get_str();
    }
    // Exact halfway cases, normal and subnormal.
    const mpq_class one_u = q(std::ldexp(1.0, -53));
    auto rd = [](const mpq_class& x) { return round_to_double(x.get_mpq_t()); };
    EXPECT_EQ(rd(q(1.0) + one_u), 1.0);
    EXPECT_EQ(rd(q(1.0) + 3 * one_u), 1.0 + 4 * std::ldexp(1.0, -53));
    EXPECT_EQ(rd(q(std::ldexp(1.0, -1074)) / 2), 0.0);
    EXPECT_EQ(rd(q(std::ldexp(3.0, -1074)) / 2), std::ldexp(1.0, -1073));
    EXPECT_EQ(rd(q(std::ldexp(5.0, -1074)) / 2), std::ldexp(1.0, -1073));
    EXPECT_EQ(round_to_double(mpq_class(1, 3).get_mpq_t()), 1.0 / 3);
    EXPECT_EQ(round_to_double(mpq_class(-2, 3).get_mpq_t()), -2.0 / 3);
    mpq_class huge = q(DBL_MAX) * 3;
    EXPECT_EQ(round_to_double(huge.get_mpq_t()), HUGE_VAL);
    EXPECT_EQ(Rational(0.1).to_double(), 0.1);
}

TEST(ExactSum, AddWideMatchesGmp) {
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 2000; ++trial) {
        ExactSum s;
        mpq_class ref = 0;
        for (int i = 0; i < 20; ++i) {
            uint64_t limbs[6];
            const int n = 1 + static_cast<int>(rng() % 6);
            for (int k = 0; k < n; ++k) limbs[k] = rng() >> (rng() % 64);
            const bool neg = (rng() & 1u) != 0;
            const int exponent = -1074 + static_cast<int>(rng() % 1700);
            s.add_wide(limbs, n, neg, exponent);
            mpz_class m = 0;
            for (int k = n - 1; k >= 0; --k) m = (m << 64) + mpz_class(static_cast<unsigned long>(limbs[k]));
            mpq_class v(m);
            if (exponent >= 0) {
                mpq_mul_2exp(v.get_mpq_t(), v.get_mpq_t(), static_cast<mp_bitcnt_t>(exponent));
            } else {
                mpq_div_2exp(v.get_mpq_t(), v.get_mpq_t(), static_cast<mp_bitcnt_t>(-exponent));
            }
            ref += neg ? -v : v;
            if (i % 3 == 0) {
                const double x = random_double(rng, -1000, 600);
                s.add(x);
                ref += q(x);
            }
        }
        ASSERT_EQ(mpq_class(Rational(s).get()), ref) << trial;
        ASSERT_TRUE(is_correctly_rounded(s.round(), ref));
    }
}
