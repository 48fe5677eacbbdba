// analyze_topology on meshes whose every figure is known by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include "common/topology_compare.hpp"
#include "fixtures.hpp"
#include "polyvol/topology.hpp"

namespace polyvol {
namespace {

using test::add_box;
using test::box;
using test::expect_same_counts;
using test::quad_torus;
using test::tetrahedron;
using test::triangle;
using test::unit_cube;
using test::unwelded;

TopologyReport analyze(const Mesh& m) { return analyze_topology(m.view()); }

void expect_closed_oriented_manifold(const TopologyReport& r) {
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.nonmanifold_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 0u);
    EXPECT_EQ(r.unbalanced_edges, 0u);
    EXPECT_TRUE(r.closed);
    EXPECT_TRUE(r.edge_manifold);
    EXPECT_TRUE(r.consistently_oriented);
    EXPECT_TRUE(r.closed_2_cycle);
    EXPECT_FALSE(r.unbalanced_example.has_value());
}

TEST(Topology, EmptyMesh) {
    const TopologyReport r = analyze(Mesh{});
    EXPECT_EQ(r.faces, 0u);
    EXPECT_EQ(r.edges, 0u);
    EXPECT_EQ(r.euler_characteristic, 0);
    EXPECT_EQ(r.components_edge_connected, 0u);
    EXPECT_EQ(r.components_vertex_connected, 0u);
    EXPECT_TRUE(r.closed_2_cycle);
    EXPECT_TRUE(r.shells.empty());
}

TEST(Topology, Tetrahedron) {
    const TopologyReport r = analyze(tetrahedron());
    EXPECT_EQ(r.faces, 4u);
    EXPECT_EQ(r.faces_with_lt3_vertices, 0u);
    EXPECT_EQ(r.triangles, 4u);
    EXPECT_EQ(r.vertices_welded, 4u);
    EXPECT_EQ(r.vertices_referenced, 4u);
    EXPECT_EQ(r.edges, 6u);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 2);
    EXPECT_EQ(r.components_vertex_connected, 1u);
    EXPECT_EQ(r.components_edge_connected, 1u);
    EXPECT_EQ(r.degenerate_edge_uses, 0u);
    EXPECT_EQ(r.triangles_with_repeated_vertex, 0u);
    EXPECT_EQ(r.zero_area_triangles, 0u);
    ASSERT_EQ(r.shells.size(), 1u);
    const Shell& s = r.shells[0];
    EXPECT_DOUBLE_EQ(s.signed_volume, 1.0 / 6);
    EXPECT_EQ(s.faces, 4u);
    EXPECT_EQ(s.vertices, 4u);
    EXPECT_EQ(s.edges, 6u);
    EXPECT_EQ(s.boundary_edges, 0u);
    EXPECT_EQ(s.unbalanced_edges, 0u);
    EXPECT_EQ(s.euler_characteristic, 2);
    EXPECT_EQ(s.genus, 0);
    EXPECT_EQ(s.winding_of_others, 0.0);
    EXPECT_EQ(s.role, ShellRole::solid);
    EXPECT_EQ(r.cavities + r.inside_out_shells + r.nested_shells, 0u);
}

TEST(Topology, TriangulatedCube) {
    const TopologyReport r = analyze(unit_cube());
    EXPECT_EQ(r.faces, 12u);
    EXPECT_EQ(r.triangles, 12u);
    EXPECT_EQ(r.vertices_referenced, 8u);
    EXPECT_EQ(r.edges, 18u);  // 12 cube edges + 6 face diagonals, which are triangle sides here
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 2);
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 1.0);
    EXPECT_EQ(r.shells[0].genus, 0);
    EXPECT_EQ(r.shells[0].role, ShellRole::solid);
}

TEST(Topology, QuadCubeCountsPolygonSidesNotFanDiagonals) {
    const TopologyReport r = analyze(unit_cube({.quads = true}));
    EXPECT_EQ(r.faces, 6u);
    EXPECT_EQ(r.triangles, 12u);
    EXPECT_EQ(r.edges, 12u);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 2);  // 8 - 12 + 6
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_EQ(r.shells[0].faces, 6u);
    EXPECT_EQ(r.shells[0].edges, 12u);
    EXPECT_EQ(r.shells[0].genus, 0);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 1.0);
}

