// boolean/solid_pieces.hpp — private: the boundary of {W >= level} for the
// bodies of one operand, triangle by triangle, from their crossings.
//
// A point x of triangle t of body i lies on the boundary of {W >= m} iff W
// on t's front side is m - 1 there: W_others(x) = c_i, c_i = m - 1 for an
// outward body, m for an inward one (its own winding is -1 in front).
// So the boundary is, per triangle, the region R_t = {x in t : W_others = c_i},
// bounded by
//   * the intervals of t's edges where W_others = c_i: W_others changes by σ
//     at each crossing λ (sorted along the edge);
//   * the cuts t ∩ s (s in body j), run P -> Q along N_t × N_s with the back
//     of s on its left: R_t lies on its left where W_r = c_i - 1 and on its
//     right where W_r = c_i, W_r being W_others on the front of s:
//     W_r = W_{not i, j} + f_j (f = 0 outward, -1 inward). Where a third
//     body r crosses the cut, W_{not i, j} changes: the cut is split there
//     (the triple points t ∩ s ∩ r); each portion [μ, μ'] bounds R_t with
//     multiplicity κ = [W_r = c - 1] - [W_r = c] (and R_s likewise, run Q -> P).
// solid_volume.cpp sums the cones of these pieces (6 |{W >= m}| = Σ_t 6
// cone(R_t), each fanned from t's first corner a, where only edge b -> c and
// the cuts count); the grid takes the segments themselves (level_pieces.cpp).
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <map>
#include <span>
#include <stdexcept>
#include <vector>

#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "boolean/symbolic.hpp"
#include "measure/sums.hpp"

namespace polyvol::boolean {

constexpr int kSums = measure::cone::kSumCount;  // volume, first and second moment sums

// Where edge `edge` of triangle `owner` crosses the plane of triangle `plane`
// (both of one operand, bodies moved by their shifts).
struct CrossingRef {
    uint32_t owner;
    uint8_t edge;
    uint32_t plane;
};

// The crossing point at ε = 0 (exact_terms.hpp's plane_crossing).
using Point0 = ExactPoint;

class SolidPieces {
public:
    SolidPieces(const Operand& g, const Crossings& cross, const std::vector<int32_t>& winding,
                const std::vector<int>& body_sign, const Scale& scale, int level = 1)
        : g_(g), cross_(cross), w_(winding), sign_(body_sign), scale_(scale), level_(level) {
        hits_ = cross.a_hits;
        hits_.insert(hits_.end(), cross.b_hits.begin(), cross.b_hits.end());
        std::sort(hits_.begin(), hits_.end(), [](const EdgeHit& x, const EdgeHit& y) {
            return std::tie(x.tri, x.edge) < std::tie(y.tri, y.edge);
        });
        // (triangle, cut) for both triangles of every cut, by triangle.
        cut_of_.reserve(2 * cross.cuts.size());
        for (std::size_t c = 0; c < cross.cuts.size(); ++c) {
            cut_of_.push_back({cross.cuts[c].a, static_cast<uint32_t>(c)});
            cut_of_.push_back({cross.cuts[c].b, static_cast<uint32_t>(c)});
        }
        std::sort(cut_of_.begin(), cut_of_.end());
        for (std::size_t i = 0; i < cut_of_.size(); ++i)
            if (i == 0 || cut_of_[i][0] != cut_of_[i - 1][0]) crossed_.push_back(cut_of_[i][0]);
    }

    // Adds the pieces to out (out.size() == 1: volume; kSums: moments too);
    // triangles with no crossing on edge b -> c and W_others = c there go to
    // `whole` instead (summed by measure's exact kernels).
    void sum(std::span<PieceSum> out, std::vector<uint32_t>& whole) {
        moments_ = out.size() > 1 ? out : std::span<PieceSum>();
        for (std::size_t t = 0; t < g_.triangles(); ++t) edge_pieces(static_cast<uint32_t>(t), out[0], whole);
        for (const Cut& cut : cross_.cuts) cut_pieces(cut, out[0]);
    }

