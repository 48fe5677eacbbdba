// Small meshes with known topology, built in code.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "common/shapes.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::test {

// Options for box(): triangles or quads, and turned inside out.
struct BoxOptions {
    bool quads = false;
    bool inverted = false;
};

// Axis-aligned box [lo, hi] with 8 shared vertices, faces counter-clockwise
// seen from outside (clockwise when inverted). Vertex i is corner
// (x = i & 1, y = i >> 1 & 1, z = i >> 2 & 1).
inline void add_box(Mesh& m, std::array<double, 3> lo, std::array<double, 3> hi, BoxOptions o = {}) {
    const uint32_t base = static_cast<uint32_t>(m.vertex_count());
    for (int i = 0; i < 8; ++i)
        m.add_vertex(i & 1 ? hi[0] : lo[0], i >> 1 & 1 ? hi[1] : lo[1], i >> 2 & 1 ? hi[2] : lo[2]);
    static constexpr uint32_t kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                              {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : kQuads) {
        std::array<uint32_t, 4> f{base + q[0], base + q[1], base + q[2], base + q[3]};
        if (o.inverted) f = {f[0], f[3], f[2], f[1]};
        if (o.quads) {
            m.add_face(f);
        } else {
            m.add_triangle(f[0], f[1], f[2]);
            m.add_triangle(f[0], f[2], f[3]);
        }
    }
}

inline Mesh box(std::array<double, 3> lo, std::array<double, 3> hi, BoxOptions o = {}) {
    Mesh m;
    add_box(m, lo, hi, o);
    return m;
}

inline Mesh unit_cube(BoxOptions o = {}) { return box({0, 0, 0}, {1, 1, 1}, o); }

// The corner tetrahedron (0, e1, e2, e3), outward: volume 1/6.
inline Mesh tetrahedron() { return polyvol::test::unit_tetrahedron(); }

// A torus of n × k quads (major radius 2, minor 0.5), outward.
inline Mesh quad_torus(uint32_t n, uint32_t k) {
    Mesh m;
    const double two_pi = 2 * std::numbers::pi;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < k; ++j) {
            const double u = two_pi * i / n, v = two_pi * j / k;
            const double r = 2 + 0.5 * std::cos(v);
            m.add_vertex(r * std::cos(u), r * std::sin(u), 0.5 * std::sin(v));
        }
    const auto at = [&](uint32_t i, uint32_t j) { return (i % n) * k + j % k; };
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < k; ++j) {
            const std::array<uint32_t, 4> q{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            m.add_face(q);
        }
    return m;
}

// Every triangle with its own three vertices, as an STL file stores it.
inline Mesh unwelded(const Mesh& in) {
    Mesh out;
    const MeshView v = in.view();
    for (std::size_t f = 0; f < v.face_count(); ++f) {
        std::vector<uint32_t> face;
        for (uint32_t i : v.face(f))
            face.push_back(out.add_vertex(in.positions[3 * i], in.positions[3 * i + 1], in.positions[3 * i + 2]));
        out.add_face(face);
    }
    return out;
}

}  // namespace polyvol::test
