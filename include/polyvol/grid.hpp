// polyvol/grid.hpp — the exact volume of one or many solids in every cell of
// a rectilinear grid (volume-of-fluid initialisation, ore-body and reservoir
// models, conservative voxelization).
//
// The grid. Cell (i, j, k) is the box [x[i], x[i+1]] × [y[j], y[j+1]] ×
// [z[k], z[k+1]] of GridAxes; nx = x.size() - 1, ny, nz likewise. Every
// per-cell array below is in C order with k fastest:
//     cell(i, j, k) = (i * ny + j) * nz + k,     cells = nx * ny * nz
// and, with several bodies, the body axis first:
//     volumes[b * cells + cell(i, j, k)]
//     first_moments[(b * cells + cell(i, j, k)) * 3 + a]   (a = 0, 1, 2: ∫x, ∫y, ∫z)
// which is a NumPy array of shape (bodies, nx, ny, nz) (and (..., 3)) with no
// copy. The solid may reach outside the grid: only its part inside counts.
//
// The method (see docs/grid.md). For the cell with floor z_k and height h_k,
// the divergence theorem with F = (0, 0, z - z_k) gives
//     V(i,j,k) = Q(i,j,k) + h_k * A_top(i,j,k),
//     Q = Σ over the surface pieces in the cell of ∫ (z - z_k) n_z dA,
//     A_top = Σ over the pieces in the cells above (same column) of P,  P = ∫ n_z dA,
// so one pass clips every triangle into pieces, one per cell it crosses, and
// scatters (P, Q) of each piece into its cell; a reverse prefix sum down each
// column then gives every cell — cells without surface included, with no
// flood fill. Cost O(triangles + pieces + cells), memory O(cells + triangles),
// both passes parallel (oneTBB), results bit-identical for any thread count.
//
// What "exact up to rounding" means here:
//   * The pieces meet exactly. A triangle is split by the x planes, then each
//     part by the y planes, then by the z planes; every new vertex is the
//     crossing of a plane with a straight segment — an edge of the input (or
//     of the fan of a polygon face) or a cut line inside one triangle —
//     computed in double from that segment's two end points taken in
//     lexicographic order, with the plane's coordinate set exactly and the
//     others clamped to the edge being split. Both triangles of an edge (and
//     both sides of a cut line) therefore get bit-identical points, and the
//     pieces of a closed mesh form a closed polyhedral surface S' whose
//     vertices are within a few units in the last place of the exact
//     crossings (at most three interpolations deep). Grid planes through
//     vertices, edges and faces need no special case: a point on a plane
//     belongs to both sides and is never interpolated.
//   * Each cell's value is the volume of S' in that cell up to the rounding
//     of its terms: P and Q of each piece are computed in double from
//     cell-local coordinates (x - x_i, ...), every sum (per cell and down
//     the column) is a double-double, and V = Q + h A is formed from those
//     in double at the end. The error is a few units of 2^-53 times
//     h_k Σ|P| + Σ|Q| over the pieces involved: about (number of surface
//     sheets in the column above) × 2^-50 × cell volume. (Measured against
//     exact rational clipping of a rotated cube: <= 3.5e-16 × cell volume.)
//   * A cell that no piece enters (its interior meets no surface; pieces
//     lying in one of its faces do not count) is exactly w × cell volume,
//     w = round(A_top / cell area), the winding number of the solid there:
//     exactly 0 or exactly the cell volume for a solid.
//   * cell volume = (x[i+1] - x[i]) * (y[j+1] - y[j]) * (z[k+1] - z[k]) in
//     double. Totals are the exact sums of the cell values, rounded once.
// Consequently the cells sum to the mesh volume within ~1e-15 relative for
// meshes of ordinary size (the pieces' rounding), and a refined grid's 8
// children sum to their parent within a few ulps of the parent's volume
// (measured on the corpus: <= 1.4e-15 relative, and <= 9.5e-16 × cell volume).
//
// Several bodies (overlapping solids, each a closed mesh with outward
// normals): each body's volume per cell as above, and the union's (and on
// request the intersection's) volume per cell, exact in the same sense in
// every cell. Where at most one body's surface enters a cell, or some body
// fills it (an empty one, for the intersection), the bodies' own values
// decide it. In a "contact" cell, entered by the surfaces of two or more
// bodies, it is the column scan again, over the boundary of the union
// (intersection) itself: the parts of the bodies' triangles outside (inside)
// every other body, cut along the curves where the surfaces cross
// (polyvol/boolean.hpp's method: exact predicates, one symbolic
// perturbation for touching and coincident surfaces, crossing points
// rounded once to doubles that every triangle sharing them shares). Only
// asked-for union outputs start this. The bodies must be outward and must not
// cross themselves: an inside-out body is an error, a body crossing itself
// is found only where it disturbs the others' windings, else its self-overlap
// counts by its winding number.
// Input meshes must be closed 2-cycles (polyvol::analyze_topology's
// closed_2_cycle); for open surfaces the numbers are meaningless. A body
// turned inside out gives negative values. Fan triangles of polygon faces
// are used as in measure.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "polyvol/cell_class.hpp"
#include "polyvol/device.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol {

