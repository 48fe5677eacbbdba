// boolean/vertex_windings.cpp — the other operand's winding number at every
// vertex of one operand.
//
// Along an edge x -> y the winding number w of a closed surface changes by
// the signed count of its triangles the edge crosses (+1 entering the solid):
// w(y) = w(x) + k(x, y). Almost every edge crosses nothing (k = 0): a
// union–find over those edges gives the parts of one winding;
// a union–find with offsets relates the parts over the few crossed edges
// (and finds a contradiction there: a body that is not closed). Each group
// of related parts then needs one value: 0 at a vertex outside the other
// operand's box, else the signed crossings of a ray from a vertex to a
// point beyond that box (where w = 0).
#include <gmpxx.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "boolean/operand.hpp"
#include "core/union_find.hpp"
#include "boolean/predicates.hpp"
#include "boolean/symbolic.hpp"

namespace polyvol::boolean {
namespace {

// Union–find in which every vertex knows w(v) - w(parent(v)).
class OffsetForest {
public:
    explicit OffsetForest(std::size_t n) : parent_(n), offset_(n, 0), size_(n, 1) {
        for (std::size_t v = 0; v < n; ++v) parent_[v] = static_cast<uint32_t>(v);
    }
    // The root of v, with w(v) - w(root) in `offset`.
    uint32_t find(uint32_t v, int64_t& offset) {
        int64_t total = 0;
        uint32_t r = v;
        while (parent_[r] != r) {
            total += offset_[r];
            r = parent_[r];
        }
        // Path compression: every vertex on the path points at r directly.
        int64_t remaining = total;
        while (parent_[v] != v) {
            const uint32_t next = parent_[v];
            const int64_t step = offset_[v];
            parent_[v] = r;
            offset_[v] = remaining;
            remaining -= step;
            v = next;
        }
        offset = total;
        return r;
    }
    // Records w(y) - w(x) == k; false when it contradicts what is known.
    bool relate(uint32_t x, uint32_t y, int64_t k) {
        int64_t ox, oy;
        uint32_t rx = find(x, ox), ry = find(y, oy);
        if (rx == ry) return oy - ox == k;
        // w(ry) = w(y) - oy = w(x) + k - oy = w(rx) + ox + k - oy
        int64_t d = ox + k - oy;
        if (size_[rx] < size_[ry]) {
            std::swap(rx, ry);
            d = -d;
        }
        parent_[ry] = rx;
        offset_[ry] = d;
        size_[rx] += size_[ry];
        return true;
    }

private:
    std::vector<uint32_t> parent_;
    std::vector<int64_t> offset_;
    std::vector<uint32_t> size_;
};

bool strictly_outside(const double* p, const std::array<double, 6>& box) {
    for (int k = 0; k < 3; ++k)
        if (p[k] < box[k] || p[k] > box[3 + k]) return true;
    return false;
}

// The winding number at p (a vertex of self's body `body`, moved by
// `shift` δ) of the other operand's bodies but that one: minus the signed
// crossings of the segment from p to a point beyond the other's box.
int64_t ray_winding(const double* p, uint32_t body, int32_t shift, const Operand& other, bool same) {
    const double reach = other.bounds[3] + (other.bounds[3] - other.bounds[0]) + 1.0;
    const double far[3] = {reach, p[1], p[2]};
    int64_t crossings = 0;
    for (std::size_t s = 0; s < other.triangles(); ++s) {
        const float* box = &other.box[6 * s];
        if (other.degenerate[s] || (same && other.body(s) == body) || box[3] < p[0] || box[1] > p[1] ||
            box[4] < p[1] || box[2] > p[2] || box[5] < p[2])
            continue;
        const int point_shift = shift > other.shift(s) ? 1 : -1;  // p relative to the triangle
        const double* const S[3] = {other.corner(s, 0), other.corner(s, 1), other.corner(s, 2)};
        const int from = perturbed_side(S[0], S[1], S[2], p, point_shift);
        const int to = perturbed_side(S[0], S[1], S[2], far, point_shift);
        if (from == to) continue;
        const int o0 = perturbed_orient_edges(p, far, S[0], S[1], -point_shift);
        if (o0 != perturbed_orient_edges(p, far, S[1], S[2], -point_shift) ||
            o0 != perturbed_orient_edges(p, far, S[2], S[0], -point_shift))
            continue;
        crossings += from;  // +1: entering the other solid
    }
    return -crossings;
}

using Q3 = RationalPoint;

int orient_sign(const Q3& s0, const Q3& s1, const Q3& s2, const Q3& x) { return sgn(orient_of<mpq_class>(s0, s1, s2, x)); }

// The sign of (y - x) × (z - x) projected along axis k.
int orient2_sign(const Q3& x, const Q3& y, const Q3& z, int k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    return sgn(mpq_class((y[i] - x[i]) * (z[j] - x[j]) - (y[j] - x[j]) * (z[i] - x[i])));
}

struct Touch {};  // the ray or the segment meets a triangle other than by crossing its interior

// The body's own winding in front of triangle t at its centroid, less the
// crossings of the segment from t's corner 0 to the centroid: the winding
// in front of the surface at corner 0 (operand.hpp, own_front_seed).
int64_t own_front_at_corner(const Operand& op, uint32_t body, uint32_t t) {
    const Q3 a = rational_point(op.corner(t, 0)), b = rational_point(op.corner(t, 1)), c = rational_point(op.corner(t, 2));
    Q3 q;
    for (int k = 0; k < 3; ++k) q[k] = (a[k] + b[k] + c[k]) / 3;
    // The ray: from q along ±e_k, k the largest component of N_t, toward t's front.
    const Q3 u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Q3 n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (abs(n[i]) > abs(n[k])) k = i;
    const int dir = sgn(n[k]);
    double qd[3], lo[3], hi[3];  // q in double, and the segment a -> q's box, with a margin
    for (int i = 0; i < 3; ++i) {
        qd[i] = q[i].get_d();
        const double margin = 1e-9 * (std::fabs(qd[i]) + std::fabs(op.corner(t, 0)[i])) + 1e-300;
        lo[i] = std::min(qd[i], op.corner(t, 0)[i]) - margin;
        hi[i] = std::max(qd[i], op.corner(t, 0)[i]) + margin;
    }
    const int ii = (k + 1) % 3, jj = (k + 2) % 3;
    const double mi = 1e-9 * std::fabs(qd[ii]) + 1e-300, mj = 1e-9 * std::fabs(qd[jj]) + 1e-300;
    int64_t entering = 0, along = 0;
    for (std::size_t s = 0; s < op.triangles(); ++s) {
        if (s == t || op.body(s) != body || op.degenerate[s]) continue;
        // s's exact box: a triangle admitted here whose plane holds q throws
        // Touch, so the float filter's wider box would refuse more seeds.
        double box[6];
        for (int d = 0; d < 3; ++d) {
            box[d] = std::min({op.corner(s, 0)[d], op.corner(s, 1)[d], op.corner(s, 2)[d]});
            box[3 + d] = std::max({op.corner(s, 0)[d], op.corner(s, 1)[d], op.corner(s, 2)[d]});
        }
        const bool on_ray = box[ii] <= qd[ii] + mi && box[3 + ii] >= qd[ii] - mi && box[jj] <= qd[jj] + mj &&
                            box[3 + jj] >= qd[jj] - mj;
        const bool on_segment = box[0] <= hi[0] && box[3] >= lo[0] && box[1] <= hi[1] && box[4] >= lo[1] &&
                                box[2] <= hi[2] && box[5] >= lo[2];
        if (!on_ray && !on_segment) continue;
        const Q3 s0 = rational_point(op.corner(s, 0)), s1 = rational_point(op.corner(s, 1)), s2 = rational_point(op.corner(s, 2));
        const int oq = orient_sign(s0, s1, s2, q);
        if (on_ray) {
            // Where the ray pierces s's plane, q's projection along e_k is inside s's.
            const int e0 = orient2_sign(s0, s1, q, k), e1 = orient2_sign(s1, s2, q, k), e2 = orient2_sign(s2, s0, q, k);
            const int nsk = orient2_sign(s0, s1, s2, k);  // sign of N_s[k]
            if (nsk != 0 && (e0 == 0 || e1 == 0 || e2 == 0)) {
                if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) throw Touch{};
            } else if (nsk != 0 && e0 == e1 && e1 == e2) {
                if (oq == 0) throw Touch{};                // q on s
                if (oq == -dir * nsk) entering += oq;      // ahead of q: +1 from s's front to its back
            }
        }
        if (on_segment && !op.share_corner(s, t)) {
            // Triangles sharing a vertex with t meet the segment only where
            // the body folds (refused by the crossing search).
            const int oa = orient_sign(s0, s1, s2, a);
            if (oq == 0) throw Touch{};
            if (oa != 0 && oa != oq) {
                // The crossing of segment a -> q with s's plane is inside s iff
                // orient(a, q, s_j, s_j+1) has one sign for the three edges.
                const int f0 = orient_sign(a, q, s0, s1), f1 = orient_sign(a, q, s1, s2), f2 = orient_sign(a, q, s2, s0);
                if (f0 == 0 || f1 == 0 || f2 == 0) {
                    if ((f0 >= 0 && f1 >= 0 && f2 >= 0) || (f0 <= 0 && f1 <= 0 && f2 <= 0)) throw Touch{};
                } else if (f0 == f1 && f1 == f2) {
                    along += oa;  // +1: from s's front to its back, the winding in front of t rises
                }
            }
        }
    }
    // W(q front) = -entering; W(q front) = W(a front) + along.
    return -entering - along;
}

}  // namespace

