// boolean/solid_volume.cpp — the volume of the solid a file's shells bound
// together: the region where their winding number W is >= 1.
//
// A point x of triangle t of shell i lies on the boundary of {W >= 1} iff W
// on t's front side is 0 there: W_others(x) = c_i, c_i = 0 for an outward
// shell, 1 for an inward one (a cavity: its own winding is -1 in front).
// So the boundary is, per triangle, the region R_t = {x in t : W_others = c_i},
// and 6 |{W >= 1}| = Σ_t 6 cone(R_t), each fanned from t's first corner a
// (boolean_volumes.cpp):
//   * edge b -> c: W_others changes by σ at each crossing λ (sorted along
//     the edge); the intervals where W_others = c_i give (λ' - λ) det(a, b, c);
//   * a cut t ∩ s (s in shell j), run P -> Q along N_t × N_s with the back of
//     s on its left: R_t lies on its left where W_r = c_i - 1 and on its
//     right where W_r = c_i, W_r being W_others on the front of s:
//     W_r = W_{not i, j} + f_j (f = 0 outward, -1 inward). Where a third shell
//     r crosses the cut, W_{not i, j} changes: the cut is split there (the
//     triple points t ∩ s ∩ r). With s's share (run Q -> P), each portion
//     [μ, μ'] gives (μ' - μ) det(κ_t a_t - κ_s a_s, P, Q),
//     κ = [W_r = c - 1] - [W_r = c].
// Shells whose boxes overlap no other shell's are their own solid (or
// nothing, inward) and cost nothing more. Each shell must not cross itself.
#include <algorithm>
#include <limits>
#include <map>
#include <span>
#include <numeric>
#include <stdexcept>

#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "boolean/predicates.hpp"
#include "boolean/symbolic.hpp"
#include "measure/cone.hpp"
#include "exact/eft.hpp"
#include "exact/expansion.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"
#include "topology/edges.hpp"
#include "topology/shells.hpp"
#include "topology/union_find.hpp"
#include "topology/welded.hpp"

namespace polyvol {
namespace boolean {
namespace {

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
                const std::vector<int>& body_sign, const Scale& scale)
        : g_(g), cross_(cross), w_(winding), sign_(body_sign), scale_(scale) {
        hits_ = cross.a_hits;
        hits_.insert(hits_.end(), cross.b_hits.begin(), cross.b_hits.end());
        std::sort(hits_.begin(), hits_.end(), [](const EdgeHit& x, const EdgeHit& y) {
            return std::tie(x.tri, x.edge) < std::tie(y.tri, y.edge);
        });
        cuts_of_.resize(g.triangles());
        for (std::size_t c = 0; c < cross.cuts.size(); ++c) {
            cuts_of_[cross.cuts[c].a].push_back(static_cast<uint32_t>(c));
            cuts_of_[cross.cuts[c].b].push_back(static_cast<uint32_t>(c));
        }
    }

    // Adds the pieces to out (out.size() == 1: volume; kSums: moments too);
    // triangles with no crossing on edge b -> c and W_others = c there go to
    // `whole` instead (summed by measure's exact kernels).
    void sum(std::span<PieceSum> out, std::vector<uint32_t>& whole) {
        moments_ = out.size() > 1 ? out : std::span<PieceSum>();
        for (std::size_t t = 0; t < g_.triangles(); ++t) edge_pieces(static_cast<uint32_t>(t), out[0], whole);
        for (const Cut& cut : cross_.cuts) cut_pieces(cut, out[0]);
    }

private:
    struct WalkEntry {
        uint32_t other;
        int sign;
        mpz_class num, den;  // λ = num / den, den > 0
        int64_t w_before;    // W_others just before this crossing
    };