    // Twice the area of the boundary of {W >= level} on these triangles. A
    // triangle no cut crosses lies in it whole or not at all (W_others = c at
    // its corners); a crossed one gives its region R_t, from its boundary
    // segments X -> Y counted k times, a its first corner:
    //   2 area(R_t) = Σ k ((X - a) × (Y - a)) · N / |N|,   N = (b - a) × (c - a),
    // each term an exact ratio (integer units) rounded once (approx_ratio,
    // within 2^-51), so |error| <= (terms + 4) 2^-51 Σ|term| / |N| + 8u |2 area(R_t)|
    // (|N| from N's rounded components).
    AreaSum twice_area() {
        AreaSum area;
        std::size_t next = 0;  // crossed_ is increasing
        for (uint32_t t = 0; t < g_.triangles(); ++t) {
            if (next < crossed_.size() && crossed_[next] == t) {
                ++next;
                continue;
            }
            if (w_[g_.tri[3 * t]] != c_of(g_.body(t))) continue;
            const Geometry geo = triangle_geometry(corner(t, 0), corner(t, 1), corner(t, 2));
            area.add(geo.normal_length, geo.normal_error + 0x1p-53 * geo.normal_length);
        }
        struct Region {
            double sum = 0, magnitude = 0;
            std::size_t terms = 0;
        };
        std::vector<Region> region(crossed_.size());
        std::vector<IntPoint> a(crossed_.size()), normal(crossed_.size());
        for (std::size_t i = 0; i < crossed_.size(); ++i) {
            const uint32_t t = crossed_[i];
            a[i] = scale_.of(corner(t, 0));
            const IntPoint b = scale_.of(corner(t, 1)), c = scale_.of(corner(t, 2));
            const IntPoint u = {b[0] - a[i][0], b[1] - a[i][1], b[2] - a[i][2]};
            const IntPoint v = {c[0] - a[i][0], c[1] - a[i][1], c[2] - a[i][2]};
            normal[i] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        }
        boundary_segments([&](uint32_t t, const Point0& X, const Point0& Y, int k) {
            const std::size_t i = static_cast<std::size_t>(
                std::lower_bound(crossed_.begin(), crossed_.end(), t) - crossed_.begin());
            IntPoint x, y;
            for (int j = 0; j < 3; ++j) {
                x[j] = X.num[j] - a[i][j] * X.den;
                y[j] = Y.num[j] - a[i][j] * Y.den;
            }
            const IntPoint& n = normal[i];
            const mpz_class cross_n = (x[1] * y[2] - x[2] * y[1]) * n[0] + (x[2] * y[0] - x[0] * y[2]) * n[1] +
                                      (x[0] * y[1] - x[1] * y[0]) * n[2];
            const double term = k * approx_ratio(cross_n, mpz_class(X.den * Y.den), 0);
            region[i].sum += term;
            region[i].magnitude += std::fabs(term);
            ++region[i].terms;
        });
        for (std::size_t i = 0; i < crossed_.size(); ++i) {
            const IntPoint& n = normal[i];
            const double nd[3] = {n[0].get_d(), n[1].get_d(), n[2].get_d()};
            const double length = norm3(nd);
            if (!(length > 0)) continue;
            const Region& r = region[i];
            const double value = r.sum / length;
            const double error = static_cast<double>(r.terms + 4) * 0x1p-51 * r.magnitude / length +
                                 8 * 0x1p-53 * std::fabs(value);
            area.add(std::ldexp(value, 2 * scale_.e0), std::ldexp(error, 2 * scale_.e0));
        }
        return area;
    }

    // The triangles some cut crosses, increasing (on the others W_others is
    // one value all over the triangle).
    const std::vector<uint32_t>& crossed() const { return crossed_; }

