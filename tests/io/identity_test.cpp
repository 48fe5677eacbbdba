// The same mesh written as ASCII STL, binary STL, OBJ, OFF and PLY (ascii,
// binary little and big endian) reads back to the same positions and faces
// (STL welded after its soup expansion: the facets' corners, three new
// vertices per facet, welded as polyvol::welded welds them).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/shapes.hpp"
#include "io_helpers.hpp"

namespace {

using namespace iotest;

std::vector<std::vector<uint32_t>> faces(const Mesh& m) {
    std::vector<std::vector<uint32_t>> f;
    for (std::size_t i = 0; i < m.face_count(); ++i) f.push_back(face_of(m, i));
    return f;
}

void expect_same(const Mesh& got, const Mesh& want) {
    EXPECT_EQ(got.positions, want.positions);
    EXPECT_EQ(faces(got), faces(want));
    // Signs of zeros too (EXPECT_EQ on doubles says -0 == 0).
    ASSERT_EQ(got.positions.size(), want.positions.size());
    for (std::size_t i = 0; i < got.positions.size(); ++i)
        EXPECT_EQ(std::signbit(got.positions[i]), std::signbit(want.positions[i])) << i;
}

struct Case {
    std::string name;
    std::string data;
    Format format;
    std::string encoding;
    bool is_stl;
};

std::vector<Case> cases(const Mesh& m, bool triangles) {
    std::vector<Case> c = {
        {"m.stl", write_ascii_stl(m), Format::stl, "ascii", true},
        {"m.obj", write_obj(m), Format::obj, "ascii", false},
        {"m.off", write_off(m), Format::off, "ascii", false},
        {"m.ply", write_ply(m, PlyEnc::ascii), Format::ply, "ascii", false},
        {"le.ply", write_ply(m, PlyEnc::le), Format::ply, "binary_le", false},
        {"be.ply", write_ply(m, PlyEnc::be), Format::ply, "binary_be", false},
    };
    if (triangles) c.push_back({"b.stl", write_binary_stl(m), Format::stl, "binary_le", true});
    return c;
}

void check_all(const Mesh& m, bool triangles) {
    // What an STL reader gives: the soup of the facets' corners, welded.
    const Mesh as_stl = polyvol::welded(polyvol::test::unwelded(m).view());
    EXPECT_EQ(as_stl.vertex_count(), m.vertex_count());
    for (const Case& c : cases(m, triangles)) {
        SCOPED_TRACE(c.name);
        // Detected by content: the name gives no hint.
        const LoadedMesh r = read(c.data, "noext");
        EXPECT_EQ(r.format, c.format);
        EXPECT_EQ(r.encoding, c.encoding);
        EXPECT_FALSE(r.gzip);
        expect_same(r.mesh, c.is_stl ? as_stl : m);
        EXPECT_EQ(r.vertices_in_file, c.is_stl ? m.indices.size() : m.vertex_count());
        // And the same through gzip.
        const LoadedMesh z = read(gzip_stored(c.data), c.name + ".gz");
        EXPECT_TRUE(z.gzip);
        ASSERT_FALSE(z.notes.empty());
        EXPECT_EQ(z.notes.front(), "gzip-compressed");
        expect_same(z.mesh, c.is_stl ? as_stl : m);
    }
}

TEST(Identity, TrianglesInEveryFormat) {
    const Mesh m = octahedron();
    EXPECT_TRUE(m.face_offsets.empty());
    check_all(m, true);
}

TEST(Identity, QuadsInEveryFormat) {
    const Mesh m = quad_cube();
    EXPECT_FALSE(m.face_offsets.empty());
    check_all(m, false);
}

TEST(Identity, DoublePrecisionTextKeepsEveryBit) {
    // Values that float32 would round: text formats must give the exact doubles.
    Mesh m;
    m.add_vertex(0.1, 1.0 / 3.0, -2.718281828459045);
    m.add_vertex(1e-310, 6.02214076e23, 0.30000000000000004);
    m.add_vertex(-123456.789, 9007199254740993.0, 5e-324);
    m.add_triangle(0, 1, 2);
    expect_same(read(write_ascii_stl(m), "d.stl").mesh, m);  // three distinct corners: welded, the same
    expect_same(read(write_obj(m), "d.obj").mesh, m);
    expect_same(read(write_off(m), "d.off").mesh, m);
    expect_same(read(write_ply(m, PlyEnc::ascii), "d.ply").mesh, m);
}

TEST(Identity, Utf16ObjReadsLikeItsAsciiText) {
    const std::string ascii = write_obj(quad_cube());
    for (bool be : {true, false}) {
        std::string u = be ? std::string("\xfe\xff") : std::string("\xff\xfe");
        for (char c : ascii) {
            if (be) u += '\0';
            u += c;
            if (!be) u += '\0';
        }
        const LoadedMesh r = read(u, "u.obj");
        EXPECT_EQ(r.format, Format::obj);
        expect_same(r.mesh, quad_cube());
        ASSERT_FALSE(r.notes.empty());
        EXPECT_EQ(r.notes.front(), be ? "utf16-be-bom" : "utf16-le-bom");
    }
}

TEST(Identity, ReadFileEqualsReadMemory) {
    const std::string path = std::string(POLYVOL_CORPUS_DIR) + "/meshes/libcgal-demo/tetrahedron.off";
    const LoadedMesh a = polyvol::read_mesh_file(path);
    std::FILE* f = std::fopen(path.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    std::string s;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
    std::fclose(f);
    const LoadedMesh b = read(s, path);
    expect_same(a.mesh, b.mesh);
    EXPECT_EQ(a.mesh.vertex_count(), 4u);
    EXPECT_EQ(a.mesh.face_count(), 4u);
    // "-" reads standard input (here redirected to the same file).
    ASSERT_NE(std::freopen(path.c_str(), "rb", stdin), nullptr);
    const LoadedMesh c = polyvol::read_mesh_file("-");
    EXPECT_EQ(c.format, Format::off);
    expect_same(c.mesh, a.mesh);
}

}  // namespace
