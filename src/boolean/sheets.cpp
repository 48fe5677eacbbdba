// boolean/sheets.cpp — a body that crosses itself, cut into 2-manifold
// sheets where its surface is not one (operand.hpp, split_sheets).
//
// Around an edge u -> w used by 2k triangles, order them by the angle θ of
// their third vertex about e = w - u: orient(u, w, x_i, x_j) > 0 iff x_j lies
// within π after x_i (positive rotation about e). A triangle running u -> w
// has its front at +θ (N = e × (x - u)), so W falls by one crossing it toward
// +θ; one running w -> u raises it. Rises and falls are matched like
// parentheses: each pair bounds a wedge, and the front windings on either
// side of a pair agree (a path between them crosses every other pair twice).
#include <algorithm>
#include <tuple>
#include <vector>

#include "boolean/operand.hpp"
#include "boolean/predicates.hpp"
#include "core/union_find.hpp"

namespace polyvol::boolean {

void split_sheets(Operand& op) {
    struct HalfEdge {
        uint32_t lo, hi;  // vertex ids, lo < hi
        uint32_t t;
        uint8_t e;        // edge e of t: corner e -> corner e + 1
        int8_t dir;       // +1: runs lo -> hi
    };
    std::vector<HalfEdge> half;
    std::vector<uint32_t> tris;
    for (std::size_t t = 0; t < op.triangles(); ++t) {
        if (!op.crosses_itself(op.body(t))) continue;
        tris.push_back(static_cast<uint32_t>(t));
        for (int e = 0; e < 3; ++e) {
            const uint32_t u = op.tri[3 * t + e], w = op.tri[3 * t + (e + 1) % 3];
            if (u == w) continue;
            half.push_back({std::min(u, w), std::max(u, w), static_cast<uint32_t>(t), static_cast<uint8_t>(e),
                            static_cast<int8_t>(u < w ? 1 : -1)});
        }
    }
    std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return std::tie(x.lo, x.hi, x.t, x.e) < std::tie(y.lo, y.hi, y.t, y.e);
    });
    // Corners (t, i) joined where their triangles are paired across an edge at that corner.
    auto corner = [&](uint32_t t, int i) { return 3 * std::size_t{t} + static_cast<std::size_t>(i % 3); };
    core::UnionFind fans(op.tri.size());
    auto join = [&](const HalfEdge& a, const HalfEdge& b) {  // a runs u -> w, b w -> u
        if (a.dir == b.dir) throw SelfContact("boolean: an edge of a body that crosses itself is used twice in one direction");
        fans.unite(static_cast<uint32_t>(corner(a.t, a.e)), static_cast<uint32_t>(corner(b.t, b.e + 1)));
        fans.unite(static_cast<uint32_t>(corner(a.t, a.e + 1)), static_cast<uint32_t>(corner(b.t, b.e)));
    };
    bool split = false;
    for (std::size_t i = 0; i < half.size();) {
        std::size_t j = i;
        while (j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi) ++j;
        const std::size_t n = j - i;
        if (n == 2) {
            join(half[i], half[i + 1]);
        } else if (n > 2) {
            split = true;
            if (n % 2 != 0) throw SelfContact("boolean: an edge of a body that crosses itself has an odd number of triangles");
            const double* u = op.point(half[i].lo);
            const double* w = op.point(half[i].hi);
            auto third = [&](const HalfEdge& h) { return op.point(op.tri[3 * std::size_t{h.t} + (h.e + 2) % 3]); };
            const double* x0 = third(half[i]);
            // Angle from x0's half-plane: (0, π) first, then (π, 2π).
            auto half_of = [&](const HalfEdge& h) {
                if (&h == &half[i]) return -1;
                const int o = orient3d_sign(u, w, x0, third(h));
                if (o == 0) throw SelfContact("boolean: triangles around an edge of a body that crosses itself lie in one plane");
                return o > 0 ? 0 : 1;
            };
            std::vector<std::pair<int, const HalfEdge*>> around;
            for (std::size_t k = i; k < j; ++k) around.push_back({half_of(half[k]), &half[k]});
            std::sort(around.begin(), around.end(), [&](const auto& x, const auto& y) {
                if (x.first != y.first) return x.first < y.first;
                if (x.second == y.second) return false;
                const int o = orient3d_sign(u, w, third(*x.second), third(*y.second));
                if (o == 0) throw SelfContact("boolean: triangles around an edge of a body that crosses itself lie in one plane");
                return o > 0;
            });
            // Crossing a triangle toward +θ, W rises by s = -dir. Matched as
            // parentheses from a start where the running sum never drops
            // below 0: each fall pairs with the last unmatched rise, the two
            // bounding one wedge (nested wedges, or sheets crossing along
            // the edge, which bound the same winding numbers).
            int sum = 0, lowest = 0;
            std::size_t start = 0;
            for (std::size_t k = 0; k < n; ++k) {
                sum -= around[k].second->dir;
                if (sum < lowest) {
                    lowest = sum;
                    start = k + 1;
                }
            }
            if (sum != 0) throw SelfContact("boolean: the triangles around an edge of a body that crosses itself do not balance");
            std::vector<const HalfEdge*> open;
            for (std::size_t k = 0; k < n; ++k) {
                const HalfEdge* h = around[(start + k) % n].second;
                if (h->dir < 0) {
                    open.push_back(h);
                } else {
                    join(*h, *open.back());
                    open.pop_back();
                }
            }
        } else {
            throw SelfContact("boolean: an edge of a body that crosses itself has one triangle");
        }
        i = j;
    }
    // Vertices on more than one fan: a copy per fan (non-manifold edges, or a pinch).
    std::vector<uint32_t> first_root(op.mesh.vertex_count(), UINT32_MAX);
    std::vector<std::pair<uint32_t, uint32_t>> copies;  // (fan root, new vertex), sorted by root
    std::vector<std::pair<std::size_t, uint32_t>> moves;
    for (const uint32_t t : tris)
        for (int c = 0; c < 3; ++c) {
            const std::size_t k = corner(t, c);
            const uint32_t v = op.tri[k];
            const uint32_t root = fans.find(static_cast<uint32_t>(k));
            if (first_root[v] == UINT32_MAX) first_root[v] = root;
            if (first_root[v] != root) moves.push_back({k, root});
        }
    if (moves.empty() && !split) return;
    if (op.site.empty()) {
        op.site.resize(op.mesh.vertex_count());
        for (uint32_t v = 0; v < op.site.size(); ++v) op.site[v] = v;
    }
    std::sort(moves.begin(), moves.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
    for (std::size_t a = 0; a < moves.size();) {
        const uint32_t v = op.tri[moves[a].first];
        const double* p = op.point(v);
        const uint32_t copy = op.mesh.add_vertex(p[0], p[1], p[2]);
        op.site.push_back(op.site[v]);
        std::size_t b = a;
        for (; b < moves.size() && moves[b].second == moves[a].second; ++b) op.tri[moves[b].first] = copy;
        a = b;
    }
}

}  // namespace polyvol::boolean
