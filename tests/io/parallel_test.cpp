// The parallel text readers against the serial ones (src/io/chunks.hpp): on
// the same bytes both must give bit-identical positions, the same faces and
// notes, or the same error (file, line, message). Tiny chunk sizes split even
// small files in many places; generated inputs of a few MB use realistic
// ones; errors are injected into multi-chunk inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/kernel_levels.hpp"
#include "common/manifest.hpp"
#include "io/chunks.hpp"
#include "io/text.hpp"
#include "io_helpers.hpp"
#include "parse_helpers.hpp"

namespace {

using namespace iotest;
using polyvol::io::ParseOptions;
using polyvol::io::ParseReport;
using polyvol::io::ScopedParseOptions;

struct Outcome {
    bool ok = false;
    LoadedMesh mesh;
    std::string what;  // the error, formatted
    uint64_t line = 0;
    ParseReport report;
};

Outcome read_with(const std::string& data, const std::string& name, const ParseOptions& options) {
    ScopedParseOptions scope(options);
    polyvol::io::thread_parse_report() = {};  // (detection may not reach a reader)
    Outcome r;
    try {
        r.mesh = read(data, name);
        r.ok = true;
    } catch (const ReadError& e) {
        r.what = e.what();
        r.line = e.line;
    }
    r.report = polyvol::io::thread_parse_report();
    return r;
}

// Compares a parallel reading with the serial one.
void expect_same(const Outcome& serial, const Outcome& par, const std::string& what) {
    ASSERT_EQ(serial.ok, par.ok) << what << ": serial " << (serial.ok ? "read" : serial.what) << ", parallel "
                                 << (par.ok ? "read" : par.what);
    if (!serial.ok) {
        EXPECT_EQ(serial.what, par.what) << what;
        EXPECT_EQ(serial.line, par.line) << what;
        return;
    }
    const LoadedMesh& a = serial.mesh;
    const LoadedMesh& b = par.mesh;
    expect_same_mesh(b.mesh, a.mesh, what);
    EXPECT_EQ(a.notes, b.notes) << what;
    EXPECT_EQ(a.vertices_in_file, b.vertices_in_file) << what;
    EXPECT_EQ(a.format, b.format) << what;
    EXPECT_EQ(a.encoding, b.encoding) << what;
    EXPECT_EQ(a.gzip, b.gzip) << what;
}

// Reads data serially and with each chunk size; returns the parallel outcomes.
std::vector<Outcome> compare(const std::string& data, const std::string& name, std::vector<std::size_t> sizes) {
    const Outcome serial = read_with(data, name, kSerial);
    EXPECT_EQ(serial.report.chunks, 0u) << name;
    std::vector<Outcome> out;
    for (std::size_t size : sizes) {
        out.push_back(read_with(data, name, chunked(size)));
        expect_same(serial, out.back(), name + " with chunks of " + std::to_string(size) + " bytes");
    }
    return out;
}

// parse_int's fast path for short tokens gives what std::from_chars gives.
TEST(ParseInt, SameAsFromChars) {
    std::mt19937 rng(5);
    const char chars[] = "0123456789-+ x.";
    for (int i = 0; i < 200000; ++i) {
        std::string t;
        const std::size_t n = rng() % 24;
        for (std::size_t k = 0; k < n; ++k) t += rng() % 8 ? chars[rng() % 10] : chars[rng() % (sizeof chars - 1)];
        std::string_view v = t;
        if (!v.empty() && v[0] == '+') v.remove_prefix(1);
        int64_t want = 0;
        const auto r = std::from_chars(v.data(), v.data() + v.size(), want);
        const bool ok = !v.empty() && r.ec == std::errc() && r.ptr == v.data() + v.size() &&
                        !(t.size() > 1 && t[0] == '+' && t[1] == '-');
        int64_t got = 0;
        ASSERT_EQ(polyvol::io::text::parse_int(t, got), ok) << t;
        if (ok) {
            ASSERT_EQ(got, want) << t;
        }
    }
    for (const char* t : {"999999999999999999", "-999999999999999999", "9223372036854775807", "-9223372036854775808",
                          "9223372036854775808", "0000000000000000000000001", "-0", "+0", "+-1", "-", "+"}) {
        int64_t a = 0;
        std::string_view v = t;
        if (v[0] == '+') v.remove_prefix(1);
        const auto r = std::from_chars(v.data(), v.data() + v.size(), a);
        const bool ok = !v.empty() && r.ec == std::errc() && r.ptr == v.data() + v.size() && std::string(t) != "+-1";
        int64_t b = 0;
        EXPECT_EQ(polyvol::io::text::parse_int(t, b), ok) << t;
        if (ok) {
            EXPECT_EQ(a, b) << t;
        }
    }
}

// Cursor::next_finite_number, with next() and parse_double behind it as the
// ASCII STL reader uses them, reads what next() and parse_double read: the
// same finite values (bit for bit), the same tokens refused, the same lines
// and offsets, with and without a comment character.
TEST(Cursor, NextFiniteNumberReadsAsNextAndParseDouble) {
    using polyvol::io::text::Cursor;
    using polyvol::io::text::parse_double;
    std::mt19937 rng(11);
    const char* pieces[] = {"1", "-2.5", "+3", "+-1", "4e5", "1e-400", "1e400", ".5", "5.", "-0", "inf", "-nan", "0x1p3",
                            "7#", "#c", "1.5e", "--1", "2,5", "1e+2", "00.125", "9007199254740993", "x"};
    const char* gaps[] = {" ", "  ", "\t", "\n", "\r\n", "\r", " \n "};
    for (int round = 0; round < 4000; ++round) {
        std::string text;
        const int n = static_cast<int>(rng() % 12);
        for (int i = 0; i < n; ++i) {
            if (i > 0 || rng() % 2) text += gaps[rng() % std::size(gaps)];
            text += pieces[rng() % std::size(pieces)];
        }
        if (rng() % 2) text += gaps[rng() % std::size(gaps)];
        for (char comment : {'\0', '#'}) {
            Cursor a(text, comment), b(text, comment);
            for (int step = 0; step < 40; ++step) {
                double x = 0, y = 0;
                bool ok_a = a.next_finite_number(x);
                std::string_view tok_a;
                if (!ok_a) {
                    tok_a = a.next();
                    ok_a = parse_double(tok_a, x) && std::isfinite(x);
                }
                const std::string_view tok_b = b.next();
                const bool ok_b = parse_double(tok_b, y) && std::isfinite(y);
                ASSERT_EQ(ok_a, ok_b) << text << " step " << step;
                if (ok_a) {
                    ASSERT_EQ(std::bit_cast<uint64_t>(x), std::bit_cast<uint64_t>(y)) << text;
                } else {
                    ASSERT_EQ(tok_a, tok_b) << text;
                }
                ASSERT_EQ(a.offset(), b.offset()) << text;
                ASSERT_EQ(a.line(), b.line()) << text;
                if (tok_b.empty()) break;
            }
        }
    }
}

// count_lines (with its vector-at-a-time path, at every kernel level)
// against a plain reading of the definition: line ends as text::Cursor
// counts them, and lines whose first non-blank byte is neither a line end
// nor the comment character.
TEST(CountLines, MatchesTheDefinition) {
    const polyvol::test::LevelGuard guard;
    std::mt19937 rng(11);
    const std::string alphabets[] = {"1 \n", "12.5 \n", "ab\n\n \t#", "1\r\n", "x\n\r\v\f#"};
    for (int i = 0; i < 20000; ++i) {
        const std::string& a = alphabets[i % std::size(alphabets)];
        std::string s;
        const std::size_t n = rng() % (i % 10 == 0 ? 400 : 60);
        if (i % 3 == 0) {
            // Plain lines (the fast path), sometimes with one odd line start.
            while (s.size() < n) {
                s += "1.5 2";
                for (auto k = rng() % 20; k > 0; --k) s += ' ';
                s += rng() % 3 ? "7\n" : "8";
            }
            if (rng() % 2 && !s.empty()) s[rng() % s.size()] = "\n #\r\t"[rng() % 5];
        } else {
            for (std::size_t k = 0; k < n; ++k) s += a[rng() % a.size()];
        }
        for (char comment : {'\0', '#'}) {
            uint64_t ends = 0, data = 0;
            bool at_start = true, seen = false;  // in a line: only blanks so far / counted
            for (std::size_t k = 0; k < s.size(); ++k) {
                const char c = s[k];
                if (c == '\n' || c == '\r') {
                    if (c == '\r' && k + 1 < s.size() && s[k + 1] == '\n') continue;
                    ++ends;
                    at_start = true;
                    seen = false;
                } else if (at_start && (c == ' ' || c == '\t' || c == '\v' || c == '\f')) {
                } else {
                    if (at_start && !seen && !(comment != '\0' && c == comment)) ++data;
                    at_start = false;
                    seen = true;
                }
            }
            for (int level : polyvol::test::kLevels) {
                polyvol::test::cap_kernel_level(level);
                const polyvol::io::chunks::LineCounts got = polyvol::io::chunks::count_lines(s, comment);
                ASSERT_EQ(got.line_ends, ends) << i << " level " << level;
                ASSERT_EQ(got.data_lines, data) << i << " level " << level;
            }
            ASSERT_EQ(polyvol::io::chunks::count_line_ends(s), ends) << i;
        }
    }
}

// ---- the corpus ------------------------------------------------------------

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(ParallelCorpus, EveryTextFileReadsAsSerially) {
    const nlohmann::json& manifest = polyvol::test::corpus_manifest();
    ASSERT_FALSE(manifest.empty()) << "no manifest in " << polyvol::test::corpus_dir();
    std::size_t files = 0, parallel = 0, fallback = 0;
    for (const nlohmann::json& e : manifest) {
        const std::string format = e.value("format", "");
        if (format != "stl" && format != "obj" && format != "off" && format != "ply") continue;
        const std::string rel = e.at("path");
        const std::string data = slurp(polyvol::test::corpus_file(rel));
        ASSERT_FALSE(data.empty() && e.value("bytes", 0) > 0) << rel;
        for (const Outcome& o : compare(data, rel, {64, 1, 4096})) {
            parallel += o.report.chunks > 1 && !o.report.serial_fallback;
            fallback += o.report.serial_fallback;
        }
        ++files;
    }
    EXPECT_GE(files, 100u);
    // Most text files split into several chunks that decide alone.
    EXPECT_GE(parallel, files);
    std::cout << "[ corpus ] " << files << " files; " << parallel << " parallel readings, " << fallback
              << " fell back to serial\n";
}

// ---- generated inputs --------------------------------------------------------

// Numbers in the many spellings the readers accept.
class Numbers {
public:
    explicit Numbers(uint32_t seed) : rng_(seed) {}
    std::string coord() {
        const double v = std::uniform_real_distribution<double>(-100, 100)(rng_);
        switch (rng_() % 6) {
            case 0: return num(v);
            case 1: {
                char b[40];
                std::snprintf(b, sizeof b, "%.17g", v);
                return b;
            }
            case 2: {
                char b[40];
                std::snprintf(b, sizeof b, "%e", v);
                return b;
            }
            case 3: return std::to_string(static_cast<int>(v));
            case 4: return "-0";
            default: {
                char b[40];
                std::snprintf(b, sizeof b, "%.3f", v);
                return b;
            }
        }
    }
    uint32_t below(uint32_t n) { return static_cast<uint32_t>(rng_() % n); }

private:
    std::mt19937 rng_;
};

// ASCII STL: several solids (one without endsolid, one closed under another
// name, keywords in other cases, a quad loop, CRLF lines), about `bytes` bytes.
std::string big_stl(std::size_t bytes, uint32_t seed) {
    Numbers r(seed);
    std::string s;
    int solid = 0;
    while (s.size() < bytes) {
        const std::string name = "part" + std::to_string(solid);
        s += solid % 3 == 1 ? "SOLID " : "solid ";
        s += name;
        s += '\n';
        const uint32_t facets = 500 + r.below(1000);
        for (uint32_t f = 0; f < facets; ++f) {
            const bool crlf = solid % 4 == 2;
            const char* eol = crlf ? "\r\n" : "\n";
            s += f % 1000 == 7 ? "  FACET NORMAL 0 0 1" : "  facet normal 0 0 1";
            s += eol;
            s += "    outer loop";
            s += eol;
            const uint32_t k = f % 997 == 5 ? 4 : 3;
            for (uint32_t v = 0; v < k; ++v) {
                s += "      vertex ";
                s += r.coord();
                s += ' ';
                s += r.coord();
                s += ' ';
                s += r.coord();
                s += eol;
            }
            s += "    endloop";
            s += eol;
            s += "  endfacet";
            s += eol;
            if (f % 700 == 3) s += "\n  \n";  // blank lines between facets
        }
        if (solid % 5 == 3) {
            // no endsolid: the next solid starts at once
        } else if (solid % 5 == 4) {
            s += "endsolid other\n";
        } else {
            s += "endsolid " + name + "\n";
        }
        ++solid;
    }
    return s;
}

// OBJ: vertices and faces interleaved, negative indices, a few forward
// references, slashes, quads, comments, groups, continuation lines, w.
std::string big_obj(std::size_t bytes, uint32_t seed) {
    Numbers r(seed);
    std::string s = "# generated\nmtllib x.mtl\n";
    uint32_t n = 0;
    std::size_t line = 0;
    while (s.size() < bytes) {
        ++line;
        if (line % 5000 == 1) s += "g group" + std::to_string(line) + "\n";
        const uint32_t nv = 1 + r.below(6);
        for (uint32_t i = 0; i < nv; ++i) {
            s += "v " + r.coord() + " " + r.coord() + " " + r.coord();
            if (line % 3001 == 2) s += " 1.0";
            s += '\n';
            ++n;
        }
        if (line % 2003 == 4) s += "vn 0 0 1\nvt 0.5 0.5\n";
        if (n < 4) continue;
        switch (r.below(5)) {
            case 0: s += "f -1 -2 -3\n"; break;
            case 1: s += "f " + std::to_string(n) + "/1 " + std::to_string(n - 1) + "/1 " + std::to_string(n - 3) + "/2\n"; break;
            case 2: s += "f -4//1 -3//1 -2//1 -1//1\n"; break;
            case 3: s += "f " + std::to_string(1 + r.below(n)) + " -1 \\\n  -2\n"; break;  // continued
            default: s += "f " + std::to_string(n + 2) + " " + std::to_string(n) + " -1  # forward\n"; break;
        }
        if (line % 4001 == 9) s += "l 1 2\np 3\n";
    }
    // The forward references must exist at the end.
    for (int i = 0; i < 3; ++i) s += "v 0 0 " + std::to_string(i) + "\n";
    return s;
}

// OFF: comments and blank lines in the body, vertex colours, polygons, face
// colours, trailing data.
std::string big_off(std::size_t vertices, uint32_t seed) {
    Numbers r(seed);
    const std::size_t faces = 2 * vertices;
    std::string s = "COFF\n# comment\n\n" + std::to_string(vertices) + " " + std::to_string(faces) + " 0\n";
    for (std::size_t v = 0; v < vertices; ++v) {
        s += r.coord() + " " + r.coord() + "\t" + r.coord();
        if (v % 3 == 0) s += " 255 0 0 255";
        if (v % 1000 == 5) s += "  # a vertex comment\n\n# a comment line";
        s += '\n';
    }
    for (std::size_t f = 0; f < faces; ++f) {
        const uint32_t k = f % 50 == 1 ? 4 : 3;
        s += std::to_string(k);
        for (uint32_t j = 0; j < k; ++j) s += " " + std::to_string(r.below(static_cast<uint32_t>(vertices)));
        if (f % 7 == 0) s += " 0.5 0.5 0.5";
        s += f % 900 == 3 ? "\r\n\r\n" : "\n";
    }
    s += "1 2 3\n";  // trailing data
    return s;
}

// ASCII PLY: extra vertex properties, a face list, another element after.
std::string big_ply(std::size_t vertices, uint32_t seed) {
    Numbers r(seed);
    const std::size_t faces = 2 * vertices;
    std::string s = "ply\nformat ascii 1.0\ncomment generated\nelement vertex " + std::to_string(vertices) +
                    "\nproperty float x\nproperty uchar red\nproperty float y\nproperty float z\n"
                    "property list uchar float extra\nelement face " +
                    std::to_string(faces) +
                    "\nproperty list uchar int vertex_indices\nproperty int flags\n"
                    "element edge 3\nproperty int a\nproperty int b\nend_header\n";
    for (std::size_t v = 0; v < vertices; ++v) {
        s += r.coord() + " 7 " + r.coord() + " " + r.coord();
        s += v % 4 == 0 ? " 2 0.5 1.5" : " 0";
        s += v % 777 == 3 ? "\n\n" : "\n";
    }
    for (std::size_t f = 0; f < faces; ++f) {
        const uint32_t k = f % 40 == 1 ? 4 : 3;
        s += std::to_string(k);
        for (uint32_t j = 0; j < k; ++j) s += " " + std::to_string(r.below(static_cast<uint32_t>(vertices)));
        s += " 0\n";
    }
    s += "0 1\n1 2\n2 0\n";
    return s;
}

struct Generated {
    std::string name;
    std::string data;
};

const std::vector<Generated>& generated() {
    static const std::vector<Generated> g = {
        {"big.stl", big_stl(3 << 20, 1)},
        {"big.obj", big_obj(3 << 20, 2)},
        {"big.off", big_off(60000, 3)},
        {"big.ply", big_ply(60000, 4)},
    };
    return g;
}

TEST(ParallelGenerated, SameAsSerialWithRealisticChunks) {
    for (const Generated& g : generated()) {
        ASSERT_GT(g.data.size(), std::size_t{2} << 20) << g.name;
        const Outcome serial = read_with(g.data, g.name, kSerial);
        ASSERT_TRUE(serial.ok) << serial.what;
        for (const ParseOptions& o : {chunked(64 << 10), chunked(1 << 20), ParseOptions{}}) {
            const Outcome par = read_with(g.data, g.name, o);
            expect_same(serial, par, g.name + " with chunks of " + std::to_string(o.chunk_bytes));
            EXPECT_GT(par.report.chunks, 1u) << g.name;
            EXPECT_FALSE(par.report.serial_fallback) << g.name;
        }
    }
}

TEST(ParallelGenerated, TheQuirksAreThere) {
    const Outcome stl = read_with(generated()[0].data, "big.stl", chunked(64 << 10));
    ASSERT_TRUE(stl.ok);
    for (const char* note : {"stl-missing-endsolid", "stl-endsolid-name-mismatch", "stl-loop-with-4-vertices"})
        EXPECT_NE(std::find(stl.mesh.notes.begin(), stl.mesh.notes.end(), note), stl.mesh.notes.end()) << note;
    const Outcome obj = read_with(generated()[1].data, "big.obj", chunked(64 << 10));
    ASSERT_TRUE(obj.ok);
    for (const char* note : {"obj-negative-indices", "obj-slash-index-syntax", "obj-multiple-groups-or-objects"})
        EXPECT_NE(std::find(obj.mesh.notes.begin(), obj.mesh.notes.end(), note), obj.mesh.notes.end()) << note;
    const Outcome off = read_with(generated()[2].data, "big.off", chunked(64 << 10));
    ASSERT_TRUE(off.ok);
    EXPECT_EQ(off.mesh.notes, (std::vector<std::string>{"off-header-COFF", "off-vertex-extra-values(4)",
                                                        "off-face-colors", "off-trailing-data(1 lines)"}));
    const Outcome ply = read_with(generated()[3].data, "big.ply", chunked(64 << 10));
    ASSERT_TRUE(ply.ok);
    EXPECT_EQ(ply.mesh.notes, std::vector<std::string>{"ply-other-elements(edge)"});
}

// A multi-solid STL whose endsolid names are checked in chunks other than
// the one that opened the solid.
TEST(ParallelGenerated, EndsolidNamesAcrossChunks) {
    for (const char* end_name : {"a", "b", ""}) {
        std::string s = "solid a\n";
        for (int f = 0; f < 200; ++f)
            s += "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
        s += "endsolid ";
        s += end_name;
        s += "\nsolid c\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
             "endfacet\nendsolid c\n";
        compare(s, "names.stl", {64, 1000, 5000});
    }
}

// ---- every prefix and random mutations, with tiny chunks --------------------

std::vector<Generated> small_inputs() {
    std::vector<Generated> v = {
        {"a.stl", write_ascii_stl(octahedron())},
        {"q.stl", write_ascii_stl(quad_cube())},
        {"o.obj", write_obj(quad_cube())},
        {"c.off", write_off(quad_cube())},
        {"a.ply", write_ply(quad_cube(), PlyEnc::ascii)},
        {"col.off", "COFF\n# comment\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2 0.5 0.5 0.5\n"},
        {"two.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                    "endfacet\nendsolid b\nsolid c\n facet\n outer loop\nvertex 1 1 1\nvertex 2 2 2\nendloop\n"
                    "endfacet\n"},
        {"neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf 1 2 -1\nf 5 4 3\nv 1 1 1\nf 1 \\\n 2 3\n"},
    };
    v.push_back({"big.off", big_off(40, 5)});
    v.push_back({"big.ply", big_ply(40, 6)});
    v.push_back({"big.obj", big_obj(2000, 7)});
    v.push_back({"big.stl", big_stl(1, 8).substr(0, 3000) + "endloop\nendfacet\nendsolid part0\n"});
    return v;
}

TEST(ParallelFuzz, EveryPrefix) {
    for (const Generated& g : small_inputs()) {
        for (std::size_t n = 0; n <= g.data.size(); n += 1 + n / 64) {
            const std::string prefix = g.data.substr(0, n);
            const Outcome serial = read_with(prefix, g.name, kSerial);
            for (std::size_t size : {1, 13, 64}) {
                expect_same(serial, read_with(prefix, g.name, chunked(size)),
                            g.name + " prefix " + std::to_string(n) + " chunks " + std::to_string(size));
            }
        }
    }
}

TEST(ParallelFuzz, RandomMutations) {
    std::mt19937 rng(4242);
    const char alphabet[] = "0123456789 .-+e\n\r\t#/\\xfvsolidfacetendloopvertexOFF";
    for (const Generated& g : small_inputs()) {
        for (int i = 0; i < 120; ++i) {
            std::string s = g.data;
            const int flips = 1 + static_cast<int>(rng() % 4);
            for (int k = 0; k < flips; ++k) {
                const std::size_t at = rng() % s.size();
                switch (rng() % 3) {
                    case 0: s[at] = alphabet[rng() % (sizeof alphabet - 1)]; break;
                    case 1: s.insert(at, 1, alphabet[rng() % (sizeof alphabet - 1)]); break;
                    default: s.erase(at, 1); break;
                }
            }
            const Outcome serial = read_with(s, g.name, kSerial);
            const std::size_t size = 1 + rng() % 80;
            expect_same(serial, read_with(s, g.name, chunked(size)),
                        g.name + " mutation " + std::to_string(i) + " chunks " + std::to_string(size));
        }
    }
}

// Whole lines deleted, repeated, moved or inserted: records that run across
// chunk boundaries, solids closed early, sections cut short.
TEST(ParallelFuzz, LineMutations) {
    std::mt19937 rng(777);
    const char* inserts[] = {"endsolid x", "solid y", "facet normal 1 2 3", "outer loop", "endloop", "endfacet",
                             "vertex 1 2 3", "v 1 2 3", "f -1 -2 -3", "f 1 2 3 \\", "3 0 1 2", "1 2", "", "  ",
                             "# c", "\r", "2 3 4 5 6 7", "1e400 0 0", "facet", "endsolid"};
    for (const Generated& g : small_inputs()) {
        std::vector<std::string> lines;
        std::size_t pos = 0;
        while (pos < g.data.size()) {
            const std::size_t nl = std::min(g.data.find('\n', pos), g.data.size());
            lines.push_back(g.data.substr(pos, nl - pos));
            pos = nl + 1;
        }
        for (int i = 0; i < 150; ++i) {
            std::vector<std::string> m = lines;
            const int ops = 1 + static_cast<int>(rng() % 3);
            for (int k = 0; k < ops && !m.empty(); ++k) {
                const std::size_t at = rng() % m.size();
                switch (rng() % 4) {
                    case 0: m.erase(m.begin() + static_cast<std::ptrdiff_t>(at)); break;
                    case 1: m.insert(m.begin() + static_cast<std::ptrdiff_t>(at), m[at]); break;
                    case 2: std::swap(m[at], m[rng() % m.size()]); break;
                    default:
                        m.insert(m.begin() + static_cast<std::ptrdiff_t>(at), inserts[rng() % std::size(inserts)]);
                        break;
                }
            }
            std::string s;
            for (const std::string& l : m) {
                s += l;
                s += '\n';
            }
            const Outcome serial = read_with(s, g.name, kSerial);
            for (std::size_t size : {1, 40}) {
                expect_same(serial, read_with(s, g.name, chunked(size)),
                            g.name + " line mutation " + std::to_string(i) + " chunks " + std::to_string(size));
            }
        }
    }
}

// ---- errors in multi-chunk inputs -------------------------------------------

// A facet after 'endsolid' (no new 'solid'): the chunk holding it cannot
// know that it is outside any solid; the join sees the chunk before end there.
TEST(ParallelErrors, StlFacetAfterEndsolid) {
    const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    std::string s = "solid a\n";
    for (int f = 0; f < 50; ++f) s += facet;
    s += "endsolid a\n";
    for (int f = 0; f < 50; ++f) s += facet;
    const Outcome serial = read_with(s, "after.stl", kSerial);
    ASSERT_FALSE(serial.ok);
    EXPECT_NE(serial.what.find("after 'endsolid', found 'facet'"), std::string::npos) << serial.what;
    for (std::size_t size : {1, 64, 1000}) expect_same(serial, read_with(s, "after.stl", chunked(size)), "after");
}


// The start of line `line` (1-based) of s.
std::size_t line_start(const std::string& s, std::size_t line) {
    std::size_t pos = 0;
    for (std::size_t l = 1; l < line; ++l) pos = s.find('\n', pos) + 1;
    return pos;
}

// s with the first token of line `line` replaced by `bad`.
std::string inject(std::string s, std::size_t line, const std::string& bad) {
    std::size_t a = line_start(s, line);
    while (s[a] == ' ' || s[a] == '\t') ++a;
    std::size_t b = a;
    while (b < s.size() && s[b] != ' ' && s[b] != '\n' && s[b] != '\r') ++b;
    return s.replace(a, b - a, bad);
}

// A line of s past `from` (1-based) whose first token is `kw`.
std::size_t line_with(const std::string& s, std::size_t from, const std::string& kw) {
    std::size_t pos = line_start(s, from), line = from;
    for (;;) {
        std::size_t a = pos;
        while (s[a] == ' ') ++a;
        if (s.compare(a, kw.size(), kw) == 0) return line;
        pos = s.find('\n', pos) + 1;
        ++line;
    }
}

TEST(ParallelErrors, OneBadTokenAtVariousLines) {
    struct Case {
        std::string name, data, kw;
    };
    const std::vector<Case> cases = {
        {"e.stl", big_stl(1 << 20, 11), "vertex"},
        {"e.obj", big_obj(1 << 20, 12), "v"},
        {"e.off", big_off(30000, 13), ""},
        {"e.ply", big_ply(30000, 14), ""},
    };
    for (const Case& c : cases) {
        const std::size_t lines = static_cast<std::size_t>(std::count(c.data.begin(), c.data.end(), '\n'));
        for (std::size_t at : {lines / 7, lines / 3, lines / 2 + 1, lines - 40, std::size_t{20}}) {
            const std::size_t line = c.kw.empty() ? at : line_with(c.data, at, c.kw);
            const std::string bad = inject(c.data, line, c.kw.empty() ? "1x" : c.kw + " x");
            for (std::size_t size : {std::size_t{4096}, std::size_t{64} << 10}) {
                const Outcome serial = read_with(bad, c.name, kSerial);
                const Outcome par = read_with(bad, c.name, chunked(size));
                ASSERT_FALSE(serial.ok) << c.name << " line " << line;
                expect_same(serial, par, c.name + " bad token on line " + std::to_string(line));
                EXPECT_GT(par.report.chunks, 1u);
                EXPECT_FALSE(par.report.serial_fallback) << c.name << ": " << par.what;
            }
        }
        // Two bad tokens in different chunks: the first one is reported.
        std::string two = c.data;
        const std::size_t l1 = c.kw.empty() ? lines / 4 : line_with(two, lines / 4, c.kw);
        const std::size_t l2 = c.kw.empty() ? 3 * lines / 4 : line_with(two, 3 * lines / 4, c.kw);
        two = inject(two, l2, "second!");
        two = inject(two, l1, "first!");
        const Outcome serial = read_with(two, c.name, kSerial);
        const Outcome par = read_with(two, c.name, chunked(16 << 10));
        ASSERT_FALSE(serial.ok);
        EXPECT_NE(serial.what.find("first"), std::string::npos) << serial.what;
        expect_same(serial, par, c.name + " two bad tokens");
        EXPECT_FALSE(par.report.serial_fallback);
        // And only the later one.
        const std::string late = inject(c.data, l2, "second!");
        expect_same(read_with(late, c.name, kSerial), read_with(late, c.name, chunked(16 << 10)),
                    c.name + " late bad token");
    }
}

TEST(ParallelErrors, ObjIndexErrorsUseTheGlobalVertexCount) {
    const std::string base = big_obj(1 << 20, 21);
    const std::size_t lines = static_cast<std::size_t>(std::count(base.begin(), base.end(), '\n'));
    // A negative index reaching before the first vertex, late in the file.
    const std::string neg = base + "f -1 -2 -99999999\n";
    // A forward reference never defined, early in the file, and index 0.
    std::string fwd = base;
    fwd.insert(line_start(fwd, lines / 5), "f 1 2 99999999\n");
    std::string zero = base;
    zero.insert(line_start(zero, lines / 2), "f 1 0 2\n");
    for (const std::string* s : std::vector<const std::string*>{&neg, &fwd, &zero}) {
        const Outcome serial = read_with(*s, "i.obj", kSerial);
        ASSERT_FALSE(serial.ok);
        const Outcome par = read_with(*s, "i.obj", chunked(32 << 10));
        expect_same(serial, par, "index error: " + serial.what);
        EXPECT_FALSE(par.report.serial_fallback);
    }
}

// The PLY check of an element's rows against the bytes left, where the
// element starts in a later chunk.
TEST(ParallelErrors, PlyRowCountAgainstBytesInALaterChunk) {
    std::string s = "ply\nformat ascii 1.0\nelement vertex 3000\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                    "element pair 9000\nproperty int a\nproperty int b\nproperty int c\nend_header\n";
    for (int v = 0; v < 3000; ++v) s += "1 2 3\n";
    s += "3 0 1 2\n\n\n";
    // One value a line where a row has three, and not a number: a chunk
    // reading the first row would fail on it, but the serial reader fails
    // first on the count, at the end of the face row.
    for (int i = 0; i < 9000; ++i) s += "x\n";
    const Outcome serial = read_with(s, "rows.ply", kSerial);
    ASSERT_FALSE(serial.ok);
    EXPECT_EQ(serial.what, "rows.ply:3014: element 'pair' declares 9000 rows but only 18003 bytes follow");
    for (std::size_t size : {64, 1000, 4096}) {
        const Outcome par = read_with(s, "rows.ply", chunked(size));
        expect_same(serial, par, "rows");
        EXPECT_FALSE(par.report.serial_fallback);
    }
}

// ---- binary PLY -------------------------------------------------------------

// A binary PLY of a strip of quads or triangles (k = 0: mixed sizes), with a
// skipped property and a list before the indices.
std::string big_binary_ply(std::size_t vertices, uint32_t k, bool be) {
    std::string s = "ply\nformat ";
    s += be ? "binary_big_endian" : "binary_little_endian";
    s += " 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty double y\nproperty uchar flag\nproperty float z\nelement face " +
         std::to_string(vertices - 4) +
         "\nproperty list uchar uchar tex\nproperty list uchar int vertex_indices\nproperty short s\nend_header\n";
    Numbers r(9);
    for (std::size_t v = 0; v < vertices; ++v) {
        put_f32(s, static_cast<float>(std::stod(r.coord())), be);
        put_f64(s, std::stod(r.coord()), be);
        s += '\x05';
        put_f32(s, static_cast<float>(v), be);
    }
    for (std::size_t f = 0; f + 4 < vertices; ++f) {
        s += '\x01';
        s += '\x07';
        const uint32_t size = k != 0 ? k : (f % 100 == 7 ? 4 : 3);
        s += static_cast<char>(size);
        for (uint32_t j = 0; j < size; ++j) put_u32(s, static_cast<uint32_t>(f + j), be);
        put_u16(s, 3, be);
    }
    return s;
}

TEST(ParallelBinaryPly, SameAsSerial) {
    for (bool be : {false, true}) {
        for (uint32_t k : {3u, 4u, 0u}) {
            const std::string s = big_binary_ply(100000, k, be);
            const Outcome serial = read_with(s, "b.ply", kSerial);
            ASSERT_TRUE(serial.ok) << serial.what;
            for (std::size_t size : {std::size_t{4096}, std::size_t{1} << 20}) {
                const Outcome par = read_with(s, "b.ply", chunked(size));
                expect_same(serial, par, "binary ply k=" + std::to_string(k));
                EXPECT_GT(par.report.chunks, 1u);
                EXPECT_EQ(par.report.serial_fallback, k == 0);  // faces of mixed sizes: read serially
            }
        }
    }
}

// A first row whose list uses up every byte left, then a plain property and
// another list: the layout check of row 0 once subtracted past zero there and
// read the second list's count beyond the end of the buffer (issue #23).
// Parallel and serial now give the same error, at the same byte.
TEST(ParallelBinaryPly, ARowLongerThanTheFileIsTruncation) {
    for (bool be : {false, true}) {
        std::string s = "ply\nformat ";
        s += be ? "binary_big_endian" : "binary_little_endian";
        s += " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 2\nproperty list uchar int vertex_indices\nproperty double w\n"
             "property list uchar int extra\nend_header\n";
        for (int v = 0; v < 9; ++v) put_f32(s, static_cast<float>(v), be);
        s += static_cast<char>(60);  // 60 indices: 240 bytes, all that follows
        for (uint32_t j = 0; j < 60; ++j) put_u32(s, j % 3, be);
        s = std::string(s.begin(), s.end());  // no spare capacity: a read past the end is one for ASan
        const Outcome serial = read_with(s, "long.ply", kSerial);
        ASSERT_FALSE(serial.ok);
        EXPECT_NE(serial.what.find("truncated PLY body"), std::string::npos) << serial.what;
        for (std::size_t size : {std::size_t{16}, std::size_t{4096}}) {
            const Outcome par = read_with(s, "long.ply", chunked(size));
            EXPECT_FALSE(par.ok);
            EXPECT_EQ(par.what, serial.what);
        }
    }
}

TEST(ParallelBinaryPly, ErrorsAtTheSameByte) {
    const std::string s = big_binary_ply(100000, 3, false);
    const std::size_t body = s.find("end_header\n") + 11;
    const std::size_t vrow = 4 + 8 + 1 + 4, frow = 2 + 1 + 12 + 2;
    const std::size_t faces = body + 100000 * vrow;
    auto nan_at = [&](std::string t, std::size_t v) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        std::memcpy(&t[body + v * vrow + 13], &nan, 4);  // z of vertex v
        return t;
    };
    auto bad_index_at = [&](std::string t, std::size_t f) {
        t[faces + f * frow + 3 + 4 + 3] = '\x7f';  // the second index, far out of range
        return t;
    };
    const std::vector<std::string> bad = {
        nan_at(s, 70000), nan_at(nan_at(s, 90000), 30000), bad_index_at(s, 50000),
        bad_index_at(bad_index_at(s, 99000), 20000), bad_index_at(nan_at(s, 99999), 0),
    };
    for (const std::string& t : bad) {
        const Outcome serial = read_with(t, "e.ply", kSerial);
        ASSERT_FALSE(serial.ok);
        for (std::size_t size : {std::size_t{4096}, std::size_t{64} << 10}) {
            const Outcome par = read_with(t, "e.ply", chunked(size));
            expect_same(serial, par, "binary ply error: " + serial.what);
            EXPECT_FALSE(par.report.serial_fallback);
        }
    }
}

