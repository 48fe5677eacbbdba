// The STL reader welds the facets' corners (LoadedMesh, io.hpp): whatever
// path it takes (serial, ASCII chunks, blocks of binary records), the mesh
// is welded(soup) of the corners it read, bit for bit, and has one vertex
// per distinct point of the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "io/chunks.hpp"
#include "io_helpers.hpp"
#include "parse_helpers.hpp"

namespace {

using namespace iotest;
using polyvol::io::ParseOptions;
using polyvol::io::ScopedParseOptions;

LoadedMesh read_with(const std::string& data, const std::string& name, const ParseOptions& options) {
    const ScopedParseOptions scope(options);
    return read(data, name);
}

const ParseOptions kSoup{.weld_stl = false};

// A closed surface with shared vertices as an STL soup: the n x n lattice
// on a torus, (i, j) at (i - n/2, j - n/2, (7i + 3j) mod 5 / 4), two
// triangles a cell (every 97th cell a quad, when quads), facets shuffled
// when asked so that a point's corners fall in different chunks and blocks.
// A point with x == 0 is written as +0 or -0 at random, corner by corner.
// Every value is a float32, so binary and ASCII files hold the same numbers.
Mesh lattice_soup(int n, bool quads, bool shuffled, uint32_t seed) {
    std::mt19937 rng(seed);
    Mesh m;
    auto corner = [&](int i, int j) {
        i = (i + n) % n;
        j = (j + n) % n;
        double x = i - n / 2;
        if (x == 0 && rng() % 2) x = -0.0;
        return m.add_vertex(x, j - n / 2, ((7 * i + 3 * j) % 5) / 4.0);
    };
    std::vector<std::pair<int, int>> cells;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) cells.emplace_back(i, j);
    if (shuffled) std::shuffle(cells.begin(), cells.end(), rng);
    for (const auto& [i, j] : cells) {
        if (quads && (i * n + j) % 97 == 5) {
            const uint32_t q[4] = {corner(i, j), corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1)};
            m.add_face(q);
            continue;
        }
        const uint32_t a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1);
        m.add_triangle(a, b, c);
        const uint32_t d = corner(i, j), e = corner(i + 1, j + 1), f = corner(i, j + 1);
        m.add_triangle(d, e, f);
    }
    return m;
}

// Checks every way of reading `data` against welded(soup).
void expect_welded_everywhere(const std::string& data, const std::string& name, std::size_t distinct_points,
                              const std::vector<ParseOptions>& parallel) {
    const LoadedMesh soup = read_with(data, name, kSoup);
    ASSERT_EQ(soup.mesh.indices.size(), soup.mesh.vertex_count()) << name << ": corner i is vertex i";
    EXPECT_EQ(soup.vertices_in_file, soup.mesh.vertex_count()) << name;
    const Mesh want = polyvol::welded(soup.mesh.view());
    EXPECT_EQ(want.vertex_count(), distinct_points) << name;
    const LoadedMesh serial = read_with(data, name, kSerial);
    expect_same_mesh(serial.mesh, want, name + " serially");
    EXPECT_EQ(serial.vertices_in_file, soup.vertices_in_file) << name;
    EXPECT_EQ(serial.notes, soup.notes) << name;
    for (const ParseOptions& o : parallel) {
        const LoadedMesh par = read_with(data, name, o);
        const std::string what = name + " with chunks of " + std::to_string(o.chunk_bytes);
        expect_same_mesh(par.mesh, want, what);
        EXPECT_EQ(par.vertices_in_file, soup.vertices_in_file) << what;
        EXPECT_EQ(par.notes, soup.notes) << what;
        EXPECT_GT(polyvol::io::thread_parse_report().chunks, 1u) << what;
    }
}

TEST(StlWeld, AsciiInChunksIsTheWeldedSoup) {
    for (bool shuffled : {false, true}) {
        const int n = 120;  // 28 800 facets, about 6 MB of text
        const Mesh soup = lattice_soup(n, true, shuffled, 7);
        const std::string data = write_ascii_stl(soup);
        expect_welded_everywhere(data, shuffled ? "shuffled.stl" : "ordered.stl", std::size_t(n) * n,
                                 {chunked(64 << 10), chunked(1 << 20), ParseOptions{}});
    }
}

TEST(StlWeld, BinaryInBlocksIsTheWeldedSoup) {
    for (bool shuffled : {false, true}) {
        const int n = 130;  // 33 800 triangles (1.7 MB): three blocks of the welding reader
        const Mesh soup = lattice_soup(n, false, shuffled, 11);
        const std::string data = write_binary_stl(soup);
        expect_welded_everywhere(data, shuffled ? "shuffled.bin.stl" : "ordered.bin.stl", std::size_t(n) * n,
                                 {chunked(1 << 20), ParseOptions{}});
    }
}

