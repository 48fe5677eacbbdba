// Bad input, built in memory: every error is a ReadError whose message names
// the file and the line or byte offset, and says what was expected.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include <zlib.h>

#include "io/readers.hpp"
#include "io_helpers.hpp"

namespace {

using namespace iotest;

void expect_what(const ReadError& e, const std::string& start, const std::string& part) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(start, 0), 0u) << what;
    EXPECT_NE(what.find(part), std::string::npos) << what;
}

TEST(ReadErrorFormat, TextBinaryAndWholeFile) {
    const ReadError a("f.obj", 12, "index 0");
    EXPECT_STREQ(a.what(), "f.obj:12: index 0");
    EXPECT_EQ(a.line, 12u);
    EXPECT_FALSE(a.has_byte_offset);
    const ReadError b = ReadError::at_byte("f.stl", 80, "size mismatch");
    EXPECT_STREQ(b.what(), "f.stl: byte 80: size mismatch");
    EXPECT_TRUE(b.has_byte_offset);
    EXPECT_EQ(b.byte_offset, 80u);
    EXPECT_EQ(b.message, "size mismatch");
    EXPECT_EQ(b.file, "f.stl");
    const ReadError c = ReadError::whole_file("f.ply", "empty file");
    EXPECT_STREQ(c.what(), "f.ply: empty file");
}

TEST(Empty, IsAnErrorExceptForObj) {
    for (const char* name : {"e.stl", "e.off", "e.ply", "e.amf", "e.3mf", "noext"}) {
        const ReadError e = read_error("", name);
        EXPECT_EQ(std::string(e.what()), std::string(name) + ": empty file");
    }
    const LoadedMesh m = read("", "e.obj");
    EXPECT_EQ(m.format, Format::obj);
    EXPECT_EQ(m.mesh.vertex_count(), 0u);
    EXPECT_EQ(m.mesh.face_count(), 0u);
    // An explicit hint beats the extension.
    EXPECT_EQ(read("", "e.dat", Format::obj).format, Format::obj);
    // Empty after gunzip too.
    EXPECT_EQ(std::string(read_error(gzip_stored(""), "e.stl.gz").what()), "e.stl.gz: empty file");
}

TEST(BinaryStl, TruncatedFileIsASizeMismatch) {
    const std::string full = write_binary_stl(octahedron());
    ASSERT_EQ(full.size(), 84u + 8 * 50);
    const ReadError e = read_error(full.substr(0, full.size() - 7), "t.stl");
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_EQ(e.byte_offset, 80u);
    EXPECT_EQ(e.message, "binary STL size mismatch: header declares 8 triangles (484 bytes) but file has 477 bytes");
    expect_what(e, "t.stl: byte 80: ", "size mismatch");
}

TEST(BinaryStl, CountBeyondTheFileFailsAtOnce) {
    std::string s = write_binary_stl(octahedron());
    s[80] = s[81] = s[82] = s[83] = '\xff';  // 4294967295 triangles
    const auto t0 = std::chrono::steady_clock::now();
    const ReadError e = read_error(s, "huge.stl");
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));
    expect_what(e, "huge.stl: byte 80: ", "header declares 4294967295 triangles (214748364834 bytes) but file has 484 bytes");
}

TEST(BinaryStl, TooShort) {
    const ReadError e = read_error("abc", "short.stl");
    expect_what(e, "short.stl: ", "file too short for binary STL (3 bytes)");
}

TEST(BinaryStl, NonFiniteCoordinate) {
    std::string s = write_binary_stl(octahedron());
    const std::size_t at = 84 + 50 * 2 + 12 + 4;  // triangle 2, first vertex, y
    s[at] = 0;
    s[at + 1] = 0;
    s[at + 2] = '\xc0';
    s[at + 3] = '\x7f';  // NaN
    ReadError e = read_error(s, "nan.stl");
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_EQ(e.byte_offset, at);
    EXPECT_NE(e.message.find("non-finite coordinate"), std::string::npos);
    s[at + 2] = '\x80';  // +Inf
    e = read_error(s, "inf.stl");
    expect_what(e, "inf.stl: byte " + std::to_string(at) + ": ", "non-finite coordinate");
}