WindingSeed own_front_seed(const Operand& op, uint32_t body, int front, const std::vector<uint32_t>& all) {
    std::vector<uint32_t> candidates;
    for (const uint32_t t : all)
        if (!op.degenerate[t]) candidates.push_back(t);
    constexpr std::size_t kTries = 16;
    for (std::size_t i = 0; i < std::min(kTries, candidates.size()); ++i) {
        const uint32_t t = candidates[i * candidates.size() / std::min(kTries, candidates.size())];
        try {
            return {op.tri[3 * std::size_t{t}], own_front_at_corner(op, body, t) - front};
        } catch (const Touch&) {
        }
    }
    throw SelfContact("boolean: no clean ray for the winding of a body that crosses itself");
}

std::vector<int32_t> vertex_windings(const Operand& self, const Operand& other, const std::vector<EdgeHit>& hits,
                                     const std::vector<WindingSeed>& seeds) {
    const std::size_t nv = self.mesh.vertex_count(), nt = self.triangles();
    const bool same = &self == &other;
    // The edges some hit crosses, with their signed counts k (3 t + e each);
    // every other edge joins two vertices of one winding.
    std::vector<std::pair<std::size_t, int64_t>> crossed;
    crossed.reserve(hits.size());
    for (const EdgeHit& h : hits) crossed.emplace_back(3 * std::size_t{h.tri} + h.edge, h.sign);
    std::sort(crossed.begin(), crossed.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::size_t kept = 0;
    for (std::size_t i = 0; i < crossed.size(); ++i) {
        if (kept > 0 && crossed[kept - 1].first == crossed[i].first)
            crossed[kept - 1].second += crossed[i].second;
        else
            crossed[kept++] = crossed[i];
    }
    crossed.resize(kept);
    std::vector<uint8_t> crossed_edges(nt, 0);  // bit e: edge e of the triangle is in `crossed`
    for (const auto& [edge, k] : crossed) crossed_edges[edge / 3] |= uint8_t(1u << (edge % 3));

    // Parts of equal winding: the vertices joined by uncrossed edges. One
    // thread: a concurrent union–find was slower on two cores, its threads
    // writing the same cache lines wherever the vertex order is not spatial.
    core::UnionFind parts(nv);
    std::vector<uint8_t> used(nv, 0);
    for (std::size_t t = 0; t < nt; ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t x = self.tri[3 * t + e], y = self.tri[3 * t + (e + 1) % 3];
            used[x] = 1;
            if (!(crossed_edges[t] >> e & 1)) parts.unite(x, y);
        }
    std::vector<uint32_t> part(nv);  // the part's root
    for (uint32_t v = 0; v < nv; ++v) part[v] = parts.find(v);

    // The parts related by the crossed edges: w(y) - w(x) = k between their
    // parts, in an offset forest over the parts' roots (few: those the
    // crossed edges touch stand apart, the rest are their own groups).
    std::vector<uint32_t> roots;
    for (uint32_t v = 0; v < nv; ++v)
        if (part[v] == v && used[v] != 0) roots.push_back(v);
    auto group_of = [&](uint32_t v) {
        return static_cast<uint32_t>(std::lower_bound(roots.begin(), roots.end(), part[v]) - roots.begin());
    };
    OffsetForest groups(roots.size());
    for (const auto& [edge, k] : crossed) {
        const std::size_t t = edge / 3;
        const int e = static_cast<int>(edge % 3);
        if (!groups.relate(group_of(self.tri[3 * t + e]), group_of(self.tri[3 * t + (e + 1) % 3]), k))
            throw Contradiction("boolean: winding numbers along edges disagree (an operand is not closed)");
    }
    std::vector<uint32_t> group_root(roots.size());  // each group's root in `groups`
    std::vector<int64_t> group_offset(roots.size());  // w(group) - w(its root)
    std::size_t unknown = 0;                          // roots without a value
    for (uint32_t g = 0; g < roots.size(); ++g) {
        group_root[g] = groups.find(g, group_offset[g]);
        unknown += group_root[g] == g;
    }
    // One value per root: a seed's, 0 at a vertex outside the other's box,
    // else a ray's.
    constexpr int64_t kUnknown = INT64_MIN;
    std::vector<int64_t> value(roots.size(), kUnknown);
    auto unknown_at = [&](uint32_t v) { return value[group_root[group_of(v)]] == kUnknown; };
    auto settle = [&](uint32_t v, int64_t w_at_v) {  // w(v) = w_at_v, where v's root has no value yet
        const uint32_t g = group_of(v);
        if (value[group_root[g]] != kUnknown) return;
        value[group_root[g]] = w_at_v - group_offset[g];
        --unknown;
    };
    auto ray = [&](uint32_t v) {
        std::size_t corner = 0;  // a triangle using v: its body and shift
        while (self.tri[corner] != v) ++corner;
        const std::size_t t = corner / 3;
        return ray_winding(self.point(v), self.body(t), self.shift(t), other, same);
    };
    for (const WindingSeed& seed : seeds)  // bodies crossing themselves: their own part too
        settle(seed.vertex, ray(seed.vertex) + seed.own);
    auto is_used = [&](uint32_t v) { return used[v] != 0; };
    const bool far_away_exists = other.triangles() > 0;
    for (uint32_t v = 0; v < nv && unknown > 0; ++v)
        if (is_used(v) && (!far_away_exists || (!same && strictly_outside(self.point(v), other.bounds)))) settle(v, 0);
    for (uint32_t v = 0; v < nv && unknown > 0; ++v)
        if (is_used(v) && unknown_at(v)) settle(v, ray(v));
    std::vector<int32_t> w(nv, 0);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, static_cast<uint32_t>(nv), 4096), [&](const auto& range) {
        for (uint32_t v = range.begin(); v != range.end(); ++v) {
            if (!is_used(v)) continue;
            const uint32_t g = group_of(v);
            w[v] = static_cast<int32_t>(value[group_root[g]] + group_offset[g]);
        }
    });
    return w;
}

}  // namespace polyvol::boolean
