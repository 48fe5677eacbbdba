#include "topology/shells.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <tbb/parallel_for.h>

#include "exact/eft.hpp"
#include "polyvol/measure.hpp"

namespace polyvol::topology {

ShellLabels label_shells(core::UnionFind& polygon_sets) {
    ShellLabels s;
    const std::size_t n = polygon_sets.size();
    s.of_polygon.assign(n, kNone);
    // Roots get their label when first met, so shells are numbered by first polygon.
    std::vector<uint32_t> label_of_root(n, kNone);
    for (uint32_t p = 0; p < n; ++p) {
        uint32_t& label = label_of_root[polygon_sets.find(p)];
        if (label == kNone) label = static_cast<uint32_t>(s.count++);
        s.of_polygon[p] = label;
    }
    return s;
}

ShellLabels edge_connected_shells(const WeldedMesh& mesh) {
    core::UnionFind polygon_sets(mesh.polygons);
    build_edge_table(mesh, &polygon_sets);
    return label_shells(polygon_sets);
}

ShellTriangles gather_shell_triangles(const WeldedMesh& m, const ShellLabels& shells) {
    ShellTriangles t;
    t.offsets.assign(shells.count + 1, 0);
    m.for_each_polygon([&](uint32_t p, std::span<const uint32_t> c) {
        t.offsets[shells.of_polygon[p] + 1] += c.size() - 2;
    });
    for (std::size_t s = 0; s < shells.count; ++s) t.offsets[s + 1] += t.offsets[s];
    t.tris.resize(t.offsets[shells.count]);
    std::vector<std::size_t> fill(t.offsets.begin(), t.offsets.end() - 1);
    m.for_each_polygon([&](uint32_t p, std::span<const uint32_t> c) {
        std::size_t& at = fill[shells.of_polygon[p]];
        const uint32_t a = m.id[c[0]];
        for (std::size_t i = 1; i + 1 < c.size(); ++i) t.tris[at++] = {a, m.id[c[i]], m.id[c[i + 1]]};
    });
    return t;
}

namespace {

// Nonmanifold and misoriented edges per shell (for the genus only).
struct EdgeDefects {
    std::vector<std::size_t> nonmanifold, misoriented;
};

EdgeDefects count_shell_edges(const ShellLabels& shells, const EdgeTable& edges,
                              std::vector<ShellGeometry>& out) {
    EdgeDefects d{std::vector<std::size_t>(shells.count), std::vector<std::size_t>(shells.count)};
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const uint32_t s = shells.of_polygon[edges.polygon[e]];
        const uint8_t f = edges.flags[e];
        Shell& r = out[s].report;
        ++r.edges;
        r.boundary_edges += (f & kBoundary) != 0;
        r.unbalanced_edges += (f & kUnbalanced) != 0;
        d.nonmanifold[s] += (f & kNonmanifold) != 0;
        d.misoriented[s] += (f & kMisoriented) != 0;
    }
    return d;
}

// Σ det(a, b, c) / 6 over a shell's triangles about the origin (which for a
// balanced shell is the origin-free value too), correctly rounded: measure's
// cone rule, whose filter decides nearly always and which is exact for any
// finite coordinates. A shell with at least a quarter as many triangles as
// the mesh has vertices is passed as indices into the welded positions
// (measure may read every position it is given: at most four per
// triangle), when all of them are in measure's safe range (one coordinate
// out of it elsewhere would send every such shell down measure's
// big-integer path); any other shell as its own soup of corners. So the
// calls read O(triangles) in all, whatever the number of shells.
double shell_volume(const WeldedMesh& m, std::span<const std::array<uint32_t, 3>> tris, bool positions_safe) {
    std::vector<uint32_t> indices(3 * tris.size());
    std::vector<double> corners;
    // (indices too when a soup's corner ids would not fit in 32 bits)
    const bool indexed = (positions_safe && 4 * tris.size() >= m.referenced()) || 3 * tris.size() > UINT32_MAX;
    if (!indexed) corners.resize(9 * tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::size_t at = 3 * t + k;
            if (indexed) {
                indices[at] = tris[t][k];
            } else {
                indices[at] = static_cast<uint32_t>(at);
                std::copy_n(m.position(tris[t][k]), 3, &corners[3 * at]);
            }
        }
    const MeshView shell{indexed ? std::span<const double>(m.xyz) : std::span<const double>(corners), {}, indices};
    return signed_volume(shell, Method::cone, Accuracy::correctly_rounded);
}

// Twice the squared area of triangle (a, b, c), up to a factor: |(b-a)×(c-a)|².
double cross_norm2(const double* a, const double* b, const double* c) {
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
    return x * x + y * y + z * z;
}

// Volume, probe point and bounding box of a shell from its triangles.
void measure_geometry(const WeldedMesh& m, std::span<const std::array<uint32_t, 3>> tris, bool positions_safe,
                      ShellGeometry& g) {
    double largest = -1;
    constexpr double inf = std::numeric_limits<double>::infinity();
    g.box = {inf, inf, inf, -inf, -inf, -inf};
    for (const auto& t : tris) {
        const double *a = m.position(t[0]), *b = m.position(t[1]), *c = m.position(t[2]);
        const double n2 = cross_norm2(a, b, c);
        if (n2 > largest) {
            largest = n2;
            for (int k = 0; k < 3; ++k) g.probe[k] = (a[k] + b[k] + c[k]) / 3.0;
        }
        for (const double* p : {a, b, c}) {
            for (int k = 0; k < 3; ++k) {
                g.box[k] = std::min(g.box[k], p[k]);
                g.box[k + 3] = std::max(g.box[k + 3], p[k]);
            }
        }
    }
    g.report.signed_volume = shell_volume(m, tris, positions_safe);
}

}  // namespace

