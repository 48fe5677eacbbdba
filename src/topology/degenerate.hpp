// Degenerate fan triangles.
#pragma once

#include <cstddef>

#include "topology/welded.hpp"

namespace polyvol::topology {

// True when (b - a) × (c - a) is exactly zero in real arithmetic on the given
// doubles, i.e. a, b, c are collinear or coincide. Each component of the
// cross product is an orient2d determinant of a coordinate projection; a
// static filter (Shewchuk's ccwerrboundA) decides almost every triangle, and
// the rest are evaluated as an exact expansion (Shewchuk) of six two_prod
// products after scaling by a power of two. Exact for finite coordinates unless the
// coordinates of one triangle span more than ~2^500 (products underflow).
bool cross_product_is_zero(const double* a, const double* b, const double* c);

struct DegenerateCounts {
    std::size_t triangles_with_repeated_vertex = 0;  // two corners weld together
    std::size_t zero_area_triangles = 0;             // cross product exactly zero
};

// Over the fan triangles (v0, vi, vi+1) of every polygon.
DegenerateCounts count_degenerate_triangles(const WeldedMesh& mesh);

}  // namespace polyvol::topology