TEST(Topology, QuadTorusHasGenusOne) {
    const TopologyReport r = analyze(quad_torus(12, 8));
    EXPECT_EQ(r.faces, 96u);
    EXPECT_EQ(r.triangles, 192u);
    EXPECT_EQ(r.vertices_referenced, 96u);
    EXPECT_EQ(r.edges, 192u);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 0);
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_EQ(r.shells[0].genus, 1);
    EXPECT_GT(r.shells[0].signed_volume, 0);
    EXPECT_EQ(r.shells[0].role, ShellRole::solid);
}

TEST(Topology, MissingFaceLeavesThreeBoundaryEdges) {
    Mesh m = tetrahedron();
    m.indices.resize(9);  // drop triangle (1, 2, 3)
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.faces, 3u);
    EXPECT_EQ(r.edges, 6u);
    EXPECT_EQ(r.boundary_edges, 3u);
    EXPECT_EQ(r.unbalanced_edges, 3u);
    EXPECT_EQ(r.nonmanifold_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 0u);
    EXPECT_FALSE(r.closed);
    EXPECT_FALSE(r.closed_2_cycle);
    EXPECT_TRUE(r.edge_manifold);
    EXPECT_TRUE(r.consistently_oriented);
    EXPECT_EQ(r.euler_characteristic, 1);  // a disc
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_EQ(r.shells[0].boundary_edges, 3u);
    EXPECT_EQ(r.shells[0].unbalanced_edges, 3u);
    EXPECT_FALSE(r.shells[0].genus.has_value());
    EXPECT_EQ(r.shells[0].role, ShellRole::open);
    // About the origin: the three remaining faces all contain it, so 0.
    EXPECT_EQ(r.shells[0].signed_volume, 0.0);
    // The example runs the way the remaining faces use it: the reverse of a
    // side of the dropped triangle 1 -> 2 -> 3.
    ASSERT_TRUE(r.unbalanced_example.has_value());
    const auto& e = *r.unbalanced_example;
    const std::array<std::array<double, 6>, 3> reversed_sides{{
        {0, 1, 0, 1, 0, 0},   // 2 -> 1
        {0, 0, 1, 0, 1, 0},   // 3 -> 2
        {1, 0, 0, 0, 0, 1},   // 1 -> 3
    }};
    EXPECT_TRUE(e == reversed_sides[0] || e == reversed_sides[1] || e == reversed_sides[2]);
}

// The problem edges as unordered segments {min end, max end} with their bits.
std::set<std::pair<std::array<double, 6>, int>> problem_segments(const TopologyReport& r) {
    std::set<std::pair<std::array<double, 6>, int>> out;
    for (const ProblemEdge& e : r.problem_edges) {
        std::array<double, 3> p{e.ends[0], e.ends[1], e.ends[2]}, q{e.ends[3], e.ends[4], e.ends[5]};
        if (q < p) std::swap(p, q);
        out.insert({{p[0], p[1], p[2], q[0], q[1], q[2]}, e.problems});
    }
    return out;
}

