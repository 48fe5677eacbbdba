// Format features and quirks, one small file each, with the values they must
// read to and the notes they must leave.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "io_helpers.hpp"

namespace {

using namespace iotest;

bool has_note(const LoadedMesh& m, const std::string& note) {
    return std::find(m.notes.begin(), m.notes.end(), note) != m.notes.end();
}

std::string notes(const LoadedMesh& m) {
    std::string s;
    for (const auto& n : m.notes) s += n + "; ";
    return s;
}

std::vector<std::size_t> sizes(const Mesh& m) {
    std::vector<std::size_t> s;
    for (std::size_t f = 0; f < m.face_count(); ++f) s.push_back(m.view().face_size(f));
    return s;
}

// ---- detection -------------------------------------------------------------

TEST(Detect, FormatNamesAndExtensions) {
    EXPECT_EQ(polyvol::format_name(Format::stl), "stl");
    EXPECT_EQ(polyvol::format_name(Format::obj), "obj");
    EXPECT_EQ(polyvol::format_name(Format::off), "off");
    EXPECT_EQ(polyvol::format_name(Format::ply), "ply");
    EXPECT_EQ(polyvol::format_name(Format::threemf), "3mf");
    EXPECT_EQ(polyvol::format_name(Format::amf), "amf");
    EXPECT_EQ(polyvol::format_name(Format::unknown), "unknown");
    using polyvol::format_from_extension;
    EXPECT_EQ(format_from_extension("a/b/c.STL"), Format::stl);
    EXPECT_EQ(format_from_extension("x.stl.gz"), Format::stl);
    EXPECT_EQ(format_from_extension("x.Obj.GZ"), Format::obj);
    EXPECT_EQ(format_from_extension("x.off"), Format::off);
    EXPECT_EQ(format_from_extension("x.ply"), Format::ply);
    EXPECT_EQ(format_from_extension("x.3mf"), Format::threemf);
    EXPECT_EQ(format_from_extension("x.amf"), Format::amf);
    EXPECT_EQ(format_from_extension("x.gz"), Format::unknown);
    EXPECT_EQ(format_from_extension("dir.obj/file"), Format::unknown);
    EXPECT_EQ(format_from_extension(".stl"), Format::unknown);
    EXPECT_EQ(format_from_extension("-"), Format::unknown);
    EXPECT_EQ(format_from_extension(""), Format::unknown);
}

TEST(Detect, ContentBeatsTheExtension) {
    const std::string obj = write_obj(quad_cube());
    EXPECT_EQ(read(obj, "wrong.stl").format, Format::obj);
    EXPECT_EQ(read(write_off(quad_cube()), "wrong.ply").format, Format::off);
    EXPECT_EQ(read(write_ply(quad_cube(), PlyEnc::le), "wrong.obj").format, Format::ply);
    EXPECT_EQ(read(write_binary_stl(octahedron()), "wrong.off").format, Format::stl);
    // A hint overrides the extension where content cannot decide.
    EXPECT_EQ(read("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "counts.txt", Format::off).format, Format::off);
}

TEST(Detect, ZipGoesTo3mfOrAmf) {
    // Not valid archives: only the dispatch is checked, through the error of
    // the reader that was chosen (which names the file).
    const std::string tmf = std::string("PK\x03\x04", 4) + "....3D/3dmodel.model....";
    const std::string amf = std::string("PK\x03\x04", 4) + "....model.amf....";
    const ReadError a = read_error(tmf, "a.zip");
    const ReadError b = read_error(amf, "b.zip");
    EXPECT_NE(std::string(a.what()).find("a.zip"), std::string::npos);
    EXPECT_NE(std::string(b.what()).find("b.zip"), std::string::npos);
}

// ---- STL -------------------------------------------------------------------

TEST(Stl, BinaryIsDecidedBySizeEvenWithASolidHeader) {
    const Mesh m = octahedron();
    const LoadedMesh r = read(write_binary_stl(m, "solid looks like ascii"), "s.stl");
    EXPECT_EQ(r.encoding, "binary_le");
    EXPECT_EQ(r.vertices_in_file, 24u);
    EXPECT_EQ(r.mesh.vertex_count(), 6u);  // welded
    EXPECT_EQ(r.mesh.face_count(), 8u);
    EXPECT_TRUE(r.mesh.face_offsets.empty());
    EXPECT_TRUE(has_note(r, "binary-stl-header-starts-with-solid")) << notes(r);
    EXPECT_FALSE(has_note(r, "stl-nonzero-attribute-bytes"));
    // Float32 widened exactly.
    std::string s = write_binary_stl(m);
    const float third = 1.0f / 3.0f;
    std::string f;
    put_f32(f, third);
    s.replace(84 + 12, 4, f);
    s[84 + 48] = 1;  // attribute bytes
    const LoadedMesh t = read(s, "t.stl");
    EXPECT_EQ(t.mesh.positions[0], static_cast<double>(third));
    EXPECT_TRUE(has_note(t, "stl-nonzero-attribute-bytes"));
    // A zero-triangle binary file.
    std::string empty(80, ' ');
    put_u32(empty, 0);
    EXPECT_EQ(read(empty, "e.stl").mesh.face_count(), 0u);
}

TEST(Stl, AsciiQuirks) {
    const std::string facet =
        "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n";
    // Two solids, the second without endsolid; CRLF line ends; upper case keywords.
    std::string two = "solid a\r\n" + facet + "endsolid a\r\nSOLID b\r\nFACET NORMAL 0 0 1\r\nOUTER LOOP\r\n"
                      "VERTEX 2 0 0\r\nVERTEX 3 0 0\r\nVERTEX 2 1 0\r\nENDLOOP\r\nENDFACET\r\n";
    LoadedMesh r = read(two, "two.stl");
    EXPECT_EQ(r.mesh.face_count(), 2u);
    EXPECT_EQ(r.mesh.positions[9], 2.0);
    EXPECT_TRUE(has_note(r, "stl-multiple-solids(2)")) << notes(r);
    EXPECT_TRUE(has_note(r, "stl-missing-endsolid")) << notes(r);
    // Name mismatch; an endsolid without a name is no mismatch.
    r = read("solid a b\n" + facet + "endsolid a\n", "mm.stl");
    EXPECT_TRUE(has_note(r, "stl-endsolid-name-mismatch"));
    r = read("solid a b\n" + facet + "endsolid\n", "nm.stl");
    EXPECT_TRUE(r.notes.empty()) << notes(r);
    // Normals: unparseable, missing.
    r = read("solid\nfacet normal -1.#IND00 0 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n"
             " endloop\nendfacet\nendsolid\n",
             "n.stl");
    EXPECT_TRUE(has_note(r, "stl-unparseable-normal")) << notes(r);
    EXPECT_EQ(r.mesh.face_count(), 1u);
    r = read("solid\nfacet\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\nendsolid\n",
             "w.stl");
    EXPECT_TRUE(has_note(r, "stl-facet-without-normal")) << notes(r);
    // Everything on one line.
    r = read("solid x facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet endsolid x",
             "one.stl");
    EXPECT_EQ(r.mesh.face_count(), 0u);  // "x facet normal ..." is the solid's name line
    r = read("solid x\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet endsolid x",
             "one.stl");
    EXPECT_EQ(r.mesh.face_count(), 1u);
    // Trailing NUL padding is tolerated.
    r = read("solid\n" + facet + "endsolid\n" + std::string(20, '\0'), "pad.stl");
    EXPECT_EQ(r.mesh.face_count(), 1u);
}

TEST(Stl, LoopsOfOtherSizesArePolygons) {
    const std::string s =
        "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n"
        "facet normal 0 0 1\nouter loop\nvertex 5 5 5\nvertex 6 5 5\nvertex 5 6 5\nendloop\nendfacet\nendsolid q\n";
    const LoadedMesh r = read(s, "q.stl");
    EXPECT_EQ(r.vertices_in_file, 9u);
    EXPECT_EQ(r.mesh.vertex_count(), 7u);  // the 2-vertex loop's are the quad's first two
    EXPECT_EQ(sizes(r.mesh), (std::vector<std::size_t>{4, 2, 3}));
    EXPECT_EQ(r.mesh.view().triangle_count(), 3u);
    EXPECT_EQ(face_of(r.mesh, 1), (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(face_of(r.mesh, 2), (std::vector<uint32_t>{4, 5, 6}));
    EXPECT_EQ(r.mesh.positions[3 * 6], 5.0);
    EXPECT_EQ(r.mesh.positions[3 * 6 + 1], 6.0);
    EXPECT_TRUE(has_note(r, "stl-loop-with-4-vertices"));
    EXPECT_TRUE(has_note(r, "stl-loop-with-2-vertices"));
}

// ---- OBJ -------------------------------------------------------------------

TEST(Obj, IndexFormsGroupsAndElements) {
    const std::string s =
        "# comment\r\n"
        "mtllib x.mtl\r\n"
        "o first\r\n"
        "v 0 0 0\r\n"
        "v 1 0 0 1.0\r\n"
        "v 1 1 0 0.5 0.5 0.5\r\n"
        "v 0 1 0\r\n"
        "vt 0 0\r\nvn 0 0 1\r\n"
        "g second\r\n"
        "usemtl m\r\ns off\r\n"
        "f 1/1/1 2/1/1 3/1/1\r\n"
        "f 1//1 2//1 \\\r\n"
        "  3//1 4//1 # a quad continued on the next line\r\n"
        "f -4 -2 -1\r\n"
        "l 1 2\r\np 3\r\n"
        "f 1 2";  // no final newline; a 2-corner face
    const LoadedMesh r = read(s, "o.obj");
    EXPECT_EQ(r.mesh.vertex_count(), 4u);
    EXPECT_EQ(sizes(r.mesh), (std::vector<std::size_t>{3, 4, 3, 2}));
    EXPECT_EQ(face_of(r.mesh, 0), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(face_of(r.mesh, 1), (std::vector<uint32_t>{0, 1, 2, 3}));
    EXPECT_EQ(face_of(r.mesh, 2), (std::vector<uint32_t>{0, 2, 3}));
    EXPECT_EQ(face_of(r.mesh, 3), (std::vector<uint32_t>{0, 1}));
    for (const char* n : {"obj-slash-index-syntax", "obj-negative-indices", "obj-vertex-colors",
                          "obj-multiple-groups-or-objects", "obj-line-elements-ignored(1)",
                          "obj-point-elements-ignored(1)", "obj-face-with-2-vertices"})
        EXPECT_TRUE(has_note(r, n)) << n << ": " << notes(r);
    EXPECT_FALSE(has_note(r, "obj-vertex-w-not-1(ignored)"));
    EXPECT_TRUE(has_note(read("v 0 0 0 2\n", "w.obj"), "obj-vertex-w-not-1(ignored)"));
}

TEST(Obj, QuadContinuedOverALine) {
    const LoadedMesh r = read("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\n3 4\nf 1 2 3\n", "c.obj");
    ASSERT_EQ(r.mesh.face_count(), 2u);
    EXPECT_EQ(face_of(r.mesh, 0), (std::vector<uint32_t>{0, 1, 2, 3}));
    EXPECT_EQ(face_of(r.mesh, 1), (std::vector<uint32_t>{0, 1, 2}));
    // The line after the continuation is counted: an error there has the right line.
    const ReadError e = read_error("v 0 0 0\nf 1 \\\n1 1\nf 0 1 1\n", "c2.obj");
    EXPECT_EQ(e.line, 4u);
}

TEST(Obj, ForwardReferencesAreResolvedAtTheEnd) {
    const LoadedMesh r = read("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "fwd.obj");
    EXPECT_EQ(r.mesh.face_count(), 1u);
    EXPECT_EQ(face_of(r.mesh, 0), (std::vector<uint32_t>{0, 1, 2}));
}

TEST(Obj, FacesKeepFileOrderAcrossGroups) {
    const LoadedMesh r = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng a\nf 1 2 3\ng b\nf 1 2 4\ng a\nf 2 3 4\n", "g.obj");
    ASSERT_EQ(r.mesh.face_count(), 3u);
    EXPECT_EQ(face_of(r.mesh, 0), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(face_of(r.mesh, 1), (std::vector<uint32_t>{0, 1, 3}));
    EXPECT_EQ(face_of(r.mesh, 2), (std::vector<uint32_t>{1, 2, 3}));
}

// ---- OFF -------------------------------------------------------------------

TEST(Off, HeadersColoursCommentsAndTrailingData) {
    const std::string body = "3 1 0\n0 0 0 # first\n1 0 0\n0 1 0\n3 0 1 2\n";
    for (const char* h : {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCNOFF"}) {
        const LoadedMesh r = read(std::string(h) + "\n" + body, "h.off");
        EXPECT_EQ(r.mesh.face_count(), 1u) << h;
        EXPECT_EQ(has_note(r, std::string("off-header-") + h), std::string(h) != "OFF") << h << notes(r);
    }
    // nOFF with dimension 3; counts on the keyword line.
    EXPECT_EQ(read("nOFF\n3\n" + body, "n.off").mesh.face_count(), 1u);
    EXPECT_EQ(read("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "l.off").mesh.face_count(), 1u);
    // Colours on vertices and faces, comments everywhere, CRLF, trailing data.
    const LoadedMesh r = read(
        "# leading comment\r\nCOFF\r\n# another\r\n4 2 0\r\n\r\n0 0 0 255 0 0 255\r\n1 0 0 0 255 0 255#c\r\n"
        "1 1 0 0 0 255 255\r\n0 1 0 1 1 1 1\r\n3 0 1 2 0.5 0.5 0.5\r\n# between faces\r\n3 0 2 3\r\n"
        "3 1 2 3\r\n\r\n",
        "c.off");
    EXPECT_EQ(r.mesh.vertex_count(), 4u);
    EXPECT_EQ(r.mesh.face_count(), 2u);
    EXPECT_EQ(r.mesh.positions, (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}));
    for (const char* n : {"off-header-COFF", "off-vertex-extra-values(4)", "off-face-colors", "off-trailing-data(1 lines)"})
        EXPECT_TRUE(has_note(r, n)) << n << ": " << notes(r);
}

TEST(Off, MissingHeaderWithTheHint) {
    const std::string s = "# comment\n3 1 3\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const LoadedMesh r = read(s, "x.off");
    EXPECT_EQ(r.format, Format::off);
    EXPECT_EQ(r.mesh.face_count(), 1u);
    EXPECT_TRUE(has_note(r, "off-missing-header"));
    EXPECT_THROW(read(s, "x.dat"), ReadError);  // no hint: not recognised
}

TEST(Off, FacesMaySpanLinesAndHaveAnySize) {
    const LoadedMesh r = read("OFF\n5 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n5 0 1\n2 3 4\n0\n2 3 4\n", "s.off");
    EXPECT_EQ(sizes(r.mesh), (std::vector<std::size_t>{5, 0, 2}));
    EXPECT_EQ(face_of(r.mesh, 0), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(r.mesh.view().triangle_count(), 3u);
}

// ---- PLY -------------------------------------------------------------------

TEST(Ply, AnyTypesOrderAndOtherElementsBinaryBigEndian) {
    // Vertex after face, double z, short y, list properties in other elements.
    std::string s =
        "ply\r\nformat binary_big_endian 1.0\r\ncomment c\r\nobj_info o\r\nsome unknown line\r\n"
        "element material 1\r\nproperty list ushort float weights\r\nproperty uchar id\r\n"
        "element face 2\r\nproperty uchar flags\r\nproperty list uint8 uint16 vertex_index\r\nproperty float q\r\n"
        "element vertex 4\r\nproperty double z\r\nproperty int16 y\r\nproperty list uchar int texcoord\r\n"
        "property float32 x\r\nend_header\r\n";
    // material: 2 weights, id
    put_u16(s, 2, true);
    put_f32(s, 1.5f, true);
    put_f32(s, 2.5f, true);
    s += '\x09';
    // faces
    s += '\x01';
    s += '\x03';
    for (int i : {0, 1, 2}) put_u16(s, static_cast<uint16_t>(i), true);
    put_f32(s, 0.0f, true);
    s += '\x00';
    s += '\x04';
    for (int i : {0, 1, 2, 3}) put_u16(s, static_cast<uint16_t>(i), true);
    put_f32(s, 0.0f, true);
    // vertices: z (double), y (int16), texcoord list, x (float)
    const double zs[] = {0.1, -0.2, 0.3, 1e300};
    const int16_t ys[] = {-1, 2, -300, 32767};
    const float xs[] = {0.5f, 1.25f, -7.0f, 3.0e38f};
    for (int i = 0; i < 4; ++i) {
        put_f64(s, zs[i], true);
        put_u16(s, static_cast<uint16_t>(ys[i]), true);
        s += static_cast<char>(i % 3);
        for (int k = 0; k < i % 3; ++k) put_u32(s, 77, true);
        put_f32(s, xs[i], true);
    }
    const LoadedMesh r = read(s, "be.ply");
    EXPECT_EQ(r.encoding, "binary_be");
    ASSERT_EQ(r.mesh.vertex_count(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(r.mesh.positions[3 * i], static_cast<double>(xs[i]));
        EXPECT_EQ(r.mesh.positions[3 * i + 1], ys[i]);
        EXPECT_EQ(r.mesh.positions[3 * i + 2], zs[i]);
    }
    EXPECT_EQ(sizes(r.mesh), (std::vector<std::size_t>{3, 4}));
    EXPECT_EQ(face_of(r.mesh, 1), (std::vector<uint32_t>{0, 1, 2, 3}));
    for (const char* n : {"ply-vertex_index-name", "ply-unknown-header-line-ignored", "ply-double-coordinates",
                          "ply-other-elements(material)"})
        EXPECT_TRUE(has_note(r, n)) << n << ": " << notes(r);
}

TEST(Ply, AsciiValuesAreDoublesAndNoFacesIsFine) {
    const std::string s =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nend_header\n0.1 0.2 0.3 255\n1e-5 -0 +3 0\n";
    const LoadedMesh r = read(s, "pts.ply");
    EXPECT_EQ(r.mesh.positions, (std::vector<double>{0.1, 0.2, 0.3, 1e-5, -0.0, 3.0}));  // not float32
    EXPECT_EQ(r.mesh.face_count(), 0u);
    EXPECT_TRUE(has_note(r, "ply-no-faces"));
}

TEST(Ply, IntegerCoordinatesAndIndexTypes) {
    std::string s =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty int x\nproperty uint y\n"
        "property char z\nelement face 1\nproperty list int uint vertex_indices\nend_header\n";
    for (int v : {-5, 0, 1}) {
        put_u32(s, static_cast<uint32_t>(v));
        put_u32(s, 4000000000u);
        s += static_cast<char>(-128);
    }
    put_u32(s, 3);
    for (uint32_t i : {2u, 1u, 0u}) put_u32(s, i);
    const LoadedMesh r = read(s, "int.ply");
    EXPECT_EQ(r.mesh.positions, (std::vector<double>{-5, 4e9, -128, 0, 4e9, -128, 1, 4e9, -128}));
    EXPECT_EQ(face_of(r.mesh, 0), (std::vector<uint32_t>{2, 1, 0}));
}

}  // namespace
