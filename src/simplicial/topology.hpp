// simplicial/topology.hpp — private: welding, (n-2)-face matching and the dual
// graph of a chain.
//
// Faces. For a simplex with welded vertex ids listed (c_0 .. c_{n-1}), sorting
// them by a permutation pi gives (d_0 < ... < d_{n-1}) with
// (c_0 .. c_{n-1}) = sgn(pi) (d_0 .. d_{n-1}) as oriented simplices, so
//   boundary = sgn(pi) sum_q (-1)^q (d_0 .. ^d_q .. d_{n-1}):
// the face omitting d_q carries the induced sign sgn(pi) (-1)^q. A face is
// identified by two sums of keyed 64-bit mixes of its vertex ids (the whole
// simplex's sums minus the omitted vertex's: O(1) per face); the uses are
// radix-sorted by the top bits of the first sum and grouped by both. The
// keys are drawn at random per process, so two different faces are taken for
// one with probability about 2^-128 per pair, whatever the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "polyvol/simplicial.hpp"

namespace polyvol::simplicial {

inline constexpr uint32_t kNone = 0xFFFFFFFFu;
inline constexpr int kMaxDimension = 64;

// Throws std::invalid_argument unless 2 <= n <= kMaxDimension, the array sizes
// are multiples of n, every index < vertex_count() and there are fewer than
// 2^32 - 1 simplices.
void check_arrays(const ChainView& chain);

// Canonical ids: result[v] is the smallest index of a vertex with bit-identical
// coordinates (-0.0 == +0.0; a vertex with a NaN coordinate is only itself).
std::vector<uint32_t> weld(const ChainView& chain);

struct Topology {
    int n = 0;
    std::vector<uint32_t> canon;       // per input vertex: canonical id
    std::vector<uint8_t> degenerate;   // per simplex: a repeated (welded) vertex
    // Neighbour across the face omitting LISTED position p of simplex s:
    // nb[n*s + p], kNone unless that face is used by exactly two simplices.
    std::vector<uint32_t> nb;
    // For those pairs: 1 when both induce the same orientation on the face.
    std::vector<uint8_t> same;
    // Face-connected component of each non-degenerate simplex (kNone for degenerate ones), numbered 0.. in
    // order of first simplex.
    std::vector<uint32_t> component;
    ChainReport report;
};

// Everything above; nb/same/component only when want_graph.
Topology analyze(const ChainView& chain, bool want_graph);

// Walk over the dual graph (walk.cpp).
enum class StepKind : uint8_t {
    fresh,  // factorise afresh (start, or a jump to a non-adjacent simplex)
    next,   // adjacent to the previous step's simplex; counted
    pass,   // adjacent, already counted: walked through to reach a new simplex
};
struct Step {
    uint32_t simplex;
    StepKind kind;
};

// Every non-degenerate simplex exactly once as fresh or next, in an order
// where most steps are adjacent to the previous one: greedy, preferring the
// unvisited neighbour with the fewest unvisited neighbours (Warnsdorff's
// rule; ties go to the step whose leaving vertex entered the factors last,
// the cheapest update); when stuck, a breadth-first search through visited
// simplices up to pass_depth intermediate steps, else a jump.
std::vector<Step> dual_walk(const Topology& topology, const ChainView& chain, int pass_depth);

}  // namespace polyvol::simplicial
