// The volume formulas other than the cone rule (prism, pyramid, vtnb), the fan
// area and the welded edge length (src/measure/methods.hpp): closed-form
// fixtures, invariants (translation by powers of two, reflection, quads vs
// their fans), agreement between the methods on random closed meshes, the
// certified error bounds against exact references (GMP), and the corpus.
#include <gtest/gtest.h>

#include <gmpxx.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "measure/methods.hpp"
#include "polyvol/measure.hpp"
#include "common/manifest.hpp"
#include "common/shapes.hpp"
#include "cone_fixtures.hpp"
#include "polyvol/io.hpp"
#include "polyvol/mesh.hpp"

namespace {

using polyvol::Mesh;
using polyvol::MeshView;
using polyvol::measure::SumWithBound;
using polyvol::measure::VtnbResult;

constexpr int kPrec = 512;  // bits of the mpf references

// ---- meshes -------------------------------------------------------------

using polyvol::fixtures::box;
using polyvol::test::unit_tetrahedron;

// Every polygon replaced by its fan (v0, vi, vi+1), explicitly.
Mesh explicit_fan(const Mesh& in) {
    Mesh m;
    m.positions = in.positions;
    const MeshView v = in.view();
    for (std::size_t f = 0; f < v.face_count(); ++f) {
        const auto face = v.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i) m.add_triangle(face[0], face[i], face[i + 1]);
    }
    return m;
}

Mesh translated(const Mesh& in, double dx, double dy, double dz) {
    Mesh m = in;
    for (std::size_t i = 0; i < m.positions.size(); i += 3) {
        m.positions[i] += dx;
        m.positions[i + 1] += dy;
        m.positions[i + 2] += dz;
    }
    return m;
}

Mesh reflected(const Mesh& in, int axis) {
    Mesh m = in;
    for (std::size_t i = static_cast<std::size_t>(axis); i < m.positions.size(); i += 3)
        m.positions[i] = -m.positions[i];
    return m;
}

// A closed triangle mesh: the octahedron with each face cut into k² triangles,
// its vertices pushed to radius 1 ± amp (random per vertex: the mesh stays
// closed by construction), optionally rounded to multiples of quantum.
Mesh octasphere(int k, uint64_t seed, double amp, double quantum = 0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    Mesh m;
    std::map<std::array<int, 3>, uint32_t> ids;
    auto vertex = [&](const std::array<int, 3>& l) {
        const auto it = ids.find(l);
        if (it != ids.end()) return it->second;
        const double x = l[0], y = l[1], z = l[2];
        const double s = (1 + amp * uni(rng)) / std::sqrt(x * x + y * y + z * z);
        double p[3] = {x * s, y * s, z * s};
        if (quantum > 0)
            for (double& c : p) c = std::round(c / quantum) * quantum;
        const uint32_t id = m.add_vertex(p[0], p[1], p[2]);
        ids.emplace(l, id);
        return id;
    };
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int sz : {-1, 1}) {
                std::array<int, 3> A{sx * k, 0, 0}, B{0, sy * k, 0}, C{0, 0, sz * k};
                if (sx * sy * sz < 0) std::swap(B, C);
                auto P = [&](int a, int b) {
                    std::array<int, 3> l{};
                    for (int j = 0; j < 3; ++j) l[j] = A[j] + a * (B[j] - A[j]) / k + b * (C[j] - A[j]) / k;
                    return vertex(l);
                };
                for (int a = 0; a < k; ++a)
                    for (int b = 0; a + b < k; ++b) {
                        m.add_triangle(P(a, b), P(a + 1, b), P(a, b + 1));
                        if (a + b + 1 < k) m.add_triangle(P(a + 1, b), P(a + 1, b + 1), P(a, b + 1));
                    }
            }
    return m;
}

// ---- references ---------------------------------------------------------

using Vec = std::array<double, 3>;
Vec vert(const MeshView& m, uint32_t i) {
    return {m.positions[3 * std::size_t{i}], m.positions[3 * std::size_t{i} + 1],
            m.positions[3 * std::size_t{i} + 2]};
}

template <class F>
void for_each_fan_triangle(const MeshView& m, F f) {
    for (std::size_t i = 0; i < m.face_count(); ++i) {
        const auto face = m.face(i);
        for (std::size_t j = 1; j + 1 < face.size(); ++j)
            f(vert(m, face[0]), vert(m, face[j]), vert(m, face[j + 1]));
    }
}

// Exact cone rule Σ det(a,b,c)/6 (doubles convert to mpq exactly).
mpq_class exact_volume(const MeshView& m) {
    mpq_class sum = 0;
    for_each_fan_triangle(m, [&](const Vec& a, const Vec& b, const Vec& c) {
        const mpq_class ax = a[0], ay = a[1], az = a[2], bx = b[0], by = b[1], bz = b[2];
        const mpq_class cx = c[0], cy = c[1], cz = c[2];
        sum += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    });
    return sum / 6;
}

// Plain double cone rule, the simplest independent cross-check.
double cone_double(const MeshView& m) {
    double sum = 0;
    for_each_fan_triangle(m, [&](const Vec& a, const Vec& b, const Vec& c) {
        sum += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    });
    return sum / 6;
}

// Fan area to kPrec bits: sqrt of the exact |(b-a)×(c-a)|².
mpf_class exact_area(const MeshView& m) {
    mpf_class sum(0, kPrec);
    for_each_fan_triangle(m, [&](const Vec& a, const Vec& b, const Vec& c) {
        mpq_class d1[3], d2[3];
        for (int j = 0; j < 3; ++j) {
            d1[j] = mpq_class(b[j]) - mpq_class(a[j]);
            d2[j] = mpq_class(c[j]) - mpq_class(a[j]);
        }
        const mpq_class nx = d1[1] * d2[2] - d1[2] * d2[1], ny = d1[2] * d2[0] - d1[0] * d2[2],
                        nz = d1[0] * d2[1] - d1[1] * d2[0];
        const mpf_class n2(nx * nx + ny * ny + nz * nz, kPrec);
        sum += sqrt(n2) / 2;
    });
    return sum;
}