// Plane coordinates of a rectilinear grid; each axis strictly increasing,
// finite, with at least 2 planes (1 cell). Non-uniform spacing is allowed.
struct GridAxes {
    std::vector<double> x, y, z;

    std::size_t nx() const { return x.empty() ? 0 : x.size() - 1; }
    std::size_t ny() const { return y.empty() ? 0 : y.size() - 1; }
    std::size_t nz() const { return z.empty() ? 0 : z.size() - 1; }
    std::size_t cell_count() const { return nx() * ny() * nz(); }
    // (i * ny + j) * nz + k
    std::size_t cell(std::size_t i, std::size_t j, std::size_t k) const { return (i * ny() + j) * nz() + k; }
    // (x[i+1] - x[i]) * (y[j+1] - y[j]) * (z[k+1] - z[k]), in double.
    double cell_volume(std::size_t i, std::size_t j, std::size_t k) const {
        return (x[i + 1] - x[i]) * (y[j + 1] - y[j]) * (z[k + 1] - z[k]);
    }
    // {xmin, ymin, zmin, xmax, ymax, zmax}
    std::array<double, 6> bounds() const { return {x.front(), y.front(), z.front(), x.back(), y.back(), z.back()}; }
    // True when every axis has equal spacing up to 1e-9 relative (then the
    // grid is a VTK ImageData).
    bool uniform() const;
};

// n cells of equal size between lo and hi on each axis (the last plane is hi
// exactly). Throws std::invalid_argument unless lo < hi and n >= 1.
GridAxes uniform_axes(const std::array<double, 6>& bounds, const std::array<uint32_t, 3>& dims);

// How to choose a grid for some bodies when the caller does not give planes.
// Without bounds the grid covers the bodies' bounding box padded by (at
// least) one cell on every side, centred; with bounds it covers them exactly.
struct GridSpec {
    // Cells along the longest side, cubic cells (the default: 128 cells
    // along the longest side of the padded box). Must be >= 3 without bounds.
    uint32_t cells = 128;
    // > 0: cubic cells of this edge length instead (with bounds: the largest
    // spacing <= cell_size that divides each side).
    double cell_size = 0;
    // All three > 0: exactly these counts instead (without bounds, each axis
    // is padded by one of its cells when it has >= 3).
    std::array<uint32_t, 3> dims{0, 0, 0};
    // {xmin, ymin, zmin, xmax, ymax, zmax}; unset: the bounding box of the
    // bodies' vertices used by faces, padded as above.
    std::optional<std::array<double, 6>> bounds{};
};

