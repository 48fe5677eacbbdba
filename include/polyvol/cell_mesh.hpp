// polyvol/cell_mesh.hpp — a mesh of polyhedral cells as plain arrays, in
// OpenFOAM's face-based form (polyMesh), which VTK unstructured grids and
// corner-point grids are also turned into.
//
// Conventions (Geometric Tools style, in three lines):
//   * points: point p is (points[3p], points[3p+1], points[3p+2]), doubles as read;
//   * face f is the polygon face_points[face_offsets[f] .. face_offsets[f+1]),
//     wound counter-clockwise seen from the side its normal points to: out of
//     owner[f], into neighbour[f] (kNoCell for a boundary face);
//   * a cell is the closed surface of its faces (its owner faces as wound,
//     its neighbour faces reversed); every face a cell uses appears once.
// Faces that are not planar are split into triangles by one rule, the fan
// from the face's point first in (x, y, z) order (`face_triangles`), so the
// two cells sharing a face split it alike and the cells tile space exactly
// (docs/cells.md compares this with OpenFOAM's face-centre decomposition).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace polyvol {

inline constexpr uint32_t kNoCell = 0xFFFFFFFFu;

struct CellMeshView {
    std::span<const double> points;
    std::span<const uint32_t> face_offsets;  // face_count() + 1 entries, the first 0
    std::span<const uint32_t> face_points;
    std::span<const uint32_t> owner;      // per face
    std::span<const uint32_t> neighbour;  // per face; kNoCell on the boundary
    std::size_t cells = 0;

    std::size_t point_count() const { return points.size() / 3; }
    std::size_t face_count() const { return face_offsets.empty() ? 0 : face_offsets.size() - 1; }
    std::size_t cell_count() const { return cells; }
    std::span<const uint32_t> face(std::size_t f) const {
        return face_points.subspan(face_offsets[f], face_offsets[f + 1] - face_offsets[f]);
    }
};

struct CellMesh {
    std::vector<double> points;
    std::vector<uint32_t> face_offsets{0};
    std::vector<uint32_t> face_points;
    std::vector<uint32_t> owner, neighbour;
    std::size_t cells = 0;

    CellMeshView view() const { return {points, face_offsets, face_points, owner, neighbour, cells}; }
};

// The mesh of some of m's cells (each listed once, in the order given: cell
// i of the result is cells[i]): their faces, a face between a kept cell and
// one left out becoming a boundary face wound out of the kept one; all of
// m's points. Throws std::invalid_argument for a cell out of range or
// listed twice, and a face naming a cell out of range.
CellMesh cells_subset(const CellMeshView& m, std::span<const uint32_t> cells);

// The triangles a face is split into, as point indices, in the face's
// winding: with m the position of the face's point that comes first in
// (x, y, z) order (ties — equal points — by the smaller index) and k its
// size, (v[m], v[m+i], v[m+i+1]) for i = 1 .. k-2 (indices mod k). A rule of
// the points' positions, not their numbering: the two cells sharing a face,
// a renumbered mesh and the pieces of a decomposed case all split it alike.
// Calls fn(a, b, c) for each.
template <class Fn>
void face_triangles(std::span<const uint32_t> face, std::span<const double> points, Fn&& fn) {
    const std::size_t k = face.size();
    if (k < 3) return;
    auto before = [&](uint32_t p, uint32_t q) {
        const double* a = &points[3 * std::size_t{p}];
        const double* b = &points[3 * std::size_t{q}];
        if (a[0] != b[0]) return a[0] < b[0];
        if (a[1] != b[1]) return a[1] < b[1];
        if (a[2] != b[2]) return a[2] < b[2];
        return p < q;
    };
    std::size_t m = 0;
    for (std::size_t i = 1; i < k; ++i)
        if (before(face[i], face[m])) m = i;
    for (std::size_t i = 1; i + 1 < k; ++i) fn(face[m], face[(m + i) % k], face[(m + i + 1) % k]);
}

}  // namespace polyvol
