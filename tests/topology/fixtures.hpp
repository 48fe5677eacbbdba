// Small meshes with known topology, built in code (more, with the box and
// the tetrahedron, in common/shapes.hpp).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "common/shapes.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::test {

// The box [0, 1]^3 (see add_box).
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

}  // namespace polyvol::test
