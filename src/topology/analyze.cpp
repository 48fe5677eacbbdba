// analyze_topology: weld, build the edge table, split into shells, classify.
// Definitions in polyvol/topology.hpp; the reference figures they must
// reproduce are described in the corpus README (fields `counts`, `topology`,
// `components`, `nesting`).
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "polyvol/topology.hpp"
#include "topology/degenerate.hpp"
#include "topology/edges.hpp"
#include "topology/shells.hpp"
#include "core/union_find.hpp"
#include "topology/welded.hpp"
#include "topology/winding.hpp"

namespace polyvol {
namespace {

using topology::EdgeTable;
using topology::ShellGeometry;
using topology::WeldedMesh;

void count_faces(const MeshView& mesh, TopologyReport& r) {
    r.faces = mesh.face_count();
    for (std::size_t f = 0; f < r.faces; ++f) r.faces_with_lt3_vertices += mesh.face_size(f) < 3;
    r.triangles = mesh.triangle_count();
}

// Holes: the boundary edges joined through their shared (welded) ends
// (called only when there are some).
std::size_t count_boundary_loops(const WeldedMesh& m, const EdgeTable& edges) {
    core::UnionFind ends(m.referenced());
    std::vector<char> on_boundary(m.referenced(), 0);
    for (const auto& [a, b, flags] : edges.flagged) {
        if (!(flags & topology::kBoundary)) continue;
        ends.unite(a, b);
        on_boundary[a] = on_boundary[b] = 1;
    }
    std::size_t loops = 0;
    for (uint32_t v = 0; v < on_boundary.size(); ++v) loops += on_boundary[v] && ends.find(v) == v;
    return loops;
}

// The first `limit` flagged edges, as positions.
void list_problem_edges(const WeldedMesh& m, const EdgeTable& edges, std::size_t limit, TopologyReport& r) {
    const std::size_t n = std::min(limit, edges.flagged.size());
    r.problem_edges.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& [a, b, flags] = edges.flagged[i];
        const double *p = m.position(a), *q = m.position(b);
        r.problem_edges.push_back({{p[0], p[1], p[2], q[0], q[1], q[2]}, flags});
    }
}

void count_edges(const WeldedMesh& m, const EdgeTable& edges, TopologyReport& r) {
    r.edges = edges.size();
    for (uint8_t f : edges.flags) {
        r.boundary_edges += (f & topology::kBoundary) != 0;
        r.nonmanifold_edges += (f & topology::kNonmanifold) != 0;
        r.misoriented_edges += (f & topology::kMisoriented) != 0;
        r.unbalanced_edges += (f & topology::kUnbalanced) != 0;
    }
    r.degenerate_edge_uses = edges.degenerate_uses;
    r.closed = r.boundary_edges == 0;
    r.edge_manifold = r.nonmanifold_edges == 0;
    r.consistently_oriented = r.misoriented_edges == 0;
    r.closed_2_cycle = r.unbalanced_edges == 0;
    r.holes = r.boundary_edges ? count_boundary_loops(m, edges) : 0;
    if (edges.unbalanced_example) {
        const double* from = m.position((*edges.unbalanced_example)[0]);
        const double* to = m.position((*edges.unbalanced_example)[1]);
        r.unbalanced_example = std::array{from[0], from[1], from[2], to[0], to[1], to[2]};
    }
}

// Components of the polygons joined through shared (welded) vertices.
std::size_t count_vertex_components(const WeldedMesh& m) {
    core::UnionFind vertices(m.referenced());
    m.for_each_polygon([&](uint32_t, std::span<const uint32_t> c) {
        for (std::size_t i = 1; i < c.size(); ++i) vertices.unite(m.id[c[0]], m.id[c[i]]);
    });
    return vertices.count_roots();  // every dense vertex is used by a polygon
}

// Balanced shells only: inside = the other shells wind around it at least
// halfway (≈1 inside a solid, ≈0 outside or inside a cavity of it).
ShellRole classify(const Shell& s) {
    if (s.unbalanced_edges != 0) return ShellRole::open;
    if (std::isnan(s.winding_of_others)) return ShellRole::undecided;
    const bool inside = s.winding_of_others >= 0.5;
    if (s.signed_volume < 0) return inside ? ShellRole::cavity : ShellRole::inside_out;
    return inside ? ShellRole::nested : ShellRole::solid;
}

// Shells by |volume| descending; equal ones keep the order of their first face.
std::vector<Shell> order_shells(std::vector<ShellGeometry>&& geometry, std::span<const double> winding) {
    std::vector<Shell> shells(geometry.size());
    for (std::size_t s = 0; s < shells.size(); ++s) {
        shells[s] = geometry[s].report;
        shells[s].winding_of_others = winding[s];
        shells[s].role = classify(shells[s]);
    }
    // NaN volumes (non-finite coordinates) go last.
    const auto size = [](const Shell& s) { return std::isnan(s.signed_volume) ? -1.0 : std::abs(s.signed_volume); };
    std::stable_sort(shells.begin(), shells.end(), [&](const Shell& a, const Shell& b) { return size(a) > size(b); });
    return shells;
}

}  // namespace

