// polyvol/soup.hpp — volume, centroid, area and closedness of a triangle soup
// given as float32 records, accumulated window by window in constant memory.
//
// The input is any array of triangles whose nine coordinates are float32
// (little-endian, as in binary STL — measure never knows the file format; the
// caller says where the floats are):
//   coordinate k of vertex v of triangle t is the float32 at
//     data + t * stride + offset + 12 * v + 4 * k        (v, k in 0..2)
//   (binary STL records: stride 50, offset 12; unaligned is fine)
// Triangles are counter-clockwise seen from outside; nothing is welded.
//
// What is accumulated (same conventions as measure.hpp), with the
// guarantees mass_properties gives for the same triangles (Method::cone,
// Accuracy::correctly_rounded), in its result type:
//   volume, first moments Σ det·(a_i+b_i+c_i)/24 and centroid: each the exact
//                  value for the coordinates as read, rounded once to nearest
//                  (ties to even); the moments and centroid within a bound
//                  instead when SoupWants::moments is fast;
//   area           Σ |(b-a)×(c-a)|/2 with a rigorous relative bound;
//   triangles, whether a coordinate is NaN or infinite, and
//   a closedness fingerprint (below).
// Second moments, inertia and edge length need the welded mesh: NaN here.
//
// Closedness fingerprint: each triangle adds the Vandermonde determinant
// (H(b) - H(a)) (H(c) - H(a)) (H(c) - H(b)) of a keyed hash H of its
// points into F_p, p = 2^31 - 1, in four lanes. A closed 2-cycle sums to
// exactly 0; an unclosed surface does with probability below 2^-113
// (Schwartz–Zippel; the argument: docs/numerics.md, "The closedness
// fingerprint"). A nonzero fingerprint proves an unbalanced edge; its count
// and an example need the welded topology (polyvol::analyze_topology).
//
// Passes. The volume and the first moments are decided by a filter: pass 1
// (float32-exact products, double-double terms and sums, error <= 512 u²
// Σ 6 M_b³ n_b for the volume and 1024 u² Σ 18 M_b⁴ n_b for the moments,
// M_b the largest |coordinate| of a block of n_b <= 32 triangles — decides
// unless the mesh is far from the origin compared with its size, or a
// result is exactly a rounding boundary such as 0: a centred, symmetric
// part), pass 2 (measure/cone.cpp's translated double-double kernels, for
// the volume and the moments still undecided; skipped for a moment that
// may be 0), pass 3 for what is still undecided (exact). Area,
// counts and the fingerprint come from pass 1. After feeding every triangle
// once, call next_pass(): when it returns true, feed the same triangles
// again (in any windows), then call it again.
//
// Determinism. Blocks are triangles [32 j, 32 j + 32) of the whole input, so
// every window must start at a triangle index that is a multiple of 32;
// the area's and the bounded moments' sums across blocks are exact (a
// superaccumulator), the volume and the correctly rounded moments and
// centroid are the exact values rounded once and the fingerprint is a sum
// mod p, so the results are bit-identical for any window sizes, any
// order of the windows and any number of threads. (Pass 1 sums the volume
// and the moments of up to four neighbouring blocks in double-double
// first, so its approximation depends a little on the windows: `passes`
// could differ between two window sizes when a result is within the
// filter's bound of a rounding boundary; the results cannot.)
//
// Thread safety: add() may be called concurrently (different windows);
// next_pass() and result() must not run concurrently with add().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "polyvol/measure.hpp"