// Undirected polygon edges between distinct points, each once (coordinates
// compared as values: -0.0 == +0.0), to kPrec bits. Independent of weld_vertices.
mpf_class exact_edge_length(const MeshView& m) {
    auto key = [&](uint32_t i) {
        Vec p = vert(m, i);
        for (double& c : p) c += 0.0;  // -0.0 -> +0.0
        return p;
    };
    std::set<std::pair<Vec, Vec>> edges;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = m.face(f);
        if (face.size() < 3) continue;
        for (std::size_t j = 0; j < face.size(); ++j) {
            Vec a = key(face[j]), b = key(face[(j + 1) % face.size()]);
            if (a == b) continue;
            if (b < a) std::swap(a, b);
            edges.emplace(a, b);
        }
    }
    mpf_class sum(0, kPrec);
    for (const auto& [a, b] : edges) {
        mpq_class l2 = 0;
        for (int j = 0; j < 3; ++j) {
            const mpq_class d = mpq_class(b[j]) - mpq_class(a[j]);
            l2 += d * d;
        }
        sum += sqrt(mpf_class(l2, kPrec));
    }
    return sum;
}

// |s.value - exact| <= s.error_bound, exactly.
testing::AssertionResult within(const SumWithBound& s, const mpq_class& exact) {
    if (!std::isfinite(s.value) || !std::isfinite(s.error_bound))
        return testing::AssertionFailure() << "value " << s.value << " bound " << s.error_bound;
    const mpq_class err = abs(mpq_class(s.value) - exact);
    if (err <= mpq_class(s.error_bound)) return testing::AssertionSuccess();
    return testing::AssertionFailure() << "value " << s.value << " exact " << exact.get_d() << " error "
                                       << err.get_d() << " > bound " << s.error_bound;
}
// The same against a kPrec-bit reference (its own error, ~2^-500 relative, is
// far below any bound here).
testing::AssertionResult within(const SumWithBound& s, const mpf_class& ref) {
    if (!std::isfinite(s.value) || !std::isfinite(s.error_bound))
        return testing::AssertionFailure() << "value " << s.value << " bound " << s.error_bound;
    const mpf_class err = abs(mpf_class(s.value, kPrec) - ref);
    if (err <= mpf_class(s.error_bound, kPrec)) return testing::AssertionSuccess();
    return testing::AssertionFailure() << "value " << s.value << " ref " << ref.get_d() << " error "
                                       << err.get_d() << " > bound " << s.error_bound;
}
testing::AssertionResult within(const SumWithBound& s, double exact) { return within(s, mpq_class(exact)); }

// Two results of the same exact quantity agree within the sum of their bounds.
testing::AssertionResult agree(const SumWithBound& a, const SumWithBound& b) {
    const double d = std::fabs(a.value - b.value);
    if (d <= (a.error_bound + b.error_bound) * (1 + 0x1p-50)) return testing::AssertionSuccess();
    return testing::AssertionFailure() << a.value << " vs " << b.value << ": " << d << " > "
                                       << a.error_bound << " + " << b.error_bound;
}

struct All {
    SumWithBound prism, pyramid;
    VtnbResult vtnb;
    SumWithBound area, length;
};
All measure_all(const Mesh& m) {
    const MeshView v = m.view();
    return {polyvol::measure::prism_volume(v), polyvol::measure::pyramid_volume(v),
            polyvol::measure::vtnb_measures(v), polyvol::measure::fan_area(v),
            polyvol::measure::welded_edge_length(v)};
}

// ---- closed-form fixtures -------------------------------------------------

TEST(Methods, Box2x3x5IsFranklinsCheck) {
    // Franklin's check: a 2x3x5 box has volume 30, area 62, edge length 40.
    for (bool quads : {true, false}) {
        for (const Mesh& m : {box(0, 0, 0, 2, 3, 5, quads), box(-7, 1, 0.5, -5, 4, 5.5, quads)}) {
            SCOPED_TRACE(quads ? "quads" : "triangles");
            const All r = measure_all(m);
            EXPECT_TRUE(within(r.prism, 30.0));
            EXPECT_TRUE(within(r.pyramid, 30.0));
            EXPECT_TRUE(within(r.vtnb.volume, 30.0));
            EXPECT_TRUE(within(r.vtnb.area, 62.0));
            EXPECT_TRUE(within(r.area, 62.0));
            if (quads) {
                EXPECT_TRUE(within(r.vtnb.length, 40.0));
                EXPECT_TRUE(within(r.length, 40.0));
            } else {
                // The fan diagonals are edges of the triangle mesh.
                const mpf_class l = 40 + 2 * (sqrt(mpf_class(13, kPrec)) + sqrt(mpf_class(29, kPrec)) +
                                              sqrt(mpf_class(34, kPrec)));
                EXPECT_TRUE(within(r.vtnb.length, l));
                EXPECT_TRUE(within(r.length, l));
            }
            for (const SumWithBound* s : {&r.prism, &r.pyramid, &r.vtnb.volume, &r.vtnb.area,
                                          &r.vtnb.length, &r.area, &r.length})
                EXPECT_LT(s->error_bound, 1e-12 * std::fabs(s->value));
        }
    }
}

