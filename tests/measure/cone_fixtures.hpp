// Shared by cone_test.cpp and mass_properties_test.cpp: meshes with known
// values and an independent GMP reference of the cone rule's sums.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <random>
#include <unordered_map>
#include <vector>

#include "common/shapes.hpp"
#include "exact/exact_sum.hpp"
#include "exact/rational.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::fixtures {

// The exact value held by a superaccumulator; a rational rounded once.
inline mpq_class as_mpq(const exact::ExactSum& s) { return mpq_class(exact::Rational(s).get()); }
inline double rnd(const mpq_class& x) { return exact::round_to_double(x.get_mpq_t()); }

inline mpq_class q(double x) {
    mpq_class r;
    mpq_set_d(r.get_mpq_t(), x);
    return r;
}

// The ten sums Σdet, Σdet s_i, Σdet q_ij (see measure/cone.hpp) over the fan
// triangles, in plain rational arithmetic.
inline std::array<mpq_class, 10> reference_sums(const MeshView& m) {
    std::array<mpq_class, 10> s;
    for (auto& x : s) x = 0;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = m.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i) {
            const uint32_t v[3] = {face[0], face[i], face[i + 1]};
            mpq_class p[3][3];
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < 3; ++k) p[a][k] = q(m.positions[3 * v[a] + static_cast<std::size_t>(k)]);
            const mpq_class det = p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) +
                                  p[0][1] * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) +
                                  p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
            s[0] += det;
            mpq_class sum[3];
            for (int k = 0; k < 3; ++k) {
                sum[k] = p[0][k] + p[1][k] + p[2][k];
                s[1 + k] += det * sum[k];
            }
            const int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
            for (int k = 0; k < 6; ++k) {
                const int x = I[k], y = J[k];
                s[4 + k] += det * (p[0][x] * p[0][y] + p[1][x] * p[1][y] + p[2][x] * p[2][y] + sum[x] * sum[y]);
            }
        }
    }
    return s;
}

// The box [x0,x1]×[y0,y1]×[z0,z1] of common/shapes.hpp, 12 outward triangles
// or 6 quads, by its six bounds (as the measure tests write them).
inline Mesh box(double x0, double y0, double z0, double x1, double y1, double z1, bool quads = false) {
    return test::box({x0, y0, z0}, {x1, y1, z1}, {.quads = quads});
}

inline Mesh unit_tetrahedron() { return polyvol::test::unit_tetrahedron(); }

// |x| + |y| + |z| <= r, outward.
inline Mesh octahedron(double r = 1) {
    Mesh m;
    m.add_vertex(r, 0, 0);
    m.add_vertex(-r, 0, 0);
    m.add_vertex(0, r, 0);
    m.add_vertex(0, -r, 0);
    m.add_vertex(0, 0, r);
    m.add_vertex(0, 0, -r);
    for (uint32_t sx = 0; sx < 2; ++sx)
        for (uint32_t sy = 0; sy < 2; ++sy)
            for (uint32_t sz = 0; sz < 2; ++sz) {
                const uint32_t a = sx, b = 2 + sy, c = 4 + sz;
                // Outward when (sign x)(sign y)(sign z) > 0 for the order (a, b, c).
                if ((sx + sy + sz) % 2 == 0) {
                    m.add_triangle(a, b, c);
                } else {
                    m.add_triangle(a, c, b);
                }
            }
    return m;
}

// A closed, outward, star-shaped polyhedron: the octahedron subdivided
// `levels` times, vertices pushed to a sphere of radius r with random
// perturbation, then translated by t (coordinates rounded to doubles).
inline Mesh random_sphere(std::mt19937_64& rng, int levels, double r, std::array<double, 3> t, double jitter = 0.1) {
    Mesh m = octahedron(1);
    for (int l = 0; l < levels; ++l) {
        Mesh next;
        next.positions = m.positions;
        std::unordered_map<uint64_t, uint32_t> mids;
        auto mid = [&](uint32_t a, uint32_t b) {
            if (a > b) std::swap(a, b);
            const uint64_t key = (uint64_t{a} << 32) | b;
            const auto it = mids.find(key);
            if (it != mids.end()) return it->second;
            const uint32_t v = next.add_vertex((next.positions[3 * a] + next.positions[3 * b]) / 2,
                                               (next.positions[3 * a + 1] + next.positions[3 * b + 1]) / 2,
                                               (next.positions[3 * a + 2] + next.positions[3 * b + 2]) / 2);
            mids.emplace(key, v);
            return v;
        };
        for (std::size_t f = 0; f < m.face_count(); ++f) {
            const uint32_t a = m.indices[3 * f], b = m.indices[3 * f + 1], c = m.indices[3 * f + 2];
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.add_triangle(a, ab, ca);
            next.add_triangle(ab, b, bc);
            next.add_triangle(ca, bc, c);
            next.add_triangle(ab, bc, ca);
        }
        m = std::move(next);
    }
    std::uniform_real_distribution<double> d(1 - jitter, 1 + jitter);
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        double* p = &m.positions[3 * v];
        const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        const double s = r * d(rng) / n;
        for (int k = 0; k < 3; ++k) p[k] = p[k] * s + t[static_cast<std::size_t>(k)];
    }
    return m;
}

}  // namespace polyvol::fixtures
