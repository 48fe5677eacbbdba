// The readers' parse options (src/io/chunks.hpp) and a bit-for-bit mesh
// comparison, for the tests that read the same bytes several ways.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include "io/chunks.hpp"
#include "polyvol/mesh.hpp"

namespace iotest {

inline const polyvol::io::ParseOptions kSerial{.parallel = false};

// Parallel with chunks of about `bytes`, whatever the input's size.
inline polyvol::io::ParseOptions chunked(std::size_t bytes) {
    return {.parallel = true, .chunk_bytes = bytes, .min_parallel_bytes = 0};
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Positions (signs of zero and NaN payloads too), indices and face offsets.
inline void expect_same_mesh(const polyvol::Mesh& got, const polyvol::Mesh& want, const std::string& what) {
    EXPECT_TRUE(same_bytes(got.positions, want.positions))
        << what << ": positions differ (" << got.positions.size() << " vs " << want.positions.size() << ")";
    EXPECT_TRUE(same_bytes(got.indices, want.indices))
        << what << ": indices differ (" << got.indices.size() << " vs " << want.indices.size() << ")";
    EXPECT_TRUE(same_bytes(got.face_offsets, want.face_offsets))
        << what << ": face offsets differ (" << got.face_offsets.size() << " vs " << want.face_offsets.size() << ")";
}

}  // namespace iotest
