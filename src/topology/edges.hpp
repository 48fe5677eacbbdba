// The undirected edge table of the polygon mesh.
//
// Each polygon side (a, b) between different welded vertices is one use of
// the undirected edge {a, b}, in direction a->b; a side whose ends weld
// together is a degenerate use and belongs to no edge. Fan diagonals are not
// edges. The table is built by a counting sort on the smaller end followed by
// a sort of each (small) bucket on the larger end: O(n) expected, O(n log n)
// worst case, no per-face allocation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/union_find.hpp"
#include "polyvol/topology.hpp"
#include "topology/welded.hpp"

namespace polyvol::topology {

// The public EdgeProblem bits (polyvol/topology.hpp).
enum EdgeFlag : uint8_t {
    kBoundary = edge_boundary,        // used once
    kNonmanifold = edge_nonmanifold,  // used more than twice
    kMisoriented = edge_misoriented,  // used twice in the same direction
    kUnbalanced = edge_unbalanced,    // uses a->b != uses b->a
};

struct EdgeTable {
    std::vector<uint32_t> polygon;  // polygon[e]: one polygon using edge e
    std::vector<uint8_t> flags;     // flags[e]: EdgeFlag bits
    std::size_t degenerate_uses = 0;
    // The first unbalanced edge in (min, max) id order, from the end it
    // leaves more often to the other (dense ids).
    std::optional<std::array<uint32_t, 2>> unbalanced_example;
    // Every edge with a flag (boundary, non-manifold, misoriented,
    // unbalanced): its two ends (dense ids, smaller first) and flags, in table order.
    struct Flagged {
        uint32_t a, b;
        uint8_t flags;
    };
    std::vector<Flagged> flagged;

    std::size_t size() const { return flags.size(); }
};

// Builds the table and, unless polygon_sets is null (the shells are not
// wanted), unites in it (one element per polygon) the polygons that share
// an edge.
EdgeTable build_edge_table(const WeldedMesh& mesh, core::UnionFind* polygon_sets);

}  // namespace polyvol::topology
