// measure/cone.hpp — private: the cone rule's kernels beyond the sums
// other modules use (measure/sums.hpp): the volume's two forms, the exact
// sums as rationals, and per-block access for the streamed soup.
#pragma once

#include <array>
#include <cstdint>

#include "exact/exact_sum.hpp"
#include "exact/rational.hpp"
#include "measure/sums.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::measure::cone {

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