TEST(Methods, UnitCube) {
    const All r = measure_all(box(0, 0, 0, 1, 1, 1, true));
    EXPECT_TRUE(within(r.prism, 1.0));
    EXPECT_TRUE(within(r.pyramid, 1.0));
    EXPECT_TRUE(within(r.vtnb.volume, 1.0));
    EXPECT_TRUE(within(r.vtnb.area, 6.0));
    EXPECT_TRUE(within(r.vtnb.length, 12.0));
    EXPECT_TRUE(within(r.area, 6.0));
    EXPECT_TRUE(within(r.length, 12.0));
}

TEST(Methods, UnitTetrahedron) {
    const All r = measure_all(unit_tetrahedron());
    const mpq_class v(1, 6);
    const mpf_class a = (3 + sqrt(mpf_class(3, kPrec))) / 2;
    const mpf_class l = 3 + 3 * sqrt(mpf_class(2, kPrec));
    EXPECT_TRUE(within(r.prism, v));
    EXPECT_TRUE(within(r.pyramid, v));
    EXPECT_TRUE(within(r.vtnb.volume, v));
    EXPECT_TRUE(within(r.vtnb.area, a));
    EXPECT_TRUE(within(r.area, a));
    EXPECT_TRUE(within(r.vtnb.length, l));
    EXPECT_TRUE(within(r.length, l));
}

TEST(Methods, InsideOutIsNegative) {
    // Reversing every face negates the volumes (outward orientation gives +).
    Mesh m = box(0, 0, 0, 2, 3, 5, true);
    for (std::size_t f = 0; f + 1 < m.face_offsets.size(); ++f)
        std::reverse(m.indices.begin() + m.face_offsets[f], m.indices.begin() + m.face_offsets[f + 1]);
    const All r = measure_all(m);
    EXPECT_TRUE(within(r.prism, -30.0));
    EXPECT_TRUE(within(r.pyramid, -30.0));
    EXPECT_TRUE(within(r.vtnb.volume, -30.0));
    EXPECT_TRUE(within(r.vtnb.area, 62.0));
    EXPECT_TRUE(within(r.vtnb.length, 40.0));
}

TEST(Methods, QuadBoxEqualsTriangulatedBox) {
    const All q = measure_all(box(-1.25, 0.5, 3, 0.75, 3.5, 8, true));
    const All t = measure_all(box(-1.25, 0.5, 3, 0.75, 3.5, 8, false));
    EXPECT_TRUE(agree(q.prism, t.prism));
    EXPECT_TRUE(agree(q.pyramid, t.pyramid));
    EXPECT_TRUE(agree(q.vtnb.volume, t.vtnb.volume));
    EXPECT_TRUE(agree(q.vtnb.area, t.vtnb.area));
    EXPECT_TRUE(agree(q.area, t.area));
    // LENGTH runs over the polygon's own edges: the fan diagonals of the quads
    // do not cancel (both fan triangles add +|diagonal|/2), they are simply not
    // edges of the quad mesh.
    const double diagonals = 2 * (std::sqrt(13.0) + std::sqrt(29.0) + std::sqrt(34.0));
    EXPECT_NEAR(t.vtnb.length.value - q.vtnb.length.value, diagonals, 1e-12);
    EXPECT_NEAR(t.length.value - q.length.value, diagonals, 1e-12);
    EXPECT_TRUE(within(q.vtnb.length, 40.0));
}

// An L-shaped prism of height h whose caps are a concave hexagon (area 3),
// written so that the caps' fans have a negative triangle.
Mesh l_prism(double h) {
    const double xy[6][2] = {{2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}};  // counter-clockwise
    Mesh m;
    for (const auto& p : xy) m.add_vertex(p[0], p[1], 0);
    for (const auto& p : xy) m.add_vertex(p[0], p[1], h);
    const std::vector<uint32_t> top = {6, 7, 8, 9, 10, 11};
    const std::vector<uint32_t> bottom = {0, 5, 4, 3, 2, 1};  // reversed, same first vertex
    m.add_face(top);
    m.add_face(bottom);
    for (uint32_t i = 0; i < 6; ++i) {
        const uint32_t j = (i + 1) % 6;
        const std::vector<uint32_t> side = {i, j, j + 6, i + 6};
        m.add_face(side);
    }
    return m;
}

TEST(Methods, ConcaveLPrism) {
    const double h = 1.5;
    const Mesh m = l_prism(h);
    const All r = measure_all(m);
    // Volume: cap area 3 times h. Area: the fans of the caps, from (2,1), are
    // triangles of areas -1/2, 1/2, 2, 1 — 4 each in absolute value — plus the
    // sides (perimeter 8 times h). Edges: 2 * 8 + 6 h.
    EXPECT_TRUE(within(r.prism, 3 * h));
    EXPECT_TRUE(within(r.pyramid, 3 * h));
    EXPECT_TRUE(within(r.vtnb.volume, 3 * h));
    EXPECT_TRUE(within(r.area, 8 * h + 8));
    EXPECT_TRUE(within(r.vtnb.area, 8 * h + 8));
    EXPECT_TRUE(within(r.length, 16 + 6 * h));
    EXPECT_TRUE(within(r.vtnb.length, 16 + 6 * h));
}

