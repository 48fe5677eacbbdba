// cells/cell_faces.hpp — private: each cell's faces, from the faces' owner
// and neighbour arrays.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "polyvol/cell_mesh.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::cells {

// Cell c's faces are faces[offsets[c] .. offsets[c+1]), each entry 2 f + s:
// face f, s = 0 where c owns it (wound outward from c), 1 where c is its
// neighbour (reversed). Faces in increasing order per cell.
struct CellFaces {
    std::vector<uint32_t> offsets;
    std::vector<uint32_t> faces;
    std::span<const uint32_t> of(std::size_t c) const {
        return std::span<const uint32_t>(faces).subspan(offsets[c], offsets[c + 1] - offsets[c]);
    }
};

// Needs owner and neighbour below the cell count (check_cell_mesh's arrays).
CellFaces cell_faces(const CellMeshView& mesh);

// The boundary faces' triangles (the faces without a neighbour) over all the
// mesh's points: the surface of the region the cells cover, whose winding
// number at a point is the number of cells covering it.
Mesh boundary_surface(const CellMeshView& mesh);

}  // namespace polyvol::cells
