// topology/welded.hpp — topology's internal interface for boolean (with
// topology/parts.hpp): the mesh as topology sees it, polygons (faces with at
// least 3 vertices) over dense ids of the welded vertices they reference.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol::topology {

inline constexpr uint32_t kNone = 0xFFFFFFFFu;

struct WeldedMesh {
    MeshView mesh;
    // id[v]: dense id in 0..referenced()-1 of original vertex v after welding,
    // kNone when no polygon uses its position. Ids are given in order of
    // first use by the polygons.
    std::vector<uint32_t> id;
    // Position of dense id d: xyz[3*d .. 3*d+3) (one of the welded originals;
    // they differ at most in the sign of zeros).
    std::vector<double> xyz;
    std::size_t welded = 0;    // distinct positions among all vertices
    std::size_t polygons = 0;  // faces with >= 3 vertices

    std::size_t referenced() const { return xyz.size() / 3; }
    const double* position(uint32_t d) const { return &xyz[3 * std::size_t{d}]; }
    // Calls fn(poly, corners) for each polygon in face order, poly counting
    // 0, 1, ...; corners are original vertex indices (map them through id).
    template <class Fn>
    void for_each_polygon(Fn&& fn) const {
        uint32_t poly = 0;
        const std::size_t faces = mesh.face_count();
        for (std::size_t f = 0; f < faces; ++f) {
            const std::span<const uint32_t> c = mesh.face(f);
            if (c.size() >= 3) fn(poly++, c);
        }
    }
};

// Checks the face arrays (offsets increasing and in range, indices <
// vertex_count) and throws std::invalid_argument naming the first defect.
void check_mesh_arrays(const MeshView& mesh);

// Welds bit-identical positions (weld_vertices) and numbers the referenced ones.
WeldedMesh weld_polygons(const MeshView& mesh);

}  // namespace polyvol::topology
