#include <bit>
#include <cstring>
#include <unordered_map>

#include "polyvol/mesh.hpp"

namespace polyvol {
namespace {

struct Key {
    uint64_t x, y, z;
    bool operator==(const Key&) const = default;
};
struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept {
        // splitmix-style mixing of the three bit patterns
        uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
        h ^= (k.y + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
        h ^= (k.z + 0x85EBCA77C2B2AE63ull) * 0x165667B19E3779F9ull;
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

// Bit pattern with -0.0 mapped to +0.0, so the two weld together.
uint64_t canonical_bits(double v) { return std::bit_cast<uint64_t>(v == 0.0 ? 0.0 : v); }

}  // namespace

std::vector<uint32_t> weld_vertices(std::span<const double> positions) {
    const std::size_t n = positions.size() / 3;
    std::vector<uint32_t> out(n);
    std::unordered_map<Key, uint32_t, KeyHash> first;
    first.reserve(n);
    for (std::size_t v = 0; v < n; ++v) {
        const double* p = &positions[3 * v];
        if (p[0] != p[0] || p[1] != p[1] || p[2] != p[2]) {  // NaN: never equal to anything
            out[v] = static_cast<uint32_t>(v);
            continue;
        }
        const Key k{canonical_bits(p[0]), canonical_bits(p[1]), canonical_bits(p[2])};
        auto [it, inserted] = first.try_emplace(k, static_cast<uint32_t>(v));
        out[v] = it->second;
    }
    return out;
}

}  // namespace polyvol
