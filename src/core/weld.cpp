// Welding bit-identical positions. Keys are compared as doubles, which is
// bit equality except that -0.0 == +0.0 (wanted) and NaN != NaN (NaN
// vertices are never welded).
//
// Small inputs: one open-addressing hash table of vertex ids (linear
// probing, capacity a power of two >= 2n, so probes stay short and no
// allocation happens per vertex). Large ones (a table of 2n ids no longer
// fits in cache, and most probes miss it): partitioned, as a radix hash
// join does. The vertices go into 2^k buckets by the top bits of their
// hash (each bucket a few thousand, copied with their coordinates, in
// increasing index order: counting pass, prefix sums, scatter), then each
// bucket is welded with a small table that stays in cache. Chunks and
// buckets run on oneTBB. Within a bucket the first of a class is its
// smallest index, so the result is the serial one, whatever the schedule.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "core/prefault.hpp"
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

bool has_nan(const double* p) { return p[0] != p[0] || p[1] != p[1] || p[2] != p[2]; }

bool same_position(const double* p, const double* q) { return q[0] == p[0] && q[1] == p[1] && q[2] == p[2]; }

// Welds m vertices in increasing index order with one table (slots: reused
// storage): out[index(j)] = index of the first of j's class. position(j),
// index(j) and hash(j) give vertex j's coordinates, original index and hash.
template <class Position, class Index, class Hash>
void weld_with_table(std::size_t m, Position position, Index index, Hash hash, std::vector<uint32_t>& slots,
                     uint32_t* out) {
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * m, 16));
    const std::size_t mask = capacity - 1;
    slots.assign(capacity, 0);  // j + 1; 0 is empty
    for (std::size_t j = 0; j < m; ++j) {
        const double* p = position(j);
        if (has_nan(p)) {  // never equal to anything
            out[index(j)] = index(j);
            continue;
        }
        std::size_t i = hash(j) & mask;
        for (;;) {
            const uint32_t s = slots[i];
            if (s == 0) {
                slots[i] = static_cast<uint32_t>(j + 1);
                out[index(j)] = index(j);
                break;
            }
            if (same_position(position(s - 1), p)) {
                out[index(j)] = index(s - 1);
                break;
            }
            i = (i + 1) & mask;
        }
    }
}

// One table for vertices [0, n) (the small-input path).
void weld_serial(const double* pos, std::size_t n, uint32_t* out) {
    std::vector<uint32_t> slots;
    weld_with_table(
        n, [pos](std::size_t v) { return pos + 3 * v; }, [](std::size_t v) { return static_cast<uint32_t>(v); },
        [pos](std::size_t v) { return position_hash(pos + 3 * v); }, slots, out);
}

// A vertex copied into its bucket.
struct Entry {
    double xyz[3];
    uint32_t index;
    uint32_t hash;  // low bits of position_hash: the slot in the bucket's table
};

constexpr std::size_t kSerialBelow = std::size_t{1} << 16;  // vertices
constexpr std::size_t kChunk = std::size_t{1} << 16;        // vertices per task of the two passes, at least
constexpr std::size_t kPerBucket = 4096;                    // about, on average

void weld_partitioned(const double* pos, std::size_t n, uint32_t* out) {
    const int bits = std::clamp(static_cast<int>(std::bit_width(n / kPerBucket)) - 1, 1, 16);
    const std::size_t buckets = std::size_t{1} << bits;
    const int shift = 64 - bits;
    // At most 64 chunks: the counts stay below 64 * 2^16 words.
    const std::size_t chunk = std::max(kChunk, (n + 63) / 64);
    const std::size_t chunks = (n + chunk - 1) / chunk;
    // count[c * buckets + b]: vertices of chunk c in bucket b, then (prefix
    // sums in bucket-major order) where chunk c's first one goes.
    std::vector<uint32_t> count(chunks * buckets, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c < r.end(); ++c) {
            uint32_t* mine = &count[c * buckets];
            const std::size_t end = std::min(n, (c + 1) * chunk);
            for (std::size_t v = c * chunk; v < end; ++v) ++mine[position_hash(pos + 3 * v) >> shift];
        }
    });
    std::vector<uint32_t> bucket_begin(buckets + 1);
    uint32_t at = 0;
    for (std::size_t b = 0; b < buckets; ++b) {
        bucket_begin[b] = at;
        for (std::size_t c = 0; c < chunks; ++c) {
            const uint32_t k = count[c * buckets + b];
            count[c * buckets + b] = at;
            at += k;
        }
    }
    bucket_begin[buckets] = at;
    // Not value-initialised (the scatter writes every entry), faulted in on
    // every core: 32 bytes a vertex, written once and read once.
    const std::unique_ptr<Entry[]> entries(new Entry[n]);
    core::prefault(entries.get(), n * sizeof(Entry));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c < r.end(); ++c) {
            uint32_t* next = &count[c * buckets];
            const std::size_t end = std::min(n, (c + 1) * chunk);
            for (std::size_t v = c * chunk; v < end; ++v) {
                const double* p = pos + 3 * v;
                const uint64_t h = position_hash(p);
                Entry& e = entries[next[h >> shift]++];
                std::memcpy(e.xyz, p, sizeof e.xyz);
                e.index = static_cast<uint32_t>(v);
                e.hash = static_cast<uint32_t>(h);
            }
        }
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, buckets, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<uint32_t> slots;  // reused by the buckets of this range
        for (std::size_t b = r.begin(); b < r.end(); ++b) {
            const Entry* e = entries.get() + bucket_begin[b];
            weld_with_table(
                bucket_begin[b + 1] - bucket_begin[b], [e](std::size_t j) { return e[j].xyz; },
                [e](std::size_t j) { return e[j].index; }, [e](std::size_t j) { return uint64_t{e[j].hash}; }, slots,
                out);
        }
    });
}

}  // namespace

std::vector<uint32_t> weld_vertices(std::span<const double> positions) {
    const std::size_t n = positions.size() / 3;
    if (n >= UINT32_MAX) throw std::length_error("weld_vertices: more than 2^32 - 2 vertices");
    std::vector<uint32_t> out(n);
    if (n < kSerialBelow) {
        weld_serial(positions.data(), n, out.data());
    } else {
        weld_partitioned(positions.data(), n, out.data());
    }
    return out;
}

Mesh welded(const MeshView& mesh) {
    const std::vector<uint32_t> canonical = weld_vertices(mesh.positions);
    const std::size_t n = canonical.size();
    std::vector<uint32_t> id(n);
    std::size_t classes = 0;
    for (std::size_t v = 0; v < n; ++v) classes += canonical[v] == v;
    Mesh out;
    out.positions.resize(3 * classes);
    uint32_t next = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (canonical[v] == v) {  // the first of its class (canonical[v] <= v)
            std::memcpy(&out.positions[3 * std::size_t{next}], &mesh.positions[3 * v], 3 * sizeof(double));
            id[v] = next++;
        } else {
            id[v] = id[canonical[v]];
        }
    }
    out.face_offsets.assign(mesh.face_offsets.begin(), mesh.face_offsets.end());
    out.indices.resize(mesh.indices.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.indices.size(), std::size_t{1} << 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i) out.indices[i] = id[mesh.indices[i]];
                      });
    return out;
}

}  // namespace polyvol
