// Closed test meshes generated in memory for the benchmarks.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "polyvol/mesh.hpp"

namespace polyvol::bench {

// A UV sphere of radius r centred at c: `rings` latitude bands, `segments`
// longitudes, 2 * segments * (rings - 1) triangles, closed and outward.
inline Mesh uv_sphere(uint32_t rings, uint32_t segments, double r = 1.0, double cx = 0, double cy = 0, double cz = 0) {
    Mesh m;
    m.positions.reserve(3 * (2 + (rings - 1) * segments));
    m.add_vertex(cx, cy, cz + r);  // north pole 0
    for (uint32_t i = 1; i < rings; ++i) {
        const double th = std::numbers::pi * i / rings;
        for (uint32_t j = 0; j < segments; ++j) {
            const double ph = 2 * std::numbers::pi * j / segments;
            m.add_vertex(cx + r * std::sin(th) * std::cos(ph), cy + r * std::sin(th) * std::sin(ph), cz + r * std::cos(th));
        }
    }
    const uint32_t south = m.add_vertex(cx, cy, cz - r);
    auto at = [&](uint32_t i, uint32_t j) { return 1 + (i - 1) * segments + j % segments; };
    m.indices.reserve(6 * segments * (rings - 1));
    for (uint32_t j = 0; j < segments; ++j) m.add_triangle(0, at(1, j), at(1, j + 1));
    for (uint32_t i = 1; i + 1 < rings; ++i)
        for (uint32_t j = 0; j < segments; ++j) {
            m.add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    for (uint32_t j = 0; j < segments; ++j) m.add_triangle(south, at(rings - 1, j + 1), at(rings - 1, j));
    return m;
}

// About n triangles.
inline Mesh sphere_with_triangles(std::size_t n, double offset = 0) {
    const auto seg = static_cast<uint32_t>(std::sqrt(static_cast<double>(n)));
    const uint32_t rings = static_cast<uint32_t>(n / (2 * seg)) + 1;
    return uv_sphere(rings, seg, 1.0, offset, offset, offset);
}

}  // namespace polyvol::bench