const std::string kTri =
    "solid a\n"                  // 1
    "  facet normal 0 0 1\n"     // 2
    "    outer loop\n"           // 3
    "      vertex 0 0 0\n"       // 4
    "      vertex 1 0 0\n"       // 5
    "      vertex 0 1 0\n"       // 6
    "    endloop\n"              // 7
    "  endfacet\n"               // 8
    "endsolid a\n";              // 9

std::string replace(const std::string& s, const std::string& from, const std::string& to) {
    const std::size_t i = s.find(from);
    EXPECT_NE(i, std::string::npos) << from;
    if (i == std::string::npos) return s;
    return s.substr(0, i) + to + s.substr(i + from.size());
}

TEST(AsciiStl, MissingEndloopEndfacetAndBadNumbers) {
    EXPECT_EQ(read(kTri, "ok.stl").mesh.face_count(), 1u);
    ReadError e = read_error(replace(kTri, "    endloop\n", ""), "noloop.stl");
    EXPECT_EQ(e.line, 7u);
    expect_what(e, "noloop.stl:7: ", "expected 'endloop', found 'endfacet'");
    e = read_error(replace(kTri, "  endfacet\n", ""), "nofacet.stl");
    expect_what(e, "nofacet.stl:8: ", "expected 'endfacet', found 'endsolid'");
    e = read_error(replace(kTri, "vertex 1 0 0", "vertex 1 blah 0"), "blah.stl");
    expect_what(e, "blah.stl:5: ", "expected a number after 'vertex', found 'blah'");
    e = read_error(replace(kTri, "outer loop", "outer lop"), "lop.stl");
    expect_what(e, "lop.stl:3: ", "expected 'loop'");
    e = read_error(kTri.substr(0, kTri.find("endloop")), "cut.stl");
    expect_what(e, "cut.stl:", "expected 'endloop', found end of file");
    e = read_error(kTri + "garbage\n", "junk.stl");
    expect_what(e, "junk.stl:10: ", "expected 'solid' or end of file");
    e = read_error(replace(kTri, "facet normal", "facets normal"), "kw.stl");
    expect_what(e, "kw.stl:2: ", "expected 'facet' or 'endsolid', found 'facets'");
}