// The grid GridSpec describes. Throws std::invalid_argument for an empty or
// degenerate bounding box (no faces, all vertices in one point) without
// bounds, non-finite coordinates, or counts above 2^20 per axis.
GridAxes make_grid(std::span<const MeshView> bodies, const GridSpec& spec);

// Per-cell class of the union of the bodies (GridOutput::cell_class):
// polyvol/cell_class.hpp.

// Caller-sized outputs (habit: callers own bulk arrays). Empty spans are not
// computed. Sizes are checked (std::invalid_argument).
struct GridOutput {
    // bodies * cells: volumes[b * cells + cell(i,j,k)] (required)
    std::span<double> volumes{};
    // bodies * cells * 3 or empty: first moments ∫x dV, ∫y dV, ∫z dV of each
    // body's part in each cell, about the origin, at
    // first_moments[(b * cells + cell(i,j,k)) * 3 + a]; the centroid of a cell's
    // part is first_moments / volumes (undefined where the volume is 0).
    std::span<double> first_moments{};
    // cells each, or empty: the union's volume in each cell, and the
    // intersection's (the part inside every body; computed only when asked
    // for). One body: both are its volumes.
    std::span<double> union_volumes{};
    std::span<double> intersection_volumes{};
    std::span<CellClass> cell_class{};  // cells, or empty
    // What the clipping learns on the way (cut-cell and VOF codes need it):
    // bodies * cells or empty: the area of each body's surface inside each
    // cell (its wetted area), at wetted_area[b * cells + cell(i,j,k)];
    std::span<double> wetted_area{};
    // bodies * cells * 3 or empty: ∫ n dA of that surface (n the outward unit
    // normal: the area-weighted normal, its length <= the wetted area), at
    // surface_normal[(b * cells + cell(i,j,k)) * 3 + a].
    // Each surface piece counts in one cell: a piece lying in a plane between
    // two cells goes to the one the clipping gives it (the cells still add up
    // to the surface's area). Sums in double, in triangle order.
    std::span<double> surface_normal{};
    // cells or empty, 3 * cells or empty: the same of the union's surface
    // (the parts of the bodies' surfaces outside every other body; where
    // surfaces cross, each piece's area counts with the sign of the side it
    // faces, so the cut triangles' parts add up to their area).
    std::span<double> union_wetted_area{};
    std::span<double> union_surface_normal{};
};

struct GridOptions {
    // Called now and then with the fraction of the work done (0..1], from
    // worker threads but never concurrently. Empty: not called.
    std::function<void(double)> progress{};
    // Where the per-cell work runs (polyvol/device.hpp): the same bits on
    // every device. `automatic` is the CPU. An OpenCL request on a machine
    // without OpenCL runs the CPU path (GridSummary::device says so); a
    // request that cannot be met otherwise throws DeviceError (device.hpp). The union's pieces on
    // the crossed triangles (exact booleans) are found on the CPU, and
    // everything per cell on the device.
    DeviceRequest device{};
};

struct GridBodySummary {
    double volume = 0;            // Σ of its cells (exact sum, rounded once)
    std::size_t triangles = 0;    // fan triangles used
    std::size_t pieces = 0;       // surface pieces (piece = triangle ∩ cell, incl. above the grid)
    std::size_t full_cells = 0;   // no surface inside, winding number >= 1
    std::size_t empty_cells = 0;  // no surface inside, winding number 0
    std::size_t cut_cells = 0;    // its surface enters the cell (or winding number < 0)
};

struct GridSummary {
    std::vector<GridBodySummary> bodies;
    // The union's volume within the grid (the sum of its cells, rounded once;
    // the body's volume for one body; with several bodies computed only when
    // some union output — union_volumes, intersection_volumes, cell_class or
    // the union's surface — was asked for, else NaN, the counts below 0), and
    // the intersection's when its cells were asked for (else NaN).
    double union_volume = 0;
    double intersection_volume = 0;
    std::size_t crossing_pairs = 0;  // triangle pairs of different bodies that cross
    // Cells by CellClass of the union (they add up to cells).
    std::size_t full_cells = 0, empty_cells = 0, cut_cells = 0, contact_cells = 0;
    // Where the cells were computed: "cpu", or "opencl: <device name>"; a
    // request the CPU path answered says why, e.g. "cpu (no OpenCL runtime ...)".
    std::string device = "cpu";
    // On an OpenCL device, wall seconds: in its kernels, in copies to and from
    // it, and building its kernels (once per device and process); else 0.
    double device_kernel_seconds = 0, device_transfer_seconds = 0, device_build_seconds = 0;
};

