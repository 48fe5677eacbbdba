// Readers of the .chain, qhull OFF and polygon text formats: values, errors
// with line numbers, every truncated prefix failing cleanly.
#include <gtest/gtest.h>

#include <cstddef>
#include <random>
#include <string>

#include "polyvol/chain_io.hpp"
#include "polyvol/simplicial.hpp"

using namespace polyvol;

namespace {

std::span<const std::byte> bytes(const std::string& s) { return {reinterpret_cast<const std::byte*>(s.data()), s.size()}; }

LoadedChain chain(const std::string& s) { return read_chain_memory(bytes(s), "t.chain"); }

uint64_t error_line(const std::string& s) {
    try {
        chain(s);
    } catch (const ReadError& e) {
        return e.line;
    }
    ADD_FAILURE() << "no error for:\n" << s;
    return 0;
}

const std::string kTetra =
    "# the unit tetrahedron's boundary\n"
    "# (counter-clockwise seen from outside)\n"
    "3 4 4\n"
    "0 0 0\n"
    "1 0 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "0 2 1\n"
    "0 1 3\n"
    "0 3 2\n"
    "1 2 3\n";

}  // namespace

TEST(ChainReader, ReadsTheDotChainFormat) {
    const LoadedChain l = chain(kTetra);
    EXPECT_EQ(l.format, ChainFormat::chain);
    EXPECT_EQ(l.chain.dimension, 3);
    EXPECT_EQ(l.chain.vertex_count(), 4u);
    EXPECT_EQ(l.chain.simplex_count(), 4u);
    EXPECT_EQ(l.chain.simplices[5], 3u);
    EXPECT_EQ(chain_volume(l.chain.view()).volume, 1.0 / 6);
    // Comments after data, blank lines, CRLF.
    const LoadedChain m = chain("\r\n2 3 3 # a triangle\r\n\r\n0 0\r\n1 0 # x\r\n0 1\r\n0 1\r\n1 2\r\n2 0\r\n");
    EXPECT_EQ(chain_volume(m.chain.view()).volume, 0.5);
}

TEST(ChainReader, ErrorsNameTheLine) {
    EXPECT_EQ(error_line("3 4\n"), 1u);                               // neither header
    EXPECT_EQ(error_line("# c\n1 1 1\n0\n0\n"), 2u);                  // dimension 1
    EXPECT_EQ(error_line("2 2 1\n0 0\n1\n0 1\n"), 3u);                // 1 coordinate
    EXPECT_EQ(error_line("2 2 1\n0 0\n1 x\n0 1\n"), 3u);              // not a number
    EXPECT_EQ(error_line("2 2 1\n0 0\n1 1\n0 2\n"), 4u);              // index out of range
    EXPECT_EQ(error_line("2 2 1\n0 0\n1 1\n0 -1\n"), 4u);             // negative index
    EXPECT_EQ(error_line("2 2 2\n0 0\n1 1\n0 1\n# room for more...\n"), 6u);  // missing simplex (end of file)
    EXPECT_EQ(error_line("2 2 1\n0 0\n1 1\n0 1\n7\n"), 5u);           // trailing data
    EXPECT_EQ(error_line("2 4000000000 1\n0 0\n"), 1u);               // counts larger than the file
    EXPECT_EQ(error_line(""), 1u);
}

TEST(ChainReader, EveryTruncatedPrefixFailsCleanly) {
    for (std::size_t len = 0; len < kTetra.size(); ++len) {
        const std::string prefix = kTetra.substr(0, len);
        try {
            const LoadedChain l = chain(prefix);
            // Only prefixes that end inside the last index's line can parse.
            EXPECT_GE(len, kTetra.size() - 6) << len;
        } catch (const ReadError& e) {
            EXPECT_GE(e.line, 1u);
        }
    }
}

