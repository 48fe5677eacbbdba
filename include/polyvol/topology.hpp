// polyvol/topology.hpp — is this surface a closed 2-cycle, and what is it made of?
//
// Everything here is computed after welding vertices with bit-identical
// coordinates (-0.0 equal to +0.0, NaN never welded); no tolerance unless
// asked. Faces with fewer than 3 vertices are only counted (`faces`,
// `faces_with_lt3_vertices`); every other figure ignores them. A polygon
// contributes its own sides as edges (not its fan's diagonals); a side whose
// two ends weld together is a degenerate edge use and belongs to no edge.
//
//   boundary edge     — undirected edge used by exactly one face
//   non-manifold edge — used by more than two faces
//   misoriented edge  — used exactly twice, both times in the same direction
//   unbalanced edge   — used a different number of times in its two directions
//   shell             — an edge-connected component of faces (a face with no
//                       edge at all, e.g. (a, a, a), is a shell of its own)
//
// The volume integrals (measure.hpp) are independent of the origin exactly
// when there is no unbalanced edge: the surface is then a closed 2-cycle.
//
// Euler characteristics are V - E + F with V the welded vertices the faces
// use, E the edges above and F the faces with at least 3 vertices.
//
// Nesting. The winding number of a set of oriented triangles at p is the sum
// of their signed solid angles over 4π (Van Oosterom–Strackee); it is 1
// inside an outward closed shell, -1 inside an inverted one, 0 outside, and
// fractional for open ones. Shell::winding_of_others is that number for all
// other shells, at the centroid of the shell's largest-area fan triangle
// (the first of equal ones). A point exactly inside a coplanar triangle of
// another shell counts half a turn positive there, so a shell touching
// another face to face counts as inside it. A balanced shell is "inside" when
// winding_of_others >= 0.5. The sums are exact double sums unless they would
// cost more than ~1.7e7 solid angles (very many shells): far clusters are then
// approximated (Barill et al. 2018), typically within 1e-3. Shells whose boxes
// all overlap defeat that too (nothing is far); past ~3.4e7 solid angles and tree nodes the
// remaining shells' windings are left NaN and closed ones are `undecided`, so
// that the report always ends in seconds.
//
// analyze_topology runs in O(n log n) (sort-based edge table, union–find),
// several million triangles per second. It throws std::invalid_argument
// when the mesh arrays are inconsistent (an index >= vertex_count(),
// face_offsets not increasing or past the end of indices, 2^31 faces or more).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol {

enum class ShellRole {
    solid,       // closed, positive volume, not inside another shell (or inside a cavity)
    cavity,      // closed, negative volume, inside a positive shell
    inside_out,  // closed, negative volume, inside nothing: the surface is turned inside out
    nested,      // closed, positive, inside another positive shell (overlapping solids)
    open,        // has unbalanced edges
    undecided,   // closed, but its nesting was not decided: the winding numbers would cost more than
                 // the work limit (a million or so shells whose boxes overlap, as in a fan of needles)
};
// "closed" here means balanced (no unbalanced edge), and volume 0 counts as positive.

// "solid", "cavity", "inside-out", "nested", "open", "undecided".
std::string_view shell_role_name(ShellRole role);

struct Shell {
    double signed_volume = 0;        // cone-rule volume of this shell's fan triangles about the
                                     // origin (any origin gives the same for a balanced shell),
                                     // correctly rounded (NaN with a non-finite coordinate)
    std::size_t faces = 0;
    std::size_t vertices = 0;        // welded vertices it references
    std::size_t edges = 0;
    std::size_t boundary_edges = 0;
    std::size_t unbalanced_edges = 0;
    int64_t euler_characteristic = 0;// V - E + F of this shell's polygons
    std::optional<int64_t> genus;    // (2 - χ)/2 for a closed, edge-manifold, consistently oriented
                                     // shell whose χ is even and <= 2 (pinched vertices can break that)
    double winding_of_others = 0;    // winding number of all other shells at a point of this one (see top;
                                     // NaN when not decided within the work limit)
    std::size_t first_face = 0;      // index (file order) of its first face
    ShellRole role = ShellRole::open;
};

// What is wrong with an edge (bits; one edge may have several): the kinds above.
enum EdgeProblem : uint8_t { edge_boundary = 1, edge_nonmanifold = 2, edge_misoriented = 4, edge_unbalanced = 8 };

