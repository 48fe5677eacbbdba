// measure/sums.hpp — measure's internal interface for the modules above it
// (boolean, solid): the cone rule's sums over fan triangles
// (Allgower & Schmidt 1986, (2.1)), in three precisions.
//
// For a fan triangle (a, b, c) with det = det(a, b, c) = a · (b × c) and
// s = a + b + c, the ten sums are (with their integral):
//   kV            Σ det                                  = 6   V
//   kMx..kMz      Σ det s_i                              = 24  ∫x_i
//   kSxx..kSzx    Σ det (a_i a_j + b_i b_j + c_i c_j + s_i s_j) = 120 ∫x_i x_j
// (order {xx, yy, zz, xy, yz, zx}).
//
// How they are summed:
//   filtered   — each term in double-double (or plain double for Accuracy::fast),
//                blocks of 32 triangles summed in lanes (volume alone in
//                double-double: 8 lanes combined into one pair per block,
//                the pairs of 4 blocks into one; the rest: 4 lanes), the
//                results added to a superaccumulator. Returns the exact sum
//                of those approximations and a rigorous bound on its
//                distance to the exact sum (the error analysis is in
//                docs/numerics.md, "The cone rule's kernels").
//   exact      — each term as an exact expansion (Shewchuk) added to the
//                superaccumulator: the exact sum.
//   gmp        — big-integer arithmetic: the exact sum for any finite
//                coordinates (the two above need the "safe range" below).
// All three run in parallel (TBB) and give bit-identical results for any
// split of the work (the superaccumulator's merge is exact).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "exact/exact_sum.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::measure::cone {

enum SumIndex : int { kV = 0, kMx, kMy, kMz, kSxx, kSyy, kSzz, kSxy, kSyz, kSzx, kSumCount };
// The divisor turning each sum into its integral: 6, 24, 120.
inline constexpr uint32_t divisor(int k) { return k == kV ? 6u : (k <= kMz ? 24u : 120u); }

// Where the coordinates of a mesh lie.
//   safe      — every coordinate is 0 or 2^-160 <= |x| <= 2^190: then every
//               product of up to five coordinates and all intermediate values
//               are multiples of 2^-1060 below 2^1000, so error-free
//               transformations are exact and no operation underflows or
//               overflows (the filtered and exact paths rely on this).
//   unsafe    — finite, but some coordinate is outside the safe range.
//   nonfinite — some coordinate is NaN or infinite.
enum class Range { safe, unsafe, nonfinite };
Range coordinate_range(const MeshView& mesh);

enum class Precision { fast, double_double };

// Sums 0..count-1 (count == 1: volume only; kSxx: volume and first moments;
// kSumCount: all).
struct ConeSums {
    int count = kSumCount;
    std::array<exact::ExactSum, kSumCount> sum{};  // exact sum of the approximated terms
    std::array<double, kSumCount> bound{};         // |sum - exact| <= bound (0: exact)
    std::size_t triangles = 0;
};

// Filtered sums (needs Range::safe for the bound to hold).
ConeSums filtered_sums(const MeshView& mesh, int count, Precision precision);

// Replaces sums[k] by the exact sum (bound 0) for every k with bit k of mask
// set (needs every coordinate of a vertex that some face uses in the safe
// range: filtered_volume's safe, or Range::safe).
void exact_sums(const MeshView& mesh, uint32_t mask, ConeSums& sums);

}  // namespace polyvol::measure::cone
