// boolean/level_pieces.cpp — level_pieces.hpp: one operand holding every
// body (body b moved by (b + 1) δ), its crossings and windings, then
// solid_pieces.hpp's boundary segments for each level, in doubles.
#include "boolean/level_pieces.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "boolean/solid_pieces.hpp"
#include "topology/welded.hpp"

namespace polyvol::boolean {
namespace {

// x = num / den · 2^e0 with each coordinate truncated to a double: a
// function of the point's value only (the quotient floor(|num| 2^s / den)
// carries at least 54 bits, and truncating it to 53 is truncating the
// value), so every triangle sharing the point gets the same double.
std::array<double, 3> to_double(const ExactPoint& x, int e0) {
    std::array<double, 3> r;
    const long den_bits = static_cast<long>(mpz_sizeinbase(x.den.get_mpz_t(), 2));
    mpz_class q;
    for (int k = 0; k < 3; ++k) {
        if (x.num[k] == 0) {
            r[k] = 0;
            continue;
        }
        const long s = 56 + den_bits - static_cast<long>(mpz_sizeinbase(x.num[k].get_mpz_t(), 2));
        mpz_abs(q.get_mpz_t(), x.num[k].get_mpz_t());
        if (s > 0)
            mpz_mul_2exp(q.get_mpz_t(), q.get_mpz_t(), static_cast<mp_bitcnt_t>(s));
        else
            mpz_tdiv_q_2exp(q.get_mpz_t(), q.get_mpz_t(), static_cast<mp_bitcnt_t>(-s));
        mpz_tdiv_q(q.get_mpz_t(), q.get_mpz_t(), x.den.get_mpz_t());
        const double v = std::ldexp(mpz_get_d(q.get_mpz_t()), e0 - static_cast<int>(s));
        r[k] = sgn(x.num[k]) < 0 ? -v : v;
    }
    return r;
}

}  // namespace

LevelPieces level_pieces(std::span<const MeshView> bodies, std::span<const int> levels) {
    if (levels.size() > 8) throw std::invalid_argument("boolean: at most 8 levels");
    LevelPieces r;
    r.whole.resize(bodies.size());
    r.fans.resize(levels.size());

    // The operand: each body's welded vertices and fan triangles, in face order.
    Operand g;
    g.body_shift.clear();
    std::vector<std::size_t> first(bodies.size() + 1, 0);  // each body's first triangle
    std::size_t vertices = 0, triangles = 0;
    for (const MeshView& m : bodies) {
        vertices += m.vertex_count();
        triangles += m.triangle_count();
    }
    g.mesh.positions.reserve(3 * vertices);
    g.tri.reserve(3 * triangles);
    g.body_of_triangle.reserve(triangles);
    int e0 = std::numeric_limits<int>::max();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const MeshView& m = bodies[b];
        const topology::WeldedMesh wm = topology::weld_polygons(m);
        const auto base = static_cast<uint32_t>(g.mesh.vertex_count());
        for (std::size_t d = 0; d < wm.referenced(); ++d) {
            const double* p = wm.position(static_cast<uint32_t>(d));
            for (int k = 0; k < 3; ++k) {
                if (!in_predicate_range(p[k]))
                    throw std::invalid_argument("body " + std::to_string(b + 1) +
                                                " has a coordinate beyond the exact predicates' range (2^180)");
                if (p[k] != 0) e0 = std::min(e0, lowest_bit_exponent(p[k]));
            }
            g.mesh.add_vertex(p[0], p[1], p[2]);
        }
        g.body_shift.push_back(static_cast<int32_t>(b + 1));
        wm.for_each_polygon([&](uint32_t, std::span<const uint32_t> c) {
            for (std::size_t i = 1; i + 1 < c.size(); ++i) {
                for (const uint32_t v : {c[0], c[i], c[i + 1]}) g.tri.push_back(base + wm.id[v]);
                g.body_of_triangle.push_back(static_cast<uint32_t>(b));
            }
        });
        first[b + 1] = g.triangles();
        r.whole[b].assign(first[b + 1] - first[b], 0);
    }
    if (e0 == std::numeric_limits<int>::max()) e0 = 0;
    finish_operand(g);
    const Scale scale{e0};

    // Each body outward: a positive volume (decided exactly when close to 0).
    const std::vector<int> sign(bodies.size(), +1);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const std::span<const uint32_t> tris(g.tri.data() + 3 * first[b], 3 * (first[b + 1] - first[b]));
        const MeshView view{g.mesh.positions, {}, tris};
        VolumeSum v = cone_volume_sum(view, false);
        if (!(std::fabs(v.sum.round()) > 2 * v.bound)) v = cone_volume_sum(view, true);
        if (v.sum.sign() < 0)
            throw std::invalid_argument("body " + std::to_string(b + 1) + " is inside out (its volume is negative)");
    }

    try {
        const Crossings cross = find_crossings(g, g);
        r.crossing_pairs = cross.cuts.size();
        std::vector<EdgeHit> hits = cross.a_hits;
        hits.insert(hits.end(), cross.b_hits.begin(), cross.b_hits.end());
        const std::vector<int32_t> w = vertex_windings(g, g, hits);
        auto unit_normal = [&](uint32_t t) {
            const double *a = g.corner(t, 0), *b = g.corner(t, 1), *c = g.corner(t, 2);
            const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
            const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            return len > 0 ? std::array<double, 3>{n[0] / len, n[1] / len, n[2] / len} : std::array<double, 3>{0, 0, 0};
        };
        for (std::size_t k = 0; k < levels.size(); ++k) {
            SolidPieces pieces(g, cross, w, sign, scale, levels[k]);
            const std::vector<uint32_t>& crossed = pieces.crossed();
            std::size_t next = 0;  // in crossed
            for (uint32_t t = 0; t < g.triangles(); ++t) {
                if (next < crossed.size() && crossed[next] == t) {
                    ++next;
                    continue;
                }
                const uint32_t b = g.body(t);
                const int c = levels[k] - 1;  // W_others on the boundary (outward bodies)
                if (w[g.tri[3 * t]] == c) r.whole[b][t - first[b]] |= static_cast<uint8_t>(1u << k);
            }
            pieces.boundary_segments([&](uint32_t t, const ExactPoint& X, const ExactPoint& Y, int mult) {
                const std::array<double, 3> x = to_double(X, e0), y = to_double(Y, e0);
                const double* a = g.corner(t, 0);
                for (int copy = 0; copy < std::abs(mult); ++copy) {
                    const std::array<double, 3>& p = mult > 0 ? x : y;
                    const std::array<double, 3>& q = mult > 0 ? y : x;
                    r.fans[k].push_back({{a[0], a[1], a[2], p[0], p[1], p[2], q[0], q[1], q[2]}, unit_normal(t)});
                }
            });
        }
    } catch (const Contradiction&) {
        throw std::invalid_argument("a body's surface crosses itself or is not closed (windings disagree along an edge)");
    }
    return r;
}

}  // namespace polyvol::boolean