    // The boundary of R_t on every crossed triangle t as a 1-cycle of t's
    // plane: emit(t, X, Y, k), the segment X -> Y counted k times (k = ±1),
    // for the intervals of t's three edges (corner e -> e + 1) and the
    // portions of its cuts. The segments of one triangle close up, and every
    // one is met again, reversed, on the triangle across it (an edge's
    // neighbour or the other triangle of a cut).
    template <class Emit>
    void boundary_segments(Emit&& emit) {
        for (const uint32_t t : crossed_) {
            const int c = c_of(g_.body(t));
            for (int e = 0; e < 3; ++e) {
                const Point0 p{scale_.of(corner(t, e)), 1}, q{scale_.of(corner(t, e + 1)), 1};
                Point0 from = p;
                int64_t w = w_[g_.tri[3 * t + e]];
                for (const WalkEntry& x : walk(t, e)) {
                    Point0 at = along(p, q, x.num, x.den);
                    if (w == c) emit(t, from, at, +1);
                    w += x.sign;
                    from = std::move(at);
                }
                if (w == c) emit(t, from, q, +1);
            }
        }
        for (const Cut& cut : cross_.cuts)
            for_each_portion(cut, [&](const Point0& P, const Point0& Q, const mpz_class& n0, const mpz_class& d0,
                                      const mpz_class& n1, const mpz_class& d1, int kt, int ks) {
                const Point0 X = along(P, Q, n0, d0), Y = along(P, Q, n1, d1);
                if (kt != 0) emit(cut.a, X, Y, kt);
                if (ks != 0) emit(cut.b, Y, X, ks);
            });
    }

private:
    struct WalkEntry {
        uint32_t other;
        int sign;
        mpz_class num, den;  // λ = num / den, den > 0
        int64_t w_before;    // W_others just before this crossing
    };

    // R_t = {W_others = c}: c = level - 1 - front (the winding in front).
    int c_of(uint32_t body) const { return level_ - 1 - front_of(body); }
    int front_of(uint32_t body) const { return sign_[body] > 0 ? 0 : -1; }
    const double* corner(uint32_t t, int i) const { return g_.corner(t, i % 3); }

    // D_p, D_q of a crossing as exact integers or as polynomials in ε.
    template <class N, class Convert>
    void plane_values(const CrossingRef& x, Convert to, N& dp, N& dq, std::array<N, 3>& p, std::array<N, 3>& q) const {
        const int32_t ko = g_.shift(x.owner), kp = g_.shift(x.plane);
        p = to(corner(x.owner, x.edge), ko);
        q = to(corner(x.owner, x.edge + 1), ko);
        const auto s0 = to(corner(x.plane, 0), kp), s1 = to(corner(x.plane, 1), kp), s2 = to(corner(x.plane, 2), kp);
        dp = orient_of<N>(s0, s1, s2, p);
        dq = orient_of<N>(s0, s1, s2, q);
    }
    std::array<mpz_class, 3> int_point(const double* v, int32_t) const { return scale_.of(v); }
    EpsPoint eps_point(const double* v, int32_t k) const { return moved_point(scale_.of(v), k); }

    Point0 point0(const CrossingRef& x) const {
        mpz_class dp, dq;
        IntPoint p, q;
        plane_values<mpz_class>(x, [&](const double* v, int32_t k) { return int_point(v, k); }, dp, dq, p, q);
        return plane_crossing(p, q, dp, dq);
    }

    // P + μ (Q - P), μ = n / d: (Pn Qd (d - n) + Qn Pd n) / (Pd Qd d).
    static Point0 along(const Point0& P, const Point0& Q, const mpz_class& n, const mpz_class& d) {
        if (n == 0) return P;
        if (n == d) return Q;
        Point0 r;
        for (int k = 0; k < 3; ++k) r.num[k] = P.num[k] * Q.den * (d - n) + Q.num[k] * P.den * n;
        r.den = P.den * Q.den * d;
        return r;
    }

