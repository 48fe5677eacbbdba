// polyvol/topology.hpp — is this surface a closed 2-cycle, and what is it made of?
//
// Everything here is computed after welding vertices with bit-identical
// coordinates (-0.0 equal to +0.0); no tolerance unless asked. Faces with
// fewer than 3 vertices are ignored; a polygon contributes its own edges
// (not its fan's diagonals).
//
//   boundary edge     — undirected edge used by exactly one face
//   non-manifold edge — used by more than two faces
//   misoriented edge  — used exactly twice, both times in the same direction
//   unbalanced edge   — used a different number of times in its two directions
//   shell             — an edge-connected component of faces
//
// The volume integrals (measure.hpp) are independent of the origin exactly
// when there is no unbalanced edge: the surface is then a closed 2-cycle.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol {

enum class ShellRole {
    solid,       // closed, positive volume, not inside another shell (or inside a cavity)
    cavity,      // closed, negative volume, inside a positive shell
    inside_out,  // closed, negative volume, inside nothing: the surface is turned inside out
    nested,      // closed, positive, inside another positive shell (overlapping solids)
    open,        // has unbalanced edges
};

struct Shell {
    double signed_volume = 0;        // cone-rule volume of this shell's faces, about the origin
    std::size_t faces = 0;
    std::size_t vertices = 0;        // welded vertices it references
    std::size_t edges = 0;
    std::size_t boundary_edges = 0;
    std::size_t unbalanced_edges = 0;
    int64_t euler_characteristic = 0;// V - E + F of this shell's polygons
    std::optional<int64_t> genus;    // (2 - χ)/2 for a closed, edge-manifold, consistently oriented shell
    double winding_of_others = 0;    // winding number of all other shells at a point of this one
    ShellRole role = ShellRole::open;
};

struct TopologyReport {
    // counts of what was read
    std::size_t faces = 0;                    // as written, including those with < 3 vertices
    std::size_t faces_with_lt3_vertices = 0;
    std::size_t triangles = 0;                // fan triangles
    std::size_t vertices_welded = 0;          // distinct positions
    std::size_t vertices_referenced = 0;      // distinct positions used by faces
    // edges
    std::size_t edges = 0;
    std::size_t boundary_edges = 0;
    std::size_t nonmanifold_edges = 0;
    std::size_t misoriented_edges = 0;
    std::size_t unbalanced_edges = 0;
    std::size_t degenerate_edge_uses = 0;     // polygon sides whose two ends weld together
    // degenerate faces
    std::size_t triangles_with_repeated_vertex = 0;
    std::size_t zero_area_triangles = 0;      // cross product exactly zero
    // global
    int64_t euler_characteristic = 0;         // V - E + F of the polygon mesh
    std::size_t components_vertex_connected = 0;
    std::size_t components_edge_connected = 0;
    bool closed = true;                 // no boundary edge
    bool edge_manifold = true;          // no non-manifold edge
    bool consistently_oriented = true;  // no misoriented edge
    bool closed_2_cycle = true;         // no unbalanced edge
    // one unbalanced edge, as its two end positions (from, to), if any
    std::optional<std::array<double, 6>> unbalanced_example;
    // shells, largest |volume| first
    std::vector<Shell> shells;
    std::size_t cavities = 0, inside_out_shells = 0, nested_shells = 0;
};

TopologyReport analyze_topology(const MeshView& mesh);

}  // namespace polyvol