TEST(Methods, NonPlanarQuadMeansItsFan) {
    // Lift the corner (1,1,1) of a unit cube: three quads become non-planar.
    Mesh quads = box(0, 0, 0, 1, 1, 1, true);
    quads.positions[3 * 7 + 2] = 1.25;
    const Mesh fan = explicit_fan(quads);
    const mpq_class v = exact_volume(fan.view());
    const All q = measure_all(quads);
    const All t = measure_all(fan);
    for (const SumWithBound* s : {&q.prism, &q.pyramid, &q.vtnb.volume, &t.prism, &t.pyramid, &t.vtnb.volume})
        EXPECT_TRUE(within(*s, v));
    const mpf_class a = exact_area(fan.view());
    EXPECT_TRUE(within(q.area, a));
    EXPECT_TRUE(within(q.vtnb.area, a));
    EXPECT_TRUE(within(t.vtnb.area, a));
    // Starting the lifted top quad at another vertex is another fan, another solid.
    Mesh rotated = quads;
    std::rotate(rotated.indices.begin() + rotated.face_offsets[1],
                rotated.indices.begin() + rotated.face_offsets[1] + 1,
                rotated.indices.begin() + rotated.face_offsets[2]);
    const mpq_class v2 = exact_volume(explicit_fan(rotated).view());
    EXPECT_NE(v, v2);
    EXPECT_TRUE(within(polyvol::measure::pyramid_volume(rotated.view()), v2));
    EXPECT_TRUE(within(polyvol::measure::vtnb_measures(rotated.view()).volume, v2));
}

// ---- invariants -------------------------------------------------------------

TEST(Methods, TranslationByPowersOfTwo) {
    const Mesh m = octasphere(6, 7, 0.2, 0x1p-24);
    const mpq_class v = exact_volume(m.view());
    const All r0 = measure_all(m);
    for (const auto& d : std::vector<Vec>{{0x1p20, -0x1p21, 0x1p22}, {-0x1p10, 0, 0x1p5}, {0, 0, -0x1p26}}) {
        const Mesh t = translated(m, d[0], d[1], d[2]);
        for (std::size_t i = 0; i < m.positions.size(); ++i)
            ASSERT_EQ(t.positions[i] - d[i % 3], m.positions[i]) << "translation not exact";
        const All r = measure_all(t);
        EXPECT_TRUE(agree(r.prism, r0.prism));
        EXPECT_TRUE(agree(r.pyramid, r0.pyramid));
        EXPECT_TRUE(agree(r.vtnb.volume, r0.vtnb.volume));
        EXPECT_TRUE(agree(r.vtnb.area, r0.vtnb.area));
        EXPECT_TRUE(agree(r.vtnb.length, r0.vtnb.length));
        EXPECT_TRUE(within(r.prism, v));
        EXPECT_TRUE(within(r.pyramid, v));
        EXPECT_TRUE(within(r.vtnb.volume, v));
        // The local origin keeps the vtnb bound at the scale of the mesh.
        EXPECT_LT(r.vtnb.volume.error_bound, 1e-10);
    }
}

TEST(Methods, ReflectionNegatesVolume) {
    const Mesh m = translated(octasphere(5, 3, 0.25), 0.375, -2.5, 1.75);
    const All r0 = measure_all(m);
    for (int axis = 0; axis < 3; ++axis) {
        SCOPED_TRACE(axis);
        const All r = measure_all(reflected(m, axis));
        // Each kernel's arithmetic is symmetric under x -> -x, so the values
        // are negated exactly and the bounds are unchanged.
        EXPECT_EQ(r.prism.value, -r0.prism.value);
        EXPECT_EQ(r.pyramid.value, -r0.pyramid.value);
        EXPECT_EQ(r.vtnb.volume.value, -r0.vtnb.volume.value);
        EXPECT_EQ(r.vtnb.area.value, r0.vtnb.area.value);
        EXPECT_EQ(r.vtnb.length.value, r0.vtnb.length.value);
        EXPECT_EQ(r.area.value, r0.area.value);
        EXPECT_EQ(r.length.value, r0.length.value);
        EXPECT_EQ(r.vtnb.volume.error_bound, r0.vtnb.volume.error_bound);
    }
}

TEST(Methods, RandomClosedMeshesAgree) {
    struct Case {
        int k;
        uint64_t seed;
        double amp, scale;
        Vec shift;
    };
    const std::vector<Case> cases = {
        {3, 1, 0.1, 1, {0, 0, 0}},           {8, 2, 0.3, 1, {0.1, 0.2, -0.3}},
        {12, 3, 0.45, 1e-3, {5e-3, 0, 0}},   {16, 4, 0.2, 1e4, {3e4, -1e4, 2e4}},
        {20, 5, 0.35, 0.5, {100, 200, 300}}, {10, 6, 0.5, 1e-100, {0, 1e-100, 0}},
        {10, 7, 0.5, 1e100, {0, 0, 1e100}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.seed);
        Mesh m = octasphere(c.k, c.seed, c.amp);
        for (std::size_t i = 0; i < m.positions.size(); ++i)
            m.positions[i] = m.positions[i] * c.scale + c.shift[i % 3];
        const mpq_class v = exact_volume(m.view());
        const mpf_class a = exact_area(m.view());
        const mpf_class l = exact_edge_length(m.view());
        const All r = measure_all(m);
        const double vd = v.get_d();
        const double cone = cone_double(m.view());
        // The plain cone rule is accurate only near the origin.
        const double far = std::max({std::fabs(c.shift[0]), std::fabs(c.shift[1]), std::fabs(c.shift[2])});
        const bool near_origin = far <= 2 * c.scale;
        for (const SumWithBound* s : {&r.prism, &r.pyramid, &r.vtnb.volume}) {
            EXPECT_TRUE(within(*s, v));
            if (near_origin) {
                EXPECT_NEAR(s->value, cone, 1e-12 * std::fabs(vd));
            }
            EXPECT_NEAR(s->value, r.prism.value, 1e-12 * std::fabs(vd));
            EXPECT_LT(s->error_bound, 1e-9 * std::fabs(vd));  // certified and still useful
        }
        EXPECT_TRUE(within(r.area, a));
        EXPECT_TRUE(within(r.vtnb.area, a));
        EXPECT_TRUE(within(r.length, l));
        EXPECT_TRUE(within(r.vtnb.length, l));
        EXPECT_NEAR(r.vtnb.area.value, r.area.value, 1e-12 * r.area.value);
        EXPECT_NEAR(r.vtnb.length.value, r.length.value, 1e-12 * r.length.value);
        EXPECT_LT(r.area.error_bound, 1e-12 * r.area.value);
        EXPECT_LT(r.length.error_bound, 1e-12 * r.length.value);
    }
}

