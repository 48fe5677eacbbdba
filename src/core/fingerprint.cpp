// core/fingerprint.cpp — mesh_closedness (core/fingerprint.hpp), behind
// topology.hpp's fingerprint_closedness: whether a mesh is a closed 2-cycle, by soup.hpp's randomized fingerprint
// over keyed hashes of its points, without welding or an edge table.
//
// Each fan triangle (a, b, c) adds the Vandermonde product
// (H(b) - H(a)) (H(c) - H(a)) (H(c) - H(b)) mod p = 2^31 - 1, in four lanes
// (core/fingerprint.hpp). H depends on a point's coordinates only (their
// bit patterns, -0.0 as +0.0), so two vertices at one point are one point, as
// topology's welding makes them, and a polygon's fan sums to its boundary's
// terms (the diagonals cancel). The sum is zero for every closed 2-cycle and,
// for any other surface with fewer than p fan triangles, nonzero but with
// probability < 2^-113 over the keys (soup.hpp gives the argument). That
// bound assumes, as soup.hpp does for its portable hash, that H behaves as a
// random function of the point with four independent 31-bit words: H here is
// two keyed multiply-xor chains over the 192 bits of a point, each giving two
// words, which is a heuristic hash, not a proven universal family.
//
// Cost: one hash per vertex when vertices are shared (an indexed mesh: each
// read about six times), else one per corner (a soup, every vertex its own),
// then a few integer operations per fan triangle, on every core.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/canonical_bits.hpp"
#include "core/fingerprint.hpp"

namespace polyvol::core::fingerprint {
namespace {

namespace fp = core::fingerprint;
constexpr int kLanes = fp::kLanes;

using Hash = std::array<uint32_t, kLanes>;  // a point's lane values, each <= p

struct Keys {
    uint64_t k[2][4];  // two chains of four keys
};

// H(point): per chain, mum(mum(x ^ k0, y ^ k1) ^ k2, z ^ k3); its two 32-bit
// halves cut to 31 bits are two lanes.
Hash point_hash(const double* p, const Keys& key) {
    // The patterns weld_vertices compares (-0.0 as +0.0: they weld).
    const uint64_t x = core::canonical_bits(p[0]), y = core::canonical_bits(p[1]), z = core::canonical_bits(p[2]);
    Hash h;
    for (int c = 0; c < 2; ++c) {
        const uint64_t* k = key.k[c];
        const uint64_t t = fp::mum(fp::mum(x ^ k[0], y ^ k[1]) ^ k[2], z ^ k[3]);
        h[2 * c] = static_cast<uint32_t>(t & fp::kP);
        h[2 * c + 1] = static_cast<uint32_t>((t >> 32) & fp::kP);
    }
    return h;
}

bool finite_point(const double* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// The lanes' sums (each < 2^63: folded before 2^28 terms of < 2^34 pile up),
// the fan triangles summed, and whether a non-finite coordinate was met.
struct Sums {
    uint64_t s[kLanes] = {};
    uint64_t triangles = 0;
    bool nonfinite = false;
    void fold_all() {
        for (uint64_t& x : s) x = fp::fold(x);
    }
    void merge(const Sums& o) {
        for (int l = 0; l < kLanes; ++l) s[l] = fp::fold(s[l]) + fp::fold(o.s[l]);
        triangles += o.triangles;
        nonfinite = nonfinite || o.nonfinite;
    }
};

constexpr std::size_t kGrain = 8192;               // faces per task (the partitioner's grain)
constexpr uint64_t kFoldEvery = uint64_t{1} << 12;  // terms between folds (any < 2^28 keeps the sums < 2^63)

// Σ over the fan triangles of the faces, hash(v) giving vertex v's Hash (and
// false when it has a non-finite coordinate).
template <class HashOf>
Sums fan_sums(const MeshView& mesh, HashOf hash_of) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.face_count(), kGrain), Sums{},
        [&](const tbb::blocked_range<std::size_t>& r, Sums acc) {
            uint64_t pending = 0;
            Hash h0, h1, h2;
            for (std::size_t f = r.begin(); f < r.end(); ++f) {
                const std::span<const uint32_t> face = mesh.face(f);
                if (face.size() < 3) continue;
                if (!hash_of(face[0], h0) || !hash_of(face[1], h1)) {
                    acc.nonfinite = true;
                    continue;
                }
                for (std::size_t i = 2; i < face.size(); ++i) {
                    if (!hash_of(face[i], h2)) {
                        acc.nonfinite = true;
                        break;
                    }
                    for (int l = 0; l < kLanes; ++l) acc.s[l] += fp::vandermonde(h0[l], h1[l], h2[l]);
                    h1 = h2;
                    ++acc.triangles;
                    if (++pending == kFoldEvery) {
                        acc.fold_all();
                        pending = 0;
                    }
                }
            }
            acc.fold_all();
            return acc;
        },
        [](Sums a, const Sums& b) {
            a.merge(b);
            return a;
        });
}

Closedness closedness_with(const MeshView& mesh, const Keys& key) {
    const double* pos = mesh.positions.data();
    const std::size_t nv = mesh.vertex_count();
    Sums sums;
    if (mesh.indices.size() >= 2 * nv) {
        // Shared vertices: hash each once (non-finite: all lanes p + 1, an
        // impossible value, as a mark).
        std::vector<Hash> hashes(nv);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 1 << 14), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t v = r.begin(); v < r.end(); ++v) {
                const double* p = pos + 3 * v;
                hashes[v] = finite_point(p) ? point_hash(p, key) : Hash{0, 0, 0, uint32_t{fp::kP} + 1};
            }
        });
        sums = fan_sums(mesh, [&](uint32_t v, Hash& h) {
            h = hashes[v];
            return h[kLanes - 1] <= fp::kP;
        });
    } else {
        sums = fan_sums(mesh, [&](uint32_t v, Hash& h) {
            const double* p = pos + 3 * std::size_t{v};
            if (!finite_point(p)) return false;
            h = point_hash(p, key);
            return true;
        });
    }
    // The argument needs every edge's net use count below p in magnitude:
    // certain with fewer than p fan triangles.
    if (sums.nonfinite || sums.triangles >= fp::kP) return Closedness::undecided;
    for (const uint64_t s : sums.s)
        if (fp::reduce(s) != 0) return Closedness::open;
    return Closedness::closed;
}

Keys keys_from_seed(uint64_t seed) {
    Keys key;
    for (auto& chain : key.k)
        for (auto& x : chain) x = fp::splitmix(seed);
    return key;
}

}  // namespace

Closedness mesh_closedness(const MeshView& mesh, uint64_t seed) {
    return closedness_with(mesh, keys_from_seed(seed));
}

Closedness mesh_closedness(const MeshView& mesh) {
    std::random_device rd;
    Keys key = keys_from_seed(fp::random_word(rd));
    for (auto& chain : key.k)
        for (auto& x : chain) x ^= fp::random_word(rd);  // more entropy than one seed
    return closedness_with(mesh, key);
}

}  // namespace polyvol::core::fingerprint
