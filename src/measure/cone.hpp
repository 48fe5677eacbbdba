// measure/cone.hpp — private: the cone rule's sums over fan triangles
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
#include <cstdint>

#include "exact/exact_sum.hpp"
#include "exact/rational.hpp"
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

// The two forms of the double-double volume term (cone_terms-inl.h):
//   translated — det = a · ((b - a) × (c - a)): its error bound grows with
//                |a| |b - a| |c - a|, so it decides also far from the origin;
//   origin     — det = a · (b × c), about 40% fewer operations: its bound is
//                6 M^3 per triangle (M the largest |coordinate| the pass
//                read, or of any position when every position was checked
//                first: so its bound, not its sum, can differ between
//                instruction-set levels when some vertices are unused), so
//                it decides only for meshes not far from the origin compared
//                with their size.
enum class VolumeForm { translated, origin };

// A guess (from a sample of at most 128 vertices) at which form decides the
// rounding of the volume at the lower cost: origin when n (B / E)^3 < 2^29,
// n the fan triangles, B the sample's largest |coordinate| and E its largest
// extent along an axis. Only a guess: the caller runs the translated form
// when the origin form leaves the rounding undecided.
VolumeForm likely_volume_form(const MeshView& mesh);

// The double-double volume alone in the given form, with the range check:
// safe is set to whether every coordinate of every vertex that some face
// uses is in the safe range (the definition of Range::safe, applied to the
// coordinates the sums read; vertices no face uses do not matter). When
// each vertex is read about twice or more (at least two indices per vertex)
// every position is checked first, as cheaper; otherwise, or when one is
// out of range, the pass checks the coordinates it reads. Below AVX-512
// (the CPU's or simd::limit_to's; read once per call), where that check
// costs more than a pass over the positions, safe is coordinate_range(mesh)
// == Range::safe instead: stricter, and the caller's exact fallback gives
// the same results. When safe is false the sums are meaningless. The translated form
// is filtered_sums(mesh, 1, Precision::double_double) (the same sum and
// bound).
ConeSums filtered_volume(const MeshView& mesh, bool& safe, VolumeForm form = VolumeForm::translated);

// Replaces sums[k] by the exact sum (bound 0) for every k with bit k of mask
// set (needs every coordinate of a vertex that some face uses in the safe
// range: filtered_volume's safe, or Range::safe).
void exact_sums(const MeshView& mesh, uint32_t mask, ConeSums& sums);

// The exact sums as rationals for any coordinates; non-finite coordinates on
// a used vertex make ok false.
struct RationalSums {
    bool ok = true;
    std::array<exact::Rational, kSumCount> sum{};
};
RationalSums gmp_sums(const MeshView& mesh, int count);

// ---- Per-block access, for sources that are not a MeshView (measure/soup.cpp
// streams float32 triangle records through these). ----

// Up to kBlockTriangles triangles as structure of arrays: coordinate k of
// vertex v of triangle i is c[3*v + k][i]; slots n .. kBlockTriangles-1 must
// be zero (they then add exactly 0 to every sum).
inline constexpr int kBlockTriangles = 32;
struct TriangleBlock {
    alignas(64) double c[9][kBlockTriangles];
    int n = 0;
};

// The double-double filtered volume term of one block (the kernel of
// filtered_sums(mesh, 1, Precision::double_double)): adds the exact sum of the
// block's approximated det terms to sum and their magnitudes to magnitude.
// |Σ det - sum| <= filtered_bound(kV, double_double, magnitude.round()).
// Needs Range::safe (every finite float32 is in it).
void filtered_volume_block(const TriangleBlock& b, exact::ExactSum& sum, exact::ExactSum& magnitude);

// The double-double filtered terms of the volume and the first moments
// (sums kV .. kMz, the kernel of filtered_sums(mesh, kSxx, double_double):
// translated form) of one block: adds the exact sums of the approximations
// to sum[k] and their magnitudes to magnitude[k]; |Σ_k - sum[k]| <=
// filtered_bound(k, double_double, magnitude[k].round()). Needs Range::safe.
void filtered_first_moments_block(const TriangleBlock& b, exact::ExactSum* sum, exact::ExactSum* magnitude);

// The rigorous bound on |sum - exact sum| for sum k from the rounded sum of
// magnitudes (what filtered_sums reports in ConeSums::bound).
double filtered_bound(int k, Precision precision, double magnitude);

// Adds the exact terms of one block to acc[k] for every k with bit k of mask
// set (the kernel of exact_sums; needs Range::safe).
void exact_block_sums(const TriangleBlock& b, uint32_t mask, exact::ExactSum* acc);

}  // namespace polyvol::measure::cone
