// Shells: the edge-connected components of the polygons, and what is
// measured on each of them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "polyvol/topology.hpp"
#include "core/union_find.hpp"
#include "topology/edges.hpp"
#include "topology/parts.hpp"
#include "topology/welded.hpp"

namespace polyvol::topology {

// The fan triangles (dense vertex ids) grouped by shell, face order kept
// within a shell: shell s owns tris[offsets[s] .. offsets[s+1]).
struct ShellTriangles {
    std::vector<std::size_t> offsets;
    std::vector<std::array<uint32_t, 3>> tris;
};

ShellTriangles gather_shell_triangles(const WeldedMesh& mesh, const ShellLabels& shells);

// A shell's report entry plus the geometry the winding numbers need.
struct ShellGeometry {
    Shell report;                        // all fields but winding_of_others and role
    std::array<double, 3> probe{};       // centroid of its largest-area fan triangle (first of equals)
    std::array<double, 6> box{};         // min x, y, z, max x, y, z of its vertices
    bool balanced() const { return report.unbalanced_edges == 0; }
};

// Per shell: faces, vertices, edge counts, Euler characteristic, genus,
// signed volume, probe point and bounding box. The volume is the cone rule
// about the origin (the convention for open surfaces; any origin gives the
// same for a balanced shell), correctly rounded (measure's signed_volume:
// exact for any finite coordinates).
std::vector<ShellGeometry> measure_shells(const WeldedMesh& mesh, const ShellLabels& shells,
                                          const EdgeTable& edges, const ShellTriangles& triangles);

}  // namespace polyvol::topology
