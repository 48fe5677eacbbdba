// measure/cone_kernels.hpp — private: the seam between the cone rule's
// drivers (cone.cpp: which faces, which precision, the bound) and its
// kernels (cone_kernels.cpp: per face range, gather the fan triangles into
// blocks, form the terms, sum them), which are compiled once per
// instruction set by Highway and chosen at run time by the library's
// dispatch (core/hwy_dispatch.hpp).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "measure/cone.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::measure::cone {

constexpr int kBlock = kBlockTriangles;
using Block = TriangleBlock;

// The range check of coordinates over their bit patterns a = |x| (monotone
// in |x|; NaN and infinity above every finite value): hi = max a and lo =
// min (a - 1) (0 wraps to the largest value). The coordinates are in the
// safe range iff hi <= pattern(2^190) and lo + 1 >= pattern(2^-160).
constexpr uint64_t kAbsMask = ~(uint64_t{1} << 63);
constexpr uint64_t kSafeHi = 0x4BD0000000000000ull;  // 2^190
constexpr uint64_t kSafeLo = 0x35F0000000000000ull;  // 2^-160
static_assert(core::bit_cast<double>(kSafeHi) == exact::kSafeMax && core::bit_cast<double>(kSafeLo) == exact::kSafeMin);

struct Extremes {
    uint64_t hi = 0, lo = ~uint64_t{0};
    void merge(const Extremes& o) {
        hi = std::max(hi, o.hi);
        lo = std::min(lo, o.lo);
    }
    bool safe() const { return hi <= kSafeHi && lo >= kSafeLo - 1; }
    double largest() const { return core::bit_cast<double>(hi); }
};

// What a volume pass checks of the coordinates' range (VolumeAccumulator::range):
//   none: nothing (the caller has; range is never safe());
//   referenced: the coordinates the pass reads, so that vertices no face uses
//     do not matter (cheap only with 64-bit integer minimum and maximum:
//     kernels_check_what_they_read());
//   positions: every position, each face range a slice of them in
//     proportion to its faces.
enum class RangeCheck { none, referenced, positions };

// The volume pass's per-range result: the exact sum of the blocks' (sum,
// error) pairs, of their magnitudes (translated form), and the extremes of
// what it checked.
struct VolumeAccumulator {
    exact::ExactSum sum;
    exact::ExactSum magnitude;
    Extremes range;
    std::size_t triangles = 0;
    void merge(const VolumeAccumulator& o) {
        sum.merge(o.sum);
        magnitude.merge(o.magnitude);
        range.merge(o.range);
        triangles += o.triangles;
    }
    bool safe() const { return range.safe(); }
};

// The other passes' per-range result: the exact sums of the first N terms
// (filtered: of their approximations) and of their magnitudes. Exact, so
// that neither sum nor bound depends on how the faces were split.
template <int N>
struct Accumulator {
    exact::ExactSum sum[N];
    exact::ExactSum magnitude[N];
    std::size_t triangles = 0;
    void merge(const Accumulator& o) {
        for (int k = 0; k < N; ++k) {
            sum[k].merge(o.sum[k]);
            magnitude[k].merge(o.magnitude[k]);
        }
        triangles += o.triangles;
    }
};

// ---- the kernels, each over the fan triangles of faces [f0, f1) ----------

// The double-double volume alone, in blocks of 32 summed by Sum2 in 8 lanes
// of 4, the blocks' pairs in groups of 4 into the superaccumulator, with the
// range check `check`.
void volume_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeForm form, RangeCheck check,
                  VolumeAccumulator& acc);

// The first N sums (1, kSxx or kSumCount), each term in double-double (dd)
// or plain double, blocks summed by Sum2 in 4 lanes of 8 (translated form).
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<1>& acc);
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSxx>& acc);
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSumCount>& acc);

// The exact sums k with bit k of mask set (needs the safe range).
void exact_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, uint32_t mask, Accumulator<kSumCount>& acc);

// The extremes of the bit patterns of |x| over n doubles.
void extremes_of(const double* x, std::size_t n, Extremes& e);

// Whether the kernels the dispatch chooses now check the coordinates they
// read at little cost (RangeCheck::referenced): AVX-512's 64-bit minimum
// and maximum. Elsewhere that check works, at a higher cost.
bool kernels_check_what_they_read();

// One triangle's exact terms as integers, when each axis's three
// coordinates are k 2^e with |k| < 2^60 (cone_exact.cpp); false (nothing
// added) otherwise.
bool integer_triangle(const double* a, const double* b, const double* c, uint32_t mask, exact::ExactSum* acc);

}  // namespace polyvol::measure::cone
