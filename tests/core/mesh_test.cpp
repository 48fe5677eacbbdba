#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>
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

// The canonical ids by an ordered map (first index of each class; -0.0 as
// +0.0; NaN never welded), independent of weld_vertices.
std::vector<uint32_t> map_reference(const std::vector<double>& p, std::size_t* distinct) {
    std::vector<uint32_t> ref(p.size() / 3);
    std::map<std::array<double, 3>, uint32_t> first;
    *distinct = 0;
    for (std::size_t v = 0; v < ref.size(); ++v) {
        const std::array<double, 3> key{p[3 * v] + 0.0, p[3 * v + 1] + 0.0, p[3 * v + 2] + 0.0};  // -0.0 + 0.0 == +0.0
        if (std::isnan(key[0]) || std::isnan(key[1]) || std::isnan(key[2])) {
            ref[v] = static_cast<uint32_t>(v);
            continue;
        }
        const auto [it, inserted] = first.try_emplace(key, static_cast<uint32_t>(v));
        *distinct += inserted;
        ref[v] = it->second;
    }
    return ref;
}

// Positions with heavy duplication: x from 50 integers plus one of eight
// values (0, -0.0, NaN, 1e300, ...), y and z one of those values.
std::vector<double> duplicated_positions(std::size_t n, uint64_t state) {
    std::vector<double> p;
    auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return state >> 33;
    };
    const double values[] = {0.0, -0.0, 1.0, 0.5, -3.25, 1e300, 2.0000000000000004, std::nan("")};
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            const double v = values[next() % 8];
            p.push_back(k == 0 ? v + double(next() % 50) : v);  // -0.0 kept in y and z
        }
    return p;
}

// Against the map reference on many vertices (the partitioned path: buckets
// welded apart, on several threads), NaN never welded, and -0.0 in every
// coordinate.
TEST(Weld, ManyDuplicatesMatchAnOrderedMapReference) {
    const std::vector<double> p = duplicated_positions(200000, 12345);
    const auto w = polyvol::weld_vertices(p);
    ASSERT_EQ(w.size(), p.size() / 3);
    std::size_t distinct = 0;
    const std::vector<uint32_t> ref = map_reference(p, &distinct);
    for (std::size_t v = 0; v < w.size(); ++v) ASSERT_EQ(w[v], ref[v]) << "vertex " << v;
    EXPECT_GT(distinct, 1000u);
    EXPECT_LT(distinct, w.size() / 4);
}

// Both sides of the size where the partitioned path starts (2^16 vertices),
// and one where the last chunk and bucket are short.
TEST(Weld, SerialAndPartitionedPathsAgreeAtTheirBoundary) {
    for (const std::size_t n : {std::size_t{65535}, std::size_t{65536}, std::size_t{65537}, std::size_t{300001}}) {
        const std::vector<double> p = duplicated_positions(n, n);
        std::size_t distinct = 0;
        EXPECT_EQ(polyvol::weld_vertices(p), map_reference(p, &distinct)) << n << " vertices";
    }
}