std::string_view shell_role_name(ShellRole role) {
    switch (role) {
        case ShellRole::solid: return "solid";
        case ShellRole::cavity: return "cavity";
        case ShellRole::inside_out: return "inside-out";
        case ShellRole::nested: return "nested";
        case ShellRole::open: return "open";
        case ShellRole::undecided: return "undecided";
    }
    return "open";
}

TopologyReport analyze_topology(const MeshView& mesh, const TopologyOptions& options) {
    topology::check_mesh_arrays(mesh);
    TopologyReport r;
    count_faces(mesh, r);

    const WeldedMesh m = topology::weld_polygons(mesh);
    r.vertices_welded = m.welded;
    r.vertices_referenced = m.referenced();

    // The polygon sets (shells) only when they are asked for.
    core::UnionFind polygon_sets(options.shells ? m.polygons : 0);
    const EdgeTable edges = topology::build_edge_table(m, options.shells ? &polygon_sets : nullptr);
    count_edges(m, edges, r);
    list_problem_edges(m, edges, options.problem_edges, r);
    r.euler_characteristic = static_cast<int64_t>(r.vertices_referenced) -
                             static_cast<int64_t>(r.edges) + static_cast<int64_t>(m.polygons);
    if (!options.shells) return r;

    const topology::DegenerateCounts degenerate = topology::count_degenerate_triangles(m);
    r.triangles_with_repeated_vertex = degenerate.triangles_with_repeated_vertex;
    r.zero_area_triangles = degenerate.zero_area_triangles;

    r.components_vertex_connected = count_vertex_components(m);
    const topology::ShellLabels labels = topology::label_shells(polygon_sets);
    r.components_edge_connected = labels.count;

    const topology::ShellTriangles triangles = topology::gather_shell_triangles(m, labels);
    std::vector<ShellGeometry> geometry = topology::measure_shells(m, labels, edges, triangles);
    // Each shell's first face in file order (shells are numbered by their first polygon).
    std::vector<uint8_t> seen(labels.count, 0);
    for (std::size_t f = 0, poly = 0; f < mesh.face_count(); ++f) {
        if (mesh.face_size(f) < 3) continue;
        const uint32_t sh = labels.of_polygon[poly++];
        if (!seen[sh]) {
            seen[sh] = 1;
            geometry[sh].report.first_face = f;
        }
    }
    const std::vector<double> winding = topology::winding_of_other_shells(m, triangles, geometry);
    std::vector<std::size_t> first_of_label(labels.count);  // order_shells reorders them: known by first face
    for (uint32_t sh = 0; sh < labels.count; ++sh) first_of_label[sh] = geometry[sh].report.first_face;
    r.shells = order_shells(std::move(geometry), winding);
    if (options.face_shells) {
        std::unordered_map<std::size_t, uint32_t> index_of_first;
        for (uint32_t i = 0; i < r.shells.size(); ++i) index_of_first[r.shells[i].first_face] = i;
        r.face_shell.assign(mesh.face_count(), TopologyReport::kNoShell);
        for (std::size_t f = 0, poly = 0; f < mesh.face_count(); ++f) {
            if (mesh.face_size(f) < 3) continue;
            r.face_shell[f] = index_of_first.at(first_of_label[labels.of_polygon[poly++]]);
        }
    }
    for (const Shell& s : r.shells) {
        r.cavities += s.role == ShellRole::cavity;
        r.inside_out_shells += s.role == ShellRole::inside_out;
        r.nested_shells += s.role == ShellRole::nested;
    }
    return r;
}

}  // namespace polyvol
