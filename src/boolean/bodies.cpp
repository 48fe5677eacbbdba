// boolean/bodies.cpp — bodies.hpp.
#include "boolean/bodies.hpp"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <tuple>
#include <vector>

#include "core/union_find.hpp"

namespace polyvol::boolean {

topology::ShellLabels bodies_of(const topology::WeldedMesh& wm) {
    struct Use {
        uint64_t key;  // (min, max) vertex index
        uint32_t poly;
        int32_t dir;   // +1 when the polygon runs min -> max
    };
    std::vector<Use> uses;
    uses.reserve(wm.mesh.indices.size());
    wm.for_each_polygon([&](uint32_t poly, std::span<const uint32_t> c) {
        for (std::size_t i = 0; i < c.size(); ++i) {
            const uint32_t u = c[i], v = c[(i + 1) % c.size()];
            uses.push_back({(uint64_t{std::min(u, v)} << 32) | std::max(u, v), poly, u < v ? 1 : -1});
        }
    });
    tbb::parallel_sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) { return x.key < y.key; });
    core::UnionFind parts(wm.polygons);
    for (std::size_t i = 1; i < uses.size(); ++i)
        if (uses[i].key == uses[i - 1].key) parts.unite(uses[i].poly, uses[i - 1].poly);
    topology::ShellLabels labels = topology::label_shells(parts);
    // Balanced per part: every welded edge used as often in each direction.
    // Where no two vertices share a position, a welded edge is one index
    // pair, all of whose uses lie in one part: its uses' sum says it.
    if (wm.welded == wm.mesh.vertex_count()) {
        for (std::size_t i = 0; i < uses.size();) {
            int balance = 0;
            std::size_t j = i;
            for (; j < uses.size() && uses[j].key == uses[i].key; ++j) balance += uses[j].dir;
            if (balance != 0 && (uses[i].key >> 32) != (uses[i].key & 0xffffffffu))
                return topology::edge_connected_shells(wm);
            i = j;
        }
        return labels;
    }
    struct Directed {
        uint32_t part, lo, hi;
        int dir;
    };
    std::vector<Directed> edges;
    edges.reserve(uses.size());
    wm.for_each_polygon([&](uint32_t poly, std::span<const uint32_t> c) {
        for (std::size_t i = 0; i < c.size(); ++i) {
            const uint32_t u = wm.id[c[i]], v = wm.id[c[(i + 1) % c.size()]];
            if (u != v) edges.push_back({labels.of_polygon[poly], std::min(u, v), std::max(u, v), u < v ? 1 : -1});
        }
    });
    tbb::parallel_sort(edges.begin(), edges.end(), [](const Directed& x, const Directed& y) {
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
            return topology::edge_connected_shells(wm);
        }
        i = j;
    }
    return labels;
}

}  // namespace polyvol::boolean