// Files of exactly one and two blocks, one more, and none: the same.
TEST(StlWeld, BinaryAtBlockBoundaries) {
    const Mesh big = lattice_soup(130, false, true, 5);  // 33 800 triangles
    for (std::size_t triangles : {std::size_t{0}, std::size_t{1}, std::size_t{16383}, std::size_t{16384},
                                  std::size_t{16385}, std::size_t{32768}}) {
        Mesh m;
        m.positions.assign(big.positions.begin(), big.positions.begin() + static_cast<std::ptrdiff_t>(9 * triangles));
        m.indices.assign(big.indices.begin(), big.indices.begin() + static_cast<std::ptrdiff_t>(3 * triangles));
        const std::string data = write_binary_stl(m);
        const std::string what = std::to_string(triangles) + " triangles";
        const LoadedMesh soup = read_with(data, "b.stl", kSoup);
        ASSERT_EQ(soup.mesh.vertex_count(), 3 * triangles) << what;
        const Mesh want = polyvol::welded(soup.mesh.view());
        for (const ParseOptions& o : {kSerial, chunked(1)}) {
            const LoadedMesh r = read_with(data, "b.stl", o);
            expect_same_mesh(r.mesh, want, what);
            EXPECT_EQ(r.vertices_in_file, 3 * triangles) << what;
            EXPECT_EQ(r.mesh.face_count(), triangles) << what;
        }
    }
}

// The corners of a point keep the first one's sign of zero: welded(soup)
// takes the first corner's position, and the reader does too.
// Also when the corners are in different blocks or chunks: here the point
// (0, 1, 2) is first met as -0 and (0, 3, 4) as +0, in the first facet, and
// again with the other sign in the last.
TEST(StlWeld, TheFirstCornerDecidesTheSignOfZero) {
    for (std::size_t filler : {std::size_t{0}, std::size_t{20000}}) {
        Mesh soup;
        soup.add_triangle(soup.add_vertex(-0.0, 1, 2), soup.add_vertex(0.0, 3, 4), soup.add_vertex(0, 1, 0));
        for (std::size_t t = 0; t < filler; ++t) {
            const double x = static_cast<double>(t + 10);
            soup.add_triangle(soup.add_vertex(x, 0, 0), soup.add_vertex(x, 1, 0), soup.add_vertex(x, 0, 1));
        }
        soup.add_triangle(soup.add_vertex(0.0, 1, 2), soup.add_vertex(0, 1, 0), soup.add_vertex(-0.0, 3, 4));
        for (const std::string& data : {write_ascii_stl(soup), write_binary_stl(soup)}) {
            for (const ParseOptions& o : {kSerial, chunked(64 << 10)}) {
                const LoadedMesh r = read_with(data, "z.stl", o);
                ASSERT_EQ(r.mesh.vertex_count(), 3 + 3 * filler);
                EXPECT_TRUE(std::signbit(r.mesh.positions[0]));
                EXPECT_FALSE(std::signbit(r.mesh.positions[3]));
                EXPECT_EQ(r.vertices_in_file, 6 + 3 * filler);
                EXPECT_EQ(face_of(r.mesh, filler + 1), (std::vector<uint32_t>{0, 2, 1}));
            }
        }
    }
}

// Blocks are read in parallel; the error is still the first bad coordinate
// in the file.
TEST(StlWeld, BinaryErrorIsTheFirstNonFiniteCoordinate) {
    const std::string data = write_binary_stl(lattice_soup(130, false, false, 3));  // 33 800 triangles
    auto nan_at = [](std::string s, std::size_t triangle, int coordinate) {
        const auto nan = std::bit_cast<std::array<char, 4>>(std::numeric_limits<float>::quiet_NaN());
        s.replace(84 + 50 * triangle + 12 + 4 * static_cast<std::size_t>(coordinate), 4, nan.data(), 4);
        return s;
    };
    struct Case {
        std::string data;
        std::size_t triangle;
        int coordinate;
    };
    const std::vector<Case> cases = {
        {nan_at(data, 30000, 4), 30000, 4},
        {nan_at(nan_at(data, 33799, 8), 9000, 2), 9000, 2},
        {nan_at(nan_at(data, 16384, 0), 16383, 8), 16383, 8},
    };
    for (const Case& c : cases) {
        for (const ParseOptions& o : {kSerial, chunked(1 << 20), kSoup}) {
            const ScopedParseOptions scope(o);
            const ReadError e = read_error(c.data, "nan.stl");
            EXPECT_TRUE(e.has_byte_offset);
            EXPECT_EQ(e.byte_offset, 84 + 50 * c.triangle + 12 + 4 * static_cast<std::size_t>(c.coordinate));
            EXPECT_NE(e.message.find("non-finite coordinate in triangle " + std::to_string(c.triangle)),
                      std::string::npos)
                << e.message;
        }
    }
}

// Every STL of the corpus: read_mesh_file's mesh is welded(soup).
TEST(StlWeld, EveryCorpusStlIsTheWeldedSoup) {
    std::size_t files = 0;
    for (const nlohmann::json& e : polyvol::test::corpus_manifest()) {
        if (e.value("format", "") != "stl" || polyvol::test::invalid_entry(e)) continue;
        const std::string path = polyvol::test::corpus_file(e.at("path").get<std::string>());
        SCOPED_TRACE(path);
        LoadedMesh soup;
        {
            const ScopedParseOptions scope(kSoup);
            soup = polyvol::read_mesh_file(path);
        }
        const LoadedMesh r = polyvol::read_mesh_file(path);
        expect_same_mesh(r.mesh, polyvol::welded(soup.mesh.view()), path);
        EXPECT_EQ(r.vertices_in_file, soup.mesh.vertex_count());
        EXPECT_EQ(r.notes, soup.notes);
        ++files;
    }
    EXPECT_GE(files, 30u);
}

}  // namespace
