// boolean/operand.hpp — private: an operand's fan triangles and what the
// crossing search finds between two operands.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol::boolean {

// One operand: its welded vertices and fan triangles (v0, vi, vi+1).
//   corner(t, i) = positions of vertex tri[3 t + i]
//   edge e of triangle t runs from corner e to corner (e + 1) % 3
struct Operand {
    Mesh mesh;                       // welded(input): one vertex per position
    std::vector<uint32_t> tri;       // 3 per fan triangle
    std::vector<uint8_t> degenerate; // 1 where (b - a) × (c - a) == 0 exactly
    std::vector<double> box;         // 6 per triangle: xmin ymin zmin xmax ymax zmax
    std::array<double, 6> bounds{};  // of the used vertices (empty operand: inverted)

    std::size_t triangles() const { return tri.size() / 3; }
    const double* point(uint32_t v) const { return mesh.positions.data() + 3 * std::size_t{v}; }
    const double* corner(std::size_t t, int i) const { return point(tri[3 * t + i]); }
};

Operand make_operand(const MeshView& view);

// Edge `edge` of triangle `tri` of one operand crosses triangle `other` of
// the other operand (under the perturbation, at an interior point of both).
// sign = +1 when the edge, run from its first corner, enters the other solid
// (passes from the front of `other` to its back), -1 when it leaves.
struct EdgeHit {
    uint32_t tri;
    uint32_t other;
    uint8_t edge;
    int8_t sign;
};

// An end of a cut segment: edge `edge` of operand `of_b ? B : A`'s triangle.
struct CutEnd {
    uint8_t of_b;
    uint8_t edge;
};

// Triangle a of A and triangle b of B cross along a segment, run from start
// to end in the direction N_a × N_b.
struct Cut {
    uint32_t a;
    uint32_t b;
    CutEnd start;
    CutEnd end;
};

struct Crossings {
    std::vector<EdgeHit> a_hits;  // A's edges through B's triangles
    std::vector<EdgeHit> b_hits;  // B's edges through A's triangles
    std::vector<Cut> cuts;
    std::size_t candidate_pairs = 0;  // triangle pairs whose boxes meet
};

// Every crossing between A and B (B translated by the perturbation δ):
// a uniform grid over the common box, each of A's triangles tested against
// B's triangles in its cells (in parallel).
Crossings find_crossings(const Operand& a, const Operand& b);

// Winding number of the other operand (translated by the perturbation) at
// every vertex of `self` (`self_is_b`: self is B); vertices no face uses get 0.
// hits: self's edges through other's triangles. Throws std::logic_error when
// the crossings contradict each other (an operand that is not a closed 2-cycle).
std::vector<int32_t> vertex_windings(const Operand& self, const Operand& other, bool self_is_b,
                                     const std::vector<EdgeHit>& hits);

}  // namespace polyvol::boolean
