#include <gtest/gtest.h>

#include "polyvol/mesh.hpp"

using polyvol::Mesh;

TEST(Mesh, TrianglesStayOnTheFastPath) {
    Mesh m;
    m.add_vertex(0, 0, 0);
    m.add_vertex(1, 0, 0);
    m.add_vertex(0, 1, 0);
    m.add_triangle(0, 1, 2);
    m.add_triangle(0, 2, 1);
    EXPECT_TRUE(m.face_offsets.empty());
    EXPECT_EQ(m.view().face_count(), 2u);
    EXPECT_EQ(m.view().triangle_count(), 2u);
}

TEST(Mesh, APolygonSwitchesToCompressedRows) {
    Mesh m;
    for (int i = 0; i < 5; ++i) m.add_vertex(i, i * i, 0);
    m.add_triangle(0, 1, 2);
    const uint32_t quad[] = {0, 1, 3, 4};
    m.add_face(quad);
    const uint32_t edge[] = {1, 2};
    m.add_face(edge);
    const auto v = m.view();
    ASSERT_EQ(v.face_count(), 3u);
    EXPECT_EQ(v.face_size(0), 3u);
    EXPECT_EQ(v.face_size(1), 4u);
    EXPECT_EQ(v.face_size(2), 2u);
    EXPECT_EQ(v.face(1)[2], 3u);
    EXPECT_EQ(v.triangle_count(), 3u);  // 1 + 2 + 0
}

TEST(Weld, BitIdenticalAndSignedZero) {
    const double p[] = {0.0, 1.0, 2.0,  -0.0, 1.0, 2.0,  0.0, 1.0, 2.0000000000000004,  0.0, 1.0, 2.0};
    const auto w = polyvol::weld_vertices(p);
    ASSERT_EQ(w.size(), 4u);
    EXPECT_EQ(w[0], 0u);
    EXPECT_EQ(w[1], 0u);  // -0.0 welds with +0.0
    EXPECT_EQ(w[2], 2u);  // one ulp apart: distinct
    EXPECT_EQ(w[3], 0u);
}