TEST(Topology, ProblemEdgesAreListedWithTheirEndsAndKinds) {
    Mesh open = tetrahedron();
    open.indices.resize(9);  // drop triangle (1, 2, 3): its sides are the boundary
    EXPECT_TRUE(analyze_topology(open.view()).problem_edges.empty());  // listed only when asked
    const int boundary = edge_boundary | edge_unbalanced;
    EXPECT_EQ(problem_segments(analyze_topology(open.view(), {.problem_edges = 100})),
              (std::set<std::pair<std::array<double, 6>, int>>{{{0, 0, 1, 0, 1, 0}, boundary},
                                                                {{0, 0, 1, 1, 0, 0}, boundary},
                                                                {{0, 1, 0, 1, 0, 0}, boundary}}));
    EXPECT_EQ(analyze_topology(open.view(), {.problem_edges = 2}).problem_edges.size(), 2u);

    Mesh flipped = tetrahedron();
    std::swap(flipped.indices[10], flipped.indices[11]);  // (1, 2, 3) -> (1, 3, 2)
    const int misoriented = edge_misoriented | edge_unbalanced;
    EXPECT_EQ(problem_segments(analyze_topology(flipped.view(), {.problem_edges = 100})),
              (std::set<std::pair<std::array<double, 6>, int>>{{{0, 0, 1, 0, 1, 0}, misoriented},
                                                                {{0, 0, 1, 1, 0, 0}, misoriented},
                                                                {{0, 1, 0, 1, 0, 0}, misoriented}}));

    Mesh two;
    add_box(two, {0, 0, 0}, {1, 1, 1}, {.quads = true});
    add_box(two, {1, 1, 0}, {2, 2, 1}, {.quads = true});  // shares the edge x = y = 1
    EXPECT_EQ(problem_segments(analyze_topology(two.view(), {.problem_edges = 100})),
              (std::set<std::pair<std::array<double, 6>, int>>{{{1, 1, 0, 1, 1, 1}, edge_nonmanifold}}));
    EXPECT_TRUE(analyze_topology(unit_cube().view(), {.problem_edges = 100}).problem_edges.empty());
}

TEST(Topology, OpenShellVolumeIsAboutTheOrigin) {
    const TopologyReport r = analyze(triangle({1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 1.0 / 6);
    EXPECT_EQ(r.euler_characteristic, 1);
    EXPECT_EQ(r.boundary_edges, 3u);
}

TEST(Topology, FlippedFaceGivesMisorientedEdges) {
    Mesh m = tetrahedron();
    std::swap(m.indices[10], m.indices[11]);  // (1, 2, 3) -> (1, 3, 2)
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.edges, 6u);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 3u);
    EXPECT_EQ(r.unbalanced_edges, 3u);
    EXPECT_EQ(r.nonmanifold_edges, 0u);
    EXPECT_TRUE(r.closed);
    EXPECT_TRUE(r.edge_manifold);
    EXPECT_FALSE(r.consistently_oriented);
    EXPECT_FALSE(r.closed_2_cycle);
    EXPECT_TRUE(r.unbalanced_example.has_value());
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_FALSE(r.shells[0].genus.has_value());
    EXPECT_EQ(r.shells[0].role, ShellRole::open);
}

TEST(Topology, TwoCubesSharingAnEdgeAreNonManifold) {
    Mesh m;
    add_box(m, {0, 0, 0}, {1, 1, 1}, {.quads = true});
    add_box(m, {1, 1, 0}, {2, 2, 1}, {.quads = true});  // shares the edge x = y = 1
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.vertices_welded, 14u);
    EXPECT_EQ(r.edges, 23u);
    EXPECT_EQ(r.nonmanifold_edges, 1u);
    EXPECT_EQ(r.unbalanced_edges, 0u);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_FALSE(r.edge_manifold);
    EXPECT_TRUE(r.closed);
    EXPECT_TRUE(r.closed_2_cycle);
    EXPECT_EQ(r.euler_characteristic, 3);  // 14 - 23 + 12
    EXPECT_EQ(r.components_edge_connected, 1u);
    EXPECT_EQ(r.components_vertex_connected, 1u);
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 2.0);
    EXPECT_FALSE(r.shells[0].genus.has_value());
    EXPECT_EQ(r.shells[0].role, ShellRole::solid);
}

TEST(Topology, TetrahedraSharingAVertexAreOneVertexComponentTwoShells) {
    Mesh m = tetrahedron();
    Mesh t = tetrahedron();
    for (double& x : t.positions) x = -x;  // point reflection through the shared vertex 0 ...
    for (std::size_t i = 0; i < t.indices.size(); i += 3) std::swap(t.indices[i + 1], t.indices[i + 2]);  // ... kept outward
    m.append(t);
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.vertices_welded, 7u);
    EXPECT_EQ(r.components_vertex_connected, 1u);
    EXPECT_EQ(r.components_edge_connected, 2u);
    EXPECT_EQ(r.euler_characteristic, 3);  // 7 - 12 + 8
    ASSERT_EQ(r.shells.size(), 2u);
    for (const Shell& s : r.shells) {
        EXPECT_DOUBLE_EQ(s.signed_volume, 1.0 / 6);
        EXPECT_EQ(s.vertices, 4u);
        EXPECT_EQ(s.euler_characteristic, 2);
        EXPECT_EQ(s.genus, 0);
        EXPECT_EQ(s.role, ShellRole::solid);
    }
}

