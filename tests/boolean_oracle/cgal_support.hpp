// Shared by the CGAL oracle tests (tests/boolean_oracle): test meshes, CGAL's
// copy of a mesh over the same doubles, and exact volumes as GMP rationals.
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/real_pairs.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::oracle {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vec3 = std::array<double, 3>;

// ---- Meshes -----------------------------------------------------------------

// The unit icosphere: the icosahedron's faces split `levels` times into four,
// every new vertex the normalized midpoint (in double) of its edge. Indexed
// (midpoints shared), outward; levels = 3 gives 642 vertices, 1280 triangles.
inline Mesh icosphere(int levels) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    const double s = 1 / std::sqrt(1 + t * t);
    Mesh m;
    const double corners[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const auto& c : corners) m.add_vertex(c[0] * s, c[1] * s, c[2] * s);
    std::vector<std::array<uint32_t, 3>> faces = {
        {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            if (auto it = midpoints.find(key); it != midpoints.end()) return it->second;
            double p[3];
            for (int k = 0; k < 3; ++k) p[k] = m.positions[3 * a + k] + m.positions[3 * b + k];
            const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            const uint32_t v = m.add_vertex(p[0] / n, p[1] / n, p[2] / n);
            midpoints.emplace(key, v);
            return v;
        };
        std::vector<std::array<uint32_t, 3>> finer;
        for (const auto& f : faces) {
            const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({f[1], bc, ab});
            finer.push_back({f[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = std::move(finer);
    }
    for (const auto& f : faces) m.add_triangle(f[0], f[1], f[2]);
    return m;
}

// The torus about the z axis with major radius R and minor radius r, on a
// (nu x nv) grid of its angles, each grid quad split into two triangles;
// indexed, outward ((d/du) x (d/dv) points away from the tube's core).
inline Mesh torus(double R, double r, uint32_t nu, uint32_t nv) {
    Mesh m;
    const double pi = std::acos(-1.0);
    for (uint32_t i = 0; i < nu; ++i) {
        const double u = 2 * pi * i / nu;
        for (uint32_t j = 0; j < nv; ++j) {
            const double v = 2 * pi * j / nv;
            m.add_vertex((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
        }
    }
    auto id = [&](uint32_t i, uint32_t j) { return (i % nu) * nv + j % nv; };
    for (uint32_t i = 0; i < nu; ++i)
        for (uint32_t j = 0; j < nv; ++j) {
            m.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            m.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    return m;
}

// m with every vertex p replaced by rot(axis, angle) p + shift, each
// coordinate computed in double (so rounded): the doubles both tools see.
using test::transformed;

// m translated by shift (each coordinate p + shift rounded to double).
inline Mesh translated(const Mesh& m, Vec3 shift) {
    Mesh out = m;
    for (std::size_t i = 0; i < out.positions.size(); ++i) out.positions[i] += shift[i % 3];
    return out;
}

// CGAL's copy of m: the same double coordinates (exact in Epeck), each face
// fan-triangulated from its first vertex as polyvol reads it. Empty, with
// the reason in why, when Surface_mesh refuses a face (a non-manifold vertex
// or edge).
inline std::optional<CgalMesh> to_cgal(const Mesh& m, std::string& why) {
    CgalMesh out;
    std::vector<CgalMesh::Vertex_index> vertex;
    vertex.reserve(m.vertex_count());
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        vertex.push_back(
            out.add_vertex(Kernel::Point_3(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2])));
    const MeshView view = m.view();
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto face = view.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i)
            if (out.add_face(vertex[face[0]], vertex[face[i]], vertex[face[i + 1]]) == CgalMesh::null_face()) {
                why = "Surface_mesh::add_face refused face " + std::to_string(f) + " (non-manifold)";
                return std::nullopt;
            }
    }
    return out;
}

// ---- Exact values -----------------------------------------------------------

// GMP's mpq_t behind a value of Epeck's exact field type: mpq_class when
// CGAL is configured with gmpxx (CGAL_USE_GMPXX, Debian's CGAL 5.5), else
// CGAL::Gmpq or boost::multiprecision's gmp_rational.
template <class Exact>
inline mpq_srcptr mpq_of(const Exact& q) {
    if constexpr (requires { q.get_mpq_t(); })
        return q.get_mpq_t();
    else if constexpr (requires { q.mpq(); })
        return q.mpq();
    else
        return q.backend().data();
}

// The exact volume of a closed CGAL mesh as a GMP rational (the lazy value
// of PMP::volume forced to its exact rational).
inline mpq_class exact_volume(const CgalMesh& m) {
    const Kernel::FT v = PMP::volume(m);
    return mpq_class(mpq_of(CGAL::exact(v)));
}

}  // namespace polyvol::oracle