TEST(ChainReader, ReadsQhullOffOutputAndOrientsFacets) {
    // qconvex o Qt output of a square pyramid's hull, facets listed in an
    // arbitrary orientation: the reader turns them outward.
    const std::string q =
        "3\n5 6 9\n"
        "0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 1\n"
        "3 0 1 2\n3 0 2 3\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    const LoadedChain l = chain(q);
    EXPECT_EQ(l.format, ChainFormat::qhull);
    EXPECT_EQ(l.chain.simplex_count(), 6u);
    EXPECT_EQ(l.facets_undecided, 0u);
    EXPECT_GT(l.facets_reoriented, 0u);
    const ChainVolume v = chain_volume(l.chain.view());
    EXPECT_EQ(v.topology.unmatched_faces, 0u);
    EXPECT_EQ(v.volume, 4.0 / 3);
    // Without Qt, 3D facets are polygons in cyclic order: fanned.
    const std::string cube =
        "3\n8 6 12\n"
        "-0.5 -0.5 -0.5\n-0.5 -0.5 0.5\n-0.5 0.5 -0.5\n-0.5 0.5 0.5\n"
        "0.5 -0.5 -0.5\n0.5 -0.5 0.5\n0.5 0.5 -0.5\n0.5 0.5 0.5\n"
        "4 4 6 2 0\n4 1 5 4 0\n4 5 7 6 4\n4 3 1 0 2\n4 7 3 2 6\n4 3 7 5 1\n";
    const LoadedChain lc = chain(cube);
    EXPECT_EQ(lc.chain.simplex_count(), 12u);
    EXPECT_EQ(chain_volume(lc.chain.view()).volume, 1.0);
    // In R^4, a non-simplicial facet needs Qt.
    try {
        chain("4\n5 1 0\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n5 0 1 2 3 4\n");
        ADD_FAILURE();
    } catch (const ReadError& e) {
        EXPECT_EQ(e.line, 8u);
        EXPECT_NE(e.message.find("Qt"), std::string::npos);
    }
}

TEST(PolygonReader, OneLoopPerLine) {
    const std::string text =
        "# outer square counter-clockwise, hole clockwise\n"
        "0 0 10 0 10 10 0 10\n"
        "\n"
        "4 4 4 6 6 6 6 4\n";
    const Polygons p = read_polygons_memory(bytes(text), "p.txt");
    EXPECT_EQ(p.loop_count(), 2u);
    EXPECT_EQ(p.vertex_count(), 8u);
    EXPECT_EQ(polygon_area(p.view()).volume, 96.0);
    try {
        read_polygons_memory(bytes("0 0 1 0 1\n"), "p.txt");
        ADD_FAILURE();
    } catch (const ReadError& e) {
        EXPECT_EQ(e.line, 1u);
    }
}

TEST(ChainReader, MutatedInputsFailCleanly) {
    // Byte flips, insertions and deletions in valid .chain, qhull and polygon
    // texts: every result is a chain the library accepts, or a ReadError.
    const std::string qhull =
        "3\n5 6 9\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 1\n3 0 1 2\n3 0 2 3\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    const std::string polygons = "0 0 10 0 10 10 0 10\n2 2 2 8 8 8 8 2\n";
    std::mt19937_64 rng(99);
    const char alphabet[] = "0123456789 -+.eE#\n\r\tx";
    for (const std::string* base : {&kTetra, &qhull, &polygons}) {
        for (int trial = 0; trial < 600; ++trial) {
            std::string s = *base;
            const int edits = 1 + static_cast<int>(rng() % 4);
            for (int e = 0; e < edits && !s.empty(); ++e) {
                const std::size_t at = rng() % s.size();
                const char ch = alphabet[rng() % (sizeof alphabet - 1)];
                switch (rng() % 3) {
                    case 0: s[at] = ch; break;
                    case 1: s.insert(s.begin() + static_cast<std::ptrdiff_t>(at), ch); break;
                    default: s.erase(at, 1); break;
                }
            }
            try {
                if (base == &polygons) {
                    const Polygons p = read_polygons_memory(bytes(s), "fuzz");
                    (void)polygon_area(p.view());
                } else {
                    const LoadedChain l = chain(s);
                    ChainOptions o;
                    o.accuracy = trial % 2 ? ChainAccuracy::bounded : ChainAccuracy::automatic;
                    (void)chain_volume(l.chain.view(), o);
                    Chain c = l.chain;
                    (void)orient_chain(c);
                }
            } catch (const ReadError&) {
            }
        }
    }
}