    // sign of orient(r, P) for the crossing point P of x (exactly, perturbed).
    int side(const CrossingRef& x, const Point0& P, uint32_t r) const {
        const IntPoint r0 = scale_.of(corner(r, 0)), r1 = scale_.of(corner(r, 1)), r2 = scale_.of(corner(r, 2));
        const IntPoint pr = {P.num[0] - r0[0] * P.den, P.num[1] - r0[1] * P.den, P.num[2] - r0[2] * P.den};
        const IntPoint u = {r1[0] - r0[0], r1[1] - r0[1], r1[2] - r0[2]};
        const IntPoint v = {r2[0] - r0[0], r2[1] - r0[1], r2[2] - r0[2]};
        const mpz_class s = det3(u, v, pr);  // den > 0
        if (s != 0) return sgn(s);
        EpsPoly dp, dq;
        EpsPoint p, q;
        plane_values<EpsPoly>(x, [&](const double* w, int32_t k) { return eps_point(w, k); }, dp, dq, p, q);
        const EpsPoly den = dp - dq;
        const EpsPoint num = {dp * q[0] - dq * p[0], dp * q[1] - dq * p[1], dp * q[2] - dq * p[2]};
        const int32_t kr = g_.shift(r);
        const EpsPoint e0 = eps_point(corner(r, 0), kr), e1 = eps_point(corner(r, 1), kr), e2 = eps_point(corner(r, 2), kr);
        const EpsPoint a = {e1[0] - e0[0], e1[1] - e0[1], e1[2] - e0[2]};
        const EpsPoint b = {e2[0] - e0[0], e2[1] - e0[1], e2[2] - e0[2]};
        const EpsPoint d = {num[0] - e0[0] * den, num[1] - e0[1] * den, num[2] - e0[2] * den};
        const int sign = det3_of<EpsPoly>(a, b, d).sign() * den.sign();
        // Zero for every ε: r and the point's triangles are of one body
        // crossing itself. The point is on r's plane; on r itself the body
        // touches itself there, else 0 (no triple point at that end).
        if (sign == 0 && in_triangle(P, r))
            throw SelfContact("boolean: a crossing point of a body that crosses itself lies on its own surface");
        return sign;
    }

