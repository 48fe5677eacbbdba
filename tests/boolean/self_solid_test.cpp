// solid_volume(mesh, {.within_shells = true}): the solid {W >= 1} of a
// shell that crosses itself (generate::join_by_tube builds the shells).
//
// The identity the tests rest on: two closed meshes A and B joined into one
// shell S by a tube (a face fa of A and a face fb of B removed, their rims
// joined by three quads) are, as 2-chains, A + B + T, where T is the tube
// closed by fa and fb reversed. Winding numbers add, so S bounds the same
// solid {W >= 1} as the file of the three separate shells A, B and T, which
// solid_volume resolves between shells (checked against CGAL's exact union in
// tests/boolean_oracle). The tube runs from A's far side to B's far side
// through both, so S crosses itself along the curve where A and B meet and
// wherever the tube leaves them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol {
namespace {

Mesh reversed(Mesh m) {
    for (std::size_t f = 0; f < m.indices.size() / 3; ++f) std::swap(m.indices[3 * f + 1], m.indices[3 * f + 2]);
    return m;
}

void expect_same_solid(const Mesh& one, const Mesh& three, bool moments) {
    const SolidVolume s = solid_volume(one.view(), {.moments = moments, .within_shells = true});
    const SolidVolume r = solid_volume(three.view(), {.moments = moments});
    ASSERT_EQ(s.status, BooleanStatus::ok) << boolean_status_message(s.status);
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_TRUE(s.within_checked);
    EXPECT_GT(s.self_crossing_pairs, 0u);
    EXPECT_EQ(s.shells_crossing_themselves, 1u);
    EXPECT_EQ(s.properties.volume, r.properties.volume);
    EXPECT_EQ(s.winding_volume, r.winding_volume);
    EXPECT_LT(s.properties.volume, s.winding_volume);  // the overlap of A and B counts once
    if (moments) {
        for (int i = 0; i < 3; ++i) EXPECT_EQ(s.properties.first_moments[i], r.properties.first_moments[i]) << i;
        for (int k = 0; k < 6; ++k) EXPECT_EQ(s.properties.second_moments[k], r.properties.second_moments[k]) << k;
    }
}

TEST(SelfSolid, TwoSpheresJoinedByATubeEqualThreeShells) {
    const Mesh a = generate::uv_sphere(12, 24);
    const Mesh b = generate::uv_sphere(10, 20, 0.8, 0.9, 0.0625, 0.03125);
    const generate::Joined j = generate::join_by_tube(a, b);
    expect_same_solid(j.one, j.three, true);
}

TEST(SelfSolid, FarFromTheOriginAndAtOtherSizes) {
    for (const auto& [rings, offset] : {std::pair{6u, 0.0}, std::pair{16u, 1e6}, std::pair{24u, -37.5}}) {
        const Mesh a = generate::uv_sphere(rings, 2 * rings, 1.0, offset, offset, offset);
        const Mesh b = generate::uv_sphere(rings + 1, 2 * rings + 2, 0.7, offset + 1.1, offset + 0.125, offset - 0.0625);
        const generate::Joined j = generate::join_by_tube(a, b);
        expect_same_solid(j.one, j.three, false);
    }
}

// A UV sphere whose pole fans are replaced by the flat polygons of their
// rings (each ring has one z), fanned from one corner: coplanar triangles
// sharing a vertex or an edge, the fold check's flat cases.
Mesh flat_capped_sphere(uint32_t rings, uint32_t segments, double r, double cx, double cy, double cz) {
    const Mesh m = generate::uv_sphere(rings, segments, r, cx, cy, cz);
    Mesh out;
    out.positions = m.positions;
    auto at = [&](uint32_t i, uint32_t j) { return 1 + (i - 1) * segments + j % segments; };
    for (uint32_t i = 1; i + 1 < segments; ++i) out.add_triangle(at(1, 0), at(1, i), at(1, i + 1));
    for (uint32_t i = 1; i + 1 < segments; ++i)
        out.add_triangle(at(rings - 1, 0), at(rings - 1, segments - i), at(rings - 1, segments - i - 1));
    for (uint32_t f = segments; f + segments < m.indices.size() / 3; ++f) {
        const auto c = generate::triangle_of(m, f);
        out.add_triangle(c[0], c[1], c[2]);
    }
    return out;
}

TEST(SelfSolid, FlatCapsCrossingTheOtherSphere) {
    const Mesh a = flat_capped_sphere(10, 20, 1.0, 0, 0, 0);
    const Mesh b = flat_capped_sphere(9, 18, 0.8, 0.9, 0.0625, 0.4);  // its south cap crosses a
    ASSERT_EQ(solid_volume(a.view()).properties.volume,
              solid_volume(a.view(), {.within_shells = true}).properties.volume);
    const generate::Joined j = generate::join_by_tube(a, b);
    expect_same_solid(j.one, j.three, true);
}

// A sphere whose vertex (0.75, 1, -0.25) lies on the face y = 1 of a box
// joined to it: the shell touches itself there, a status.
TEST(SelfSolid, TouchingIsAStatus) {
    const generate::Joined touching = generate::join_by_tube(test::box({-1, -1, -1}, {1, 1, 1}), generate::uv_sphere(12, 24, 0.9, 0.75, 0.1, -0.25));
    EXPECT_EQ(solid_volume(touching.one.view(), {.within_shells = true}).status, BooleanStatus::shell_touches_itself);
}

// With other shells in the file: a third sphere crossing S, and S inside out
// as a cavity of a big sphere (its default front winding is -1 there).
TEST(SelfSolid, AmongOtherShellsAndAsACavity) {
    const generate::Joined j = generate::join_by_tube(generate::uv_sphere(10, 20), generate::uv_sphere(9, 18, 0.75, 1.0, 0.1, -0.05));
    const Mesh c = generate::uv_sphere(8, 16, 0.6, 0.5, 0.7, 0.2);
    Mesh one = j.one, three = j.three;
    one.append(c);
    three.append(c);
    {
        const SolidVolume s = solid_volume(one.view(), {.within_shells = true});
        const SolidVolume r = solid_volume(three.view());
        ASSERT_EQ(s.status, BooleanStatus::ok) << boolean_status_message(s.status);
        EXPECT_EQ(s.properties.volume, r.properties.volume);
        EXPECT_GT(s.crossing_pairs, 0u);  // S and the third sphere
    }
    const Mesh big = generate::uv_sphere(16, 32, 4.0, 0.4, 0.0, 0.0);
    Mesh hollow_one = big, hollow_three = big;
    hollow_one.append(reversed(j.one));
    hollow_three.append(reversed(j.three));
    const SolidVolume s = solid_volume(hollow_one.view(), {.moments = true, .within_shells = true});
    const SolidVolume r = solid_volume(hollow_three.view(), {.moments = true});
    ASSERT_EQ(s.status, BooleanStatus::ok) << boolean_status_message(s.status);
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_EQ(s.properties.volume, r.properties.volume);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.properties.first_moments[i], r.properties.first_moments[i]);
    // The cavity removes the solid S bounds: |big| - |{W_S >= 1}|.
    const SolidVolume solid_s = solid_volume(j.one.view(), {.within_shells = true});
    const SolidVolume solid_big = solid_volume(big.view());
    EXPECT_NEAR(s.properties.volume, solid_big.properties.volume - solid_s.properties.volume,
                1e-12 * solid_big.properties.volume);
}