TEST(Topology, CubeWithInvertedInnerCubeIsACavity) {
    Mesh m;
    add_box(m, {0, 0, 0}, {3, 3, 3});
    add_box(m, {1, 1, 1}, {2, 2, 2}, {.inverted = true});
    const TopologyReport r = analyze(m);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 4);
    ASSERT_EQ(r.shells.size(), 2u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 27.0);
    EXPECT_EQ(r.shells[0].role, ShellRole::solid);
    EXPECT_NEAR(r.shells[0].winding_of_others, 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(r.shells[1].signed_volume, -1.0);
    EXPECT_NEAR(r.shells[1].winding_of_others, 1.0, 1e-12);
    EXPECT_EQ(r.shells[1].role, ShellRole::cavity);
    EXPECT_EQ(r.cavities, 1u);
    EXPECT_EQ(r.inside_out_shells, 0u);
    EXPECT_EQ(r.nested_shells, 0u);
}

TEST(Topology, InvertedCubeAloneIsInsideOut) {
    const TopologyReport r = analyze(unit_cube({.inverted = true}));
    expect_closed_oriented_manifold(r);  // consistently oriented, only the wrong way round
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, -1.0);
    EXPECT_EQ(r.shells[0].role, ShellRole::inside_out);
    EXPECT_EQ(r.shells[0].genus, 0);
    EXPECT_EQ(r.inside_out_shells, 1u);
    EXPECT_EQ(r.cavities, 0u);
}

TEST(Topology, TwoDisjointCubes) {
    Mesh m;
    add_box(m, {0, 0, 0}, {1, 1, 1});
    add_box(m, {3, 0, 0}, {5, 2, 2});
    const TopologyReport r = analyze(m);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.components_edge_connected, 2u);
    EXPECT_EQ(r.components_vertex_connected, 2u);
    EXPECT_EQ(r.euler_characteristic, 4);
    ASSERT_EQ(r.shells.size(), 2u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 8.0);  // largest |volume| first
    EXPECT_DOUBLE_EQ(r.shells[1].signed_volume, 1.0);
    for (const Shell& s : r.shells) {
        EXPECT_EQ(s.role, ShellRole::solid);
        EXPECT_NEAR(s.winding_of_others, 0.0, 1e-12);
    }
}

TEST(Topology, PositiveCubeInsideAnotherIsNested) {
    Mesh m;
    add_box(m, {1, 1, 1}, {2, 2, 2});
    add_box(m, {0, 0, 0}, {3, 3, 3});
    const TopologyReport r = analyze(m);
    ASSERT_EQ(r.shells.size(), 2u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 27.0);
    EXPECT_EQ(r.shells[0].role, ShellRole::solid);
    EXPECT_EQ(r.shells[1].role, ShellRole::nested);
    EXPECT_NEAR(r.shells[1].winding_of_others, 1.0, 1e-12);
    EXPECT_EQ(r.nested_shells, 1u);
    EXPECT_EQ(r.cavities, 0u);
}

TEST(Topology, SolidInsideACavityIsASolid) {
    Mesh m;
    add_box(m, {0, 0, 0}, {5, 5, 5});
    add_box(m, {1, 1, 1}, {4, 4, 4}, {.inverted = true});
    add_box(m, {2, 2, 2}, {3, 3, 3});
    const TopologyReport r = analyze(m);
    ASSERT_EQ(r.shells.size(), 3u);
    EXPECT_EQ(r.shells[0].role, ShellRole::solid);
    EXPECT_EQ(r.shells[1].role, ShellRole::cavity);
    EXPECT_NEAR(r.shells[1].winding_of_others, 1.0, 1e-12);
    EXPECT_EQ(r.shells[2].role, ShellRole::solid);
    EXPECT_NEAR(r.shells[2].winding_of_others, 0.0, 1e-12);  // 1 - 1
    EXPECT_EQ(r.cavities, 1u);
    EXPECT_EQ(r.nested_shells, 0u);
}

