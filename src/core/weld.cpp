// Welding bit-identical positions: an open-addressing hash table of vertex
// ids (linear probing, capacity a power of two >= 2n, so probes stay short
// and no allocation happens per vertex). Keys are compared as doubles, which
// is bit equality except that -0.0 == +0.0 (wanted) and NaN != NaN (NaN
// vertices are never inserted).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "polyvol/mesh.hpp"

namespace polyvol {
namespace {

// Bit pattern with -0.0 mapped to +0.0, so the two hash alike.
uint64_t canonical_bits(double v) { return std::bit_cast<uint64_t>(v == 0.0 ? 0.0 : v); }

// Mixes the three bit patterns (multiply-xorshift, as in splitmix64).
uint64_t position_hash(const double* p) {
    uint64_t h = canonical_bits(p[0]) * 0x9E3779B97F4A7C15ull;
    h ^= (canonical_bits(p[1]) + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (canonical_bits(p[2]) + 0x85EBCA77C2B2AE63ull) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 32);
}

}  // namespace

std::vector<uint32_t> weld_vertices(std::span<const double> positions) {
    const std::size_t n = positions.size() / 3;
    if (n >= UINT32_MAX) throw std::length_error("weld_vertices: more than 2^32 - 2 vertices");
    std::vector<uint32_t> out(n);
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * n, 16));
    const std::size_t mask = capacity - 1;
    std::vector<uint32_t> slots(capacity, 0);  // vertex id + 1; 0 is empty
    const double* pos = positions.data();
    for (std::size_t v = 0; v < n; ++v) {
        const double* p = pos + 3 * v;
        if (p[0] != p[0] || p[1] != p[1] || p[2] != p[2]) {  // NaN: never equal to anything
            out[v] = static_cast<uint32_t>(v);
            continue;
        }
        std::size_t i = position_hash(p) & mask;
        for (;;) {
            const uint32_t s = slots[i];
            if (s == 0) {
                slots[i] = static_cast<uint32_t>(v + 1);
                out[v] = static_cast<uint32_t>(v);
                break;
            }
            const double* q = pos + 3 * (s - 1);
            if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) {
                out[v] = s - 1;
                break;
            }
            i = (i + 1) & mask;
        }
    }
    return out;
}

Mesh welded(const MeshView& mesh) {
    const std::vector<uint32_t> canonical = weld_vertices(mesh.positions);
    const std::size_t n = canonical.size();
    std::vector<uint32_t> id(n);
    Mesh out;
    uint32_t next = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (canonical[v] == v) {  // the first of its class (canonical[v] <= v)
            id[v] = next++;
            out.positions.insert(out.positions.end(), mesh.positions.begin() + 3 * v,
                                 mesh.positions.begin() + 3 * v + 3);
        } else {
            id[v] = id[canonical[v]];
        }
    }
    out.face_offsets.assign(mesh.face_offsets.begin(), mesh.face_offsets.end());
    out.indices.resize(mesh.indices.size());
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) out.indices[i] = id[mesh.indices[i]];
    return out;
}

}  // namespace polyvol
