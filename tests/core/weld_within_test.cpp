// weld_within: points within the tolerance merge, transitively, onto the
// first of them; others, and NaN points, stay.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "polyvol/mesh.hpp"

namespace {

using polyvol::Mesh;

TEST(WeldWithin, MergesChainsOntoTheFirstPoint) {
    Mesh m;
    m.add_vertex(0, 0, 0);
    m.add_vertex(1, 0, 0);
    m.add_vertex(0.6e-9, 0, 0);  // within 1e-9 of vertex 0
    m.add_vertex(1.5e-9, 0, 0);  // within 1e-9 of vertex 2 only: chained to 0
    m.add_vertex(1, 2e-9, 0);    // too far from vertex 1
    m.add_triangle(0, 1, 4);
    m.add_triangle(2, 3, 1);
    const polyvol::ToleranceWeld w = polyvol::weld_within(m, 1e-9);
    EXPECT_EQ(w.moved, 2u);
    EXPECT_DOUBLE_EQ(w.largest_move, 1.5e-9);  // more than the tolerance, by chaining
    ASSERT_EQ(m.vertex_count(), 3u);
    EXPECT_EQ(m.positions[0], 0.0);  // the first point keeps its position
    EXPECT_EQ(m.indices[3], m.indices[0]);
    EXPECT_EQ(m.indices[4], m.indices[0]);
    EXPECT_NE(m.indices[2], m.indices[1]);
}

TEST(WeldWithin, NeighbouringCellsAndNaN) {
    Mesh m;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    m.add_vertex(0.999999, 2.0000001, -0.0000005);  // across cell borders from the next
    m.add_vertex(1.0000001, 1.999999, 0.0000004);
    m.add_vertex(nan, 0, 0);
    m.add_vertex(nan, 0, 0);
    m.add_triangle(0, 1, 2);
    m.add_triangle(1, 2, 3);
    const polyvol::ToleranceWeld w = polyvol::weld_within(m, 1e-5);
    EXPECT_EQ(w.moved, 1u);
    EXPECT_EQ(m.vertex_count(), 3u);  // two NaN points stay two
    EXPECT_THROW(polyvol::weld_within(m, 0), std::invalid_argument);
    EXPECT_THROW(polyvol::weld_within(m, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

// A tolerance far below the coordinates' spacing (1e-17 at 100: the
// doubles there are 1.4e-14 apart) merges only equal points, at once.
TEST(WeldWithin, ATinyToleranceMergesOnlyEqualPoints) {
    Mesh m;
    for (int i = 0; i < 200000; ++i) m.add_vertex(100 + i * 0x1p-40, 100, 100);
    m.add_vertex(100, 100, 100);  // equal to the first
    const polyvol::ToleranceWeld w = polyvol::weld_within(m, 1e-17);
    EXPECT_EQ(w.moved, 0u);
    EXPECT_EQ(m.vertex_count(), 200000u);
}

}  // namespace
