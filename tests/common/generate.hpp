// Closed meshes generated in memory, for the tests and the benchmarks.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "polyvol/cell_mesh.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::generate {

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

// Two closed meshes A and B joined into one shell by a tube: the face of A
// furthest along -x and the face of B furthest along +x removed, their rims
// joined by three quads (six triangles) through both. As 2-chains that shell
// is A + B + T, T the tube closed by the two faces reversed, so both bound
// the same solid {W >= 1} (tests/boolean/self_solid_test.cpp). Triangle
// meshes only.
struct Joined {
    Mesh one;    // one shell, crossing itself
    Mesh three;  // A, B and T: three shells
};

inline std::array<uint32_t, 3> triangle_of(const Mesh& m, uint32_t f) {
    return {m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
}

// The face of m whose centroid is furthest along `sign` x.
inline uint32_t extreme_face(const Mesh& m, double sign) {
    uint32_t best = 0;
    double best_x = -INFINITY;
    for (uint32_t f = 0; f < m.indices.size() / 3; ++f) {
        double x = 0;
        for (uint32_t v : triangle_of(m, f)) x += m.positions[3 * v];
        if (sign * x > best_x) {
            best_x = sign * x;
            best = f;
        }
    }
    return best;
}

inline Joined join_by_tube(const Mesh& a, const Mesh& b) {
    const uint32_t fa = extreme_face(a, -1), fb = extreme_face(b, +1);
    Joined j;
    // The walls run along fa's edges a_i -> a_i+1 and fb's b_m -> b_m+1 (the
    // rims' other uses are the reverse), pairing a_i with b_(k - i), k the
    // rotation that pairs the nearest corners (a twisted tube folds onto itself).
    auto copy_without = [](Mesh& to, const Mesh& from, uint32_t skip) {
        const auto base = static_cast<uint32_t>(to.vertex_count());
        to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
        for (uint32_t f = 0; f < from.indices.size() / 3; ++f)
            if (f != skip) {
                const auto c = triangle_of(from, f);
                to.add_triangle(base + c[0], base + c[1], base + c[2]);
            }
        return base;
    };
    const uint32_t base_a = copy_without(j.one, a, fa);
    const uint32_t base_b = copy_without(j.one, b, fb);
    const std::array<uint32_t, 3> ra = triangle_of(a, fa), rb = triangle_of(b, fb);
    int k = 0;
    double best = INFINITY;
    for (int rot = 0; rot < 3; ++rot) {
        double d2 = 0;
        for (int i = 0; i < 3; ++i)
            for (int c = 0; c < 3; ++c) {
                const double d = a.positions[3 * ra[i] + c] - b.positions[3 * rb[(rot + 3 - i) % 3] + c];
                d2 += d * d;
            }
        if (d2 < best) {
            best = d2;
            k = rot;
        }
    }
    auto walls = [&](Mesh& m, const std::array<uint32_t, 3>& av, const std::array<uint32_t, 3>& bv) {
        auto partner = [&](int i) { return bv[(k + 3 - i) % 3]; };
        for (int i = 0; i < 3; ++i) {
            const uint32_t p = av[i], q = av[(i + 1) % 3], r = partner((i + 1) % 3), s = partner(i);
            m.add_triangle(p, q, r);
            m.add_triangle(p, r, s);
        }
    };
    walls(j.one, {base_a + ra[0], base_a + ra[1], base_a + ra[2]}, {base_b + rb[0], base_b + rb[1], base_b + rb[2]});
    j.three = a;
    j.three.append(b);
    Mesh t;
    std::array<uint32_t, 3> ta{}, tb{};
    for (int i = 0; i < 3; ++i) {
        ta[i] = t.add_vertex(a.positions[3 * ra[i]], a.positions[3 * ra[i] + 1], a.positions[3 * ra[i] + 2]);
        tb[i] = t.add_vertex(b.positions[3 * rb[i]], b.positions[3 * rb[i] + 1], b.positions[3 * rb[i] + 2]);
    }
    walls(t, ta, tb);
    t.add_triangle(ta[0], ta[2], ta[1]);
    t.add_triangle(tb[0], tb[2], tb[1]);
    j.three.append(t);
    return j;
}

// n^3 hexahedra over [lo, hi]^3, interior points moved by up to `jitter`
// of a cell along each axis (a random but fixed pattern): warped faces.
inline CellMesh hex_cells(int n, double lo, double hi, double jitter, unsigned seed = 7) {
    CellMesh m;
    const double h = (hi - lo) / n;
    auto p = [n](int i, int j, int k) { return static_cast<uint32_t>(i + (n + 1) * (j + (n + 1) * k)); };
    auto c = [n](int i, int j, int k) { return static_cast<uint32_t>(i + n * (j + n * k)); };
    uint64_t state = seed;
    auto random = [&] {  // in [-1, 1)
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(state >> 11) * 0x1p-52 - 1.0;
    };
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const int ijk[3] = {i, j, k};
                for (int a = 0; a < 3; ++a) {
                    const bool inner = ijk[a] > 0 && ijk[a] < n;
                    m.points.push_back(lo + h * ijk[a] + (inner ? jitter * h * random() : 0.0));
                }
            }
    auto face = [&](std::array<uint32_t, 4> q, uint32_t owner, uint32_t neighbour) {
        m.face_points.insert(m.face_points.end(), q.begin(), q.end());
        m.face_offsets.push_back(static_cast<uint32_t>(m.face_points.size()));
        m.owner.push_back(owner);
        m.neighbour.push_back(neighbour);
    };
    // The face of normal +axis at the plane through (i, j, k).
    auto plus = [&](int axis, int i, int j, int k) -> std::array<uint32_t, 4> {
        if (axis == 0) return {p(i, j, k), p(i, j + 1, k), p(i, j + 1, k + 1), p(i, j, k + 1)};
        if (axis == 1) return {p(i, j, k), p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j, k)};
        return {p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k)};
    };
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int ijk[3] = {i, j, k};
                for (int a = 0; a < 3; ++a) {
                    int q[3] = {i, j, k};
                    ++q[a];
                    if (q[a] < n) face(plus(a, q[0], q[1], q[2]), c(i, j, k), c(q[0], q[1], q[2]));
                    if (ijk[a] == 0) {
                        auto f = plus(a, i, j, k);
                        std::reverse(f.begin(), f.end());
                        face(f, c(i, j, k), kNoCell);
                    }
                    if (q[a] == n) face(plus(a, q[0], q[1], q[2]), c(i, j, k), kNoCell);
                }
            }
    m.cells = static_cast<std::size_t>(n) * n * n;
    return m;
}

}  // namespace polyvol::generate
