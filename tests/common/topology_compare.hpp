// Comparing two topology reports field by field, for the test programs
// that check that two readings or two forms of a mesh agree.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>

#include "polyvol/topology.hpp"

namespace polyvol::test {

// Every count, flag and shell figure (the shells' volumes to a few ulps).
inline void expect_same_counts(const TopologyReport& a, const TopologyReport& b) {
    EXPECT_EQ(a.faces, b.faces);
    EXPECT_EQ(a.faces_with_lt3_vertices, b.faces_with_lt3_vertices);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.vertices_welded, b.vertices_welded);
    EXPECT_EQ(a.vertices_referenced, b.vertices_referenced);
    EXPECT_EQ(a.edges, b.edges);
    EXPECT_EQ(a.boundary_edges, b.boundary_edges);
    EXPECT_EQ(a.nonmanifold_edges, b.nonmanifold_edges);
    EXPECT_EQ(a.misoriented_edges, b.misoriented_edges);
    EXPECT_EQ(a.unbalanced_edges, b.unbalanced_edges);
    EXPECT_EQ(a.degenerate_edge_uses, b.degenerate_edge_uses);
    EXPECT_EQ(a.triangles_with_repeated_vertex, b.triangles_with_repeated_vertex);
    EXPECT_EQ(a.zero_area_triangles, b.zero_area_triangles);
    EXPECT_EQ(a.euler_characteristic, b.euler_characteristic);
    EXPECT_EQ(a.components_vertex_connected, b.components_vertex_connected);
    EXPECT_EQ(a.components_edge_connected, b.components_edge_connected);
    EXPECT_EQ(a.closed, b.closed);
    EXPECT_EQ(a.edge_manifold, b.edge_manifold);
    EXPECT_EQ(a.consistently_oriented, b.consistently_oriented);
    EXPECT_EQ(a.closed_2_cycle, b.closed_2_cycle);
    ASSERT_EQ(a.shells.size(), b.shells.size());
    for (std::size_t s = 0; s < a.shells.size(); ++s) {
        EXPECT_EQ(a.shells[s].faces, b.shells[s].faces);
        EXPECT_EQ(a.shells[s].vertices, b.shells[s].vertices);
        EXPECT_EQ(a.shells[s].edges, b.shells[s].edges);
        EXPECT_EQ(a.shells[s].role, b.shells[s].role);
        EXPECT_DOUBLE_EQ(a.shells[s].signed_volume, b.shells[s].signed_volume);
    }
}

}  // namespace polyvol::test
