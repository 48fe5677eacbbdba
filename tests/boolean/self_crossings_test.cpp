// self_crossings: a surface crossing itself within one connected piece is
// found (a box and a tetrahedron sharing a corner and poking through it;
// the counts from the crossing segments drawn by hand), and nothing is found
// on closed surfaces that do not (a box, spheres, two shells crossing each
// other: those are solid_volume's).
#include <gtest/gtest.h>

#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol {
namespace {

// test::box_and_tetrahedron_on_its_edge: one body (joined through that
// edge, used by four faces), whose surface crosses itself where the
// tetrahedron leaves the box through its top face z = 2.
TEST(SelfCrossings, TetrahedronThroughTheBoxItSharesAnEdgeWith) {
    const Mesh m = test::box_and_tetrahedron_on_its_edge();
    EXPECT_EQ(m.positions[3 * 1], 2.0);  // p
    const SelfCrossings s = self_crossings(m.view());
    ASSERT_EQ(s.status, BooleanStatus::ok);
    // At z = 2 the tetrahedron's section is the quadrilateral A = (8/15, 0.4)
    // on o q, B = (1.2, 0.4) on p q, C = (22/15, 14/15) on p r, D = (0.8,
    // 14/15) on o r, in (x, y); its sides lie in the faces o p q (A B),
    // p r q (B C), o r p (C D) and o q r (D A). The box's top face is two
    // triangles split along y = x: a segment crosses both when its ends lie
    // on both sides of y = x, else one: 1 + 1 + 2 + 2.
    const double pts[4][2] = {{8.0 / 15, 0.4}, {1.2, 0.4}, {22.0 / 15, 14.0 / 15}, {0.8, 14.0 / 15}};
    std::size_t expected = 0;
    for (int i = 0; i < 4; ++i) {
        const auto& a = pts[i];
        const auto& b = pts[(i + 1) % 4];
        expected += ((a[1] > a[0]) != (b[1] > b[0])) ? 2 : 1;
    }
    ASSERT_EQ(expected, 6u);
    EXPECT_EQ(s.pairs, expected);
    ASSERT_TRUE(s.example.has_value());
    EXPECT_LT((*s.example)[0], 12u);  // a face of the box
    EXPECT_GE((*s.example)[1], 12u);  // and one of the tetrahedron
    // solid_volume takes them as one body: its volume counts the overlap twice.
    const SolidVolume v = solid_volume(m.view());
    EXPECT_EQ(v.crossing_pairs, 0u);
    EXPECT_EQ(v.properties.volume, v.winding_volume);
}

// A vertex of the tetrahedron lying on the box's top face, inside it: the two
// surfaces touch there and cross nowhere. Moving one triangle of a pair by δ
// pushes that vertex through the face one way and not the other, so a pair
// counts only when it crosses both ways: none here.
TEST(SelfCrossings, TouchingIsNotCrossing) {
    Mesh m = test::box({0, 0, 0}, {2, 2, 2});
    const uint32_t o = 0, p = 1;
    const uint32_t q = m.add_vertex(1.2, 0.5, 2), r = m.add_vertex(1, 1.5, 1);
    m.add_triangle(p, r, q);  // (o, p, r, q) positively oriented: outward faces
    m.add_triangle(o, q, r);
    m.add_triangle(o, p, q);
    m.add_triangle(o, r, p);
    const SelfCrossings s = self_crossings(m.view());
    ASSERT_EQ(s.status, BooleanStatus::ok);
    EXPECT_EQ(s.pairs, 0u);
    EXPECT_GT(s.candidate_pairs, 0u);
}

// Sharing only a vertex, the box and a tetrahedron are two parts (joined
// through no edge): solid_volume's bodies, which it resolves, so no
// self-crossing.
TEST(SelfCrossings, PartsSharingAVertexAreSolidVolumesBodies) {
    Mesh m = test::box({0, 0, 0}, {2, 2, 2});
    const uint32_t o = 0;
    const uint32_t a = m.add_vertex(3, 0.5, 0.6), b = m.add_vertex(3, 1.5, 0.7), c = m.add_vertex(3, 1.0, 1.6);
    m.add_triangle(a, b, c);
    m.add_triangle(o, b, a);
    m.add_triangle(o, c, b);
    m.add_triangle(o, a, c);
    EXPECT_EQ(self_crossings(m.view()).pairs, 0u);
    const SolidVolume v = solid_volume(m.view());
    EXPECT_EQ(v.crossing_pairs, 5u);  // the box's face x = 2 and the tetrahedron's sides
    EXPECT_LT(v.properties.volume, v.winding_volume);
}

TEST(SelfCrossings, NoneOnSurfacesThatDoNotCrossThemselves) {
    for (const Mesh& m : {test::box({0, 0, 0}, {1, 2, 3}), generate::uv_sphere(24, 48), generate::torus(40, 16)}) {
        const SelfCrossings s = self_crossings(m.view());
        EXPECT_EQ(s.status, BooleanStatus::ok);
        EXPECT_EQ(s.pairs, 0u);
        EXPECT_FALSE(s.example.has_value());
    }
    // Two shells crossing each other: not a self-crossing of either.
    Mesh two = test::box({0, 0, 0}, {2, 2, 2});
    test::add_box(two, {1, 1, 1}, {3, 3, 3});
    EXPECT_EQ(self_crossings(two.view()).pairs, 0u);
    EXPECT_GT(solid_volume(two.view()).crossing_pairs, 0u);
}

TEST(SelfCrossings, BadCoordinatesAreAStatus) {
    Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    m.positions[0] = 1e300;
    EXPECT_EQ(self_crossings(m.view()).status, BooleanStatus::invalid_coordinates);
    m.indices[0] = 999;
    EXPECT_THROW(self_crossings(m.view()), std::invalid_argument);
}

}  // namespace
}  // namespace polyvol