    // Whether the point P of r's plane lies in the closed triangle r: the
    // three 2D orientations along r's largest normal axis agree.
    bool in_triangle(const Point0& P, uint32_t r) const {
        const IntPoint c[3] = {scale_.of(corner(r, 0)), scale_.of(corner(r, 1)), scale_.of(corner(r, 2))};
        const IntPoint u = {c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
        const IntPoint v = {c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
        int k = 0;
        mpz_class best = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const int i = (axis + 1) % 3, j = (axis + 2) % 3;
            const mpz_class n = abs(mpz_class(u[i] * v[j] - u[j] * v[i]));
            if (n > best) {
                best = n;
                k = axis;
            }
        }
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        int pos = 0, neg = 0;
        for (int e = 0; e < 3; ++e) {
            const IntPoint& x = c[e];
            const IntPoint& y = c[(e + 1) % 3];
            // (y - x) × (P - x) along k, P = num / den (den > 0)
            const mpz_class o = (y[i] - x[i]) * (P.num[j] - x[j] * P.den) - (y[j] - x[j]) * (P.num[i] - x[i] * P.den);
            pos += sgn(o) > 0;
            neg += sgn(o) < 0;
        }
        return pos == 0 || neg == 0;
    }

    // The crossings along edge e of triangle t, in order, with W_others before each.
    const std::vector<WalkEntry>& walk(uint32_t t, int e) {
        const uint64_t key = 3 * uint64_t{t} + e;
        auto found = walks_.find(key);
        if (found != walks_.end()) return found->second;
        std::vector<WalkEntry> entries;
        struct Lambda {
            CrossingRef ref;
            int sign;
            mpz_class num, den;
        };
        std::vector<Lambda> ls;
        const EdgeHit probe{t, 0, static_cast<uint8_t>(e), 0};
        auto it = std::lower_bound(hits_.begin(), hits_.end(), probe, [](const EdgeHit& x, const EdgeHit& y) {
            return std::tie(x.tri, x.edge) < std::tie(y.tri, y.edge);
        });
        if (it == hits_.end() || it->tri != t || it->edge != e) {  // nothing crosses the edge (most edges)
            static const std::vector<WalkEntry> none;
            if (w_[g_.tri[3 * t + e]] != w_[g_.tri[3 * t + (e + 1) % 3]])
                throw Contradiction("boolean: windings along an edge disagree with its end (a shell crosses itself?)");
            return none;
        }
        for (; it != hits_.end() && it->tri == t && it->edge == e; ++it) {
            Lambda l{{t, static_cast<uint8_t>(e), it->other}, it->sign, 0, 0};
            mpz_class dq;
            IntPoint p, q;
            plane_values<mpz_class>(l.ref, [&](const double* v, int32_t k) { return int_point(v, k); }, l.num, dq, p, q);
            l.den = l.num - dq;
            if (l.den < 0) {
                l.den = -l.den;
                l.num = -l.num;
            }
            ls.push_back(std::move(l));
        }
        // By λ at ε = 0, then each run of equal λ by the perturbed λ (its
        // polynomials computed once per crossing, not once per comparison).
        std::sort(ls.begin(), ls.end(), [&](const Lambda& x, const Lambda& y) {
            return sgn(mpz_class(x.num * y.den - y.num * x.den)) < 0;
        });
        for (std::size_t i = 0; i < ls.size();) {
            std::size_t j = i + 1;
            while (j < ls.size() && ls[j].num * ls[i].den == ls[i].num * ls[j].den) ++j;
            if (j - i > 1) perturbed_sort(std::span<Lambda>(ls).subspan(i, j - i));
            i = j;
        }
        int64_t w = w_[g_.tri[3 * t + e]];
        for (Lambda& l : ls) {
            entries.push_back({l.ref.plane, l.sign, std::move(l.num), std::move(l.den), w});
            w += l.sign;
        }
        if (w != w_[g_.tri[3 * t + (e + 1) % 3]])
            throw Contradiction("boolean: windings along an edge disagree with its end (a shell crosses itself?)");
        return walks_.emplace(key, std::move(entries)).first->second;
    }

    // Orders crossings of one edge that coincide at ε = 0 by their perturbed
    // λ = D_p / (D_p - D_q): λx - λy = (D_px dy - D_py dx) / (dx dy).
    template <class L>
    void perturbed_sort(std::span<L> run) const {
        struct Key {
            EpsPoly dp, d;
            int d_sign;
        };
        std::vector<Key> keys;
        keys.reserve(run.size());
        auto to = [&](const double* v, int32_t k) { return eps_point(v, k); };
        for (const L& l : run) {
            EpsPoly dp, dq;
            EpsPoint p, q;
            plane_values<EpsPoly>(l.ref, to, dp, dq, p, q);
            EpsPoly d = dp - dq;
            const int ds = d.sign();
            keys.push_back({std::move(dp), std::move(d), ds});
        }
        std::vector<std::size_t> order(run.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            const Key &x = keys[a], &y = keys[b];
            const int s = (x.dp * y.d - y.dp * x.d).sign() * x.d_sign * y.d_sign;
            if (s != 0) return s < 0;
            // The same point for every ε: any order, unless a body crossing
            // itself is involved (its own planes meet the edge at one point).
            for (const L* l : {&run[a], &run[b]})
                if (g_.crosses_itself(g_.body(l->ref.plane)) || g_.crosses_itself(g_.body(l->ref.owner)))
                    throw SelfContact("boolean: an edge meets a body that crosses itself where it crosses itself");
            return run[a].ref.plane < run[b].ref.plane;
        });
        std::vector<L> sorted;
        sorted.reserve(run.size());
        for (std::size_t i : order) sorted.push_back(std::move(run[i]));
        std::move(sorted.begin(), sorted.end(), run.begin());
    }

    // Adds sign × λ × d to out (λ = num / den, den > 0, 0 <= λ <= 1).
    static void add_scaled(PieceSum& out, int sign, const mpz_class& num, const mpz_class& den, const mpz_class& d) {
        if (num == 0 || d == 0) return;
        if (num == den) {
            out.integer += sign * d;
        } else {
            out.add_fraction(sign * num * d, den);
        }
    }

