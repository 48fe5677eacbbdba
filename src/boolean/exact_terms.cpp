#include "boolean/exact_terms.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <optional>

#include "exact/rational.hpp"
#include "measure/sums.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::boolean {

static_assert(sizeof(mp_limb_t) == sizeof(uint64_t), "GMP limbs of 64 bits");

int lowest_bit_exponent(double x) {
    // x = m 2^e with the IEEE fields: e = max(field, 1) - 1075, m with its implicit bit.
    const auto bits = core::bit_cast<uint64_t>(x);
    const int field = static_cast<int>((bits >> 52) & 0x7FF);
    uint64_t m = bits & ((uint64_t{1} << 52) - 1);
    if (field != 0) m |= uint64_t{1} << 52;
    return std::max(field, 1) - 1075 + std::countr_zero(m);
}

double approx_ratio(const mpz_class& n, const mpz_class& d, int e) {
    long ne, de;
    const double mn = mpz_get_d_2exp(&ne, n.get_mpz_t());
    const double md = mpz_get_d_2exp(&de, d.get_mpz_t());
    return std::ldexp(mn / md, static_cast<int>(ne - de) + e);
}

double norm3(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

Geometry triangle_geometry(const double* a, const double* b, const double* c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    Geometry g;
    g.n[0] = u[1] * v[2] - u[2] * v[1];
    g.n[1] = u[2] * v[0] - u[0] * v[2];
    g.n[2] = u[0] * v[1] - u[1] * v[0];
    g.normal_length = norm3(g.n);
    g.normal_error = 16 * 0x1p-53 * norm3(u) * norm3(v);
    return g;
}

// a0 (b1 c2 - b2 c1) + a1 (b2 c0 - b0 c2) + a2 (b0 c1 - b1 c0), each minor in t.
void det3_into(mpz_class& out, const IntPoint& a, const IntPoint& b, const IntPoint& c, mpz_class& t) {
    mpz_mul(t.get_mpz_t(), b[1].get_mpz_t(), c[2].get_mpz_t());
    mpz_submul(t.get_mpz_t(), b[2].get_mpz_t(), c[1].get_mpz_t());
    mpz_mul(out.get_mpz_t(), a[0].get_mpz_t(), t.get_mpz_t());
    mpz_mul(t.get_mpz_t(), b[2].get_mpz_t(), c[0].get_mpz_t());
    mpz_submul(t.get_mpz_t(), b[0].get_mpz_t(), c[2].get_mpz_t());
    mpz_addmul(out.get_mpz_t(), a[1].get_mpz_t(), t.get_mpz_t());
    mpz_mul(t.get_mpz_t(), b[0].get_mpz_t(), c[1].get_mpz_t());
    mpz_submul(t.get_mpz_t(), b[1].get_mpz_t(), c[0].get_mpz_t());
    mpz_addmul(out.get_mpz_t(), a[2].get_mpz_t(), t.get_mpz_t());
}

mpz_class det3(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
    mpz_class out, t;
    det3_into(out, a, b, c, t);
    return out;
}

void orient_into(mpz_class& out, const IntPoint& s0, const IntPoint& s1, const IntPoint& s2, const IntPoint& x,
                 DetScratch& d) {
    for (int k = 0; k < 3; ++k) {
        mpz_sub(d.u[k].get_mpz_t(), s1[k].get_mpz_t(), s0[k].get_mpz_t());
        mpz_sub(d.v[k].get_mpz_t(), s2[k].get_mpz_t(), s0[k].get_mpz_t());
        mpz_sub(d.w[k].get_mpz_t(), x[k].get_mpz_t(), s0[k].get_mpz_t());
    }
    det3_into(out, d.u, d.v, d.w, d.t);
}

void plane_crossing_into(ExactPoint& x, const IntPoint& p, const IntPoint& q, const mpz_class& dp, const mpz_class& dq) {
    if (dp == 0 || dq == 0) {
        x.num = dp == 0 ? p : q;
        x.den = 1;
        return;
    }
    mpz_sub(x.den.get_mpz_t(), dp.get_mpz_t(), dq.get_mpz_t());
    for (int k = 0; k < 3; ++k) {
        mpz_mul(x.num[k].get_mpz_t(), dp.get_mpz_t(), q[k].get_mpz_t());
        mpz_submul(x.num[k].get_mpz_t(), dq.get_mpz_t(), p[k].get_mpz_t());
    }
    if (x.den < 0) {
        mpz_neg(x.den.get_mpz_t(), x.den.get_mpz_t());
        for (auto& c : x.num) mpz_neg(c.get_mpz_t(), c.get_mpz_t());
    }
}

ExactPoint plane_crossing(const IntPoint& p, const IntPoint& q, const mpz_class& dp, const mpz_class& dq) {
    ExactPoint x;
    plane_crossing_into(x, p, q, dp, dq);
    return x;
}

void PieceSum::add_fraction(mpz_class n, mpz_class d) {
    if (n == 0) return;
    if (d < 0) {
        n = -n;
        d = -d;
    }
    fractions.emplace_back(std::move(n), std::move(d));
}

VolumeSum cone_volume_sum(const MeshView& triangles, bool exactly) {
    measure::cone::ConeSums sums = measure::cone::filtered_sums(triangles, 1, measure::cone::Precision::double_double);
    if (exactly) measure::cone::exact_sums(triangles, 1, sums);
    return {sums.sum[0], sums.bound[0]};
}

void add_integer(exact::ExactSum& sum, const mpz_class& z, int exponent) {
    const mpz_srcptr p = z.get_mpz_t();
    const int n = static_cast<int>(mpz_size(p));
    std::vector<uint64_t> limbs(n);
    for (int i = 0; i < n; ++i) limbs[i] = mpz_getlimbn(p, i);
    sum.add_wide(limbs.data(), n, mpz_sgn(p) < 0, exponent);
}

namespace {

mpq_class power_of_two(int e) {
    mpz_class p = 1;
    mpz_mul_2exp(p.get_mpz_t(), p.get_mpz_t(), static_cast<unsigned long>(std::abs(e)));
    return e >= 0 ? mpq_class(p) : mpq_class(mpz_class(1), p);
}

// Every combination decided from the pieces' approximation `six` (true value
// within `bound` of it), or nothing.
bool decide(const exact::ExactSum& six, double bound, std::span<const Combination> results, uint32_t divisor,
            std::vector<double>& out) {
    for (std::size_t i = 0; i < results.size(); ++i) {
        exact::ExactSum v;
        if (results[i].base) v = *results[i].base;
        if (results[i].sign > 0) {
            v.merge(six);
        } else {
            v.subtract(six);
        }
        const auto d = exact::decided_round_div(v, bound + results[i].base_bound, divisor);
        if (!d) return false;
        out[i] = *d;
    }
    return true;
}

}  // namespace

std::vector<double> round_combinations(const PieceSum& pieces, int e0, std::span<const Combination> results,
                                       int& refinements, int degree, uint32_t divisor) {
    std::vector<double> out(results.size());
    exact::ExactSum known = pieces.whole;
    add_integer(known, pieces.integer, degree * e0);
    refinements = 0;
    bool inexact = pieces.whole_bound > 0;
    for (const Combination& c : results) inexact = inexact || c.base_bound > 0;
    if (pieces.fractions.empty()) {
        if (decide(known, pieces.whole_bound, results, divisor, out)) return out;
    } else {
        // The largest fraction is below 2^top (units included).
        long top = std::numeric_limits<long>::min();
        for (const auto& [n, d] : pieces.fractions)
            top = std::max<long>(top, static_cast<long>(mpz_sizeinbase(n.get_mpz_t(), 2)) -
                                          static_cast<long>(mpz_sizeinbase(d.get_mpz_t(), 2)) + 1 + degree * e0);
        const int count_bits = static_cast<int>(std::bit_width(pieces.fractions.size()));
        long e = std::max<long>(-1074, top - 110 - count_bits);
        for (int round = 0; round < 3; ++round) {
            exact::ExactSum six = known;
            mpz_class q, shifted;
            const long k = degree * e0 - e;  // q = floor(N 2^k / D)
            for (const auto& [n, d] : pieces.fractions) {
                if (k >= 0) {
                    mpz_mul_2exp(shifted.get_mpz_t(), n.get_mpz_t(), static_cast<unsigned long>(k));
                    mpz_fdiv_q(q.get_mpz_t(), shifted.get_mpz_t(), d.get_mpz_t());
                } else {
                    mpz_mul_2exp(shifted.get_mpz_t(), d.get_mpz_t(), static_cast<unsigned long>(-k));
                    mpz_fdiv_q(q.get_mpz_t(), n.get_mpz_t(), shifted.get_mpz_t());
                }
                add_integer(six, q, static_cast<int>(e));
            }
            const double bound =
                std::ldexp(static_cast<double>(pieces.fractions.size()), static_cast<int>(e)) + pieces.whole_bound;
            refinements = round;
            if (decide(six, bound, results, divisor, out)) return out;
            if (e == -1074) break;
            e = std::max<long>(-1074, e - 200);
        }
    }
    if (inexact) return {};
    // Exact rationals: a value that is a double or a tie, which no interval decides.
    refinements = -1;
    mpq_class sum = 0;
    for (const auto& [n, d] : pieces.fractions) sum += mpq_class(n, d);
    sum.canonicalize();
    const mpq_class six = mpq_class(exact::Rational(known).get()) + sum * power_of_two(degree * e0);
    for (std::size_t i = 0; i < results.size(); ++i) {
        const mpq_class base = results[i].base ? mpq_class(exact::Rational(*results[i].base).get()) : mpq_class(0);
        const mpq_class v = (base + results[i].sign * six) / divisor;
        out[i] = exact::round_to_double(v.get_mpq_t());
    }
    return out;
}

}  // namespace polyvol::boolean