TEST(Methods, FlatClosedMeshStaysWithinBounds) {
    // Every triangle nearly degenerate, volume tiny against |V|^3: the bounds
    // grow (the frame bound gives way to the fallback) but still hold.
    Mesh m = octasphere(10, 9, 0.3);
    for (std::size_t i = 2; i < m.positions.size(); i += 3) m.positions[i] *= 1e-9;
    m = translated(m, 0.5, 0.25, 1e-9);
    const mpq_class v = exact_volume(m.view());
    const All r = measure_all(m);
    EXPECT_TRUE(within(r.prism, v));
    EXPECT_TRUE(within(r.pyramid, v));
    EXPECT_TRUE(within(r.vtnb.volume, v));
    const mpf_class a = exact_area(m.view());
    EXPECT_TRUE(within(r.area, a));
    EXPECT_TRUE(within(r.vtnb.area, a));
    const mpf_class l = exact_edge_length(m.view());
    EXPECT_TRUE(within(r.length, l));
    EXPECT_TRUE(within(r.vtnb.length, l));
}

TEST(Methods, TriangleSoupWeldsSignedZeros) {
    // A box as an STL-like soup (every triangle with its own vertices), with
    // -0.0 in some copies of the coordinates: welding merges them.
    const Mesh b = box(0, 0, 0, 2, 3, 5, false);
    Mesh soup;
    int copy = 0;
    for (std::size_t f = 0; f < b.face_count(); ++f) {
        uint32_t t[3];
        for (int j = 0; j < 3; ++j) {
            Vec p = vert(b.view(), b.indices[3 * f + static_cast<std::size_t>(j)]);
            for (double& c : p)
                if (c == 0 && (++copy % 2)) c = -0.0;
            t[j] = soup.add_vertex(p[0], p[1], p[2]);
        }
        soup.add_triangle(t[0], t[1], t[2]);
    }
    const All r = measure_all(soup);
    const mpf_class l = 40 + 2 * (sqrt(mpf_class(13, kPrec)) + sqrt(mpf_class(29, kPrec)) +
                                  sqrt(mpf_class(34, kPrec)));
    EXPECT_TRUE(within(r.length, l));
    EXPECT_TRUE(within(r.vtnb.length, l));
    EXPECT_TRUE(within(r.vtnb.volume, 30.0));
    EXPECT_TRUE(within(r.prism, 30.0));
}

TEST(Methods, DegenerateTrianglesContributeNothing) {
    // A closed box plus zero-area triangles that keep it a 2-cycle: a
    // collinear triangle and its reverse, a triangle with a repeated vertex and
    // its reverse, and a sliver (not exactly degenerate) and its reverse.
    Mesh m = box(0, 0, 0, 2, 3, 5, false);
    const uint32_t a = m.add_vertex(0.25, 0.5, 1), b = m.add_vertex(0.5, 1, 2), c = m.add_vertex(1, 2, 4);
    const uint32_t s = m.add_vertex(0.5, 1 + 0x1p-50, 2);
    for (const auto& t : std::vector<std::array<uint32_t, 3>>{{a, b, c}, {a, c, b}, {a, a, b}, {a, b, a},
                                                               {a, s, c}, {a, c, s}})
        m.add_triangle(t[0], t[1], t[2]);
    const All r = measure_all(m);
    EXPECT_TRUE(within(r.prism, 30.0));
    EXPECT_TRUE(within(r.pyramid, 30.0));
    EXPECT_TRUE(within(r.vtnb.volume, 30.0));
    const mpf_class area = exact_area(m.view());
    EXPECT_TRUE(within(r.vtnb.area, area));
    EXPECT_TRUE(within(r.area, area));
}

TEST(Methods, ShortFacesAreIgnored) {
    Mesh m = box(0, 0, 0, 2, 3, 5, true);
    const std::vector<uint32_t> two = {0, 7}, one = {3}, none = {};
    m.add_face(two);
    m.add_face(one);
    m.add_face(none);
    const All r = measure_all(m);
    EXPECT_TRUE(within(r.prism, 30.0));
    EXPECT_TRUE(within(r.vtnb.volume, 30.0));
    EXPECT_TRUE(within(r.vtnb.length, 40.0));
    EXPECT_TRUE(within(r.length, 40.0));
    EXPECT_TRUE(within(r.area, 62.0));
}

TEST(Methods, EmptyMeshIsZero) {
    const Mesh m;
    const All r = measure_all(m);
    for (const SumWithBound* s : {&r.prism, &r.pyramid, &r.vtnb.volume, &r.vtnb.area, &r.vtnb.length,
                                  &r.area, &r.length}) {
        EXPECT_EQ(s->value, 0.0);
        EXPECT_GE(s->error_bound, 0.0);
        EXPECT_LT(s->error_bound, 1e-300);
    }
}

TEST(Methods, NonFiniteCoordinatesGiveNoGuarantee) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        Mesh m = box(0, 0, 0, 2, 3, 5, true);
        m.positions[3 * 6 + 1] = bad;
        const All r = measure_all(m);
        for (const SumWithBound* s : {&r.prism, &r.pyramid, &r.vtnb.volume, &r.vtnb.area, &r.vtnb.length,
                                      &r.area, &r.length})
            EXPECT_EQ(s->error_bound, std::numeric_limits<double>::infinity()) << s->value;
    }
}

