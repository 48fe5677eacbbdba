// polyvol/cells.hpp — volumes in the cells of a mesh of polyhedral cells
// (polyvol/cell_mesh.hpp: OpenFOAM polyMesh, VTK unstructured, corner-point
// grids): the cells' own volumes now; the volume of bodies in every cell is
// built on these (docs/cells.md says the plan and where it stands).
//
// A cell is the closed surface of its face triangles (cell_mesh.hpp's
// face_triangles rule), its volume the cone rule's sum
//   V_c = Σ_{faces f of c} ±Σ_{(a,b,d) of f} det(a, b, d) / 6
// (+ for the faces c owns, − for those it neighbours), summed exactly and
// rounded once. An internal face enters its two cells with opposite signs
// and the same triangles, so the cells' exact sums add up, exactly, to the
// volume the boundary faces enclose: `total` is that sum rounded once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "polyvol/cell_mesh.hpp"

namespace polyvol {

// What makes a mesh of cells unusable, naming the face or cell.
struct CellMeshDefect {
    std::string message;
    uint32_t cell = kNoCell;
    uint32_t face = kNoCell;
};

// The arrays (offsets increasing from 0, faces of 3 or more points in range,
// an owner per face and a neighbour or kNoCell, cells below cell_count())
// and every cell a closed surface: each edge of its faces used as often in
// each direction (the fan's diagonals cancel within a face and are not
// edges). The first defect, by face then by cell index; nothing when none.
std::optional<CellMeshDefect> check_cell_mesh(const CellMeshView& mesh);

struct CellVolumes {
    std::vector<double> volumes;     // per cell, correctly rounded (negative for a cell wound inside out)
    double total = 0;                // Σ of the cells' exact volumes, rounded once
    std::size_t negative_cells = 0;  // cells whose volume is below 0
    std::size_t face_triangles = 0;  // triangles of all faces, each face once
};

// The cells' volumes (above), in parallel, bit-identical for any number of
// threads. Throws std::invalid_argument with check_cell_mesh's message for a
// defective mesh, and for a coordinate outside 0 and 2^-160 .. 2^190 in
// magnitude (the exact arithmetic's range).
CellVolumes cell_volumes(const CellMeshView& mesh);

}  // namespace polyvol
