#include "topology/edges.hpp"

#include <algorithm>
#include <memory>

namespace polyvol::topology {
namespace {

// One use of an undirected edge, filed under its smaller end.
struct EdgeUse {
    uint32_t other;         // the larger end
    uint32_t polygon_dir;   // polygon << 1 | (1 when the side runs larger -> smaller)
    bool operator<(const EdgeUse& u) const {
        return other != u.other ? other < u.other : polygon_dir < u.polygon_dir;
    }
};

// Calls fn(a, b) for every side a -> b (dense ids, a != b) of polygon
// `corners`; returns the number of degenerate sides.
template <class Fn>
std::size_t for_each_side(const WeldedMesh& m, std::span<const uint32_t> corners, Fn&& fn) {
    std::size_t degenerate = 0;
    uint32_t a = m.id[corners.back()];
    for (uint32_t v : corners) {
        const uint32_t b = m.id[v];
        if (a == b) ++degenerate;
        else fn(a, b);
        a = b;
    }
    return degenerate;
}

// Sorts a bucket; buckets are tiny except around high-degree vertices.
void sort_bucket(EdgeUse* begin, EdgeUse* end) {
    if (end - begin <= 16) {
        for (EdgeUse* i = begin + 1; i < end; ++i)
            for (EdgeUse* j = i; j > begin && *j < *(j - 1); --j) std::swap(*j, *(j - 1));
    } else {
        std::sort(begin, end);
    }
}

}  // namespace

EdgeTable build_edge_table(const WeldedMesh& m, core::UnionFind* polygon_sets) {
    EdgeTable t;
    const std::size_t nv = m.referenced();

    // Counting sort of the uses by their smaller end.
    std::vector<std::size_t> start(nv + 1, 0);
    m.for_each_polygon([&](uint32_t, std::span<const uint32_t> c) {
        t.degenerate_uses += for_each_side(m, c, [&](uint32_t a, uint32_t b) { ++start[std::min(a, b) + 1]; });
    });
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    // Not value-initialised: the filling pass writes every use.
    const std::unique_ptr<EdgeUse[]> uses(new EdgeUse[start[nv]]);
    {
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        m.for_each_polygon([&](uint32_t poly, std::span<const uint32_t> c) {
            for_each_side(m, c, [&](uint32_t a, uint32_t b) {
                const uint32_t dir = a > b ? 1u : 0u;
                uses[fill[std::min(a, b)]++] = {std::max(a, b), poly << 1 | dir};
            });
        });
    }

    // Runs of equal (smaller, larger) ends are the undirected edges.
    t.polygon.reserve(start[nv] / 2 + 1);
    t.flags.reserve(start[nv] / 2 + 1);
    for (uint32_t a = 0; a < nv; ++a) {
        EdgeUse* const bucket_end = uses.get() + start[a + 1];
        sort_bucket(uses.get() + start[a], bucket_end);
        for (EdgeUse* run = uses.get() + start[a]; run != bucket_end;) {
            EdgeUse* run_end = run;
            std::size_t forward = 0, backward = 0;
            for (; run_end != bucket_end && run_end->other == run->other; ++run_end) {
                (run_end->polygon_dir & 1 ? backward : forward) += 1;
                if (polygon_sets) polygon_sets->unite(run->polygon_dir >> 1, run_end->polygon_dir >> 1);
            }
            const std::size_t n = forward + backward;
            uint8_t f = 0;
            if (n == 1) f |= kBoundary;
            if (n > 2) f |= kNonmanifold;
            if (n == 2 && forward != 1) f |= kMisoriented;
            if (forward != backward) {
                f |= kUnbalanced;
                if (!t.unbalanced_example)
                    t.unbalanced_example = forward > backward ? std::array{a, run->other}
                                                              : std::array{run->other, a};
            }
            if (f) t.flagged.push_back({a, run->other, f});
            t.polygon.push_back(run->polygon_dir >> 1);
            t.flags.push_back(f);
            run = run_end;
        }
    }
    return t;
}

}  // namespace polyvol::topology