namespace polyvol {

// Where the float32 coordinates are (see the top of this file).
struct Float32Triangles {
    const std::byte* data = nullptr;
    std::size_t count = 0;    // triangles
    std::size_t stride = 50;  // bytes from one triangle to the next (>= 36)
    std::size_t offset = 12;  // bytes from a triangle's start to its first coordinate
};

// Binary STL records (50 bytes each: normal, 3 vertices, 2 attribute bytes).
inline Float32Triangles stl_records(std::span<const std::byte> records) {
    return {records.data(), records.size() / 50, 50, 12};
}

// Packed triangles: nine floats each (a, b, c), as a numpy (n, 3, 3) float32
// array or polyvol::read_binary_stl_triangles (io.hpp) holds them. A trailing
// partial triangle (size not a multiple of 9) is not counted.
inline Float32Triangles packed_triangles(std::span<const float> xyz) {
    return {reinterpret_cast<const std::byte*>(xyz.data()), xyz.size() / 9, 36, 0};
}

// What pass 1 computes besides the volume. Each costs time: on 1M triangles
// in memory the volume alone takes about a third of everything.
struct SoupWants {
    bool closedness = true;        // the fingerprint (SoupResult::closed)
    bool moments_and_area = true;  // first moments, centroid, area
    // correctly_rounded: the first moments and centroid are decided, with one
    // or two passes more when pass 1 cannot (a part far from the origin; an
    // exactly or nearly cancelling sum: a part centred on the origin).
    // fast: they are pass 1's in double, with its bound (MassProperties::
    // moments_relative_error, however large: unlike mass_properties' fast
    // accuracy, no limit sends them to the exact path), and no pass of their
    // own unless every one is exactly 0 with a nonzero bound (which no
    // relative bound can carry). The volume is correctly rounded either way.
    Accuracy moments = Accuracy::correctly_rounded;
    // Scales the mass and the first moments as MeasureOptions::density does
    // (each still the exact value rounded once); finite, else the
    // accumulator's constructor throws std::invalid_argument.
    double density = 1.0;
};

struct SoupResult {
    SoupWants computed;            // what was asked for; the figures of what was not are NaN
                                   // (the fingerprint then 0 and closed false)
    uint64_t triangles = 0;
    bool nonfinite = false;        // some coordinate is NaN or ±inf (then every figure is NaN)
    // Fingerprint lanes (mod 2^31 - 1); when computed, all zero iff the surface is
    // closed, up to the probability above. Keyed per accumulator, so the values
    // mean nothing else.
    std::array<uint64_t, 4> fingerprint{};
    bool closed = false;           // fingerprint all zero and !nonfinite (false when not computed)
    int passes = 0;                // passes over the input the results needed (1..3; pass 2 may be skipped)
    // The figures with their guarantees (measure.hpp; Method::cone, the
    // accuracy SoupWants::moments asks for, SoupWants::density): volume and
    // mass (correctly rounded), first moments and centroid (correctly
    // rounded, or within moments_relative_error; the centroid NaN when the
    // volume is 0), area with area_relative_error; second moments, inertia
    // and edge length NaN.
    MassProperties properties;
};

class SoupAccumulator {
public:
    // Triangles per block: every window fed to add() starts at a multiple
    // (StlStreamOptions::alignment when streaming a file into it).
    static constexpr std::size_t kBlockTriangles = 32;
    // Keys from std::random_device.
    explicit SoupAccumulator(SoupWants wants = {});
    // Keys derived from seed (reproducible fingerprints, for tests).
    explicit SoupAccumulator(uint64_t seed, SoupWants wants = {});
    ~SoupAccumulator();
    SoupAccumulator(const SoupAccumulator&) = delete;
    SoupAccumulator& operator=(const SoupAccumulator&) = delete;

    // Adds triangles first_triangle .. first_triangle + t.count - 1 of the
    // input. first_triangle must be a multiple of 32 (std::invalid_argument
    // otherwise). Large spans are processed in parallel (oneTBB).
    void add(const Float32Triangles& t, uint64_t first_triangle);

    // Ends a pass. true: feed every triangle again. Throws std::logic_error
    // when a later pass saw a different number of triangles than the first.
    bool next_pass();

    // After next_pass() returned false.
    const SoupResult& result() const;

    int pass() const;  // 1, 2 or 3: the pass being fed

private:
    struct State;
    std::unique_ptr<State> s_;
};

// All passes over triangles held in memory.
SoupResult soup_properties(const Float32Triangles& t, SoupWants wants = {});
SoupResult soup_properties(const Float32Triangles& t, uint64_t seed, SoupWants wants = {});

// The volume alone, correctly rounded (NaN when a coordinate is NaN or
// infinite): pass 1 without the fingerprint, the moments and the area. Like
// signed_volume (measure.hpp), it does not check that the surface is closed.
double soup_volume(const Float32Triangles& t);

}  // namespace polyvol
