// boolean/level_pieces.hpp — boolean's internal interface for grid: the
// boundaries of the union and of the intersection of several solids, as
// pieces for the grid to clip (a boundary source, as a file's triangles are).
//
// With bodies B_1..B_n (closed, each not crossing itself) and W the sum of
// their winding numbers, level m is the solid {W >= m}: m = 1 the union,
// m = n the intersection. Its boundary consists of
//   * whole triangles of the bodies that nothing crosses and that lie on it
//     (W of the other bodies there is m - 1, solid_pieces.hpp), and
//   * on each crossed triangle t, the region R_t, given as the fan triangles
//     (a, X, Y) from t's first corner a over the segments X -> Y of R_t's
//     boundary: as 2-chains they add up to R_t (the parts outside R_t cancel).
// The segments' end points are exact rationals rounded to doubles (each
// coordinate truncated), so a point two triangles share is one double on
// both, and the fan triangles' edges cancel pairwise with identical ends:
// with the whole triangles they form a closed surface, as the grid's column
// scan needs.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol::boolean {

struct FanTriangle {
    std::array<double, 9> p;       // a, X, Y
    std::array<double, 3> normal;  // unit normal of the input triangle it lies in
};

struct LevelPieces {
    // Per body, per fan triangle (v0, vi, vi+1) of its faces in face order:
    // bit k set when nothing crosses the triangle and it lies on the
    // boundary of level levels[k].
    std::vector<std::vector<uint8_t>> whole;
    // Per level: the crossed triangles' parts of its boundary.
    std::vector<std::vector<FanTriangle>> fans;
    std::size_t crossing_pairs = 0;  // triangle pairs of different bodies that cross
};

// levels: up to 8 values m >= 1. The bodies must be closed 2-cycles, outward,
// not crossing themselves (polyvol/grid.hpp's contract; only partly checked
// here). Throws std::invalid_argument for a body inside out (negative
// volume), when the crossings contradict each other (a body's surface
// crosses itself, or is not closed after all: found only where it disturbs
// the other bodies' windings), or for coordinates beyond 2^180 (the exact
// predicates' range).
LevelPieces level_pieces(std::span<const MeshView> bodies, std::span<const int> levels);

}  // namespace polyvol::boolean