    // Edge b -> c of triangle t: the intervals where W_others = c.
    void edge_pieces(uint32_t t, PieceSum& out, std::vector<uint32_t>& whole) {
        const int c = c_of(g_.body(t));
        const auto& entries = walk(t, 1);
        if (entries.empty()) {
            if (w_[g_.tri[3 * t + 1]] == c) whole.push_back(t);
            return;
        }
        if (!moments_.empty()) edge_moments(t, entries, c);
        const mpz_class d = det3(scale_.of(corner(t, 0)), scale_.of(corner(t, 1)), scale_.of(corner(t, 2)));
        const mpz_class one = 1, zero = 0;
        const mpz_class* pos_num = &zero;
        const mpz_class* pos_den = &one;
        int64_t w = w_[g_.tri[3 * t + 1]];
        for (const WalkEntry& x : entries) {
            if (w == c) {
                add_scaled(out, +1, x.num, x.den, d);
                add_scaled(out, -1, *pos_num, *pos_den, d);
            }
            w += x.sign;
            pos_num = &x.num;
            pos_den = &x.den;
        }
        if (w == c) {
            out.integer += d;
            add_scaled(out, -1, *pos_num, *pos_den, d);
        }
    }

    // The moments of the cone over the portion [x, y] of the segment
    // P + λ D, fanned from a (the pieces' first and second moment sums,
    // measure/cone.hpp's kMx..kSzx), times sign: H(y) - H(x) with
    //   Δ = det(a, P, D), c = a + 2P,
    //   H_i(λ)  = Δ (λ c_i + λ² D_i)
    //   H_ij(λ) = Δ (λ (a_i a_j + 2 P_i P_j + c_i c_j)
    //              + λ² (P_i D_j + D_i P_j + c_i D_j + D_i c_j) + 2 λ³ D_i D_j)
    // (the fan triangles (a, p, q) of the portion's ends, summed in closed
    // form). In integers, without reducing fractions: P = Pn / Pd and
    // Q = Qn / Qd over L = Pd Qd are P' / L, D' / L with P' = Pn Qd,
    // D' = Qn Pd - Pn Qd, a' = a L, c' = a' + 2 P', Δ' = det(a', P', D');
    // for λ = n / d, H_i = Δ' (n d c'_i + n² D'_i) / (L⁴ d²) and
    // H_ij = Δ' (n d² K0' + n² d K1' + 2 n³ D'_i D'_j) / (L⁵ d³).
    void segment_moments(const IntPoint& a, const ExactPoint& P, const ExactPoint& Q, const mpz_class& xn,
                         const mpz_class& xd, const mpz_class& yn, const mpz_class& yd, int sign) {
        if (xn * yd == yn * xd) return;
        const mpz_class L = P.den * Q.den;
        IntPoint p, d, aa, c;
        for (int k = 0; k < 3; ++k) {
            p[k] = P.num[k] * Q.den;
            d[k] = Q.num[k] * P.den - p[k];
            aa[k] = a[k] * L;
            c[k] = aa[k] + 2 * p[k];
        }
        const mpz_class delta = det3(aa, p, d);
        if (delta == 0) return;
        const mpz_class L2 = L * L, L4 = L2 * L2, L5 = L4 * L;
        static constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
        mpz_class k0[6], k1[6], dd[6];
        for (int k = 0; k < 6; ++k) {
            const int i = kPairs[k][0], j = kPairs[k][1];
            k0[k] = aa[i] * aa[j] + 2 * p[i] * p[j] + c[i] * c[j];
            k1[k] = p[i] * d[j] + d[i] * p[j] + c[i] * d[j] + d[i] * c[j];
            dd[k] = 2 * d[i] * d[j];
        }
        for (int end = 0; end < 2; ++end) {
            const mpz_class& n = end == 0 ? yn : xn;
            const mpz_class& dn = end == 0 ? yd : xd;
            if (n == 0) continue;
            const int sg = end == 0 ? sign : -sign;
            const mpz_class den1 = L4 * dn * dn, den2 = L5 * dn * dn * dn;
            for (int i = 0; i < 3; ++i) moments_[1 + i].add_fraction(sg * delta * (n * dn * c[i] + n * n * d[i]), den1);
            for (int k = 0; k < 6; ++k)
                moments_[4 + k].add_fraction(sg * delta * (n * dn * dn * k0[k] + n * n * dn * k1[k] + n * n * n * dd[k]),
                                             den2);
        }
    }

