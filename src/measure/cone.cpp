// measure/cone.cpp — the cone rule's sums over a mesh's fan triangles
// (cone.hpp): which faces go to which kernel pass, in parallel ranges whose
// results merge exactly, and the bound each precision guarantees. The
// kernels (gathering, terms, lane sums) are in cone_kernels.cpp, compiled
// for every instruction set; the exact integer and GMP paths in
// cone_exact.cpp. The error analysis behind filtered_bound's constants is
// in docs/numerics.md, "The cone rule's kernels".
//
// Everything assumes the default floating-point environment: round to
// nearest, no flush-to-zero or denormals-are-zero.
#include "measure/cone.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <span>

#include "measure/cone_kernels.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::measure::cone {
namespace {

constexpr double kU = 0x1p-53;

// Faces per parallel task (at most). The simple partitioner halves ranges
// down to this size, so the blocks (and hence the rounding inside them) do
// not depend on scheduling: results are reproducible bit for bit, and the
// reduction itself is exact.
constexpr std::size_t kGrain = 8192;

// per_range(f0, f1, acc) over the faces in fixed ranges of at most kGrain,
// merged. Acc: default-constructible, with merge(const Acc&).
template <class Acc, class PerRange>
Acc reduce_face_ranges(const MeshView& mesh, PerRange per_range) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.face_count(), kGrain), Acc{},
        [&](const tbb::blocked_range<std::size_t>& r, Acc acc) {
            per_range(r.begin(), r.end(), acc);
            return acc;
        },
        [](Acc x, const Acc& y) {
            x.merge(y);
            return x;
        },
        tbb::simple_partitioner());
}

// The double-double volume pass in the given form, with the given check.
VolumeAccumulator volume_pass(const MeshView& mesh, VolumeForm form, RangeCheck check) {
    return reduce_face_ranges<VolumeAccumulator>(
        mesh, [&](std::size_t f0, std::size_t f1, VolumeAccumulator& acc) { volume_faces(mesh, f0, f1, form, check, acc); });
}

// The origin form's magnitude: 6 M^3 n >= Σ Perm over n triangles whose
// coordinates are at most M in magnitude (Perm = Σ_i |a_i| (|b_j c_k| +
// |b_k c_j|) <= 6 M^3 per triangle), rounded three times (relative error
// < 4u, within the bound's factor 1 + 2^-10).
double origin_magnitude(double M, std::size_t n) { return (M * M) * (M * (6.0 * static_cast<double>(n))); }

// The sums of a volume pass; M (origin form): the largest |coordinate| it read.
ConeSums volume_sums(const VolumeAccumulator& acc, VolumeForm form, double M) {
    ConeSums out;
    out.count = 1;
    out.triangles = acc.triangles;
    out.sum[kV] = acc.sum;
    const double magnitude = form == VolumeForm::origin ? origin_magnitude(M, acc.triangles) : acc.magnitude.round();
    out.bound[kV] = filtered_bound(kV, Precision::double_double, magnitude);
    return out;
}

Extremes position_extremes(std::span<const double> x) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, x.size(), std::size_t{1} << 16), Extremes{},
        [&](const tbb::blocked_range<std::size_t>& r, Extremes acc) {
            extremes_of(x.data() + r.begin(), r.size(), acc);
            return acc;
        },
        [](Extremes a, const Extremes& b) {
            a.merge(b);
            return a;
        });
}

// The first N sums: the volume alone in double-double by the volume pass
// (translated form), everything else by the blocks' terms in 4 lanes of 8.
template <int N>
ConeSums filtered_impl(const MeshView& mesh, bool dd) {
    if constexpr (N == 1) {
        if (dd) {
            return volume_sums(volume_pass(mesh, VolumeForm::translated, RangeCheck::none), VolumeForm::translated, 0);
        }
    }
    const auto acc = reduce_face_ranges<Accumulator<N>>(
        mesh, [&](std::size_t f0, std::size_t f1, Accumulator<N>& a) { sums_faces(mesh, f0, f1, dd, a); });
    ConeSums out;
    out.count = N;
    out.triangles = acc.triangles;
    for (int k = 0; k < N; ++k) {
        out.sum[k] = acc.sum[k];
        out.bound[k] = filtered_bound(k, dd ? Precision::double_double : Precision::fast, acc.magnitude[k].round());
    }
    return out;
}

}  // namespace