TEST(Coordinates, NanAndInfRejectedEverywhere) {
    for (const char* bad : {"nan", "inf", "-inf", "infinity", "NaN", "1e400", "-1e999"}) {
        SCOPED_TRACE(bad);
        ReadError e = read_error(replace(kTri, "vertex 1 0 0", std::string("vertex 1 ") + bad + " 0"), "n.stl");
        expect_what(e, "n.stl:5: ", "non-finite coordinate");
        e = read_error(std::string("v 0 0 0\nv 1 ") + bad + " 0\nv 0 1 0\nf 1 2 3\n", "n.obj");
        expect_what(e, "n.obj:2: ", "non-finite coordinate");
        e = read_error(std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 ") + bad + " 0\n3 0 1 2\n", "n.off");
        expect_what(e, "n.off:5: ", "non-finite coordinate");
        e = read_error(std::string("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                   "property float z\nend_header\n1 2 ") + bad + "\n",
                       "n.ply");
        expect_what(e, "n.ply:8: ", "non-finite coordinate");
    }
}

TEST(Numbers, StrtodSyntax) {
    const std::string obj = "v 1e-5 -0 +3\nv .5 5. 1E+2\nv 0.1 -2.5e-3 123456789012345678901234567890\nf 1 2 3\n";
    const LoadedMesh m = read(obj, "n.obj");
    const std::vector<double> want = {1e-5, -0.0, 3.0, 0.5, 5.0, 100.0, 0.1, -2.5e-3, 1.2345678901234568e29};
    ASSERT_EQ(m.mesh.positions, want);
    EXPECT_TRUE(std::signbit(m.mesh.positions[1]));
    for (const char* bad : {"0x1p3", "1.0abc", "--1", "+-1", "1e", ".", "e5", "1,5"}) {
        const ReadError e = read_error(std::string("v 0 0 0\nv 0 ") + bad + " 0\n", "bad.obj");
        expect_what(e, "bad.obj:2: ", "expected a coordinate");
    }
}

TEST(Obj, IndexZeroAndOutOfRange) {
    const std::string verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    ReadError e = read_error(verts + "f 1 2 3\nf 0 1 2\n", "zero.obj");
    EXPECT_EQ(e.line, 5u);
    expect_what(e, "zero.obj:5: ", "index 0");
    e = read_error(verts + "f 1 2 3\n\nf 1 12 2\n", "range.obj");
    EXPECT_EQ(e.line, 6u);
    expect_what(e, "range.obj:6: ", "index 12 out of range (file has 3 vertices)");
    e = read_error(verts + "f -1 -2 -4\n", "neg.obj");
    expect_what(e, "neg.obj:4: ", "index -4 out of range");
    e = read_error(verts + "f 1/2/3 x 3\n", "tok.obj");
    expect_what(e, "tok.obj:4: ", "expected a vertex index, found 'x'");
    e = read_error(verts + "f\n", "nof.obj");
    expect_what(e, "nof.obj:4: ", "expected vertex indices after 'f'");
    e = read_error("v 1 2\n", "short.obj", Format::obj);
    expect_what(e, "short.obj:1: ", "expected a coordinate after 'v', found end of file");
    // Like malformed.obj of the corpus: index 0 is reported (at once) before
    // an out-of-range index on an earlier line (checked once all vertices are read).
    e = read_error(verts + "f 1 9 2\nf 0 1 2\n", "order.obj");
    expect_what(e, "order.obj:5: ", "index 0");
}

TEST(Obj, BinaryGarbageWithObjHintIsAnError) {
    const std::string junk("v 0 0 0\n\x01\x02\x03 4\n", 15);
    const ReadError e = read_error(junk, "junk.obj");
    expect_what(e, "junk.obj:2: ", "expected an OBJ statement");
}

TEST(Off, CountsLargerThanContentFailFast) {
    const auto t0 = std::chrono::steady_clock::now();
    ReadError e = read_error("OFF\n1000000000 1 0\n0 0 0\n", "big.off");
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));
    expect_what(e, "big.off:2: ", "header declares 1000000000 vertices and 1 faces but only 6 bytes follow");
    e = read_error("OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "bigf.off");
    expect_what(e, "bigf.off:2: ", "4000000000 faces");
    e = read_error("OFF\n9223372036854775807 9223372036854775807 0\n0 0 0\n", "max.off");
    expect_what(e, "max.off:2: ", "header declares");
    e = read_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n", "k.off");
    expect_what(e, "k.off:6: ", "face 0 declares 2000000000 vertices");
    // Fewer vertices than declared: reported where the file ends.
    e = read_error("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "few.off");
    // (values are whitespace-separated, so vertex 3 is "3 0 1" and face 0 is missing)
    expect_what(e, "few.off:7: ", "expected the vertex count of face 0 of 1, found end of file");
    e = read_error("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n\n\n\n\n\n\n\n\n\n", "few2.off");
    expect_what(e, "few2.off:15: ", "expected a coordinate of vertex 3 of 4, found end of file");
}

TEST(Off, IndexOutOfRangeAndOtherErrors) {
    // The corpus's invalid.off: counts without the edge count, a "\r" inside a line.
    ReadError e = read_error("OFF\n3 4\n0.1 0.2 0.3\n0.2 0.3 0.4\n0.3 0.4 0.5\n0\n2\r20\n4\n", "invalid.off");
    expect_what(e, "invalid.off:", "face 1 index 20 out of range (file has 3 vertices)");
    e = read_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n", "neg.off");
    expect_what(e, "neg.off:6: ", "face 0 index -1 out of range");
    e = read_error("4OFF\n1 0 0\n1 2 3 4\n", "h.off");
    expect_what(e, "h.off:1: ", "OFF with 4-dimensional vertices (not a 3D mesh)");
    e = read_error("nOFF\n5\n1 0 0\n1 2 3 4 5\n", "n5.off");
    expect_what(e, "n5.off:", "OFF with 5-dimensional vertices");
    e = read_error("OFF BINARY\n", "b.off");
    expect_what(e, "b.off:1: ", "binary OFF is not supported");
    e = read_error("OFF\n", "e.off");
    expect_what(e, "e.off:", "expected the vertex count, found end of file");
    e = read_error("1 2\n", "x.off");
    expect_what(e, "x.off:1: ", "expected 'OFF' or a line of three counts");
}

const std::string kPlyHead =
    "ply\n"
    "format binary_little_endian 1.0\n"
    "element vertex 3\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";

std::string small_binary_ply() {
    std::string s = kPlyHead;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put_f32(s, v);
    s += '\x03';
    for (uint32_t i : {0u, 1u, 2u}) put_u32(s, i);
    return s;
}

TEST(Ply, UnknownFormatAndHeaderErrors) {
    ReadError e = read_error(replace(kPlyHead, "binary_little_endian", "binary_middle_endian"), "f.ply");
    EXPECT_EQ(e.line, 2u);
    expect_what(e, "f.ply:2: ", "unknown PLY format 'binary_middle_endian'");
    e = read_error(replace(kPlyHead, "end_header\n", ""), "noend.ply");
    expect_what(e, "noend.ply:", "expected 'end_header'");
    e = read_error(replace(kPlyHead, "property float y\n", ""), "noy.ply");
    expect_what(e, "noy.ply:3: ", "element 'vertex' has no property 'y'");
    e = read_error(replace(kPlyHead, "property float x", "property quad x"), "type.ply");
    expect_what(e, "type.ply:4: ", "unknown property type 'quad'");
    e = read_error(replace(kPlyHead, "format binary_little_endian 1.0\n", ""), "nofmt.ply");
    expect_what(e, "nofmt.ply:", "missing 'format' line");
    e = read_error("plyx\n", "notply.ply");
    expect_what(e, "notply.ply: ", "not a PLY file");
}

TEST(Ply, TruncatedBinaryBody) {
    const std::string full = small_binary_ply();
    EXPECT_EQ(read(full, "ok.ply").mesh.face_count(), 1u);
    const std::size_t body = kPlyHead.size();
    ReadError e = read_error(full.substr(0, full.size() - 2), "cut.ply");
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_EQ(e.byte_offset, body + 36);  // the face's list
    expect_what(e, "cut.ply: byte " + std::to_string(body + 36) + ": ", "truncated PLY body");
    e = read_error(full.substr(0, body + 10), "cut2.ply");
    expect_what(e, "cut2.ply: byte " + std::to_string(body) + ": ", "element 'vertex' declares 3 rows of at least 12 bytes but only 10 bytes remain");
    // A count far beyond the file fails before allocating.
    e = read_error(replace(full, "element vertex 3", "element vertex 5000000000"), "big.ply");
    expect_what(e, "big.ply:3: ", "too many vertices");
    e = read_error(replace(full, "element vertex 3", "element vertex 4000000000"), "bigv.ply");
    expect_what(e, "bigv.ply: byte ", "element 'vertex' declares 4000000000 rows");
    e = read_error(replace(full, "element face 1", "element face 4000000000"), "bigf.ply");
    expect_what(e, "bigf.ply: byte ", "element 'face' declares 4000000000 rows");
}

TEST(Ply, IndexOutOfRangeAndBadAsciiValues) {
    std::string s = small_binary_ply();
    s[s.size() - 4] = 9;  // last index 2 -> 9
    ReadError e = read_error(s, "r.ply");
    expect_what(e, "r.ply: byte " + std::to_string(s.size() - 4) + ": ", "face 0 index 9 out of range (file has 3 vertices)");
    const std::string ascii = replace(kPlyHead, "binary_little_endian", "ascii");
    e = read_error(ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "ra.ply");
    expect_what(e, "ra.ply:13: ", "face 0 index 3 out of range (file has 3 vertices)");
    e = read_error(ascii + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "va.ply");
    expect_what(e, "va.ply:11: ", "expected a number for property 'y' of vertex 1, found 'zero'");
    e = read_error(ascii + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "short.ply");
    expect_what(e, "short.ply:", "found end of file");
    e = read_error(ascii + "0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", "negk.ply");
    expect_what(e, "negk.ply:13: ", "expected a number for property 'vertex_indices'");
}

TEST(Detect, UnrecognisedContentSaysWhatWasTried) {
    const ReadError e = read_error("hello world\nthis is not a mesh\n", "notes.txt");
    expect_what(e, "notes.txt: ", "unrecognised content (tried gzip, zip (3MF/AMF), PLY, XML (AMF/3MF), binary STL");
    const ReadError x = read_error("<?xml version=\"1.0\"?>\n<svg></svg>\n", "pic.xml");
    expect_what(x, "pic.xml: ", "XML document with root <svg> is neither AMF");
}

TEST(Gzip, CorruptAndTruncatedStreams) {
    const std::string z = gzip_stored(write_obj(octahedron()));
    EXPECT_EQ(read(z, "o.obj.gz").mesh.face_count(), 8u);
    ReadError e = read_error(z.substr(0, z.size() / 2), "half.obj.gz");
    expect_what(e, "half.obj.gz: byte ", "truncated gzip data");
    std::string bad_crc = z;
    bad_crc[bad_crc.size() - 6] ^= 1;
    e = read_error(bad_crc, "crc.obj.gz");
    expect_what(e, "crc.obj.gz: byte ", "corrupt gzip data");
    std::string bad_block = z;
    bad_block[10] = '\x07';  // reserved block type
    e = read_error(bad_block, "blk.obj.gz");
    expect_what(e, "blk.obj.gz: byte ", "corrupt gzip data");
}

// gzip with zlib's deflate (level 9): zeros compress about 1000 to 1.
std::string gzip_deflated(const std::string& data) {
    z_stream zs{};
    EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(deflateBound(&zs, data.size()), '\0');
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    zs.avail_in = static_cast<uInt>(data.size());
    zs.next_out = reinterpret_cast<Bytef*>(out.data());
    zs.avail_out = static_cast<uInt>(out.size());
    EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
    out.resize(zs.total_out);
    deflateEnd(&zs);
    return out;
}

// A gzip bomb: 64 MiB of zeros after an OBJ line is about 64 KB of gzip,
// above the limit of 16 MiB for small files (readers.hpp); gzip in gzip
// shares the one limit. Both refused before the memory is spent.
TEST(Gzip, ExpansionBeyondTheLimitIsRefused) {
    const std::string bomb = gzip_deflated("v 0 0 0\n" + std::string(std::size_t{64} << 20, ' '));
    ASSERT_LT(bomb.size(), std::size_t{1} << 20);
    ReadError e = read_error(bomb, "bomb.obj.gz");
    expect_what(e, "bomb.obj.gz: gzip data expands", "beyond the decompression limit of 16777216 bytes");
    const std::string nested = gzip_deflated(bomb);
    e = read_error(nested, "nested.obj.gz");
    expect_what(e, "nested.obj.gz: gzip data expands", "beyond the decompression limit");
    // A file of ordinary ratio reads.
    const std::string obj = write_obj(octahedron());
    EXPECT_EQ(read(gzip_deflated(obj), "o.obj.gz").mesh.face_count(), 8u);
    EXPECT_EQ(polyvol::io::decompression_limit(1000), std::uint64_t{16} << 20);
    EXPECT_EQ(polyvol::io::decompression_limit(std::size_t{1} << 30), std::uint64_t{4} << 30);
}

TEST(ReadFile, MissingFileAndDirectory) {
    ReadError e = expect_error([] { (void)polyvol::read_mesh_file("/nonexistent/dir/m.stl"); });
    expect_what(e, "/nonexistent/dir/m.stl: ", "No such file or directory");
    e = expect_error([] { (void)polyvol::read_mesh_file("/"); });
    EXPECT_EQ(std::string(e.what()).rfind("/: ", 0), 0u) << e.what();
}

}  // namespace