TEST(Topology, EqualVolumesKeepTheOrderOfTheirFirstFace) {
    Mesh m;
    add_box(m, {0, 0, 0}, {1, 1, 1}, {.quads = true});          // 6 faces
    add_box(m, {2, 0, 0}, {3, 1, 1});                            // 12 faces, same volume
    add_box(m, {4, 0, 0}, {5, 1, 1}, {.inverted = true});        // |volume| equal too
    const TopologyReport r = analyze(m);
    ASSERT_EQ(r.shells.size(), 3u);
    EXPECT_EQ(r.shells[0].faces, 6u);
    EXPECT_EQ(r.shells[1].faces, 12u);
    EXPECT_DOUBLE_EQ(r.shells[2].signed_volume, -1.0);
}

TEST(Topology, StlSoupGivesTheSameReportAsTheWeldedMesh) {
    Mesh welded;
    add_box(welded, {0, 0, 0}, {3, 3, 3});
    add_box(welded, {1, 1, 1}, {2, 2, 2}, {.inverted = true});
    const Mesh soup = unwelded(welded);
    ASSERT_EQ(soup.vertex_count(), 72u);
    const TopologyReport a = analyze(welded), b = analyze(soup);
    expect_same_counts(a, b);
    EXPECT_EQ(b.vertices_welded, 16u);
    EXPECT_EQ(b.cavities, 1u);

    const Mesh torus = quad_torus(9, 7);
    expect_same_counts(analyze(torus), analyze(unwelded(torus)));
}

TEST(Topology, NegativeZeroWeldsWithPositiveZero) {
    Mesh m = unwelded(tetrahedron());
    for (std::size_t v = 0; v < m.vertex_count(); v += 2)
        for (std::size_t k = 0; k < 3; ++k)
            if (m.positions[3 * v + k] == 0.0) m.positions[3 * v + k] = -0.0;
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.vertices_welded, 4u);
    EXPECT_EQ(r.edges, 6u);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 2);
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_DOUBLE_EQ(r.shells[0].signed_volume, 1.0 / 6);
}

TEST(Topology, NaNPositionsNeverWeld) {
    const double nan = std::nan("");
    const TopologyReport r = analyze(triangle({nan, 0, 0}, {nan, 0, 0}, {0, 1, 0}));
    EXPECT_EQ(r.vertices_welded, 3u);
    EXPECT_EQ(r.triangles_with_repeated_vertex, 0u);
    EXPECT_EQ(r.zero_area_triangles, 0u);
}

TEST(Topology, TriangleWithARepeatedVertex) {
    Mesh m = tetrahedron();
    m.add_triangle(1, 1, 2);  // sides 1->1 (degenerate), 1->2, 2->1
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.faces, 5u);
    EXPECT_EQ(r.triangles_with_repeated_vertex, 1u);
    EXPECT_EQ(r.zero_area_triangles, 1u);
    EXPECT_EQ(r.degenerate_edge_uses, 1u);
    EXPECT_EQ(r.edges, 6u);
    EXPECT_EQ(r.nonmanifold_edges, 1u);  // {1, 2} now has 4 uses, 2 each way
    EXPECT_EQ(r.unbalanced_edges, 0u);
    EXPECT_TRUE(r.closed_2_cycle);
    EXPECT_EQ(r.euler_characteristic, 3);  // 4 - 6 + 5
}