TEST(Methods, SameBitsForAnyNumberOfThreads) {
    const Mesh m = translated(octasphere(40, 11, 0.3), 1.0 / 3, 0.1, -0.7);  // 12800 triangles
    const All many = measure_all(m);
    All one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = measure_all(m);
    }
    auto same = [](const SumWithBound& x, const SumWithBound& y) {
        return x.value == y.value && x.error_bound == y.error_bound;
    };
    EXPECT_TRUE(same(many.prism, one.prism));
    EXPECT_TRUE(same(many.pyramid, one.pyramid));
    EXPECT_TRUE(same(many.vtnb.volume, one.vtnb.volume));
    EXPECT_TRUE(same(many.vtnb.area, one.vtnb.area));
    EXPECT_TRUE(same(many.vtnb.length, one.vtnb.length));
    EXPECT_TRUE(same(many.area, one.area));
    EXPECT_TRUE(same(many.length, one.length));
}

// ---- the shared corpus ------------------------------------------------------

using polyvol::test::corpus_manifest;

// The larger spacing of doubles around x (>= the error of a correctly
// rounded reference).
double ulp(double x) {
    const double inf = std::numeric_limits<double>::infinity();
    return std::max(std::nextafter(x, inf) - x, x - std::nextafter(x, -inf));
}

// For every closed 2-cycle of the corpus: the three volume methods against
// volume.double, the areas against surface_area.double, the edge lengths
// against edge_length.double — to 1e-12 relative (the volume relative to
// max(|V|, 1e-3 · largest bbox extent³)), and within the certified bounds
// (plus the reference's own rounding). 3MF files with transforms are held to
// 1e-12 only: the reference applies transforms exactly, a reader in doubles.
TEST(Methods, CorpusClosedMeshes) {
    if (corpus_manifest().empty()) GTEST_SKIP() << "no manifest at " << polyvol::test::corpus_dir();
    int checked = 0;
    double worst_volume[3] = {0, 0, 0}, worst_area = 0, worst_length = 0;
    double largest_bound[3] = {0, 0, 0};  // error_bound / scale
    std::string worst_volume_file[3];
    for (const nlohmann::json& e : corpus_manifest()) {
        if (e.value("category", "") == "invalid" || !e.value("exact", false)) continue;
        if (!e.contains("topology") || !e["topology"].value("closed_2_cycle", false)) continue;
        const std::string rel = e.at("path");
        SCOPED_TRACE(rel);
        polyvol::LoadedMesh lm;
        try {
            lm = polyvol::read_mesh_file(polyvol::test::corpus_file(rel));
        } catch (const std::exception& ex) {
            ADD_FAILURE() << "cannot read: " << ex.what();
            continue;
        }
        ++checked;
        bool transformed = false;
        for (const auto& q : e.value("quirks", nlohmann::json::array())) {
            const std::string quirk = q.get<std::string>();
            if (quirk == "3mf-transform" || quirk == "3mf-components") transformed = true;
        }
        const All r = measure_all(lm.mesh);

        const double v_ref = e["volume"]["double"];
        double extent = 0;
        if (e.contains("bbox")) {
            const nlohmann::json& box = e["bbox"];
            for (int j = 0; j < 3; ++j)
                extent = std::max(extent, box["max"][j].get<double>() - box["min"][j].get<double>());
        }
        const double v_scale = std::max(std::fabs(v_ref), 1e-3 * extent * extent * extent);
        const SumWithBound* volumes[3] = {&r.prism, &r.pyramid, &r.vtnb.volume};
        for (int method = 0; method < 3; ++method) {
            const SumWithBound* s = volumes[method];
            const double d = std::fabs(s->value - v_ref);
            EXPECT_LE(d, 1e-12 * v_scale) << s->value << " vs " << v_ref;
            if (!transformed) {
                EXPECT_LE(d, s->error_bound + ulp(v_ref)) << "bound " << s->error_bound;
            }
            if (v_scale > 0) {
                largest_bound[method] = std::max(largest_bound[method], s->error_bound / v_scale);
                if (d / v_scale > worst_volume[method]) {
                    worst_volume[method] = d / v_scale;
                    worst_volume_file[method] = rel;
                }
            }
        }
        const double a_ref = e["surface_area"]["double"];
        for (const SumWithBound* s : {&r.area, &r.vtnb.area}) {
            const double d = std::fabs(s->value - a_ref);
            EXPECT_LE(d, 1e-12 * a_ref) << s->value << " vs " << a_ref;
            if (!transformed) {
                EXPECT_LE(d, s->error_bound + ulp(a_ref)) << "bound " << s->error_bound;
            }
            if (a_ref > 0) worst_area = std::max(worst_area, d / a_ref);
        }
        const double l_ref = e["edge_length"]["double"];
        std::vector<const SumWithBound*> lengths = {&r.length};
        // LENGTH counts every edge once when each is used by exactly two faces.
        if (e["topology"].value("closed", false) && e["topology"].value("edge_manifold", false))
            lengths.push_back(&r.vtnb.length);
        for (const SumWithBound* s : lengths) {
            const double d = std::fabs(s->value - l_ref);
            EXPECT_LE(d, 1e-12 * l_ref) << s->value << " vs " << l_ref;
            if (!transformed) {
                EXPECT_LE(d, s->error_bound + ulp(l_ref)) << "bound " << s->error_bound;
            }
            if (l_ref > 0) worst_length = std::max(worst_length, d / l_ref);
        }
    }
    EXPECT_GT(checked, 50);
    std::printf("[corpus] %d closed meshes; largest relative disagreement with the manifest:\n"
                "  volume  prism %.3g (%s)\n          pyramid %.3g (%s)\n          vtnb %.3g (%s)\n"
                "  area %.3g, edge length %.3g\n"
                "  largest volume bound / scale: prism %.3g, pyramid %.3g, vtnb %.3g\n",
                checked, worst_volume[0], worst_volume_file[0].c_str(), worst_volume[1],
                worst_volume_file[1].c_str(), worst_volume[2], worst_volume_file[2].c_str(), worst_area,
                worst_length, largest_bound[0], largest_bound[1], largest_bound[2]);
}