// An edge with a problem, as its two end positions (welded; the smaller
// dense id first) and its EdgeProblem bits: what a viewer draws.
struct ProblemEdge {
    std::array<double, 6> ends{};  // x0 y0 z0 x1 y1 z1
    uint8_t problems = 0;
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
    std::size_t holes = 0;                    // boundary loops: connected components of the boundary
                                              // edges (two loops touching at a vertex count as one)
    std::size_t nonmanifold_edges = 0;
    std::size_t misoriented_edges = 0;
    std::size_t unbalanced_edges = 0;
    std::size_t degenerate_edge_uses = 0;     // polygon sides whose two ends weld together
    // degenerate faces
    std::size_t triangles_with_repeated_vertex = 0;
    std::size_t zero_area_triangles = 0;      // cross product exactly zero (those with a repeated vertex included)
    // global
    int64_t euler_characteristic = 0;         // V - E + F of the polygon mesh
    std::size_t components_vertex_connected = 0;
    std::size_t components_edge_connected = 0;
    bool closed = true;                 // no boundary edge
    bool edge_manifold = true;          // no non-manifold edge
    bool consistently_oriented = true;  // no misoriented edge
    bool closed_2_cycle = true;         // no unbalanced edge
    // one unbalanced edge, as its two end positions (from, to), if any: from
    // is the end it leaves more often (so it runs the way the surface uses it)
    std::optional<std::array<double, 6>> unbalanced_example;
    // TopologyOptions::problem_edges: the first that many edges with a
    // problem (boundary, non-manifold, misoriented or unbalanced), in the
    // edge table's order (by smaller end, in order of first use).
    std::vector<ProblemEdge> problem_edges;
    // shells, largest |volume| first (equal ones in the order of their first face)
    std::vector<Shell> shells;
    // TopologyOptions::face_shells: per face (file order), the index in
    // `shells` of its shell; kNoShell for faces of fewer than 3 vertices.
    std::vector<uint32_t> face_shell;
    static constexpr uint32_t kNoShell = 0xFFFFFFFF;
    std::size_t cavities = 0, inside_out_shells = 0, nested_shells = 0;  // shells with those roles
};

struct TopologyOptions {
    // false: the edge counts only (faces, welded vertices, edges and their
    // kinds, the unbalanced example, Euler characteristic) — enough to tell
    // whether a volume is origin-free. Degenerate-triangle counts, components,
    // shells and nesting are then left empty (about 3x faster: no shell
    // volumes or winding numbers).
    bool shells = true;
    // With shells: TopologyReport::face_shell, each face's shell.
    bool face_shells = false;
    // Up to this many edges with a problem listed (TopologyReport::problem_edges).
    std::size_t problem_edges = 0;
};

TopologyReport analyze_topology(const MeshView& mesh, const TopologyOptions& options = {});

// Whether the surface is a closed 2-cycle (topology.hpp's closed_2_cycle:
// every edge between two distinct points used as often in each direction,
// points compared by their coordinates, -0.0 == +0.0), decided by the
// randomized fingerprint of soup.hpp over keyed hashes of the fan
// triangles' corners: one parallel pass, no welding, no edge table (a small
// fraction of analyze_topology's time). Keys come from std::random_device
// (the overload with a seed derives them from it, for reproducible tests).
//   closed     the fingerprint is zero: a closed 2-cycle; an open surface
//              gets here with probability < 2^-113 over the keys (assuming
//              the keyed hash behaves as a random function: core/fingerprint.cpp);
//   open       certainly not a closed 2-cycle (analyze_topology counts and
//              names its unbalanced edges);
//   undecided  a vertex some face uses has a NaN or infinite coordinate
//              (topology never welds NaN vertices), or there are 2^31 - 1
//              fan triangles or more (beyond the argument): analyze_topology
//              decides.
Closedness fingerprint_closedness(const MeshView& mesh);
Closedness fingerprint_closedness(const MeshView& mesh, uint64_t seed);

// The one closedness gate, which every entry point takes (volume, measure,
// check, overlap, grid, the booleans, Python): the face arrays checked
// (std::invalid_argument names the first bad index), then the fingerprint
// in one pass; the edge table (analyze_topology with `report`) is built only
// when the fingerprint does not say "closed", or when `fingerprint` is false
// because the caller wants the counts anyway. So a surface found open always
// has its edges counted and an example to name (polyvol/solid.hpp's
// unbalanced_message words it), and a closed one costs one pass.
struct ClosednessOptions {
    bool fingerprint = true;
    TopologyOptions report{.shells = false, .face_shells = false};
};

struct ClosednessCheck {
    bool closed = false;
    bool by_fingerprint = false;             // closed, decided by the fingerprint alone
    std::optional<TopologyReport> topology;  // the edges' report, unless by_fingerprint
};

ClosednessCheck check_closed(const MeshView& mesh, const ClosednessOptions& options = {});

}  // namespace polyvol
