// polyvol/cell_mesh_io.hpp — reading meshes of cells (polyvol/cell_mesh.hpp).
//
// OpenFOAM polyMesh: a case directory (its constant/polyMesh) or the
// polyMesh directory itself, holding points, faces, owner and neighbour,
// each plain or gzip-compressed (NAME.gz); ASCII or binary (`format`),
// 32- or 64-bit labels and 64- or 32-bit scalars (`arch`); faces as a
// faceList or a faceCompactList. Points are in metres (OpenFOAM's unit).
//
// Errors throw ReadError (polyvol/io.hpp) naming the file, the 1-based line
// (ASCII) or the byte offset (binary) and what was expected: a face naming a
// missing point, owner and neighbour counts that disagree with the faces, a
// count larger than the bytes that follow. No count is trusted before it is
// checked against the bytes that are there.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "polyvol/cell_mesh.hpp"
#include "polyvol/grid_io.hpp"  // CellArray

namespace polyvol {

struct LoadedCellMesh {
    CellMesh mesh;
    std::string format;    // "openfoam", "vtu" or "grdecl"
    std::string encoding;  // "ascii" or "binary" (of the points file)
    bool gzip = false;     // some file was gzip-compressed
    std::string unit;      // the length unit of the points ("m" for OpenFOAM; empty: not stated)
    std::string location;  // the directory or file read
    std::vector<std::string> notes;
    // Corner-point grids: the grid's size I×J×K, each cell's place in it,
    // i + I (j + J k) (only active cells are cells of `mesh`), and the faces
    // between neighbouring cells that do not match (faults).
    std::array<uint64_t, 3> grid_dims{};
    std::vector<uint64_t> grid_index;
    std::size_t fault_faces = 0;
    // A processor directory of a decomposed OpenFOAM case, or a cellZone of
    // a case: each cell's index in the whole case (its cellProcAddressing,
    // the zone's cellLabels); empty otherwise. case_cells: the whole case's
    // cell count where it is known (a zone), else 0.
    std::vector<uint64_t> case_index;
    std::size_t case_cells = 0;
    // Whether the cells are known to tile the region their boundary faces
    // enclose: false for a corner-point grid with a fault that is not between
    // vertical pillars (there the cells may overlap or leave gaps).
    bool cells_tile = true;
};

// Reads an OpenFOAM polyMesh (above), and in a processor directory of a
// decomposed case its cellProcAddressing (case_index). A decomposed case's
// directory (processorN/constant/polyMesh and no constant/polyMesh of its
// own) gives the whole mesh, put together from the processors' meshes by
// their point, face and cell addressing: the undecomposed case's points,
// faces and cells in its own order (location: the case directory, which
// write_foam_field then writes processor by processor). Throws ReadError.
LoadedCellMesh read_polymesh(const std::string& path);

// A decomposed case's processor directories (CASE/processorN holding
// constant/polyMesh), by N; empty when there are none.
std::vector<std::string> foam_processor_dirs(const std::string& case_dir);

// The cells of an OpenFOAM cellZone (polyMesh/cellZones, ASCII or binary,
// plain or .gz) of a mesh read by read_polymesh: the zone's cells alone
// (cells_subset: faces to the other cells become boundary faces), case_index
// their numbers in the case, case_cells its cell count. Throws ReadError
// when there is no such zone (naming those there are), for a zone naming a
// cell out of range or twice, and for a decomposed case read whole.
LoadedCellMesh cell_zone(const LoadedCellMesh& mesh, const std::string& zone);

// Values given per cell of `mesh` spread over the whole case's cells (a
// cellZone's: at case_index, 0 elsewhere), as a field of the case needs
// them; the values themselves for any other mesh.
std::vector<double> in_case_cells(const LoadedCellMesh& mesh, std::span<const double> values);

// The same from the four files' bytes (each plain or gzip), `name` naming
// them in messages (name/points, ...): for tests, fuzzing and uploads.
struct PolyMeshBytes {
    std::span<const std::byte> points, faces, owner, neighbour;
};
LoadedCellMesh read_polymesh_memory(const PolyMeshBytes& files, const std::string& name);

// Reads a VTK XML UnstructuredGrid (.vtu): ascii, binary and appended
// (raw or base64) arrays, zlib-compressed or not, 32- or 64-bit headers;
// tetra, voxel, hexahedron, wedge, pyramid and polyhedron cells. Each
// distinct face (its points as a set) once, owned by the first cell naming
// it, wound outward from it, its neighbour the second. Throws ReadError.
LoadedCellMesh read_vtu(const std::string& path);
LoadedCellMesh read_vtu_memory(std::span<const std::byte> data, const std::string& name);

// Eclipse GRDECL corner-point grid (io/grdecl.cpp): SPECGRID or DIMENS,
// COORD, ZCORN, ACTNUM (inactive cells are not cells; grid_index maps back),
// repeats N*v, comments, INCLUDE (relative to the main file's directory, as
// OPM resolves it; not from memory), the unit from GRIDUNIT, else METRIC / FIELD / LAB / PVT-M, else
// none. MAPAXES is read and not applied (a note says so). Each active cell is
// the polyhedron of its 8 corners: a corner is the point of its pillar at
// its depth, one point per (pillar, depth), so neighbouring cells share
// points and faces exactly; a face of a cell whose neighbour names other
// corners (a fault) bounds each cell alone (fault_faces counts them; the
// cells still tile where both pillars of each such face are vertical, and
// where layers that do not meet leave a gap, not an overlap: cells_tile). The
// faces are wound outward (all turned when (I, J, K) is left-handed).
// Other keywords are skipped, each up to the next keyword's line (several
// records), the rest of a line after '/' being a comment; one that changes
// a grid array (EQUALS 'ACTNUM' ..., COPY, a grid array inside BOX) is
// refused, as are radial grids and NUMRES > 1. Grids of more than max_cells
// cells (at most 2^27: cells, points and face lists are numbered in 32
// bits) and repeats expanding to more than max(2^22, 8 × the file's bytes)
// values are refused. Throws ReadError naming the file and line.
inline constexpr uint64_t kMaxGridCells = uint64_t{1} << 27;
LoadedCellMesh read_grdecl(const std::string& path, uint64_t max_cells = kMaxGridCells, bool map_axes = true);
LoadedCellMesh read_grdecl_memory(std::span<const std::byte> data, const std::string& name,
                                  uint64_t max_cells = kMaxGridCells, bool map_axes = true);

// A .vtu file (read_vtu), a .grdecl file (read_grdecl), else an OpenFOAM
// case or polyMesh directory (map_axes: read_grdecl's).
LoadedCellMesh read_cell_mesh(const std::string& path, bool map_axes = true);

// An OpenFOAM mesh's patches (constant/polyMesh/boundary), in order.
struct FoamPatch {
    std::string name, type;
};
std::vector<FoamPatch> read_foam_patches(const std::string& polymesh_dir);

// Writes the dimensionless volScalarField `name` into the case that holds
// polymesh_dir (LoadedCellMesh::location, CASE/constant/polyMesh), at
// CASE/<time>/<name> — or, for a decomposed case's directory, into each
// CASE/processorN/<time>/<name>, its cells' values by its cellProcAddressing: the internalField one value per cell, each with 17
// significant digits (the doubles exactly); the boundaryField kept verbatim
// from an existing file of that name (its boundary conditions are the
// user's), else zeroGradient on every patch (empty, wedge, symmetry,
// symmetryPlane, cyclic and processor patches get their own type). The file
// is written beside and renamed, so a failure leaves the old one. Returns
// the path written. Throws ReadError for an unreadable boundary file and
// std::runtime_error when the mesh is not in a case or the file cannot be
// written.
std::string write_foam_field(const std::string& polymesh_dir, const std::string& name, std::span<const double> values,
                             const std::string& time = "0");

// VTK XML UnstructuredGrid (.vtu) of the cells, each a VTK polyhedron (type
// 42: its faces outward, as cell_mesh.hpp winds them), with cell data (one
// value per cell and component), in VTK's binary appended form (raw, exact);
// ParaView and VTK's readers open it. Throws std::invalid_argument for an
// array without one value per cell, std::runtime_error when it cannot write.
void write_vtu(const std::string& path, const CellMeshView& mesh, std::span<const CellArray> arrays);

// A GRDECL include file of one keyword for a corner-point grid read by
// read_grdecl: one value per cell of the I×J×K grid, I fastest, inactive
// cells 0, runs as N*v, each value the shortest decimal that reads back as
// the same double. `values` has one value per active cell (per cell of
// grid.mesh). Throws std::invalid_argument for another mesh, a count that
// differs or a keyword that is not 1-8 capitals, digits or '_';
// std::runtime_error when it cannot write (the file is written beside and
// renamed).
void write_grdecl_keyword(const std::string& path, const std::string& keyword, std::span<const double> values,
                          const LoadedCellMesh& grid);

}  // namespace polyvol
