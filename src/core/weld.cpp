// Welding bit-identical positions. Keys are compared as doubles, which is
// bit equality except that -0.0 == +0.0 (wanted) and NaN != NaN (NaN
// vertices are never welded).
//
// Small inputs: one open-addressing hash table of vertex ids (linear
// probing, capacity a power of two >= 2n, so probes stay short and no
// allocation happens per vertex). Large ones, in two levels:
//   1. Local: runs of kLocal consecutive vertices are welded on their own,
//      each with a table that stays in the core's L2. Triangle soups (every
//      corner its own vertex, as an STL file lists them) repeat each
//      position about six times, mostly within a few thousand triangles
//      (neighbouring strips of the surface), so about five vertices in six
//      are settled here and only the runs' firsts (representatives) go on.
//      (The STL reader welds its blocks first, so its last weld meets few
//      copies in a run and goes straight to the global level.)
//   2. Global, over the representatives: partitioned, as a radix hash join
//      does (a table of 2n ids no longer fits in cache, and most probes
//      would miss it). They go into 2^k buckets by the top bits of their
//      hash (each bucket a few thousand, copied with their coordinates, in
//      increasing index order: counting pass, prefix sums, scatter), then
//      each bucket is welded with a small table that stays in cache.
// Then each vertex takes its representative's answer. Runs, chunks and
// buckets go on oneTBB. The first of a class is its smallest index at each
// level (the class's smallest index is the first of its run, so a
// representative), so the result is the serial one, whatever the schedule.
// An input in no useful order (few copies within a run: the first run
// tells) skips the local level after its first run.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <utility>

#include "core/canonical_bits.hpp"
#include "core/classes.hpp"
#include "core/prefault.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol {
namespace {

using core::canonical_bits;  // -0.0 and +0.0 hash alike

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

// One table for m vertices (position(j), original index(j), increasing in
// j), each position hashed as it comes.
template <class Position, class Index>
void weld_serial(std::size_t m, Position position, Index index, std::vector<uint32_t>& slots, uint32_t* out) {
    weld_with_table(m, position, index, [&](std::size_t j) { return position_hash(position(j)); }, slots, out);
}

// Accessors for consecutive vertices: the position of the j-th of an array,
// and the original index of the j-th of those that start at v0.
auto vertex_at(const double* pos) {
    return [pos](std::size_t j) { return pos + 3 * j; };
}
auto index_from(std::size_t v0) {
    return [v0](std::size_t j) { return static_cast<uint32_t>(v0 + j); };
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
constexpr std::size_t kLocal = std::size_t{1} << 15;        // vertices per run of the local level (a 256 KiB table)
static_assert(kLocal <= kSerialBelow);  // weld_large's first run is a whole one

// Welds m vertices (position(j), original index(j), increasing in j) by
// partitioning: out[index(j)] = index of the first of j's class.
template <class Position, class Index>
void weld_partitioned(std::size_t m, Position position, Index index, uint32_t* out) {
    const int bits = std::clamp(static_cast<int>(std::bit_width(m / kPerBucket)) - 1, 1, 16);
    const std::size_t buckets = std::size_t{1} << bits;
    const int shift = 64 - bits;
    // At most 64 chunks: the counts stay below 64 * 2^16 words.
    const std::size_t chunk = std::max(kChunk, (m + 63) / 64);
    const std::size_t chunks = (m + chunk - 1) / chunk;
    // count[c * buckets + b]: vertices of chunk c in bucket b, then (prefix
    // sums in bucket-major order) where chunk c's first one goes.
    std::vector<uint32_t> count(chunks * buckets, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c < r.end(); ++c) {
            uint32_t* mine = &count[c * buckets];
            const std::size_t end = std::min(m, (c + 1) * chunk);
            for (std::size_t j = c * chunk; j < end; ++j) ++mine[position_hash(position(j)) >> shift];
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
    const std::unique_ptr<Entry[]> entries(new Entry[m]);
    core::prefault(entries.get(), m * sizeof(Entry));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c < r.end(); ++c) {
            uint32_t* next = &count[c * buckets];
            const std::size_t end = std::min(m, (c + 1) * chunk);
            for (std::size_t j = c * chunk; j < end; ++j) {
                const double* p = position(j);
                const uint64_t h = position_hash(p);
                Entry& e = entries[next[h >> shift]++];
                std::memcpy(e.xyz, p, sizeof e.xyz);
                e.index = index(j);
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

// The two levels (see the top of this file) for n >= kSerialBelow vertices.
void weld_large(const double* pos, std::size_t n, uint32_t* out) {
    const std::size_t runs = (n + kLocal - 1) / kLocal;
    // 1. Each run welded alone: out[v] = the first of v's class in its run;
    // run_firsts[r]: how many firsts run r has, then (prefix sums) where
    // they go in `firsts`.
    std::vector<uint32_t> run_firsts(runs + 1, 0);
    const auto weld_run = [&](std::size_t run, std::vector<uint32_t>& slots) {
        const std::size_t v0 = run * kLocal, m = std::min(kLocal, n - v0);
        weld_serial(m, vertex_at(pos + 3 * v0), index_from(v0), slots, out);
        uint32_t k = 0;
        for (std::size_t v = v0; v < v0 + m; ++v) k += out[v] == v;
        run_firsts[run] = k;
    };
    // The first run decides whether the local level pays: when more than half
    // of its vertices are firsts, the input has its copies far apart (e.g.
    // triangles in random order) and the global level takes every vertex.
    {
        std::vector<uint32_t> slots;
        weld_run(0, slots);
        if (2 * std::size_t{run_firsts[0]} > kLocal) {
            weld_partitioned(n, vertex_at(pos), index_from(0), out);
            return;
        }
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(1, runs, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<uint32_t> slots;
        for (std::size_t run = r.begin(); run < r.end(); ++run) weld_run(run, slots);
    });
    uint32_t at = 0;
    for (std::size_t run = 0; run < runs; ++run) at += std::exchange(run_firsts[run], at);
    run_firsts[runs] = at;
    std::vector<uint32_t> firsts(at);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t run = r.begin(); run < r.end(); ++run) {
            uint32_t* f = &firsts[run_firsts[run]];
            const std::size_t end = std::min(n, (run + 1) * kLocal);
            for (std::size_t v = run * kLocal; v < end; ++v)
                if (out[v] == v) *f++ = static_cast<uint32_t>(v);
        }
    });
    // 2. The firsts across runs: out[f] = the first of f's class.
    const auto position = [&](std::size_t j) { return pos + 3 * std::size_t{firsts[j]}; };
    const auto index = [&](std::size_t j) { return firsts[j]; };
    if (firsts.size() < kSerialBelow) {
        std::vector<uint32_t> slots;
        weld_serial(firsts.size(), position, index, slots, out);
    } else {
        weld_partitioned(firsts.size(), position, index, out);
    }
    // 3. Every other vertex takes the answer of its run's first r = out[v]:
    // out[r] is final and is never written here (for a first, out[out[r]]
    // == out[r]), so the pass is free of races.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kChunk), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t v = r.begin(); v < r.end(); ++v) {
            const uint32_t first = out[v], root = out[first];
            if (root != first) out[v] = root;
        }
    });
}

}  // namespace

