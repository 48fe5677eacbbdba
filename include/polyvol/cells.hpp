// polyvol/cells.hpp — volumes in the cells of a mesh of polyhedral cells
// (polyvol/cell_mesh.hpp: OpenFOAM polyMesh, VTK unstructured, corner-point
// grids): the cells' own volumes, and the volume of a body in every cell
// (docs/cells.md says how, and what is still to come).
//
// A cell is the closed surface of its face triangles (cell_mesh.hpp's
// face_triangles rule), its volume the cone rule's sum
//   V_c = Σ_{faces f of c} ±Σ_{(a,b,d) of f} det(a, b, d) / 6
// (+ for the faces c owns, − for those it neighbours), summed exactly and
// rounded once. An internal face enters its two cells with opposite signs
// and the same triangles, so the cells' exact sums add up, exactly, to the
// volume the boundary faces enclose: `total` is that sum rounded once.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "polyvol/cell_class.hpp"
#include "polyvol/cell_mesh.hpp"
#include "polyvol/mesh.hpp"

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

// The volume of the region at least one cell covers, each point once,
// correctly rounded: the solid {winding >= 1} of the boundary faces
// (polyvol/boolean.hpp's solid_volume, crossings within the surface
// resolved), the winding number at a point being the number of cells
// covering it. CellVolumes::total where the cells tile; less where they
// overlap (a corner-point grid's faults on leaning pillars); NaN where that
// solid is not decided. Throws as cell_volumes for a defective mesh.
double covered_volume(const CellMeshView& mesh);

// A body's volume in every cell: |B ∩ c| for each cell c, correctly rounded.
//   * Cells whose box meets the box of one of the body's triangles (that
//     box rounded outward to floats: a few more cells near the surface may
//     count) are "touched": each is intersected with the body exactly
//     (boolean_volumes with the cell's closed surface of face triangles as A).
//   * The other cells are full or empty. Two such cells sharing a face are
//     alike (no part of the body's surface can lie between them), so each
//     connected region of them takes one exact decision.
//   * total: |B ∩ M|, M the region the mesh's boundary faces enclose (which
//     the cells tile exactly), correctly rounded: the exact sum of the
//     cells' exact values rounded once. For a body inside the mesh it is
//     the body's volume, bit for bit.
// The body must be a closed 2-cycle, outward (polyvol/solid.hpp turns a
// file into that; shells that overlap: below); the
// cells must be wound outward (no negative cell). Throws
// std::invalid_argument naming the defect otherwise.
// This is the exact reference: each touched cell costs a boolean against
// the whole body. docs/cells.md gives the design that replaces it with one
// pass over the crossings.
struct BodyInCells {
    std::vector<double> volumes;       // per cell, correctly rounded
    std::vector<CellClass> cell_class; // cut: the body's surface enters the cell
    double total = 0;                  // |B ∩ M|, correctly rounded
    // The cells' values added exactly, rounded once: total up to the cells'
    // roundings where the cells tile M.
    double cells_sum = 0;
    // Where the cells may not tile (BodyInCellsOptions::cells_tile false: a
    // corner-point grid's faults on pillars that are not parallel), M is
    // the region at least one cell covers, each point once, and the body
    // in the cells' overlaps counts in cells_sum once per covering cell:
    // in_overlaps = cells_sum − total, the difference of the two rounded
    // values (within an ulp of each). NaN where the covered region is not
    // decided (its boundary touches itself where it crosses itself; or the
    // body's own surface does, both being resolved as solids there): total
    // is then cells_sum. The body in a gap between cells is in no cell and
    // counts as outside M. 0 where the cells tile.
    double in_overlaps = 0;
    double body_volume = 0;            // |B|, correctly rounded
    std::size_t full_cells = 0, cut_cells = 0, empty_cells = 0;
    std::size_t touched_cells = 0;     // intersected exactly one by one
    // Per cell, 1 where the body's triangles come near (a triangle's box
    // meets the cell's box); elsewhere the cell is exactly full or empty.
    std::vector<uint8_t> touched;
    // With BodyInCellsOptions::surface: per cell, the area of the body's
    // surface inside it (its wetted area), its area-weighted outward normal
    // ∫ n dA (3 per cell), and a bound that holds for the area and each
    // component. A piece of the surface lying on a face between two cells
    // counts in one of them (the booleans' perturbation decides which), so
    // the cells add up to the surface's area inside the mesh. NaN for a body
    // whose shells overlap (the reference path does not give them).
    std::vector<double> wetted_area, surface_normal, surface_bound;
    // Their sum (the cells' values added exactly, rounded once) and its bound.
    double wetted_area_total = NAN, wetted_area_total_bound = NAN;
};

// The body's solid where its shells overlap or cross themselves
// (polyvol/solid.hpp's MeshSolid::resolved): each boolean is then
// solid_boolean_volumes, within_shells resolving a shell's own crossings.
// reference: a boolean against the whole body per touched cell (the oracle
// the tests compare the default with; shells that overlap take it too).
// own: the cells' own volumes (cell_volumes(mesh).volumes) when the caller
// has them, so that several bodies do not compute them again; empty: computed.
// cells_tile: false when the cells may overlap or leave gaps
// (LoadedCellMesh::cells_tile says it of a mesh read): the total is then
// the body in the region the cells cover, and the cells' values do not add
// up to it (BodyInCells::in_overlaps).
struct BodyInCellsOptions {
    bool overlapping_shells = false;
    bool within_shells = false;
    bool reference = false;
    std::span<const double> own{};
    bool cells_tile = true;
    bool surface = false;  // also the wetted area and normal per cell
    // Called now and then with the fraction of the cells intersected one by
    // one so far (0..1], from worker threads but never concurrently.
    std::function<void(double)> progress{};
};
BodyInCells body_in_cells(const CellMeshView& mesh, const MeshView& body, const BodyInCellsOptions& options = {});

// Several bodies' union in every cell, correctly rounded: the bodies (each
// a closed outward 2-cycle, its own solid as solid.hpp makes it, its winding
// number never below 0: a cavity inside its outer shell) taken together as
// one body whose shells overlap — the region where any is. With each body's
// own result (`each`, body_in_cells of the same mesh), most cells follow
// from them: a body full in the cell (its value the cell's, so the union,
// between the two, rounds to it too) makes the union the cell; else the
// bodies not touching the cell are exactly empty there, and with one body
// touching it the union is that body's value. The cells two bodies or more
// touch (and every cell without `each`) take the exact reference path, a
// boolean per cell. options.overlapping_shells is implied; within_shells
// when a body's shell crosses itself.
BodyInCells union_in_cells(const CellMeshView& mesh, std::span<const MeshView> bodies,
                           std::span<const BodyInCells> each = {}, const BodyInCellsOptions& options = {});

// Two bodies' intersection in every cell, from three correctly rounded
// values per cell: |A ∩ B ∩ c| = |A ∩ c| + |B ∩ c| − |(A ∪ B) ∩ c|, added
// exactly, rounded once, clamped to [0, min(|A ∩ c|, |B ∩ c|)]: within
// 2 ulp(|c|) of the exact value (each term is within half an ulp of a
// value at most |c|); total the same of the three totals, within
// 2 ulp(|(A ∪ B) ∩ M|). A bound, not a correct rounding.
struct IntersectionInCells {
    std::vector<double> volumes;
    double total = 0;
};
IntersectionInCells intersection_in_cells(const BodyInCells& a, const BodyInCells& b, const BodyInCells& both);

}  // namespace polyvol
