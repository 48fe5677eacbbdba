// Closed test meshes generated in memory for the benchmarks.
#pragma once

#include <algorithm>
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

// A torus around the z axis centred at the origin: tube radius r around a
// circle of radius R, `around` segments along the circle and `tube` around
// the tube, 2 * around * tube triangles, closed and outward.
inline Mesh torus(uint32_t around, uint32_t tube, double R = 1.0, double r = 0.42) {
    Mesh m;
    m.positions.reserve(3 * std::size_t{around} * tube);
    for (uint32_t i = 0; i < around; ++i) {
        const double u = 2 * std::numbers::pi * i / around;
        for (uint32_t j = 0; j < tube; ++j) {
            const double v = 2 * std::numbers::pi * j / tube;
            const double w = R + r * std::cos(v);
            m.add_vertex(w * std::cos(u), w * std::sin(u), r * std::sin(v));
        }
    }
    auto at = [&](uint32_t i, uint32_t j) { return (i % around) * tube + j % tube; };
    m.indices.reserve(6 * std::size_t{around} * tube);
    for (uint32_t i = 0; i < around; ++i)
        for (uint32_t j = 0; j < tube; ++j) {
            m.add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            m.add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return m;
}

// About n triangles, segments in the ratio of the circle's and the tube's lengths.
inline Mesh torus_with_triangles(std::size_t n, double R = 1.0, double r = 0.42) {
    const double half = static_cast<double>(n) / 2;
    const auto tube = static_cast<uint32_t>(std::max(3.0, std::round(std::sqrt(half * r / R))));
    const auto around = static_cast<uint32_t>(std::max(3.0, std::round(half / tube)));
    return torus(around, tube, R, r);
}

}  // namespace polyvol::bench