    // Edge b -> c of triangle t: the moments of the intervals where W_others = c.
    void edge_moments(uint32_t t, const std::vector<WalkEntry>& entries, int c) {
        const IntPoint a = scale_.of(corner(t, 0));
        const ExactPoint b{scale_.of(corner(t, 1)), 1}, cc{scale_.of(corner(t, 2)), 1};
        const mpz_class zero = 0, one = 1;
        const mpz_class* pos_num = &zero;
        const mpz_class* pos_den = &one;
        int64_t w = w_[g_.tri[3 * t + 1]];
        for (const WalkEntry& x : entries) {
            if (w == c) segment_moments(a, b, cc, *pos_num, *pos_den, x.num, x.den, +1);
            w += x.sign;
            pos_num = &x.num;
            pos_den = &x.den;
        }
        if (w == c) segment_moments(a, b, cc, *pos_num, *pos_den, one, one, +1);
    }

    // W of the bodies but t's and s's at the cut end x (x's edge crosses x.plane).
    int64_t windings_at_end(const CrossingRef& x) {
        for (const WalkEntry& e : walk(x.owner, x.edge)) {
            if (e.other != x.plane) continue;
            // Just before, the edge is in front of x.plane iff it enters there.
            return e.w_before - (front_of(g_.body(x.plane)) + (e.sign > 0 ? 0 : 1));
        }
        throw Contradiction("boolean: a cut's end is not among its edge's crossings");
    }

    // The portions of cut t ∩ s between its triple points, in order along
    // P -> Q: visit(P, Q, μ0, μ1, κ_t, κ_s) with μ = num / den, den > 0.
    template <class Visit>
    void for_each_portion(const Cut& cut, Visit&& visit) {
        const uint32_t t = cut.a, s = cut.b;
        const uint32_t bi = g_.body(t), bj = g_.body(s);
        auto ref = [&](const CutEnd& e) {
            return e.of_b ? CrossingRef{s, e.edge, t} : CrossingRef{t, e.edge, s};
        };
        const CrossingRef xs = ref(cut.start), xe = ref(cut.end);
        const Point0 P = point0(xs), Q = point0(xe);

        // Triple points: third-body triangles r crossing t along a cut that meets s.
        struct Triple {
            mpz_class num, den;  // μ along P -> Q
            int sign;
        };
        std::vector<Triple> triples;
        const auto first = std::lower_bound(cut_of_.begin(), cut_of_.end(), std::array<uint32_t, 2>{t, 0});
        for (auto it = first; it != cut_of_.end() && (*it)[0] == t; ++it) {
            const Cut& other = cross_.cuts[(*it)[1]];
            const uint32_t r = other.a == t ? other.b : other.a;
            const uint32_t br = g_.body(r);
            // A body's own triangle crosses the cut only if the body crosses
            // itself, and not where it is adjacent to t or s (it meets the
            // cut at most at its end, on their shared edge).
            if ((br == bi || br == bj) && !g_.crosses_itself(br)) continue;
            if (r == s || (br == bi && g_.share_corner(r, t)) || (br == bj && g_.share_corner(r, s))) continue;
            const int sp = side(xs, P, r), sq = side(xe, Q, r);
            if (sp == sq || sp == 0 || sq == 0) continue;  // 0: the lines meet at an end, outside r
            // The cut t ∩ r must meet the plane of s between its ends.
            auto ref2 = [&](const CutEnd& e) {
                const uint32_t oa = other.a, ob = other.b;
                return e.of_b ? CrossingRef{ob, e.edge, oa} : CrossingRef{oa, e.edge, ob};
            };
            const CrossingRef ys = ref2(other.start), ye = ref2(other.end);
            const int ys_side = side(ys, point0(ys), s), ye_side = side(ye, point0(ye), s);
            if (ys_side == ye_side || ys_side == 0 || ye_side == 0) continue;
            // μ = side(P) / (side(P) - side(Q)) at ε = 0, sides as N_r·(X - r0).
            auto value = [&](const Point0& X) {
                const IntPoint r0 = scale_.of(corner(r, 0)), r1 = scale_.of(corner(r, 1)), r2 = scale_.of(corner(r, 2));
                const IntPoint u = {r1[0] - r0[0], r1[1] - r0[1], r1[2] - r0[2]};
                const IntPoint v = {r2[0] - r0[0], r2[1] - r0[1], r2[2] - r0[2]};
                const IntPoint d = {X.num[0] - r0[0] * X.den, X.num[1] - r0[1] * X.den, X.num[2] - r0[2] * X.den};
                return mpz_class(det3(u, v, d));  // side × den
            };
            const mpz_class vp = value(P), vq = value(Q);
            Triple tr{vp * Q.den, vp * Q.den - vq * P.den, sp > 0 ? +1 : -1};
            if (tr.den < 0) {
                tr.den = -tr.den;
                tr.num = -tr.num;
            }
            triples.push_back(std::move(tr));
        }
        std::sort(triples.begin(), triples.end(), [](const Triple& x, const Triple& y) {
            return sgn(mpz_class(x.num * y.den - y.num * x.den)) < 0;  // ties: zero-length portions
        });

        const int ci = c_of(bi), cj = c_of(bj), fi = front_of(bi), fj = front_of(bj);
        int64_t w = windings_at_end(xs);
        const mpz_class one = 1, zero = 0;
        const mpz_class* pos_num = &zero;
        const mpz_class* pos_den = &one;
        auto portion = [&](const mpz_class& num, const mpz_class& den) {
            const int64_t wt = w + fj, ws = w + fi;  // W on the front of s (for t), of t (for s)
            const int kt = (wt == ci - 1) - (wt == ci), ks = (ws == cj - 1) - (ws == cj);
            if (kt != 0 || ks != 0) visit(P, Q, *pos_num, *pos_den, num, den, kt, ks);
        };
        for (const Triple& tr : triples) {
            portion(tr.num, tr.den);
            w += tr.sign;
            pos_num = &tr.num;
            pos_den = &tr.den;
        }
        portion(one, one);
        if (w != windings_at_end(xe))
            throw Contradiction("boolean: windings along a cut disagree with its end");
    }