TEST(Topology, WeldedCornersMakeDegenerateSides) {
    Mesh m = tetrahedron();
    m.add_vertex(1, 0, 0);      // 4: same position as 1
    m.add_triangle(1, 4, 4);    // three degenerate sides, no edge at all
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.vertices_welded, 4u);
    EXPECT_EQ(r.triangles_with_repeated_vertex, 1u);
    EXPECT_EQ(r.zero_area_triangles, 1u);
    EXPECT_EQ(r.degenerate_edge_uses, 3u);
    EXPECT_EQ(r.edges, 6u);
    EXPECT_EQ(r.components_edge_connected, 2u);  // the edgeless face is a shell of its own
    EXPECT_EQ(r.components_vertex_connected, 1u);
    ASSERT_EQ(r.shells.size(), 2u);
    EXPECT_EQ(r.shells[1].faces, 1u);
    EXPECT_EQ(r.shells[1].edges, 0u);
    EXPECT_EQ(r.shells[1].vertices, 1u);
    EXPECT_EQ(r.shells[1].signed_volume, 0.0);
    EXPECT_EQ(r.shells[1].role, ShellRole::solid);  // balanced, volume 0, inside nothing
}

TEST(Topology, CollinearTriangleHasZeroArea) {
    Mesh m;
    m.add_vertex(0, 0, 0);
    m.add_vertex(0.1, 0.2, 0.3);
    m.add_vertex(0.2, 0.4, 0.6);  // exactly 2 × the previous one
    m.add_vertex(0.1 * 3, 0.2 * 3, 0.3 * 3);  // rounded: off the line
    m.add_triangle(0, 1, 2);
    m.add_triangle(0, 1, 3);
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.zero_area_triangles, 1u);
    EXPECT_EQ(r.triangles_with_repeated_vertex, 0u);
    EXPECT_EQ(r.degenerate_edge_uses, 0u);
}

TEST(Topology, FacesWithFewerThanThreeVerticesAreCountedOnly) {
    Mesh m = tetrahedron();
    m.add_vertex(5, 5, 5);  // 4: used by the 2-vertex face only
    m.add_face(std::array<uint32_t, 2>{0, 4});
    m.add_face(std::span<const uint32_t>{});
    m.add_face(std::array<uint32_t, 1>{3});
    const TopologyReport r = analyze(m);
    EXPECT_EQ(r.faces, 7u);
    EXPECT_EQ(r.faces_with_lt3_vertices, 3u);
    EXPECT_EQ(r.triangles, 4u);
    EXPECT_EQ(r.vertices_welded, 5u);
    EXPECT_EQ(r.vertices_referenced, 4u);
    EXPECT_EQ(r.edges, 6u);
    expect_closed_oriented_manifold(r);
    EXPECT_EQ(r.euler_characteristic, 2);
    EXPECT_EQ(r.components_edge_connected, 1u);
    EXPECT_EQ(r.components_vertex_connected, 1u);
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_EQ(r.shells[0].faces, 4u);
}

TEST(Topology, ShellVolumesAreCorrectlyRounded) {
    const TopologyReport r = analyze(box({1e8, 1e8, 1e8}, {1e8 + 1, 1e8 + 1, 1e8 + 1}));
    ASSERT_EQ(r.shells.size(), 1u);
    EXPECT_EQ(r.shells[0].signed_volume, 1.0);
    // A corner tetrahedron moved far away stays congruent (t + 1 is exact),
    // so its volume is 1/6 rounded once; naive sums about the origin lose
    // about 20 bits here.
    Mesh t = tetrahedron();
    for (std::size_t i = 0; i < t.positions.size(); ++i) t.positions[i] += 1e6 + 0.1 * static_cast<double>(i % 3 + 1);
    const TopologyReport moved = analyze(t);
    ASSERT_EQ(moved.shells.size(), 1u);
    EXPECT_EQ(moved.shells[0].signed_volume, 1.0 / 6);
}

TEST(Topology, ShellVolumesOutsideTheExactRangeAreStillComputed) {
    const double big = 0x1p+200, tiny = 0x1p-170;
    EXPECT_EQ(analyze(box({0, 0, 0}, {big, big, big})).shells.at(0).signed_volume, 0x1p+600);
    EXPECT_EQ(analyze(box({0, 0, 0}, {tiny, tiny, tiny})).shells.at(0).signed_volume, 0x1p-510);
    EXPECT_EQ(analyze(box({-big, 0, 0}, {big, 1, 1}, {.inverted = true})).shells.at(0).signed_volume, -0x1p+201);
}

