// boolean/prepared_body.hpp — boolean's internal interface for cells: one
// closed body met by many small closed surfaces (the cells of a mesh), the
// body welded and its triangles bucketed once.
//
// |c ∩ B| for a cell c needs B's winding number at c's points and B's
// triangles near c only: the part of c's surface inside B follows from
// the windings at c's points and the crossings of c's edges with B's
// triangles; the part of B's surface inside c from B's triangles that meet
// c's box, their crossings with c and their points' windings of c (c is
// closed and small). The windings at the points of many cells come from one
// pass over their faces (windings_at), as boolean_volumes gets A's.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol::boolean {

// The body welded (moved by δ, shift 1, as boolean_volumes moves B) and its
// triangles in a uniform grid of buckets (boolean/prepared_body.cpp).
struct PreparedBody;

// Throws std::invalid_argument naming the defect: not a closed surface,
// inside out, overlapping itself where a ray sees it, coordinates beyond
// the exact predicates' range.
std::shared_ptr<const PreparedBody> prepare_body(const MeshView& body);

// Whether a triangle of the body has a box meeting `box` (xmin ymin zmin xmax ymax zmax).
bool meets_box(const PreparedBody& body, const std::array<double, 6>& box);

// The body's winding number at every point (points: 3 per point) of a
// surface made of `triangles` (3 point indices each, any orientation; the
// points of one connected part related through the crossings of its
// edges, one exact ray per part). Points no triangle uses get 0.
std::vector<int32_t> windings_at(const PreparedBody& body, std::span<const double> points,
                                 std::span<const uint32_t> triangles);

// |c ∩ B|, correctly rounded, for a closed outward surface c of `triangles`
// over `points`, given B's winding at each point (0 or 1, windings_at); with
// `surface`, B's surface inside c too: its area, its vector area ∫ n dA
// (area[1..3]), and one bound for all four (operand.hpp's SurfaceInside,
// halved and rounded).
struct CellSurface {
    double area = 0;
    double normal[3] = {0, 0, 0};
    double bound = 0;
};
double cell_intersection(const PreparedBody& body, std::span<const double> points,
                         std::span<const uint32_t> triangles, std::span<const int32_t> winding,
                         CellSurface* surface = nullptr);

}  // namespace polyvol::boolean