    // The cones over a cut's portions: (μ' - μ) det(κ_t a_t - κ_s a_s, P, Q).
    void cut_pieces(const Cut& cut, PieceSum& out) {
        const IntPoint at = scale_.of(corner(cut.a, 0)), as = scale_.of(corner(cut.b, 0));
        for_each_portion(cut, [&](const Point0& P, const Point0& Q, const mpz_class& n0, const mpz_class& d0,
                                  const mpz_class& num, const mpz_class& den, int kt, int ks) {
            if (!moments_.empty()) {
                if (kt != 0) segment_moments(at, P, Q, n0, d0, num, den, kt);
                if (ks != 0) segment_moments(as, P, Q, n0, d0, num, den, -ks);
            }
            const mpz_class pq_den = P.den * Q.den;
            const IntPoint v = {kt * at[0] - ks * as[0], kt * at[1] - ks * as[1], kt * at[2] - ks * as[2]};
            const mpz_class dv = det3(v, P.num, Q.num);  // over pq_den
            for (int part = 0; part < 2; ++part) {
                const mpz_class& n = part == 0 ? num : n0;
                const mpz_class& d = part == 0 ? den : d0;
                const int sg = part == 0 ? +1 : -1;
                if (n == 0 || dv == 0) continue;
                if (n == d && pq_den == 1) {
                    out.integer += sg * dv;
                } else {
                    out.add_fraction(sg * n * dv, d * pq_den);
                }
            }
        });
    }

    const Operand& g_;
    const Crossings& cross_;
    const std::vector<int32_t>& w_;
    const std::vector<int>& sign_;
    Scale scale_;
    std::vector<EdgeHit> hits_;
    std::vector<std::array<uint32_t, 2>> cut_of_;  // (triangle, cut), sorted
    std::vector<uint32_t> crossed_;
    std::map<uint64_t, std::vector<WalkEntry>> walks_;
    int level_;
    std::span<PieceSum> moments_;  // empty: the volume only
};

}  // namespace polyvol::boolean