// ---- correctly rounded prism and pyramid (polyvol/measure.hpp) ----------------

// The nearest double to q, ties to even, independently of the library:
// mpq's get_d truncates, so the nearest is it or a neighbour.
double nearest_double(const mpq_class& q) {
    const double t = q.get_d();
    double best = t;
    mpq_class best_d = abs(mpq_class(t) - q);
    for (double c : {std::nextafter(t, -INFINITY), std::nextafter(t, INFINITY)}) {
        const mpq_class d = abs(mpq_class(c) - q);
        if (d < best_d || (d == best_d && (std::bit_cast<uint64_t>(c) & 1) == 0)) {
            best = c;
            best_d = d;
        }
    }
    return best + 0.0;  // an exact zero is +0.0
}

// The prism rule exactly: Σ (z_a + z_b + z_c) ((b - a) × (c - a))_z / 6.
mpq_class exact_prism(const MeshView& m) {
    mpq_class sum = 0;
    for_each_fan_triangle(m, [&](const Vec& a, const Vec& b, const Vec& c) {
        const mpq_class ux = mpq_class(b[0]) - a[0], uy = mpq_class(b[1]) - a[1];
        const mpq_class wx = mpq_class(c[0]) - a[0], wy = mpq_class(c[1]) - a[1];
        sum += (mpq_class(a[2]) + b[2] + c[2]) * (ux * wy - uy * wx);
    });
    return sum / 6;
}

// Franklin's pyramids exactly: Σ_faces v0 · Σ_i (v_i - v0) × (v_i+1 - v0) / 6.
mpq_class exact_pyramid(const MeshView& m) {
    mpq_class sum = 0;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = m.face(f);
        if (face.size() < 3) continue;
        const Vec v0 = vert(m, face[0]);
        mpq_class area[3] = {0, 0, 0};  // 2 × the fan's vector area
        for (std::size_t i = 1; i + 1 < face.size(); ++i) {
            const Vec p = vert(m, face[i]), q = vert(m, face[i + 1]);
            mpq_class d[3], e[3];
            for (int k = 0; k < 3; ++k) {
                d[k] = mpq_class(p[k]) - v0[k];
                e[k] = mpq_class(q[k]) - v0[k];
            }
            area[0] += d[1] * e[2] - d[2] * e[1];
            area[1] += d[2] * e[0] - d[0] * e[2];
            area[2] += d[0] * e[1] - d[1] * e[0];
        }
        sum += mpq_class(v0[0]) * area[0] + mpq_class(v0[1]) * area[1] + mpq_class(v0[2]) * area[2];
    }
    return sum / 6;
}

double cr(const MeshView& m, polyvol::Method method) {
    return polyvol::signed_volume(m, method, polyvol::Accuracy::correctly_rounded);
}

uint64_t bits(double x) { return std::bit_cast<uint64_t>(x); }

// m's faces appended to into (reversed when flip).
void append(Mesh& into, const Mesh& m, bool flip) {
    const auto base = static_cast<uint32_t>(into.positions.size() / 3);
    into.positions.insert(into.positions.end(), m.positions.begin(), m.positions.end());
    const MeshView v = m.view();
    for (std::size_t f = 0; f < v.face_count(); ++f) {
        std::vector<uint32_t> face(v.face(f).begin(), v.face(f).end());
        for (uint32_t& i : face) i += base;
        if (flip) std::reverse(face.begin(), face.end());
        into.add_face(face);
    }
}

// An open surface: the octasphere without its first faces.
Mesh opened(const Mesh& in, std::size_t drop) {
    Mesh m;
    m.positions = in.positions;
    const MeshView v = in.view();
    for (std::size_t f = drop; f < v.face_count(); ++f) {
        const auto face = v.face(f);
        m.add_triangle(face[0], face[1], face[2]);
    }
    return m;
}

TEST(Methods, PrismAndPyramidAreCorrectlyRoundedOnEveryClosedCorpusMesh) {
    if (corpus_manifest().empty()) GTEST_SKIP() << "no manifest at " << polyvol::test::corpus_dir();
    int checked = 0;
    for (const nlohmann::json& e : corpus_manifest()) {
        if (e.value("category", "") == "invalid" || !e.value("exact", false)) continue;
        if (!e.contains("topology") || !e["topology"].value("closed_2_cycle", false)) continue;
        bool transformed = false;  // the manifest transforms in rationals (see CorpusClosedMeshes)
        for (const auto& q : e.value("quirks", nlohmann::json::array()))
            transformed = transformed || q.get<std::string>().rfind("3mf-", 0) == 0;
        if (transformed) continue;
        const std::string rel = e.at("path");
        SCOPED_TRACE(rel);
        const polyvol::LoadedMesh lm = polyvol::read_mesh_file(polyvol::test::corpus_file(rel));
        const double want = polyvol::test::corpus_reference(e["volume"]);
        EXPECT_EQ(bits(cr(lm.mesh.view(), polyvol::Method::prism)), bits(want));
        EXPECT_EQ(bits(cr(lm.mesh.view(), polyvol::Method::pyramid)), bits(want));
        const polyvol::MassProperties p = polyvol::mass_properties(lm.mesh.view(), {.method = polyvol::Method::prism});
        EXPECT_TRUE(p.volume_correctly_rounded);
        EXPECT_EQ(bits(p.volume), bits(want));
        ++checked;
    }
    EXPECT_GT(checked, 50);
}

