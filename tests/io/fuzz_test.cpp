// Robustness: random bytes, every truncated prefix of small valid files, and
// random byte mutations of them go through read_mesh_memory. Each must either
// succeed with a consistent mesh or throw ReadError: no other exception, no
// crash (run under -DPOLYVOL_SANITIZE=ON to check memory too), no hang.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "io_helpers.hpp"

namespace {

using namespace iotest;

// Reads; returns true on success. A success must keep mesh.hpp's promises.
bool survives(const std::string& data, const std::string& name) {
    try {
        const LoadedMesh m = read(data, name);
        const polyvol::MeshView v = m.mesh.view();
        EXPECT_EQ(m.mesh.positions.size() % 3, 0u);
        for (uint32_t i : v.indices) EXPECT_LT(i, v.vertex_count()) << name;
        if (!v.face_offsets.empty()) {
            EXPECT_EQ(v.face_offsets.front(), 0u);
            EXPECT_EQ(v.face_offsets.back(), v.indices.size());
        } else {
            EXPECT_EQ(v.indices.size() % 3, 0u);
        }
        return true;
    } catch (const ReadError& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        EXPECT_FALSE(e.message.empty());
        return false;
    } catch (const std::exception& e) {
        ADD_FAILURE() << name << ": not a ReadError: " << e.what();
        return false;
    }
}

std::string random_bytes(std::mt19937& rng, std::size_t n) {
    std::string s(n, '\0');
    for (char& c : s) c = static_cast<char>(rng() & 0xff);
    return s;
}

TEST(Fuzz, RandomBytes) {
    std::mt19937 rng(20240611);
    const char* names[] = {"r.stl", "r.obj", "r.off", "r.ply", "r.bin", "r.stl.gz", "r.3mf", "r.amf"};
    for (int i = 0; i < 400; ++i) {
        const std::size_t n = rng() % 600;
        survives(random_bytes(rng, n), names[i % 8]);
    }
}

// Random bytes after a format's magic, so the readers themselves are reached.
TEST(Fuzz, RandomBytesAfterMagic) {
    std::mt19937 rng(7);
    const std::string magics[] = {"solid x\n", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n",
                                  "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                                  "property float y\nproperty float z\nelement face 1\n"
                                  "property list uchar int vertex_indices\nend_header\n",
                                  "OFF\n", "OFF\n3 1 0\n", "v 1 2 3\nf ", "\x1f\x8b\x08\x00", "<?xml version=\"1.0\"?>",
                                  "\xfe\xff", "\xff\xfe"};
    for (int i = 0; i < 400; ++i) {
        const std::string& magic = magics[i % std::size(magics)];
        std::string name = "m";
        name += std::to_string(i);
        survives(magic + random_bytes(rng, rng() % 300), name);
    }
}

// Random text made of the tokens the text readers look for.
TEST(Fuzz, RandomTokens) {
    std::mt19937 rng(99);
    const char* tokens[] = {"solid", "endsolid", "facet", "normal", "outer", "loop", "endloop", "endfacet",
                            "vertex", "v", "f", "l", "p", "OFF", "COFF", "ply", "end_header", "element",
                            "property", "list", "uchar", "int", "float", "format", "ascii", "0", "1", "2",
                            "-1", "3", "1e300", "nan", "#", "/", "//", "\\", "\n", "\r\n", " ", "\t", "1.5",
                            "4294967295", "99999999999999999999"};
    for (int i = 0; i < 400; ++i) {
        std::string s;
        const std::size_t n = rng() % 80;
        for (std::size_t k = 0; k < n; ++k) {
            s += tokens[rng() % std::size(tokens)];
            s += (rng() % 3 == 0) ? "\n" : " ";
        }
        survives(s, i % 2 ? "t.obj" : "t.off");
    }
}

void every_prefix(const std::string& full, const std::string& name) {
    ASSERT_TRUE(survives(full, name)) << "the full file must read";
    for (std::size_t n = 0; n < full.size(); ++n) survives(full.substr(0, n), name);
}

TEST(Fuzz, EveryPrefixOfBinaryPly) {
    every_prefix(write_ply(octahedron(), PlyEnc::le), "p.ply");
    every_prefix(write_ply(quad_cube(), PlyEnc::be), "q.ply");
}

TEST(Fuzz, EveryPrefixOfBinaryStl) {
    const std::string full = write_binary_stl(octahedron());
    every_prefix(full, "s.stl");
    // Only the full file has the right size: every proper prefix fails.
    for (std::size_t n = 0; n < full.size(); ++n) EXPECT_FALSE(survives(full.substr(0, n), "s.stl")) << n;
}

TEST(Fuzz, EveryPrefixOfAsciiOff) {
    every_prefix(write_off(quad_cube()), "c.off");
    every_prefix("COFF\n# comment\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2 0.5 0.5 0.5\n", "col.off");
}

TEST(Fuzz, EveryPrefixOfTheTextFormats) {
    every_prefix(write_ascii_stl(octahedron()), "a.stl");
    every_prefix(write_obj(quad_cube()), "o.obj");
    every_prefix(write_ply(quad_cube(), PlyEnc::ascii), "a.ply");
    every_prefix(gzip_stored(write_obj(octahedron())), "z.obj.gz");
}

TEST(Fuzz, RandomMutations) {
    std::mt19937 rng(12345);
    const std::vector<std::pair<std::string, std::string>> files = {
        {write_binary_stl(octahedron()), "m.stl"},       {write_ascii_stl(octahedron()), "ma.stl"},
        {write_obj(quad_cube()), "m.obj"},               {write_off(quad_cube()), "m.off"},
        {write_ply(quad_cube(), PlyEnc::ascii), "m.ply"}, {write_ply(octahedron(), PlyEnc::le), "ml.ply"},
        {write_ply(octahedron(), PlyEnc::be), "mb.ply"},  {gzip_stored(write_off(quad_cube())), "m.off.gz"}};
    for (const auto& [data, name] : files) {
        for (int i = 0; i < 150; ++i) {
            std::string s = data;
            const int flips = 1 + static_cast<int>(rng() % 4);
            for (int k = 0; k < flips; ++k) s[rng() % s.size()] = static_cast<char>(rng() & 0xff);
            survives(s, name);
        }
    }
}

}  // namespace
