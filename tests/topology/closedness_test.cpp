// fingerprint_closedness (polyvol/topology.hpp) against the manifest's
// closed_2_cycle on every corpus mesh, on both of its paths (a hash per
// vertex, a hash per corner), and on surfaces opened or kept closed in every
// way topology.hpp distinguishes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "common/shapes.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"
#include "polyvol/mesh.hpp"

namespace {

using namespace polyvol;

// The mesh with unused vertices appended until there are more vertices than
// half the indices: fingerprint_closedness then hashes every corner instead
// of every vertex once.
Mesh with_unused_vertices(const Mesh& m) {
    Mesh out = m;
    while (out.indices.size() >= 2 * out.vertex_count()) out.add_vertex(1e300, -3.5, 0.25);
    return out;
}

// The mesh with each face added again, forwards and reversed (a balanced
// pair), until there are at least two indices per vertex: the vertices are
// then hashed once each. Unchanged when no face has three vertices.
Mesh with_face_pairs(const Mesh& m) {
    Mesh out = m;
    std::vector<std::size_t> faces;
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (m.view().face_size(f) >= 3) faces.push_back(f);
    for (std::size_t k = 0; !faces.empty() && out.indices.size() < 2 * out.vertex_count(); ++k) {
        const auto face = m.view().face(faces[k % faces.size()]);
        std::vector<uint32_t> v(face.begin(), face.end());
        out.add_face(v);
        std::reverse(v.begin(), v.end());
        out.add_face(v);
    }
    return out;
}

Closedness expected(const nlohmann::json& e) {
    return e["topology"]["closed_2_cycle"].get<bool>() ? Closedness::closed : Closedness::open;
}

TEST(Closedness, EveryCorpusMeshAgreesWithTheManifestOnBothPaths) {
    int closed = 0, open = 0;
    for (const nlohmann::json& e : test::corpus_manifest()) {
        if (test::invalid_entry(e)) continue;
        const std::string path = e.at("path").get<std::string>();
        SCOPED_TRACE(path);
        const LoadedMesh loaded = read_mesh_file(test::corpus_file(path));
        const Mesh& m = loaded.mesh;
        const Closedness want = expected(e);
        (want == Closedness::closed ? closed : open) += 1;
        const bool shared = m.indices.size() >= 2 * m.vertex_count();
        const Mesh other = shared ? with_unused_vertices(m) : with_face_pairs(welded(m.view()));
        if (m.view().triangle_count() > 0) {
            ASSERT_NE(other.indices.size() >= 2 * other.vertex_count(), shared);
        }
        for (uint64_t seed : {1u, 2u}) {
            EXPECT_EQ(fingerprint_closedness(m.view(), seed), want);
            EXPECT_EQ(fingerprint_closedness(other.view(), seed), want);
        }
        EXPECT_EQ(fingerprint_closedness(m.view()), want);  // keys from std::random_device
    }
    EXPECT_GE(closed, 50);
    EXPECT_GE(open, 10);
}

// The unit cube as six quads (common/shapes.hpp: vertex i at corner
// (i & 1, i >> 1 & 1, i >> 2 & 1); face 0 is {0, 2, 3, 1}, face 2 {0, 1, 5, 4}).
Mesh cube() { return test::box({0, 0, 0}, {1, 1, 1}, {.quads = true}); }

// Faces of m, the k-th replaced by `face` (or dropped when empty), plus `extra`.
Mesh edited(const Mesh& m, std::size_t k, std::vector<uint32_t> face, std::vector<std::vector<uint32_t>> extra = {}) {
    Mesh out;
    out.positions = m.positions;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto old = m.view().face(f);
        if (f != k) out.add_face(old);
        else if (!face.empty()) out.add_face(face);
    }
    for (const auto& f : extra) out.add_face(f);
    return out;
}

// Both paths (indexed and as a soup), two keys.
void expect_closedness(const Mesh& m, Closedness want) {
    for (const Mesh& x : {m, test::unwelded(m), with_unused_vertices(m)})
        for (uint64_t seed : {7u, 8u}) EXPECT_EQ(fingerprint_closedness(x.view(), seed), want);
}

