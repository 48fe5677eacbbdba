// polyvol/chain.hpp — oriented simplicial boundary chains in R^n and closed
// polygons in the plane, as plain arrays, and reading them from text.
//
// A chain in R^n is a list of (n-1)-simplices, each an ordered list of n
// vertex indices (Allgower & Schmidt 1986):
//   * coordinates: vertex v is (coordinates[n*v], ..., coordinates[n*v + n-1]),
//     IEEE doubles exactly as read;
//   * simplices: simplex s is (simplices[n*s], ..., simplices[n*s + n-1]);
//   * orientation: the boundary of the simplex (v_0, ..., v_{n-1}) is the
//     (n-2)-chain  sum_i (-1)^i (v_0, ..., v_{i-1}, v_{i+1}, ..., v_{n-1}).
//     The simplices bound a polyhedron with outward orientation when, for a
//     point p inside the polyhedron next to a simplex,
//     det(v_0 - p, ..., v_{n-1} - p) > 0 — for n = 3 the triangles are
//     counter-clockwise seen from outside (as the 3D meshes), for n = 2 the
//     edges run counter-clockwise around the area they bound;
//   * a simplex with a repeated vertex index (or two vertices with
//     bit-identical coordinates) is degenerate: it is counted and contributes
//     nothing.
//
// Polygons in the plane are loops of vertices; loop l is the closed polygon
//   loop_offsets[l] .. loop_offsets[l+1]-1  (vertex indices into coordinates),
// the last vertex joined back to the first. Several loops add up as a chain:
// an outer loop counter-clockwise, a hole clockwise, an island in a hole
// counter-clockwise again (or let orient_chain choose, simplicial.hpp).
//
// Text formats (docs/chain-format.md):
//   .chain — '#' comment lines, then "n m k", m lines of n coordinates, k lines
//            of n zero-based vertex indices;
//   qhull  — the output of `qconvex o Qt` (or `qhull o Qt`): a dimension line,
//            "points facets ridges", the points, then each facet as a count and
//            its vertex indices. Facets are oriented outward from the mean of
//            the points the facets use (an interior point of a convex hull);
//            for n = 3 a facet of more than 3 vertices (no Qt) is fanned from
//            its first vertex;
//   polygon — one loop per line: x0 y0 x1 y1 ... ; '#' comment lines.
// The readers (chain_io.hpp) throw ReadError (io.hpp) with the file, the
// 1-based line and what was expected, and never allocate from a count before
// checking it against the size of the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace polyvol {

// A non-owning view of a chain (zero-copy from numpy or any caller's arrays).
struct ChainView {
    int dimension = 0;                    // n >= 2
    std::span<const double> coordinates;  // n * vertex_count()
    std::span<const uint32_t> simplices;  // n * simplex_count()

    std::size_t vertex_count() const { return dimension > 0 ? coordinates.size() / dimension : 0; }
    std::size_t simplex_count() const { return dimension > 0 ? simplices.size() / dimension : 0; }
    std::span<const uint32_t> simplex(std::size_t s) const {
        return simplices.subspan(s * dimension, static_cast<std::size_t>(dimension));
    }
    std::span<const double> vertex(std::size_t v) const {
        return coordinates.subspan(v * dimension, static_cast<std::size_t>(dimension));
    }
};

struct Chain {
    int dimension = 0;
    std::vector<double> coordinates;
    std::vector<uint32_t> simplices;

    std::size_t vertex_count() const { return dimension > 0 ? coordinates.size() / dimension : 0; }
    std::size_t simplex_count() const { return dimension > 0 ? simplices.size() / dimension : 0; }
    ChainView view() const { return {dimension, coordinates, simplices}; }
};

// Closed polygons in the plane (see the top of this file).
struct PolygonsView {
    std::span<const double> coordinates;    // vertex v: (coordinates[2v], coordinates[2v+1])
    std::span<const uint32_t> loop_offsets; // loop_count() + 1 entries, loop_offsets[0] == 0
    std::span<const uint32_t> indices;      // vertex indices of the loops, one after the other

    std::size_t vertex_count() const { return coordinates.size() / 2; }
    std::size_t loop_count() const { return loop_offsets.empty() ? 0 : loop_offsets.size() - 1; }
};

struct Polygons {
    std::vector<double> coordinates;
    std::vector<uint32_t> loop_offsets{0};
    std::vector<uint32_t> indices;

    std::size_t vertex_count() const { return coordinates.size() / 2; }
    std::size_t loop_count() const { return loop_offsets.empty() ? 0 : loop_offsets.size() - 1; }
    PolygonsView view() const { return {coordinates, loop_offsets, indices}; }
    // Appends a loop of new vertices (x0, y0, x1, y1, ...).
    void add_loop(std::span<const double> xy) {
        const auto first = static_cast<uint32_t>(vertex_count());
        coordinates.insert(coordinates.end(), xy.begin(), xy.end());
        for (uint32_t i = 0; i < xy.size() / 2; ++i) indices.push_back(first + i);
        loop_offsets.push_back(static_cast<uint32_t>(indices.size()));
    }
};

}  // namespace polyvol
