// simplicial/walk.cpp — the order in which the rank-one traversal visits the
// simplices (see topology.hpp).
//
// Successive simplices that share an (n-2)-face have matrices differing in one
// column, so the LU factors follow at O(n^2) cost; any other step costs a
// fresh O(n^3) factorisation. A Hamiltonian path of the dual graph would need
// none; Warnsdorff's rule (go to the unvisited neighbour with the fewest
// unvisited neighbours, so that no simplex is stranded) finds long paths
// greedily in O(k n). When the walk is stuck, walking back through up to
// pass_depth already-counted simplices to a new one is cheaper than a
// refactorisation when pass_depth + 1 updates cost less than one
// factorisation; otherwise the walk jumps to the lowest-numbered unvisited
// simplex.
#include <algorithm>

#include "simplicial/topology.hpp"

namespace polyvol::simplicial {

std::vector<Step> dual_walk(const Topology& t, const ChainView& c, int pass_depth) {
    const int n = t.n;
    auto simplex_vertex = [&](uint32_t s, int p) { return c.simplices[std::size_t{s} * n + p]; };
    const std::size_t k = t.degenerate.size();
    std::vector<Step> out;
    std::size_t remaining = 0;
    std::vector<uint8_t> visited(k, 0);
    std::vector<uint8_t> free_deg(k, 0);  // unvisited neighbours (n <= 64)
    for (std::size_t s = 0; s < k; ++s) {
        if (t.degenerate[s]) {
            visited[s] = 1;
            continue;
        }
        ++remaining;
        for (int p = 0; p < n; ++p)
            if (t.nb[s * n + p] != kNone) ++free_deg[s];
    }
    out.reserve(remaining + remaining / 16);
    auto visit = [&](uint32_t s) {
        visited[s] = 1;
        --remaining;
        for (int p = 0; p < n; ++p) {
            const uint32_t u = t.nb[std::size_t{s} * n + p];
            if (u != kNone) --free_deg[u];
        }
    };

    // Breadth-first search state for pass-throughs (stamped, never cleared).
    std::vector<uint32_t> stamp(pass_depth > 0 ? k : 0, 0);
    uint32_t generation = 0;
    struct Node {
        uint32_t s;
        uint32_t parent;  // index into nodes, kNone for the root
    };
    std::vector<Node> nodes;

    // Entry stamps of the vertices in the (simulated) factors: the column of
    // the vertex that leaves sits at the position of its entry, and the
    // update's eliminations run from there to the end. Among neighbours of
    // equal Warnsdorff degree, the walk prefers the one whose leaving vertex
    // entered last (fewest eliminations).
    std::vector<uint64_t> stamp_of(t.canon.size(), 0);
    std::vector<uint8_t> in_factors(t.canon.size(), 0);
    std::vector<uint32_t> current;  // the vertices of the simulated factors
    uint64_t clock = 0;
    auto enter_all = [&](uint32_t s) {
        for (uint32_t v : current) in_factors[v] = 0;
        current.clear();
        for (int p = 0; p < n; ++p) {
            const uint32_t v = t.canon[simplex_vertex(s, p)];
            stamp_of[v] = ++clock;
            in_factors[v] = 1;
            current.push_back(v);
        }
    };
    std::vector<uint32_t> mark(t.canon.size(), 0);
    uint32_t mark_gen = 0;
    auto enter_new = [&](uint32_t to) {  // `to` adjacent to the simplex of the current factors
        ++mark_gen;
        uint32_t entering = kNone;
        for (int p = 0; p < n; ++p) {
            const uint32_t v = t.canon[simplex_vertex(to, p)];
            mark[v] = mark_gen;
            if (!in_factors[v]) entering = v;
        }
        if (entering == kNone) return;
        for (uint32_t& w : current)
            if (mark[w] != mark_gen) {
                in_factors[w] = 0;
                w = entering;
                break;
            }
        in_factors[entering] = 1;
        stamp_of[entering] = ++clock;
    };

    std::size_t scan = 0;
    uint32_t cur = kNone;
    while (remaining > 0) {
        uint32_t next = kNone;
        if (cur != kNone) {
            int best = 256;
            uint64_t best_stamp = 0;
            for (int p = 0; p < n; ++p) {
                const uint32_t u = t.nb[std::size_t{cur} * n + p];
                if (u == kNone || visited[u]) continue;
                const uint64_t leaving = stamp_of[t.canon[simplex_vertex(cur, p)]];
                if (free_deg[u] < best || (free_deg[u] == best && leaving > best_stamp)) {
                    best = free_deg[u];
                    best_stamp = leaving;
                    next = u;
                }
            }
        }
        if (next != kNone) {
            out.push_back({next, StepKind::next});
            enter_new(next);
            visit(next);
            cur = next;
            continue;
        }
        if (cur != kNone && pass_depth > 0) {
            // Nearest unvisited simplex through at most pass_depth visited ones.
            ++generation;
            nodes.clear();
            nodes.push_back({cur, kNone});
            stamp[cur] = generation;
            std::size_t level_begin = 0, found = kNone;
            for (int depth = 0; depth <= pass_depth && found == kNone; ++depth) {
                const std::size_t level_end = nodes.size();
                for (std::size_t i = level_begin; i < level_end && found == kNone; ++i) {
                    for (int p = 0; p < n; ++p) {
                        const uint32_t u = t.nb[std::size_t{nodes[i].s} * n + p];
                        if (u == kNone || stamp[u] == generation) continue;
                        stamp[u] = generation;
                        nodes.push_back({u, static_cast<uint32_t>(i)});
                        if (!visited[u]) {
                            found = nodes.size() - 1;
                            break;
                        }
                    }
                }
                level_begin = level_end;
            }
            if (found != kNone) {
                std::vector<uint32_t> path;
                for (std::size_t i = found; nodes[i].parent != kNone; i = nodes[i].parent) path.push_back(nodes[i].s);
                std::reverse(path.begin(), path.end());
                for (std::size_t i = 0; i + 1 < path.size(); ++i) {
                    out.push_back({path[i], StepKind::pass});
                    enter_new(path[i]);
                }
                out.push_back({path.back(), StepKind::next});
                enter_new(path.back());
                visit(path.back());
                cur = path.back();
                continue;
            }
        }
        while (visited[scan]) ++scan;
        cur = static_cast<uint32_t>(scan);
        out.push_back({cur, StepKind::fresh});
        enter_all(cur);
        visit(cur);
    }
    return out;
}

}  // namespace polyvol::simplicial