std::vector<ShellGeometry> measure_shells(const WeldedMesh& m, const ShellLabels& shells,
                                          const EdgeTable& edges, const ShellTriangles& triangles) {
    std::vector<ShellGeometry> out(shells.count);
    for (uint32_t s : shells.of_polygon) ++out[s].report.faces;
    const EdgeDefects defects = count_shell_edges(shells, edges, out);

    const auto shell_tris = [&](std::size_t s) {
        return std::span(triangles.tris).subspan(triangles.offsets[s], triangles.offsets[s + 1] - triangles.offsets[s]);
    };
    // Distinct vertices per shell: stamp each vertex with the last shell that counted it.
    std::vector<uint32_t> stamp(m.referenced(), kNone);
    for (std::size_t s = 0; s < shells.count; ++s) {
        const auto tris = shell_tris(s);
        Shell& r = out[s].report;
        for (const auto& t : tris)
            for (uint32_t v : t)
                if (stamp[v] != s) {
                    stamp[v] = static_cast<uint32_t>(s);
                    ++r.vertices;
                }
        r.euler_characteristic = static_cast<int64_t>(r.vertices) - static_cast<int64_t>(r.edges) +
                                 static_cast<int64_t>(r.faces);
        // χ = 2 - 2g for a closed orientable surface; an even χ <= 2 is
        // required too (pinched vertices can break it).
        if (r.boundary_edges == 0 && defects.nonmanifold[s] == 0 && defects.misoriented[s] == 0 &&
            r.euler_characteristic <= 2 && r.euler_characteristic % 2 == 0)
            r.genus = (2 - r.euler_characteristic) / 2;
    }
    const bool positions_safe = std::all_of(m.xyz.begin(), m.xyz.end(), exact::in_safe_range);
    tbb::parallel_for(std::size_t{0}, shells.count,
                      [&](std::size_t s) { measure_geometry(m, shell_tris(s), positions_safe, out[s]); });
    return out;
}

}  // namespace polyvol::topology
