// measure/soup_pass1.hpp — private: the seam between the streamed soup's
// driver (soup.cpp: passes, superaccumulators, bounds, the result) and its
// pass-1 kernel (soup_pass1.cpp: per group of blocks of float32 records, the
// Sum2 lanes of the volume and the first moments, the area and the
// fingerprint),
// compiled once per instruction set by Highway and chosen at run time by
// the library's dispatch (core/hwy_dispatch.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "measure/cone.hpp"
#include "core/fingerprint.hpp"

namespace polyvol::measure::soup {

constexpr int kB = cone::kBlockTriangles;  // triangles per block (32)
constexpr int kFpLanes = core::fingerprint::kLanes;

// Pass 1 works on groups of up to kGroupBlocks consecutive blocks of a task:
// their volume sums, double-double moment sums and fingerprints are
// combined before they go into the superaccumulators (the error analysis in
// docs/numerics.md, "The streamed soup"), the rest block by block.
constexpr int kGroupBlocks = 4;

// The fingerprint's keys: AES whitening, then three round keys (one hash
// on every target).
struct Keys {
    alignas(16) uint64_t aes[4][2];
};

// What pass 1 forms of the first moments: nothing (nor the area), plain
// double sums with Σ |d| for a bound, or double-double Sum2 lanes.
enum Moments : int { kNoMoments, kPlain, kDoubleDouble };

// Per-block sums of pass 1: the area's, and (kPlain) the first moments'.
struct Pass1Block {
    double area2;   // Σ |n| (2 A)
    double cross;   // Σ X (the products of the cross products)
    double mom[3];  // Σ d s_i (24 ∫x_i), d = fl(h + lo)
    double abs_d;   // Σ |d|
};

struct Pass1Group {
    Pass1Block block[kGroupBlocks];  // per block: the area's sums (moments_and_area)
    uint32_t mx[kGroupBlocks];       // per block: the largest |coordinate| bit pattern
    double vs, ve;                   // the group's Sum2 (sum, error) of 6 V
    double ms[3], me[3];             // the group's Sum2 of 24 ∫x_i (kDoubleDouble)
    uint64_t fp[kFpLanes];           // the group's fingerprint (mod p), or 0
};

// Pass 1 over n <= kGroupBlocks kB records (base: the first coordinate of
// the first; stride: bytes between records, >= 36): false when a coordinate
// is NaN or infinite (then nothing else is set). fingerprint: the
// fingerprint, else fp = 0; moments: the first moments (and, unless
// kNoMoments, the area) as it says.
bool pass1_group(const std::byte* base, std::size_t stride, int n, const Keys& keys, bool fingerprint,
                 Moments moments, Pass1Group& g);

}  // namespace polyvol::measure::soup