TEST(Topology, RejectsBrokenArrays) {
    Mesh m = tetrahedron();
    m.indices[5] = 4;
    EXPECT_THROW(analyze(m), std::invalid_argument);
    Mesh q = unit_cube({.quads = true});
    q.face_offsets.back() = static_cast<uint32_t>(q.indices.size() + 1);
    EXPECT_THROW(analyze(q), std::invalid_argument);
    const std::vector<double> positions{0, 0, 0, 1};
    const std::vector<uint32_t> none;
    EXPECT_THROW(analyze_topology(MeshView{positions, none, none}), std::invalid_argument);
}

}  // namespace
}  // namespace polyvol

namespace polyvol {
namespace {

// A NaN or an infinite coordinate makes its shell's volume NaN (as
// measure's sums are), listed last; the other shells keep theirs.
TEST(Topology, NonFiniteCoordinatesDoNotBreakTheReport) {
    for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
        Mesh m;
        test::add_box(m, {0, 0, 0}, {1, 1, 1});
        test::add_box(m, {3, 0, 0}, {4, 1, 1});
        m.positions[3 * 9] = bad;  // one corner of the second box
        test::add_box(m, {6, 0, 0}, {8, 2, 2});
        const TopologyReport r = analyze_topology(m.view());
        EXPECT_EQ(r.components_edge_connected, 3u);
        ASSERT_EQ(r.shells.size(), 3u);
        EXPECT_EQ(r.shells[0].signed_volume, 8.0) << bad;
        EXPECT_EQ(r.shells[1].signed_volume, 1.0) << bad;
        EXPECT_TRUE(std::isnan(r.shells[2].signed_volume)) << bad;  // NaN last
    }
}

}  // namespace
}  // namespace polyvol

namespace polyvol {
namespace {

// Each shell's volume is correctly rounded for any finite coordinates, also
// outside the safe range 2^-160..2^190 (where the exact path needs big
// integers): a tetrahedron of generic coordinates, scaled by 2^195 and by
// 2^-200, has exactly 2^585 and 2^-600 times the volume of the unscaled
// one (scaling by a power of two is exact, and so is rounding the scaled
// value); ten unit boxes beside them keep their volume 1. (Some positions
// being out of the range, each shell is measured as its own soup.)
TEST(Topology, ShellVolumesAreCorrectlyRoundedOutsideTheSafeRange) {
    const double tet[4][3] = {{1.0000000000000002, -0.3333333333333333, 0.0017071067811865475},
                              {-1.9999999999999998, 1.1428571428571428, 1.4142135623730951},
                              {0.015, -1.9, -1.0999999999999999},
                              {1.2, 1.25, 1.9999999999999996}};
    const auto add_tet = [&](Mesh& m, double scale) {
        uint32_t v[4];
        for (int i = 0; i < 4; ++i) v[i] = m.add_vertex(tet[i][0] * scale, tet[i][1] * scale, tet[i][2] * scale);
        // Faces in one orientation; v1 below gives the sign.
        m.add_triangle(v[0], v[2], v[1]);
        m.add_triangle(v[0], v[1], v[3]);
        m.add_triangle(v[0], v[3], v[2]);
        m.add_triangle(v[1], v[2], v[3]);
    };
    Mesh unit;
    add_tet(unit, 1.0);
    const double v1 = analyze_topology(unit.view()).shells.at(0).signed_volume;
    ASSERT_NE(v1, 0.0);
    for (const bool with_boxes : {false, true}) {
        Mesh m;
        add_tet(m, 0x1p195);
        add_tet(m, 0x1p-200);
        for (int i = 0; with_boxes && i < 10; ++i) test::add_box(m, {10.0 + 2 * i, 0, 0}, {11.0 + 2 * i, 1, 1});
        const TopologyReport r = analyze_topology(m.view());
        ASSERT_EQ(r.shells.size(), with_boxes ? 12u : 2u);
        EXPECT_EQ(r.shells[0].signed_volume, std::ldexp(v1, 585)) << with_boxes;
        EXPECT_EQ(r.shells.back().signed_volume, std::ldexp(v1, -600)) << with_boxes;
        if (with_boxes) {
            EXPECT_EQ(r.shells[1].signed_volume, 1.0);
        }
    }
}

}  // namespace
}  // namespace polyvol