// K u² Σ magnitude (double-double) or K u Σ magnitude (plain double), the
// factor 1 + 2^-10 covering the rounding of the magnitudes; K from
// docs/numerics.md, "The cone rule's kernels".
double filtered_bound(int k, Precision precision, double magnitude) {
    const bool dd = precision == Precision::double_double;
    const double K = k == kV ? (dd ? 512 : 32) : (k <= kMz ? (dd ? 768 : 40) : (dd ? 1024 : 56));
    const double unit = dd ? kU * kU : kU;
    // + 2^-1060 covers the rounding of a bound in the subnormal range (any
    // error is a multiple of 2^-1060 in the safe range).
    return magnitude > 0 ? K * unit * magnitude * (1 + 0x1p-10) + 0x1p-1060 : 0.0;
}

Range coordinate_range(const MeshView& mesh) {
    const Extremes e = position_extremes(mesh.positions);
    // NaN and infinity: patterns above the largest finite one.
    if (e.hi > core::bit_cast<uint64_t>(std::numeric_limits<double>::max())) return Range::nonfinite;
    return e.safe() ? Range::safe : Range::unsafe;
}

VolumeForm likely_volume_form(const MeshView& mesh) {
    // Why n (B / E)^3 < 2^29: the origin form's bound, 512 u² Σ magnitude
    // with 6 B^3 per triangle, is below 2^-10 of an ulp of Σ det = 6 V (an
    // ulp of x is at least u |x|) when n B^3 < 2^34 V; a solid whose largest
    // extent is E has V >= E^3 / 32 or so (a ball: E^3 / 1.9).
    const std::size_t nv = mesh.vertex_count();
    const std::size_t step = std::max<std::size_t>(1, nv / 64);
    double lo[3], hi[3];
    std::fill(lo, lo + 3, std::numeric_limits<double>::infinity());
    std::fill(hi, hi + 3, -std::numeric_limits<double>::infinity());
    for (std::size_t v = 0; v < nv; v += step)
        for (int k = 0; k < 3; ++k) {
            const double x = mesh.positions[3 * v + k];
            lo[k] = std::min(lo[k], x);
            hi[k] = std::max(hi[k], x);
        }
    double B = 0, E = 0;
    for (int k = 0; k < 3; ++k) {
        B = std::max({B, std::fabs(lo[k]), std::fabs(hi[k])});
        E = std::max(E, hi[k] - lo[k]);
    }
    if (!(E > 0) || !(B < std::numeric_limits<double>::infinity())) return VolumeForm::translated;
    const double r = B / E;
    const double n = static_cast<double>(mesh.indices.size()) / 3;  // about the fan triangles
    return n * r * r * r < 0x1p29 ? VolumeForm::origin : VolumeForm::translated;
}

ConeSums filtered_volume(const MeshView& mesh, bool& safe, VolumeForm form) {
    // Every position checked in the pass when that costs less than checking
    // each used coordinate (at least two indices per vertex: each vertex is
    // read about twice or more), and always where the kernels cannot check
    // what they read cheaply. The origin form's M is then the largest
    // |coordinate| of any position, else of any used one.
    const bool referenced = kernels_check_what_they_read();  // once: the passes below agree
    if (!referenced || 2 * mesh.vertex_count() <= mesh.indices.size()) {
        const VolumeAccumulator acc = volume_pass(mesh, form, RangeCheck::positions);
        if (acc.safe()) {
            safe = true;
            return volume_sums(acc, form, acc.range.largest());
        }
        if (!referenced) {  // stricter than the definition; the caller's exact fallback gives the same results
            safe = false;
            return ConeSums{.count = 1};
        }
        // Out of range somewhere, maybe only on vertices no face uses: the
        // check of what the pass reads decides.
    }
    const VolumeAccumulator acc = volume_pass(mesh, form, RangeCheck::referenced);
    safe = acc.safe();
    return volume_sums(acc, form, acc.range.largest());
}

ConeSums filtered_sums(const MeshView& mesh, int count, Precision precision) {
    const bool dd = precision == Precision::double_double;
    if (count == 1) return filtered_impl<1>(mesh, dd);
    if (count == kSxx) return filtered_impl<kSxx>(mesh, dd);
    return filtered_impl<kSumCount>(mesh, dd);
}

void exact_sums(const MeshView& mesh, uint32_t mask, ConeSums& sums) {
    const auto acc = reduce_face_ranges<Accumulator<kSumCount>>(
        mesh, [&](std::size_t f0, std::size_t f1, Accumulator<kSumCount>& a) { exact_faces(mesh, f0, f1, mask, a); });
    for (int k = 0; k < sums.count; ++k) {
        if (mask & (1u << k)) {
            sums.sum[k] = acc.sum[k];
            sums.bound[k] = 0;
        }
    }
}

}  // namespace polyvol::measure::cone
