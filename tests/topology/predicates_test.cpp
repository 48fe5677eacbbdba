// The exact zero-area test and the winding numbers, on their own.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "fixtures.hpp"
#include "polyvol/topology.hpp"
#include "topology/degenerate.hpp"
#include "topology/edges.hpp"
#include "topology/shells.hpp"
#include "topology/winding.hpp"

namespace polyvol {
namespace {

using topology::cross_product_is_zero;
using topology::solid_angle;

bool zero_area(std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c) {
    return cross_product_is_zero(a.data(), b.data(), c.data());
}

TEST(CrossProductIsZero, CoincidentAndCollinearPoints) {
    EXPECT_TRUE(zero_area({1, 2, 3}, {1, 2, 3}, {1, 2, 3}));
    EXPECT_TRUE(zero_area({1, 2, 3}, {1, 2, 3}, {4, 5, 6}));
    EXPECT_TRUE(zero_area({0, 0, 0}, {0.1, 0.2, 0.3}, {0.2, 0.4, 0.6}));
    EXPECT_TRUE(zero_area({0, 0, 0}, {0, 0, 0}, {0, 0, 0}));
    EXPECT_TRUE(zero_area({-0.0, 0, 0}, {0, -0.0, 0}, {1, 0, 0}));
    // Differences that double arithmetic rounds: still exactly collinear.
    EXPECT_TRUE(zero_area({1e16, 0, 0}, {1e16 + 2, 1, 0}, {1e16 + 4, 2, 0}));
    // Scaled by powers of two, collinearity is kept.
    EXPECT_TRUE(zero_area({0x1p-900, 0x1p-899, 0}, {0x1p-898, 0x1p-897, 0}, {0, 0, 0}));
    EXPECT_TRUE(zero_area({0x1p+900, 0x1p+901, 0}, {0x1p+902, 0x1p+903, 0}, {0, 0, 0}));
}

TEST(CrossProductIsZero, NearlyCollinearIsNotZero) {
    EXPECT_FALSE(zero_area({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
    EXPECT_FALSE(zero_area({0, 0, 0}, {0.1, 0.2, 0.3}, {0.1 * 3, 0.2 * 3, 0.3 * 3}));
    // (b × c)_z = (1+2^-52)^2 - (1+2^-51) = 2^-104: rounds to 0 in doubles.
    const double e = 0x1p-52;
    ASSERT_EQ((1 + e) * (1 + e) - (1 + 2 * e) * 1, 0.0);
    EXPECT_FALSE(zero_area({0, 0, 0}, {1 + e, 1 + 2 * e, 0}, {1, 1 + e, 0}));
    // Products that overflow in plain doubles.
    EXPECT_FALSE(zero_area({0, 0, 0}, {1e300, 0, 0}, {0, 1e300, 0}));
    EXPECT_TRUE(zero_area({0, 0, 0}, {1e300, 1e300, 0}, {-1e300, -1e300, 0}));
}

TEST(CrossProductIsZero, NonFiniteIsNotZero) {
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(zero_area({0, 0, 0}, {inf, 0, 0}, {inf, 0, 0}));
    EXPECT_FALSE(zero_area({0, 0, 0}, {std::nan(""), 0, 0}, {1, 0, 0}));
}

TEST(SolidAngle, OctantTriangleFromTheOrigin) {
    const double p[3] = {0, 0, 0}, a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {0, 0, 1};
    EXPECT_NEAR(solid_angle(p, a, b, c), std::numbers::pi / 2, 1e-15);  // 4π / 8, seen from behind
    EXPECT_NEAR(solid_angle(p, a, c, b), -std::numbers::pi / 2, 1e-15);
}

TEST(SolidAngle, PointInsideACoplanarTriangleCountsHalfPositive) {
    const double p[3] = {0.25, 0.25, 0}, a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    EXPECT_EQ(solid_angle(p, a, b, c), 2 * std::numbers::pi);
    EXPECT_EQ(solid_angle(p, a, c, b), 2 * std::numbers::pi);
    const double q[3] = {2, 2, 0};  // coplanar, outside
    EXPECT_EQ(solid_angle(q, a, b, c), 0.0);
}

// Shells of a mesh, ready for winding_of_other_shells.
struct Shells {
    topology::WeldedMesh welded;
    topology::ShellTriangles triangles;
    std::vector<topology::ShellGeometry> geometry;

    explicit Shells(const Mesh& m) : welded(topology::weld_polygons(m.view())) {
        core::UnionFind sets(welded.polygons);
        const topology::EdgeTable edges = topology::build_edge_table(welded, &sets);
        const topology::ShellLabels labels = topology::label_shells(sets);
        triangles = topology::gather_shell_triangles(welded, labels);
        geometry = topology::measure_shells(welded, labels, edges, triangles);
    }
    std::vector<double> winding(topology::WindingOptions o) const {
        return topology::winding_of_other_shells(welded, triangles, geometry, o);
    }
};

// A lattice of small cubes (some inverted), a big cube around part of it,
// and open squares: the far-field approximation must agree with the exact
// sums closely enough to classify every shell the same way.
Mesh lattice() {
    Mesh m;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k) {
                const double x = 3.0 * i, y = 3.0 * j, z = 3.0 * k;
                test::add_box(m, {x, y, z}, {x + 1, y + 1.5, z + 1}, {.inverted = (i + j + k) % 5 == 0});
            }
    test::add_box(m, {-1, -1, -1}, {8.5, 17, 17});
    for (int i = 0; i < 20; ++i) {  // open unit squares, off the lattice planes
        const double x = 1.7 + 0.83 * i, z = 2.2 + 0.37 * i;
        const uint32_t a = m.add_vertex(x, 0.5, z), b = m.add_vertex(x + 1, 0.5, z);
        const uint32_t c = m.add_vertex(x + 1, 1.5, z + 0.2), d = m.add_vertex(x, 1.5, z + 0.2);
        m.add_face(std::array<uint32_t, 4>{a, b, c, d});
    }
    return m;
}

TEST(Winding, FarFieldApproximationAgreesWithExactSums) {
    const Shells s(lattice());
    ASSERT_EQ(s.geometry.size(), 6u * 6 * 6 + 1 + 20);
    const std::vector<double> exact = s.winding({.exact_budget = 1e18});
    const std::vector<double> approx = s.winding({.exact_budget = 0});
    std::size_t inside = 0;
    for (std::size_t i = 0; i < exact.size(); ++i) {
        EXPECT_NEAR(approx[i], exact[i], 2e-3) << "shell " << i;
        if (s.geometry[i].balanced()) {
            EXPECT_EQ(exact[i] >= 0.5, approx[i] >= 0.5) << "shell " << i;
            inside += exact[i] >= 0.5;
        }
    }
    EXPECT_EQ(inside, 3u * 6 * 6);  // the cubes with i < 3
}

TEST(Winding, ManyOpenShellsStayFast) {
    // 40000 separate triangles: 1.6e9 solid angles exactly; the far field keeps it near-linear.
    Mesh m;
    for (int i = 0; i < 200; ++i)
        for (int j = 0; j < 200; ++j) {
            const double x = i, y = j, z = 0.01 * ((i * 7 + j * 13) % 17);
            const uint32_t a = m.add_vertex(x, y, z), b = m.add_vertex(x + 0.5, y, z), c = m.add_vertex(x, y + 0.5, z + 0.1);
            m.add_triangle(a, b, c);
        }
    const auto start = std::chrono::steady_clock::now();
    const TopologyReport r = analyze_topology(m.view());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.shells.size(), 40000u);
    for (const Shell& s : r.shells) {
        ASSERT_EQ(s.role, ShellRole::open);
        ASSERT_LT(std::abs(s.winding_of_others), 0.5);
    }
    EXPECT_LT(seconds, 20.0);
}

// Shells whose boxes all overlap (needles from one corner): nothing is far,
// so the sums would be quadratic. The work limit leaves the shells it does
// not reach NaN (closed ones become `undecided` in the report) instead of
// running for minutes; the ones it reaches keep their exact values.
TEST(Winding, AWorkLimitStopsSumsThatNothingMakesFar) {
    Mesh m;
    for (int t = 0; t < 3000; ++t) {  // closed thin tetrahedra from near the origin to x = t + 1
        const double x = t + 1.0, e = 1e-3 * (1 + t % 7);
        const uint32_t o = m.add_vertex(0, 0, 0), a = m.add_vertex(x, 0, e), b = m.add_vertex(x, e, 0),
                       c = m.add_vertex(x, -e, -e);
        m.add_triangle(o, b, a);
        m.add_triangle(o, c, b);
        m.add_triangle(o, a, c);
        m.add_triangle(a, b, c);
    }
    const Shells s(m);
    ASSERT_EQ(s.geometry.size(), 3000u);
    const std::vector<double> all = s.winding({.exact_budget = 0, .work_limit = 1e18});
    const std::vector<double> cut = s.winding({.exact_budget = 0, .work_limit = 2e5});
    std::size_t reached = 0;
    for (std::size_t i = 0; i < cut.size(); ++i) {
        ASSERT_FALSE(std::isnan(all[i]));
        if (std::isnan(cut[i])) continue;
        ++reached;
        EXPECT_EQ(cut[i], all[i]);
    }
    EXPECT_GT(reached, 0u);
    EXPECT_LT(reached, 3000u);
}

}  // namespace
}  // namespace polyvol