// The volume of each body in every cell of the grid (and what else `out`
// asks for). Throws std::invalid_argument for an invalid grid, wrongly sized
// outputs, a face index out of range, or a non-finite coordinate on a used
// vertex; with several bodies and union outputs asked for, also for
// coordinates beyond 2^180, a body inside out, and when the crossings
// between the bodies contradict each other (a body whose surface crosses
// itself or is not closed: bodies must be closed 2-cycles, which is not
// checked in full here; polyvol grid checks it).
GridSummary grid_volumes(std::span<const MeshView> bodies, const GridAxes& grid, const GridOutput& out,
                         const GridOptions& options = {});

// A block of a grid's cells: i in [lo[0], hi[0]), j in [lo[1], hi[1]), k in
// [lo[2], hi[2]) — one chunk of a grid too large for one machine.
struct GridBlock {
    std::array<std::size_t, 3> lo{}, hi{};
    std::size_t cell_count() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

// The cells of one block, with the same bits grid_volumes gives them in the
// whole grid, computed from the bodies alone: the outputs are sized and
// indexed as for a grid of the block's shape (bx, by, bz), and the summary
// counts the block's cells (its volumes are their sums). Only the triangles
// that reach the block's columns at or above its floor are clipped; a
// column's scan still runs from the grid's top down (the projected area of
// the surface above the block enters each of its cells, summed cell by cell
// as in the whole grid), so blocks lower in the grid cost more, and memory
// is that of the block's outputs plus a tile of sums per thread. The union
// outputs repeat the crossings of the bodies (all of them) in each block.
// Throws as grid_volumes, and std::invalid_argument for an empty block or
// one reaching outside the grid.
GridSummary grid_block_volumes(std::span<const MeshView> bodies, const GridAxes& grid, const GridBlock& block,
                               const GridOutput& out, const GridOptions& options = {});

// The same where each body is the union of some meshes (the solid of a file
// whose shells overlap, polyvol/solid.hpp's solid_as_union): body b is the
// union of parts[b], each part a closed outward mesh. A body of one part is
// grid_volumes' body; a body of several is their union's volume in every
// cell (grid_volumes' union_volumes, exact in the same sense), its wetted
// area and normal the union's surface's. first_moments and
// intersection_volumes are not computed for a body of several parts
// (std::invalid_argument); the union of the bodies is that of all parts.
// `block` as in grid_block_volumes (the whole grid: {{0, 0, 0}, {nx, ny, nz}}).
GridSummary grid_union_volumes(std::span<const std::vector<MeshView>> parts, const GridAxes& grid,
                               const GridBlock& block, const GridOutput& out, const GridOptions& options = {});

// Volume fractions in place: `arrays` consecutive per-cell arrays (cells in
// GridAxes::cell order) each divided by its cell's volume (cell_volume),
// clamped to [0, 1] unless keep_signed. A body's volume in a cell is within
// a few ulps of the cell's (docs/grid.md), so the clamp moves a fraction by
// no more than that bound.
void to_fractions(std::span<double> values, const GridAxes& grid, std::size_t arrays, bool keep_signed = false);

// Each cell's centroid of the solid in it: first_moments / volume per axis
// (3 values per cell, as GridOutput::first_moments holds them), NaN where the
// volume is 0.
std::vector<double> cell_centroids(std::span<const double> volumes, std::span<const double> first_moments);

}  // namespace polyvol
