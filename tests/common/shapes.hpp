// Small closed meshes shared by the test programs, with their exact figures.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol::test {

// One triangle (a, b, c): an open surface.
inline Mesh triangle(std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c) {
    Mesh m;
    m.add_vertex(a[0], a[1], a[2]);
    m.add_vertex(b[0], b[1], b[2]);
    m.add_vertex(c[0], c[1], c[2]);
    m.add_triangle(0, 1, 2);
    return m;
}

// The corner tetrahedron (0, e1, e2, e3), outward: volume 1/6, first moments
// 1/24, second moments 1/60 on the diagonal and 1/120 off it.
inline Mesh unit_tetrahedron() {
    Mesh m;
    m.add_vertex(0, 0, 0);
    m.add_vertex(1, 0, 0);
    m.add_vertex(0, 1, 0);
    m.add_vertex(0, 0, 1);
    m.add_triangle(0, 2, 1);
    m.add_triangle(0, 1, 3);
    m.add_triangle(0, 3, 2);
    m.add_triangle(1, 2, 3);
    return m;
}

// Options for box(): quads or their fans, and turned inside out.
struct BoxOptions {
    bool quads = false;     // 6 quads; else their fans, 12 triangles
    bool inverted = false;  // every face reversed (clockwise seen from outside)
};

// Appends the axis-aligned box [lo, hi] to m: 8 vertices of its own, vertex
// base + i at corner (x = i & 1, y = i >> 1 & 1, z = i >> 2 & 1), faces
// counter-clockwise seen from outside (clockwise when inverted).
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

// The box [lo, hi] alone (see add_box): volume Π (hi - lo).
inline Mesh box(std::array<double, 3> lo, std::array<double, 3> hi, BoxOptions o = {}) {
    Mesh m;
    add_box(m, lo, hi, o);
    return m;
}

// The box [0, 2]^3 and a tetrahedron (o, p, r, q) on its bottom front edge
// o p (o = (0, 0, 0), p = (2, 0, 0), the box's vertices 0 and 1) with
// q = (qx, 0.6, 3), r = (1.2, 1.4, 3), poking out through the box's top:
// one shell whose edge o p has four faces, and which crosses itself.
inline Mesh box_and_tetrahedron_on_its_edge(double qx = 0.8) {
    Mesh m = box({0, 0, 0}, {2, 2, 2});
    const uint32_t o = 0, p = 1;
    const uint32_t q = m.add_vertex(qx, 0.6, 3), r = m.add_vertex(1.2, 1.4, 3);
    // (o, p, r, q) is positively oriented: outward faces
    m.add_triangle(p, r, q);
    m.add_triangle(o, q, r);
    m.add_triangle(o, p, q);
    m.add_triangle(o, r, p);
    return m;
}

// Every face with its own vertices, as an STL file stores a mesh.
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