    int c_of(uint32_t body) const { return sign_[body] > 0 ? 0 : 1; }
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
        return det3_of<EpsPoly>(a, b, d).sign() * den.sign();
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
        std::sort(ls.begin(), ls.end(), [&](const Lambda& x, const Lambda& y) {
            const int c = sgn(mpz_class(x.num * y.den - y.num * x.den));
            if (c != 0) return c < 0;
            return perturbed_less(x.ref, y.ref);
        });
        int64_t w = w_[g_.tri[3 * t + e]];
        for (Lambda& l : ls) {
            entries.push_back({l.ref.plane, l.sign, std::move(l.num), std::move(l.den), w});
            w += l.sign;
        }
        if (w != w_[g_.tri[3 * t + (e + 1) % 3]])
            throw std::logic_error("boolean: windings along an edge disagree with its end (a shell crosses itself?)");
        return walks_.emplace(key, std::move(entries)).first->second;
    }

    // λ(x) < λ(y) for two crossings of one edge that coincide at ε = 0.
    bool perturbed_less(const CrossingRef& x, const CrossingRef& y) const {
        auto to = [&](const double* v, int32_t k) { return eps_point(v, k); };
        EpsPoly dpx, dqx, dpy, dqy;
        EpsPoint p, q;
        plane_values<EpsPoly>(x, to, dpx, dqx, p, q);
        plane_values<EpsPoly>(y, to, dpy, dqy, p, q);
        const EpsPoly dx = dpx - dqx, dy = dpy - dqy;
        // λx - λy = (dpx dy - dpy dx) / (dx dy)
        const int s = (dpx * dy - dpy * dx).sign() * dx.sign() * dy.sign();
        if (s != 0) return s < 0;
        return x.plane < y.plane;  // the same point for every ε: any order
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
        throw std::logic_error("boolean: a cut's end is not among its edge's crossings");
    }