std::vector<uint32_t> weld_vertices(std::span<const double> positions) {
    const std::size_t n = positions.size() / 3;
    if (n >= UINT32_MAX) throw std::length_error("weld_vertices: more than 2^32 - 2 vertices");
    std::vector<uint32_t> out;
    core::resize_for_filling(out, n);
    if (n < kSerialBelow) {
        std::vector<uint32_t> slots;
        weld_serial(n, vertex_at(positions.data()), index_from(0), slots, out.data());
    } else {
        weld_large(positions.data(), n, out.data());
    }
    return out;
}

namespace core {

// A count of firsts per run, prefix sums, then the firsts numbered and
// copied and the others looked up, each pass in parallel. The arrays are
// faulted in on every core (core/prefault.hpp): a first touch from one core
// took longer than the passes that fill them.
void number_classes(std::span<const uint32_t> canonical, std::span<const double> positions,
                    std::vector<uint32_t>& id, std::vector<double>& xyz) {
    const std::size_t n = canonical.size();
    const std::size_t runs = (n + kChunk - 1) / kChunk;
    std::vector<uint32_t> run_begin(runs + 1, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t run = r.begin(); run < r.end(); ++run) {
            uint32_t k = 0;
            for (std::size_t v = run * kChunk; v < std::min(n, (run + 1) * kChunk); ++v) k += canonical[v] == v;
            run_begin[run] = k;
        }
    });
    uint32_t classes = 0;
    for (std::size_t run = 0; run < runs; ++run) classes += std::exchange(run_begin[run], classes);
    run_begin[runs] = classes;
    xyz.clear();
    resize_for_filling(xyz, 3 * std::size_t{classes});
    id.clear();
    resize_for_filling(id, n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t run = r.begin(); run < r.end(); ++run) {
            uint32_t next = run_begin[run];
            for (std::size_t v = run * kChunk; v < std::min(n, (run + 1) * kChunk); ++v)
                if (canonical[v] == v) {
                    std::memcpy(&xyz[3 * std::size_t{next}], &positions[3 * v], 3 * sizeof(double));
                    id[v] = next++;
                }
        }
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kChunk), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t v = r.begin(); v < r.end(); ++v)
            if (canonical[v] != v) id[v] = id[canonical[v]];  // a first: numbered in the pass before
    });
}

}  // namespace core

namespace {

// out[i] = id[in[i]] for every index (in and out may be the same array).
void map_indices(std::span<const uint32_t> in, const std::vector<uint32_t>& id, uint32_t* out) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), kChunk),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i) out[i] = id[in[i]];
                      });
}

}  // namespace

Mesh welded(const MeshView& mesh) {
    const std::vector<uint32_t> canonical = weld_vertices(mesh.positions);
    Mesh out;
    std::vector<uint32_t> id;
    core::number_classes(canonical, mesh.positions, id, out.positions);
    out.face_offsets.assign(mesh.face_offsets.begin(), mesh.face_offsets.end());
    core::resize_for_filling(out.indices, mesh.indices.size());
    map_indices(mesh.indices, id, out.indices.data());
    return out;
}

void weld_in_place(Mesh& mesh) {
    const std::vector<uint32_t> canonical = weld_vertices(mesh.positions);
    std::vector<uint32_t> id;
    std::vector<double> xyz;
    core::number_classes(canonical, mesh.positions, id, xyz);
    mesh.positions = std::move(xyz);
    map_indices(mesh.indices, id, mesh.indices.data());
}

}  // namespace polyvol