TEST(ParallelBinaryPly, PrefixesAndByteFlips) {
    std::mt19937 rng(31);
    for (const std::string& full : {write_ply(octahedron(), PlyEnc::le), write_ply(quad_cube(), PlyEnc::be),
                                    big_binary_ply(40, 0, false), big_binary_ply(40, 3, true)}) {
        for (std::size_t n = 0; n <= full.size(); ++n) {
            const std::string t = full.substr(0, n);
            expect_same(read_with(t, "p.ply", kSerial), read_with(t, "p.ply", chunked(1 + n % 50)),
                        "binary prefix " + std::to_string(n));
        }
        for (int i = 0; i < 300; ++i) {
            std::string t = full;
            for (int k = 0; k < 3; ++k) t[rng() % t.size()] = static_cast<char>(rng() & 0xff);
            expect_same(read_with(t, "p.ply", kSerial), read_with(t, "p.ply", chunked(1 + rng() % 60)),
                        "binary flip " + std::to_string(i));
        }
    }
}

// ---- inputs that are read serially ------------------------------------------

TEST(ParallelFallback, RecordsSpanningLinesAreReadSerially) {
    // OFF values may run onto the next line; PLY rows may share lines.
    std::string off = "OFF\n2000 1 0\n";
    for (int v = 0; v < 2000; ++v) off += v % 2 ? "1 2\n3\n" : "1 2 3\n";
    off += "3 0 1 2\n";
    std::string ply = "ply\nformat ascii 1.0\nelement vertex 2000\nproperty float x\nproperty float y\n"
                      "property float z\nend_header\n";
    for (int v = 0; v < 1000; ++v) ply += v == 600 ? "1 2 3 4 5 6\n" : "1 2 3\n1 2 3\n";
    ply += "1 2 3\n1 2 3\n";
    // An STL facet whose normal runs onto a line starting with 'facet'.
    std::string stl = "solid x\n";
    for (int f = 0; f < 300; ++f) {
        stl += f == 150 ? "facet normal 0 0\nfacet outer loop\n" : "facet normal 0 0 1\nouter loop\n";
        stl += "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    }
    stl += "endsolid x\n";
    for (const auto& [data, name] : {std::pair{off, "s.off"}, std::pair{ply, "s.ply"}, std::pair{stl, "s.stl"}}) {
        const Outcome serial = read_with(data, name, kSerial);
        ASSERT_TRUE(serial.ok) << serial.what;
        for (std::size_t size : {1, 64, 4096}) {
            const Outcome par = read_with(data, name, chunked(size));
            expect_same(serial, par, name);
            // The STL quirk is inside a chunk unless chunks start at every facet.
            if (size == 1 || std::string(name) != "s.stl") {
                EXPECT_TRUE(par.report.serial_fallback) << name << size;
            }
        }
    }
}

TEST(ParallelFallback, SmallInputsAreReadSerially) {
    const std::string s = write_obj(quad_cube());
    const Outcome o = read_with(s, "small.obj", ParseOptions{});
    ASSERT_TRUE(o.ok);
    EXPECT_EQ(o.report.chunks, 0u);
    // Past the threshold, even when smaller than one default chunk, an
    // input is cut into several.
    const std::string mid = big_obj(std::size_t{3} << 19, 40);
    const Outcome m = read_with(mid, "mid.obj", ParseOptions{});
    ASSERT_TRUE(m.ok) << m.what;
    EXPECT_GE(m.report.chunks, 8u);
    EXPECT_FALSE(m.report.serial_fallback);
}

}  // namespace
