// polyvol/mesh.hpp — the mesh as plain arrays.
//
// Conventions (every module relies on them):
//   * positions: vertex v is (positions[3*v], positions[3*v+1], positions[3*v+2]),
//     IEEE doubles exactly as read (float32 input widened exactly).
//   * faces in compressed rows: face f uses the vertex indices
//       indices[face_offsets[f] .. face_offsets[f+1])
//     with face_offsets.size() == face_count() + 1 and face_offsets[0] == 0.
//     Fast path: when face_offsets is EMPTY every face is a triangle and
//     face f is indices[3*f .. 3*f+3).
//   * winding: counter-clockwise seen from outside (outward normals).
//   * a polygon (v0 v1 ... vk) means its fan (v0, vi, vi+1), i = 1..k-1, also
//     when it is concave or not planar (concave fans give negative triangles,
//     which is correct).
//   * faces with fewer than 3 vertices are kept as read (so counts match the
//     file) and contribute nothing to any measure or to topology.
//   * indices are always < vertex_count() (readers check this).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace polyvol {

// A non-owning view of a mesh: zero-copy from numpy or any caller's arrays.
struct MeshView {
    std::span<const double> positions;       // 3 * vertex_count()
    std::span<const uint32_t> face_offsets;  // empty (all triangles) or face_count() + 1
    std::span<const uint32_t> indices;

    std::size_t vertex_count() const { return positions.size() / 3; }
    bool all_triangles() const { return face_offsets.empty(); }
    std::size_t face_count() const {
        return face_offsets.empty() ? indices.size() / 3 : face_offsets.size() - 1;
    }
    std::size_t face_begin(std::size_t f) const {
        return face_offsets.empty() ? 3 * f : face_offsets[f];
    }
    std::size_t face_size(std::size_t f) const {
        return face_offsets.empty() ? 3 : face_offsets[f + 1] - face_offsets[f];
    }
    std::span<const uint32_t> face(std::size_t f) const {
        return indices.subspan(face_begin(f), face_size(f));
    }
    // Number of fan triangles: sum over faces of max(0, size - 2).
    std::size_t triangle_count() const;
};

// An owning mesh, as the readers produce it.
struct Mesh {
    std::vector<double> positions;
    std::vector<uint32_t> face_offsets;  // empty while every face is a triangle
    std::vector<uint32_t> indices;

    std::size_t vertex_count() const { return positions.size() / 3; }
    std::size_t face_count() const {
        return face_offsets.empty() ? indices.size() / 3 : face_offsets.size() - 1;
    }
    MeshView view() const { return {positions, face_offsets, indices}; }

    uint32_t add_vertex(double x, double y, double z) {
        positions.push_back(x);
        positions.push_back(y);
        positions.push_back(z);
        return static_cast<uint32_t>(positions.size() / 3 - 1);
    }
    // Appends a face of any size; switches to compressed rows at the first
    // face that is not a triangle.
    void add_face(std::span<const uint32_t> face);
    void add_triangle(uint32_t a, uint32_t b, uint32_t c);
    // Appends another mesh (its indices shifted).
    void append(const Mesh& other);
};

// An owning copy of a view's arrays.
Mesh to_mesh(const MeshView& view);

// The box of the vertices the faces use {xmin, ymin, zmin, xmax, ymax, zmax}
// (exact: a min and max of the coordinates); NaN when there are no faces.
std::array<double, 6> face_bounds(const MeshView& view);

// Canonical vertex ids: result[v] is the smallest index of a vertex with the
// same coordinates as v (bit-identical doubles, -0.0 equal to +0.0; NaNs are
// never welded). Expected O(n).
std::vector<uint32_t> weld_vertices(std::span<const double> positions);

// The same faces over welded vertices (weld_vertices): one vertex per class
// of equal positions, numbered in the order of each class's first vertex
// (its position is that vertex's), indices mapped, faces and their sizes
// unchanged. Merged positions are equal values (they differ at most in the
// sign of zeros), so exact and correctly rounded results do not change; a
// plain double result (Accuracy::fast) that is zero may change its sign.
// For triangle soups (every corner its own vertex, as an STL file lists
// them; the STL reader welds them so: io.hpp) it gives the indexed mesh
// other libraries hold, about a sixth of the positions to read per call.
Mesh welded(const MeshView& mesh);

// mesh = welded(mesh) without a second index array: the indices are mapped
// where they are, the faces' sizes stay, and the positions become the
// classes' (what a reader that builds a soup wants).
void weld_in_place(Mesh& mesh);

// Points within `tolerance` of one another (Euclidean distance, computed in
// double) merged, transitively (a chain of close points becomes one point),
// each class onto its vertex of smallest index, which keeps its position;
// then welded exactly (weld_in_place). Faces keep their sizes: a face whose
// corners merged repeats a vertex. Results are then those of the welded
// mesh, not of the file. NaN and infinite points are never merged. Throws
// std::invalid_argument for a tolerance that is not positive and finite, or
// one so coarse that it brings more than 2^33 pairs of points within reach.
struct ToleranceWeld {
    std::size_t moved = 0;      // points moved onto a different position
    double largest_move = 0;    // the longest distance a point moved (may exceed the tolerance by chaining)
};
ToleranceWeld weld_within(Mesh& mesh, double tolerance);

// What a one-pass closedness fingerprint says of a surface (topology.hpp's
// fingerprint_closedness gives it and says what each answer means).
enum class Closedness { closed, open, undecided };

}  // namespace polyvol