// Scaling by 2 is exact and commutes with rounding: 8 times the volume, bit for bit.
TEST(SelfSolid, ScalingByTwoGivesEightTimesTheVolume) {
    const generate::Joined j = generate::join_by_tube(generate::uv_sphere(8, 16), generate::uv_sphere(8, 16, 0.9, 0.8, 0.05, 0.1));
    Mesh doubled = j.one;
    for (double& x : doubled.positions) x *= 2;
    const SolidVolume s = solid_volume(j.one.view(), {.within_shells = true});
    const SolidVolume t = solid_volume(doubled.view(), {.within_shells = true});
    ASSERT_EQ(s.status, BooleanStatus::ok);
    ASSERT_EQ(t.status, BooleanStatus::ok);
    EXPECT_EQ(8 * s.properties.volume, t.properties.volume);
}

// Without within_shells nothing is looked for: the shell's sum stands.
TEST(SelfSolid, NotLookedForUnlessAsked) {
    const generate::Joined j = generate::join_by_tube(generate::uv_sphere(8, 16), generate::uv_sphere(8, 16, 0.9, 0.8, 0.05, 0.1));
    const SolidVolume s = solid_volume(j.one.view());
    ASSERT_EQ(s.status, BooleanStatus::ok);
    EXPECT_FALSE(s.within_checked);
    EXPECT_EQ(s.properties.volume, s.winding_volume);
}

// A shell that does not cross itself is left as it is (and costs the search).
TEST(SelfSolid, ShellsThatDoNotCrossThemselves) {
    const Mesh m = generate::torus(24, 12);
    const SolidVolume s = solid_volume(m.view(), {.within_shells = true});
    ASSERT_EQ(s.status, BooleanStatus::ok);
    EXPECT_TRUE(s.within_checked);
    EXPECT_EQ(s.self_crossing_pairs, 0u);
    EXPECT_EQ(s.properties.volume, solid_volume(m.view()).properties.volume);
}

// The box [0, 2]^3 and a tetrahedron o p q r on its bottom front edge o p,
// poking out through its top face (test::box_and_tetrahedron_on_its_edge:
// one shell, the edge o p has four triangles, split into two sheets). The solid is the box and the part of
// the tetrahedron above z = 2: its sections at s = z / 3 are parallelograms
// of area s (1 - s) C with C = 2 |tetrahedron| / 1 = 1.6, so that part is
// 3 C ∫_{2/3}^1 s (1 - s) ds = 28/135, and the solid 8 + 28/135 = 1108/135.
TEST(SelfSolid, AnEdgeOfFourTrianglesIsTwoSheets) {
    const SolidVolume s = solid_volume(test::box_and_tetrahedron_on_its_edge(0.8).view(), {.moments = true, .within_shells = true});
    ASSERT_EQ(s.status, BooleanStatus::ok) << boolean_status_message(s.status);
    EXPECT_EQ(s.properties.volume, 1108.0 / 135);
    EXPECT_EQ(s.winding_volume, 8.8);
    EXPECT_EQ(s.self_crossing_pairs, 6u);
}

// With q = (-0.5, 0.6, 3) the face o p q also leaves the box through its
// face x = 0, along a segment from the shared corner o: a fold through a
// vertex, which no cut between edge crossings represents. A status, never a number.
TEST(SelfSolid, AFoldThroughAVertexIsAStatus) {
    const SolidVolume s = solid_volume(test::box_and_tetrahedron_on_its_edge(-0.5).view(), {.within_shells = true});
    EXPECT_EQ(s.status, BooleanStatus::shell_touches_itself);
    EXPECT_TRUE(std::isnan(s.properties.volume));
}

}  // namespace
}  // namespace polyvol
