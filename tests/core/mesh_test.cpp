#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

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

// Against a std::map reference on many vertices with heavy duplication (the
// open-addressing table grows past its probe runs), NaN never welded, and
// -0.0 in every coordinate.
TEST(Weld, ManyDuplicatesMatchAnOrderedMapReference) {
    std::vector<double> p;
    uint64_t state = 12345;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return state >> 33;
    };
    const double values[] = {0.0, -0.0, 1.0, 0.5, -3.25, 1e300, 2.0000000000000004, std::nan("")};
    for (int i = 0; i < 200000; ++i)
        for (int k = 0; k < 3; ++k) {
            const double v = values[next() % 8];
            p.push_back(k == 0 ? v + double(next() % 50) : v);  // -0.0 kept in y and z
        }
    const auto w = polyvol::weld_vertices(p);
    ASSERT_EQ(w.size(), p.size() / 3);
    std::map<std::array<double, 3>, uint32_t> first;
    std::size_t distinct = 0;
    for (std::size_t v = 0; v < w.size(); ++v) {
        const std::array<double, 3> key{p[3 * v] + 0.0, p[3 * v + 1] + 0.0, p[3 * v + 2] + 0.0};  // -0.0 + 0.0 == +0.0
        if (std::isnan(key[0]) || std::isnan(key[1]) || std::isnan(key[2])) {
            EXPECT_EQ(w[v], v);
            continue;
        }
        const auto [it, inserted] = first.try_emplace(key, static_cast<uint32_t>(v));
        distinct += inserted;
        ASSERT_EQ(w[v], it->second) << "vertex " << v;
    }
    EXPECT_GT(distinct, 1000u);
    EXPECT_LT(distinct, w.size() / 4);
}