    void cut_pieces(const Cut& cut, PieceSum& out) {
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
        for (uint32_t ci : cuts_of_[t]) {
            const Cut& other = cross_.cuts[ci];
            const uint32_t r = other.a == t ? other.b : other.a;
            const uint32_t br = g_.body(r);
            if (br == bi || br == bj) continue;
            const int sp = side(xs, P, r), sq = side(xe, Q, r);
            if (sp == sq) continue;
            // The cut t ∩ r must meet the plane of s between its ends.
            auto ref2 = [&](const CutEnd& e) {
                const uint32_t oa = other.a, ob = other.b;
                return e.of_b ? CrossingRef{ob, e.edge, oa} : CrossingRef{oa, e.edge, ob};
            };
            const CrossingRef ys = ref2(other.start), ye = ref2(other.end);
            if (side(ys, point0(ys), s) == side(ye, point0(ye), s)) continue;
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

        const IntPoint at = scale_.of(corner(t, 0)), as = scale_.of(corner(s, 0));
        const mpz_class pq_den = P.den * Q.den;
        const int ci = c_of(bi), cj = c_of(bj), fi = front_of(bi), fj = front_of(bj);
        int64_t w = windings_at_end(xs);
        const mpz_class one = 1, zero = 0;
        const mpz_class* pos_num = &zero;
        const mpz_class* pos_den = &one;
        auto portion = [&](const mpz_class& num, const mpz_class& den) {
            const int64_t wt = w + fj, ws = w + fi;  // W on the front of s (for t), of t (for s)
            const int kt = (wt == ci - 1) - (wt == ci), ks = (ws == cj - 1) - (ws == cj);
            if (kt == 0 && ks == 0) return;
            if (!moments_.empty()) {
                if (kt != 0) segment_moments(at, P, Q, *pos_num, *pos_den, num, den, kt);
                if (ks != 0) segment_moments(as, P, Q, *pos_num, *pos_den, num, den, -ks);
            }
            const IntPoint v = {kt * at[0] - ks * as[0], kt * at[1] - ks * as[1], kt * at[2] - ks * as[2]};
            const mpz_class dv = det3(v, P.num, Q.num);  // over pq_den
            for (int part = 0; part < 2; ++part) {
                const mpz_class& n = part == 0 ? num : *pos_num;
                const mpz_class& d = part == 0 ? den : *pos_den;
                const int sg = part == 0 ? +1 : -1;
                if (n == 0 || dv == 0) continue;
                if (n == d && pq_den == 1) {
                    out.integer += sg * dv;
                } else {
                    out.add_fraction(sg * n * dv, d * pq_den);
                }
            }
        };
        for (const Triple& tr : triples) {
            portion(tr.num, tr.den);
            w += tr.sign;
            pos_num = &tr.num;
            pos_den = &tr.den;
        }
        portion(one, one);
        if (w != windings_at_end(xe))
            throw std::logic_error("boolean: windings along a cut disagree with its end");
    }

    const Operand& g_;
    const Crossings& cross_;
    const std::vector<int32_t>& w_;
    const std::vector<int>& sign_;
    Scale scale_;
    std::vector<EdgeHit> hits_;
    std::vector<std::vector<uint32_t>> cuts_of_;
    std::map<uint64_t, std::vector<WalkEntry>> walks_;
    std::span<PieceSum> moments_;  // empty: the volume only
};

// One group of shells whose boxes overlap: its crossings, windings and
// pieces (added to `pieces`), and what the report says of it.
void solid_group(const Operand& g, const std::vector<uint32_t>& g_face, const std::vector<uint32_t>& shells,
                 const std::vector<int>& body_sign, const Scale& scale, std::size_t faces, std::span<PieceSum> pieces,
                 Mesh& whole, SolidVolume& r) {
    const std::size_t n = g.triangles();
    const Crossings cross = find_crossings(g, g);

        r.crossing_pairs += cross.cuts.size();
        std::vector<EdgeHit> hits = cross.a_hits;
        hits.insert(hits.end(), cross.b_hits.begin(), cross.b_hits.end());
        const std::vector<int32_t> w = vertex_windings(g, g, hits);
        // Overlapping: crossing another shell, or an outward shell inside another solid.
        std::vector<uint8_t> overlapping(shells.size(), 0);
        for (const Cut& c : cross.cuts) overlapping[g.body(c.a)] = overlapping[g.body(c.b)] = 1;
        for (std::size_t t = 0; t < n; ++t)
            if (body_sign[g.body(t)] > 0 && w[g.tri[3 * t]] >= 1) overlapping[g.body(t)] = 1;
        r.overlapping_shells += static_cast<std::size_t>(std::count(overlapping.begin(), overlapping.end(), 1));
        if (!cross.cuts.empty()) {
            if (!r.crossing_example) r.crossing_example = {g_face[cross.cuts[0].a], g_face[cross.cuts[0].b]};
            if (r.face_crosses.empty()) r.face_crosses.assign(faces, 0);
            std::vector<uint8_t> crosses(shells.size(), 0);
            for (const Cut& c : cross.cuts) crosses[g.body(c.a)] = crosses[g.body(c.b)] = 1;
            for (std::size_t t = 0; t < n; ++t)
                if (crosses[g.body(t)]) r.face_crosses[g_face[t]] = 1;
        }
    std::vector<uint32_t> whole_triangles;
    SolidPieces(g, cross, w, body_sign, scale).sum(pieces, whole_triangles);
    const auto base = static_cast<uint32_t>(whole.vertex_count());
    whole.positions.insert(whole.positions.end(), g.mesh.positions.begin(), g.mesh.positions.end());
    for (uint32_t t : whole_triangles) whole.add_triangle(base + g.tri[3 * t], base + g.tri[3 * t + 1], base + g.tri[3 * t + 2]);
}

// Components of the polygons joined through shared vertex indices (as the
// file gives them), if every one is balanced on welded positions; else the
// shells joined through welded positions.
topology::ShellLabels bodies_of(const topology::WeldedMesh& wm) {
    struct Use {
        uint64_t key;  // (min, max) vertex index
        uint32_t poly;
    };
    std::vector<Use> uses;
    wm.for_each_polygon([&](uint32_t poly, std::span<const uint32_t> c) {
        for (std::size_t i = 0; i < c.size(); ++i) {
            const uint32_t u = c[i], v = c[(i + 1) % c.size()];
            uses.push_back({(uint64_t{std::min(u, v)} << 32) | std::max(u, v), poly});
        }
    });
    std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) { return x.key < y.key; });
    topology::UnionFind parts(wm.polygons);
    for (std::size_t i = 1; i < uses.size(); ++i)
        if (uses[i].key == uses[i - 1].key) parts.unite(uses[i].poly, uses[i - 1].poly);
    topology::ShellLabels labels = topology::label_shells(parts);
    // Balanced per part: every welded edge used as often in each direction.
    struct Directed {
        uint32_t part, lo, hi;
        int dir;
    };
    std::vector<Directed> edges;
    wm.for_each_polygon([&](uint32_t poly, std::span<const uint32_t> c) {
        for (std::size_t i = 0; i < c.size(); ++i) {
            const uint32_t u = wm.id[c[i]], v = wm.id[c[(i + 1) % c.size()]];
            if (u != v) edges.push_back({labels.of_polygon[poly], std::min(u, v), std::max(u, v), u < v ? 1 : -1});
        }
    });
    std::sort(edges.begin(), edges.end(), [](const Directed& x, const Directed& y) {
        return std::tie(x.part, x.lo, x.hi) < std::tie(y.part, y.lo, y.hi);
    });
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        int balance = 0;
        for (; j < edges.size() && edges[j].part == edges[i].part && edges[j].lo == edges[i].lo &&
               edges[j].hi == edges[i].hi;
             ++j)
            balance += edges[j].dir;
        if (balance != 0) {
            topology::UnionFind shells(wm.polygons);
            topology::build_edge_table(wm, &shells);
            return topology::label_shells(shells);
        }
        i = j;
    }
    return labels;
}

}  // namespace
}  // namespace boolean