// A triangle soup in strips, as an STL holds it (each grid point repeated
// up to six times, mostly close by, and across the 2^15-vertex runs that
// welding settles locally first), with -0.0 in some copies and a NaN
// vertex in every 997th triangle: against the map reference, for a grid
// whose runs leave few firsts (the second level in one table), one that
// leaves many (partitioned), and the latter with its triangles shuffled
// (copies far apart: the local level is skipped).
TEST(Weld, TriangleSoupMatchesAnOrderedMapReference) {
    struct Case {
        int w, h;
        bool shuffled;
    };
    for (const Case c : {Case{300, 100, false}, Case{1200, 100, false}, Case{1200, 100, true}}) {
        std::vector<std::array<int, 2>> corners;  // (i, j) of each triangle's corners, in order
        for (int j = 0; j + 1 < c.h; ++j)
            for (int i = 0; i + 1 < c.w; ++i)
                corners.insert(corners.end(), {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j}, {i + 1, j + 1}, {i, j + 1}});
        const std::size_t triangles = corners.size() / 3;
        std::vector<std::size_t> order(triangles);
        for (std::size_t t = 0; t < triangles; ++t) order[t] = c.shuffled ? (t * 7919) % triangles : t;
        ASSERT_TRUE(!c.shuffled || triangles % 7919 != 0);  // a permutation
        std::vector<double> p;
        for (std::size_t t = 0; t < triangles; ++t)
            for (int k = 0; k < 3; ++k) {
                const auto [i, j] = corners[3 * order[t] + k];
                const double x = i - c.w / 2, y = j - c.h / 2;
                p.push_back(t % 2 == 1 && x == 0 ? -0.0 : x);
                p.push_back(t % 997 == 5 ? std::nan("") : y);
                p.push_back(0.25 * x * y);
            }
        std::size_t distinct = 0;
        const std::vector<uint32_t> ref = map_reference(p, &distinct);
        EXPECT_EQ(polyvol::weld_vertices(p), ref) << c.w << " x " << c.h << (c.shuffled ? ", shuffled" : "");
        EXPECT_LT(distinct, p.size() / 3 / 5);  // about one vertex in six (NaN copies are distinct)

        // welded() on the soup: classes numbered in the order of their
        // firsts, each with its first's position, every corner mapped.
        polyvol::Mesh soup;
        soup.positions = p;
        for (uint32_t v = 0; v + 2 < p.size() / 3; v += 3) soup.add_triangle(v, v + 1, v + 2);
        const polyvol::Mesh w = polyvol::welded(soup.view());
        std::vector<uint32_t> number(ref.size());
        uint32_t classes = 0;
        for (std::size_t v = 0; v < ref.size(); ++v) number[v] = ref[v] == v ? classes++ : number[ref[v]];
        ASSERT_EQ(w.vertex_count(), classes);
        for (std::size_t v = 0; v < ref.size(); ++v) {
            ASSERT_EQ(w.indices[v], number[v]) << "corner " << v;
            for (int k = 0; ref[v] == v && k < 3; ++k)
                ASSERT_EQ(std::bit_cast<uint64_t>(w.positions[3 * number[v] + k]), std::bit_cast<uint64_t>(p[3 * v + k]))
                    << "class " << number[v];
        }
    }
}

// welded: equal positions become one vertex (first-of-class order, -0.0 with
// +0.0, NaN never), faces keep their order and sizes, measures unchanged.
TEST(Weld, WeldedMeshMergesEqualPositionsAndKeepsTheFaces) {
    polyvol::Mesh soup;  // a tetrahedron as a soup (3 vertices per face) plus a quad
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const uint32_t tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& t : tri) {
        const uint32_t a = soup.add_vertex(v[t[0]][0], v[t[0]][1], v[t[0]][2]);
        const uint32_t b = soup.add_vertex(v[t[1]][0], v[t[1]][1], v[t[1]][2]);
        const uint32_t c = soup.add_vertex(v[t[2]][0], v[t[2]][1], v[t[2]][2]);
        soup.add_triangle(a, b, c);
    }
    soup.positions[3 * 3] = -0.0;  // vertex 3 is (0,0,0) with a negative zero: welds with vertex 0
    const uint32_t n0 = soup.add_vertex(std::nan(""), 0, 0), n1 = soup.add_vertex(std::nan(""), 0, 0);
    const uint32_t quad[4] = {n0, n1, 0, 1};
    soup.add_face(quad);
    const polyvol::Mesh w = polyvol::welded(soup.view());
    ASSERT_EQ(w.vertex_count(), 6u);  // four corners and the two NaN vertices
    EXPECT_EQ((std::vector<double>(w.positions.begin(), w.positions.begin() + 12)),
              (std::vector<double>{0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1}));
    EXPECT_EQ(w.face_offsets, soup.face_offsets);
    EXPECT_EQ(w.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 1, 2, 1, 3, 4, 5, 0, 1}));
    for (std::size_t i = 0; i < soup.indices.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double a = soup.positions[3 * std::size_t{soup.indices[i]} + k];
            const double b = w.positions[3 * std::size_t{w.indices[i]} + k];
            EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << "index " << i;
        }
    // In place: the same mesh (positions compared as bits: NaN and -0).
    polyvol::Mesh in_place = soup;
    polyvol::weld_in_place(in_place);
    ASSERT_EQ(in_place.positions.size(), w.positions.size());
    EXPECT_EQ(std::memcmp(in_place.positions.data(), w.positions.data(), w.positions.size() * sizeof(double)), 0);
    EXPECT_EQ(in_place.indices, w.indices);
    EXPECT_EQ(in_place.face_offsets, w.face_offsets);
}
