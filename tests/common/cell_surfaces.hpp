// Cells of a CellMesh as triangle meshes, by the mesh's own face rule
// (face_triangles): for tests that measure a cell or the mesh's outside
// with the ordinary tools and compare.
#pragma once

#include <cstdint>
#include <vector>

#include "cells/cell_faces.hpp"
#include "polyvol/cell_mesh.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::test {

// Cell c's closed surface over its own points: its owner faces as wound,
// its neighbour faces reversed.
inline Mesh cell_surface(const CellMeshView& m, std::size_t c) {
    Mesh out;
    std::vector<uint32_t> local(m.point_count(), UINT32_MAX);
    auto at = [&](uint32_t p) {
        if (local[p] == UINT32_MAX) local[p] = out.add_vertex(m.points[3 * p], m.points[3 * p + 1], m.points[3 * p + 2]);
        return local[p];
    };
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const bool owns = m.owner[f] == c, neighbours = m.neighbour[f] == c;
        if (!owns && !neighbours) continue;
        face_triangles(m.face(f), m.points, [&](uint32_t a, uint32_t b, uint32_t d) {
            if (owns)
                out.add_triangle(at(a), at(b), at(d));
            else
                out.add_triangle(at(a), at(d), at(b));
        });
    }
    return out;
}

// The mesh's boundary faces as one triangle mesh over all its points: the
// surface of the region the cells fill (the library's own, cells/cell_faces.hpp).
inline Mesh boundary_surface(const CellMeshView& m) { return cells::boundary_surface(m); }

}  // namespace polyvol::test