SolidVolume solid_volume(const MeshView& mesh, bool moments) {
    using namespace boolean;
    SolidVolume r;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto fail = [&](BooleanStatus s) {
        r.status = s;
        r.volume = r.winding_volume = nan;
        return r;
    };
    TopologyOptions edges_only;
    edges_only.shells = false;
    if (!analyze_topology(mesh, edges_only).closed_2_cycle) return fail(BooleanStatus::a_not_closed);

    // The bodies: the parts as the file joins them by vertex indices, when
    // each of them is a closed 2-cycle (parts that touch or coincide stay
    // apart); otherwise the shells, joined by welded positions (topology.hpp).
    const topology::WeldedMesh wm = topology::weld_polygons(mesh);
    const topology::ShellLabels labels = bodies_of(wm);
    r.shells = labels.count;
    std::vector<std::vector<std::array<uint32_t, 3>>> shell_tris(labels.count);
    std::vector<std::vector<uint32_t>> shell_faces(labels.count);  // the face of each fan triangle
    for (uint32_t f = 0, poly = 0; f < mesh.face_count(); ++f) {
        const auto c = mesh.face(f);
        if (c.size() < 3) continue;
        const uint32_t sh = labels.of_polygon[poly++];
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            shell_tris[sh].push_back({wm.id[c[0]], wm.id[c[i]], wm.id[c[i + 1]]});
            shell_faces[sh].push_back(f);
        }
    }
    int e0 = std::numeric_limits<int>::max();
    for (std::size_t d = 0; d < wm.referenced(); ++d)
        for (int k = 0; k < 3; ++k) {
            const double x = wm.position(static_cast<uint32_t>(d))[k];
            if (!exact::in_safe_range(x) || std::fabs(x) > 0x1p180) return fail(BooleanStatus::invalid_coordinates);
            if (x != 0) e0 = std::min(e0, lowest_bit_exponent(x));
        }
    if (e0 == std::numeric_limits<int>::max()) e0 = 0;

    // Each shell's volume sign and box, and the shells' sum (the winding
    // integral): measure's double-double sums, exact where they cannot decide.
    std::vector<uint32_t> flat;  // every shell's triangles, shell after shell
    std::vector<std::size_t> first(labels.count + 1, 0);
    std::vector<std::array<double, 6>> box(labels.count, {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY});
    for (std::size_t sh = 0; sh < labels.count; ++sh) {
        for (const auto& tr : shell_tris[sh]) {
            flat.insert(flat.end(), tr.begin(), tr.end());
            for (uint32_t v : tr)
                for (int k = 0; k < 3; ++k) {
                    box[sh][k] = std::min(box[sh][k], wm.position(v)[k]);
                    box[sh][3 + k] = std::max(box[sh][3 + k], wm.position(v)[k]);
                }
        }
        first[sh + 1] = flat.size();
    }
    auto volume_sum = [&](std::span<const uint32_t> tris, bool exactly) {
        return cone_volume_sum({wm.xyz, {}, tris}, exactly);
    };
    std::vector<int> shell_sign(labels.count, 1);
    for (std::size_t sh = 0; sh < labels.count; ++sh) {
        const std::span<const uint32_t> tris(flat.data() + first[sh], first[sh + 1] - first[sh]);
        VolumeSum v = volume_sum(tris, false);
        if (!(std::fabs(v.sum.round()) > 2 * v.bound)) v = volume_sum(tris, true);
        shell_sign[sh] = v.sum.sign() >= 0 ? +1 : -1;
    }
    {
        const VolumeSum all = volume_sum(flat, false);
        const auto decided = exact::decided_round_div(all.sum, all.bound, 6);
        r.winding_volume = decided ? *decided : volume_sum(flat, true).sum.round_div(6);
    }

    // Groups of shells whose boxes overlap (closed boxes: touching counts).
    std::vector<uint32_t> order(labels.count);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return box[x][0] < box[y][0]; });
    topology::UnionFind groups(labels.count);
    for (std::size_t i = 0; i < order.size(); ++i)
        for (std::size_t j = i + 1; j < order.size() && box[order[j]][0] <= box[order[i]][3]; ++j) {
            const auto &p = box[order[i]], &q = box[order[j]];
            if (p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5]) groups.unite(order[i], order[j]);
        }
    std::map<uint32_t, std::vector<uint32_t>> members;
    for (uint32_t sh = 0; sh < labels.count; ++sh) members[groups.find(sh)].push_back(sh);

    std::vector<PieceSum> pieces(moments ? kSums : 1);
    Mesh whole;  // whole triangles of the solid's boundary, summed at the end
    const Scale scale{e0};
    for (const auto& [root, shells] : members) {
        if (shells.size() == 1) {
            if (shell_sign[shells[0]] < 0) continue;  // inward alone: no solid
            const auto base = static_cast<uint32_t>(whole.vertex_count());
            std::map<uint32_t, uint32_t> local;
            for (const auto& tr : shell_tris[shells[0]]) {
                uint32_t v[3];
                for (int i = 0; i < 3; ++i) {
                    auto [it, fresh] = local.try_emplace(tr[i], static_cast<uint32_t>(local.size()));
                    if (fresh) {
                        const double* p = wm.position(tr[i]);
                        whole.add_vertex(p[0], p[1], p[2]);
                    }
                    v[i] = base + it->second;
                }
                whole.add_triangle(v[0], v[1], v[2]);
            }
            continue;
        }
        r.shells_checked += shells.size();
        Operand g;
        std::vector<uint32_t> g_face;
        g.body_shift.clear();
        std::vector<int> body_sign;
        std::vector<uint32_t> new_id(wm.referenced(), UINT32_MAX);
        for (uint32_t b = 0; b < shells.size(); ++b) {
            const uint32_t sh = shells[b];
            g.body_shift.push_back(static_cast<int32_t>(b + 1));
            body_sign.push_back(shell_sign[sh]);
            const uint32_t first_vertex = static_cast<uint32_t>(g.mesh.vertex_count());
            g_face.insert(g_face.end(), shell_faces[sh].begin(), shell_faces[sh].end());
            for (const auto& tr : shell_tris[sh]) {
                for (uint32_t v : tr) {
                    if (new_id[v] == UINT32_MAX || new_id[v] < first_vertex) {  // each body its own vertices
                        const double* p = wm.position(v);
                        new_id[v] = g.mesh.add_vertex(p[0], p[1], p[2]);
                    }
                    g.tri.push_back(new_id[v]);
                }
                g.body_of_triangle.push_back(b);
            }
        }
        finish_operand(g);
        try {
            solid_group(g, g_face, shells, body_sign, scale, mesh.face_count(), pieces, whole, r);
        } catch (const std::logic_error&) {
            return fail(BooleanStatus::shell_crosses_itself);
        }
    }
    // The whole triangles' sums by measure's kernels (parallel): the volume
    // filtered first (an interval), exact when that leaves the rounding open.
    const Combination one[1] = {{nullptr, +1}};
    const uint32_t mask = moments ? (1u << kSums) - 1 : 1u;
    // (SolidPieces leaves every sum's whole part to these.)
    const VolumeSum whole_volume = cone_volume_sum(whole.view(), false);
    pieces[0].whole = whole_volume.sum;
    pieces[0].whole_bound = whole_volume.bound;
    std::vector<double> v = round_combinations(pieces[0], e0, one, r.refinements);
    if (v.empty() || moments) {
        measure::cone::ConeSums exact_whole;  // all sums (count = kSumCount)
        measure::cone::exact_sums(whole.view(), mask, exact_whole);
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            pieces[k].whole = exact_whole.sum[k];
            pieces[k].whole_bound = 0;
        }
        if (v.empty()) v = round_combinations(pieces[0], e0, one, r.refinements);
    }
    r.volume = v[0];
    if (!moments) return r;
    int refinements = 0;
    for (int k = 1; k < kSums; ++k) {
        const int degree = k <= measure::cone::kMz ? 4 : 5;
        const double m = round_combinations(pieces[k], e0, one, refinements, degree, measure::cone::divisor(k))[0];
        (k <= measure::cone::kMz ? r.first_moments[k - 1] : r.second_moments[k - 4]) = m;
    }
    r.moments = true;
    // Centroid F / V in double: F and V each within half an ulp, so within
    // 1.5 ulp + rounding of the quotient: a relative error below 2^-51.
    for (int i = 0; i < 3; ++i) r.centroid[i] = r.volume != 0 ? r.first_moments[i] / r.volume : nan;
    // Inertia about the centroid: Σ_c = S - V c c^T, then the tensor.
    std::array<double, 6> central = r.second_moments;
    static constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
    double scale_of_terms = 0;
    for (int k = 0; k < 6; ++k) {
        const double shift = r.first_moments[kPairs[k][0]] * r.centroid[kPairs[k][1]];
        central[k] -= shift;
        scale_of_terms = std::max({scale_of_terms, std::fabs(r.second_moments[k]), std::fabs(shift)});
    }
    r.inertia_centroid = inertia_from_second_moments(central);
    double largest = 0;
    for (double x : r.inertia_centroid) largest = std::max(largest, std::fabs(x));
    // Each central moment: two terms within 2 ulp each, one subtraction, one
    // addition in the tensor: |error| <= 16 u of the largest term.
    r.inertia_relative_error = largest > 0 ? 16 * 0x1p-53 * 2 * scale_of_terms / largest : INFINITY;
    return r;
}

}  // namespace polyvol