TEST(Closedness, OpenedOrStillClosedSurfaces) {
    const Mesh c = cube();
    {
        SCOPED_TRACE("closed");
        expect_closedness(c, Closedness::closed);
    }
    {
        SCOPED_TRACE("a face removed: a hole");
        expect_closedness(edited(c, 0, {}), Closedness::open);
    }
    {
        SCOPED_TRACE("a face flipped: its edges used twice the same way");
        expect_closedness(edited(c, 0, {0, 1, 3, 2}), Closedness::open);
    }
    {
        SCOPED_TRACE("a face twice: unbalanced by one");
        expect_closedness(edited(c, 0, {0, 2, 3, 1}, {{0, 2, 3, 1}}), Closedness::open);
    }
    {
        SCOPED_TRACE("a face and its flip added: balanced");
        expect_closedness(edited(c, 0, {0, 2, 3, 1}, {{0, 2, 3, 1}, {0, 1, 3, 2}}), Closedness::closed);
    }
    {
        SCOPED_TRACE("a quad as two triangles, the other diagonal");
        expect_closedness(edited(c, 0, {0, 2, 3}, {{0, 3, 1}}), Closedness::closed);
        expect_closedness(edited(c, 0, {2, 3, 1}, {{2, 1, 0}}), Closedness::closed);
    }
    {
        SCOPED_TRACE("faces with fewer than three vertices and degenerate triangles add nothing");
        expect_closedness(edited(c, 0, {0, 2, 3, 1}, {{4, 5}, {6}, {0, 0, 7}, {2, 3, 2}}), Closedness::closed);
    }
    {
        SCOPED_TRACE("a quad split at a new midpoint of an edge: a T-junction leaves that edge unbalanced");
        Mesh t = c;
        const uint32_t mid = t.add_vertex(0.5, 0, 0);  // on edge 0-1, shared by faces 0 and 2
        expect_closedness(edited(t, 0, {0, 2, 3, 1, mid}), Closedness::open);
    }
}

TEST(Closedness, EqualPointsAreOnePointWhateverTheirIndex) {
    // The cube with one corner duplicated (another index, the same point,
    // one copy as -0.0): the faces using either copy still close.
    Mesh c = cube();
    const uint32_t copy = c.add_vertex(-0.0, 0, -0.0);  // vertex 0 = (0, 0, 0)
    Mesh m = edited(c, 2, {copy, 1, 5, 4});
    expect_closedness(m, Closedness::closed);
    // A point only close to vertex 0 is another point: open.
    Mesh near = c;
    near.positions[3 * copy] = std::numeric_limits<double>::denorm_min();
    expect_closedness(edited(near, 2, {copy, 1, 5, 4}), Closedness::open);
}

TEST(Closedness, NonFiniteCoordinatesLeaveItUndecidedOnlyWhenUsed) {
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        // Vertex 0 starts three of the quads' fans, vertex 5 never does.
        for (const int v : {0, 5}) {
            Mesh c = cube();
            c.positions[3 * v + 1] = bad;
            expect_closedness(c, Closedness::undecided);
        }
        // An unused vertex does not matter.
        Mesh unused = cube();
        unused.add_vertex(bad, 0, 0);
        expect_closedness(unused, Closedness::closed);
    }
}

TEST(Closedness, LargePolygonsAndManyFaces) {
    // A prism over a 1000-gon: two 1000-vertex caps and 1000 quads.
    const int n = 1000;
    Mesh m;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * 3.141592653589793 * k / n;
        m.add_vertex(std::cos(a), std::sin(a), 0);
        m.add_vertex(std::cos(a), std::sin(a), 1);
    }
    std::vector<uint32_t> bottom, top;
    for (int k = 0; k < n; ++k) {
        bottom.push_back(static_cast<uint32_t>(2 * (n - 1 - k)));
        top.push_back(static_cast<uint32_t>(2 * k + 1));
        const uint32_t a = 2 * k, b = 2 * ((k + 1) % n);
        const uint32_t q[4] = {a, b, b + 1, a + 1};
        m.add_face(q);
    }
    m.add_face(bottom);
    m.add_face(top);
    expect_closedness(m, Closedness::closed);
    top.pop_back();  // the top cap's last edge replaced by a chord: open
    expect_closedness(edited(m, m.face_count() - 1, top), Closedness::open);
}

}  // namespace