TEST(Methods, PrismIsCorrectlyRoundedOnOpenSurfacesFarFromTheOrigin) {
    // Open surfaces (the prism sum then differs from the cone sum), near the
    // origin and shifted in z by 1e6 and 1e8 (each coordinate rounded to a
    // double): against the exact sum rounded once.
    int differs_from_cone = 0;
    for (uint64_t seed : {1u, 2u, 3u})
        for (double dz : {0.0, 1e6, 1e8}) {
            SCOPED_TRACE(testing::Message() << "seed " << seed << ", dz " << dz);
            const Mesh m = translated(opened(octasphere(12, seed, 0.3), 5 * seed), 0.25, -0.5, dz);
            const mpq_class exact = exact_prism(m.view());
            const double v = cr(m.view(), polyvol::Method::prism);
            EXPECT_EQ(bits(v), bits(nearest_double(exact))) << v << " vs " << exact.get_d();
            differs_from_cone += bits(v) != bits(cr(m.view(), polyvol::Method::cone));
            // --accuracy fast stays within its bound.
            EXPECT_TRUE(within(polyvol::measure::prism_volume(m.view()), exact));
        }
    EXPECT_GT(differs_from_cone, 0);
}

TEST(Methods, PrismFilterFallsBackToTheExactSum) {
    // A tetrahedron and its inside-out copy: closed, volume exactly 0, which
    // no filter can decide (the sum's interval straddles 0).
    const Mesh t = unit_tetrahedron();
    Mesh both = t;
    append(both, t, true);
    EXPECT_EQ(bits(cr(both.view(), polyvol::Method::prism)), bits(0.0));
    EXPECT_EQ(bits(cr(t.view(), polyvol::Method::prism)), bits(1.0 / 6));
    // Near-ties: the unit cube and a thin box of volume 2^-53 + 2^-105, or
    // inside out -(2^-54 + 2^-106): the exact volume lies just beyond the
    // midpoint between two doubles (1 + 2^-53 above 1, 1 - 2^-54 below),
    // far inside the filter's bound (about 2^-100 here), so the exact sum must
    // decide: up to 1 + 2^-52, and down to 1 - 2^-53.
    for (const bool inside_out : {false, true}) {
        SCOPED_TRACE(inside_out);
        Mesh m = box(0, 0, 0, 1, 1, 1);
        const Mesh thin = box(2, 2, 0, 2 + 0x1p-20, 2 + (inside_out ? 0x1p-34 : 0x1p-33), 1 + 0x1p-52);
        append(m, thin, inside_out);
        const double v = cr(m.view(), polyvol::Method::prism);
        EXPECT_EQ(bits(v), bits(inside_out ? 1 - 0x1p-53 : 1 + 0x1p-52)) << std::hexfloat << v;
        EXPECT_EQ(bits(v), bits(cr(m.view(), polyvol::Method::cone)));
        EXPECT_EQ(bits(v), bits(nearest_double(exact_prism(m.view()))));
    }
}

TEST(Methods, PrismOutsideTheSafeRangeIsStillCorrectlyRounded) {
    // Scaled by 2^-200 and 2^200 (exact): coordinates outside {0} ∪ [2^-160,
    // 2^190] take the rational path.
    for (double scale : {0x1p-200, 0x1p200}) {
        SCOPED_TRACE(scale);
        Mesh m = opened(octasphere(6, 4, 0.2), 3);
        for (double& x : m.positions) x *= scale;
        EXPECT_EQ(bits(cr(m.view(), polyvol::Method::prism)), bits(nearest_double(exact_prism(m.view()))));
    }
    Mesh bad = octasphere(3, 1, 0.1);
    bad.positions[7] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(std::isnan(cr(bad.view(), polyvol::Method::prism)));
    EXPECT_FALSE(polyvol::mass_properties(bad.view(), {.method = polyvol::Method::prism}).volume_correctly_rounded);
    // Vertices no face uses do not matter (as for the cone rule): a NaN
    // one, or one outside the safe range.
    for (double unused : {std::numeric_limits<double>::quiet_NaN(), 0x1p-300}) {
        Mesh m = opened(octasphere(6, 4, 0.2), 3);
        m.add_vertex(unused, 1, 1);
        EXPECT_EQ(bits(cr(m.view(), polyvol::Method::prism)), bits(nearest_double(exact_prism(m.view()))));
    }
}

TEST(Methods, PyramidIsTheConeForEveryMesh) {
    // Open meshes with polygon faces (quads and their fans) far from the
    // origin: the same exact sum, so the same correctly rounded double.
    for (double dz : {0.0, 1e7}) {
        const Mesh quads = translated(box(-1, -2, -3, 0.5, 4, 7, true), 0.1, 0.2, dz);
        Mesh open_quads;
        open_quads.positions = quads.positions;
        const MeshView qv = quads.view();
        for (std::size_t f = 1; f < qv.face_count(); ++f) {
            const std::vector<uint32_t> face(qv.face(f).begin(), qv.face(f).end());
            open_quads.add_face(face);
        }
        for (const Mesh* m : std::initializer_list<const Mesh*>{&quads, &open_quads}) {
            // Franklin's own formula, exactly: the identity with the cone sum.
            EXPECT_EQ(exact_pyramid(m->view()), exact_volume(m->view()));
            EXPECT_EQ(bits(cr(m->view(), polyvol::Method::pyramid)), bits(nearest_double(exact_pyramid(m->view()))));
        }
    }
}

}  // namespace
