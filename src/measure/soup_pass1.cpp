// measure/soup_pass1.cpp — pass 1 of the streamed soup (polyvol/soup.hpp)
// over a group of up to 4 blocks of 32 float32 triangle records, compiled
// once per instruction set (Highway's foreach_target) and chosen by its
// dispatch. Per triangle (a, b, c):
//   6 V      det = a · (b × c) in double-double (h + lo), summed by Sum2 in
//            8 lanes (lane j: triangles j mod 8), the lanes running on
//            across the group's blocks;
//   24 ∫x_i  (h + lo)(a_i + b_i + c_i) in double-double, summed by Sum2 in
//            lanes as the volume is (for correctly rounded moments), or
//            fl(h + lo) fl(a_i + b_i + c_i) in double, with Σ |d| for its
//            bound (for moments within a bound);
//   2 A      |(b - a) × (c - a)|, with Σ X (the cross products' products);
//   closed   the Vandermonde product of its vertices' hashes (mod p),
//            summed: the fingerprint of soup.hpp.
// The arithmetic is written once in Highway operations on rows of
// coordinates. Where the rows come from depends on the target (scalar
// loads; AVX2, and AVX-512 without IFMA or VAES: 8 x 8 transposes of the
// records into a block of doubles; AVX-512 with IFMA and VAES: the same
// transposes in registers), and so does the way the hash is computed (one
// vertex at a time by Highway's AESRound below AVX2, its scalar twin on
// HWY_SCALAR; two triangles at a time on AVX2; with IFMA and VAES, fused
// into the loop). Every target gives the same sums and the same
// fingerprint, bit for bit (tests/measure/soup_test.cpp at every level).
// All of it is Highway operations but the one block marked "AVX-512 with
// IFMA and VAES": Debian's Highway 1.0.3 has no 52-bit multiply-add, and
// AES on 512-bit vectors only in its AVX3_DL target, which the library
// does not compile (hwy_targets.hpp); that block is chosen at run time
// within the AVX3 target and checked against the others bit for bit. The
// error analysis is in docs/numerics.md, "The streamed soup".
#include "core/hwy_targets.hpp"  // before Highway

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "measure/soup_pass1.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "core/aes_round.hpp"
#include "core/simd.hpp"
#include "exact/eft.hpp"  // POLYVOL_INLINE
#include "measure/cone_terms-inl.h"
#include "measure/soup_pass1.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#if HWY_ARCH_X86
#include <immintrin.h>
#endif

// GCC 12's AVX-512 intrinsics pass an undefined vector as the unused merge
// operand, which -W(maybe-)uninitialized reports falsely.
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#pragma GCC diagnostic ignored "-Wuninitialized"

HWY_BEFORE_NAMESPACE();
namespace polyvol::measure::soup::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

using cone::HWY_NAMESPACE::D;
using cone::HWY_NAMESPACE::kN;
using cone::HWY_NAMESPACE::sum2_add;
using cone::HWY_NAMESPACE::two_prod;
using cone::HWY_NAMESPACE::two_sum;
using cone::HWY_NAMESPACE::V;
using core::fingerprint::kP;
using core::fingerprint::reduce;
using core::fingerprint::vandermonde;

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define POLYVOL_SOUP_AVX2 1
#else
#define POLYVOL_SOUP_AVX2 0
#endif
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
#define POLYVOL_SOUP_AVX512 1
// Functions that use IFMA and VAES beside the target's own extensions (the
// whole list: clang's target attribute replaces the target's, GCC's adds).
#define POLYVOL_IFMA_ATTR __attribute__((target(HWY_TARGET_STR ",avx512ifma,vaes")))
#define POLYVOL_IFMA_INLINE POLYVOL_IFMA_ATTR __attribute__((always_inline)) inline
#else
#define POLYVOL_SOUP_AVX512 0
#endif

constexpr int kSumLanes = 8;            // the volume's Sum2 lanes
constexpr int kQ = kSumLanes / kN;      // vectors per set of 8 triangles
constexpr int kSets = kB / kSumLanes;   // sets of 8 triangles per block
constexpr uint32_t kNonFinite = 0x7F800000u;  // |coordinate| patterns from here: NaN or infinity

// ---- the arithmetic, on rows --------------------------------------------------

// Rows of a set of 8 triangles: c[3 v + k][q] holds coordinate k of vertex
// v of triangles q kN .. q kN + kN - 1 of the set.
struct SetRows {
    V c[9][kQ];
};

// A block's lanes: the Sum2 (S, E) of the volume and (kDoubleDouble) of the
// first moments (MS, ME); the plain sums of the first moments and Σ |d|
// (kPlain), and of the area.
struct BlockLanes {
    V S[kQ], E[kQ];
    V MS[3][kQ], ME[3][kQ];
    V M[3][kQ], AD[kQ];
    V X[kQ], T[kQ];
};

// Set g of a block into its lanes (the error analysis: docs/numerics.md).
template <Moments kM>
HWY_INLINE void add_set(int g, const SetRows& r, BlockLanes& s) {
    for (int q = 0; q < kQ; ++q) {
        const V ax = r.c[0][q], ay = r.c[1][q], az = r.c[2][q];
        const V bx = r.c[3][q], by = r.c[4][q], bz = r.c[5][q];
        const V cx = r.c[6][q], cy = r.c[7][q], cz = r.c[8][q];
        // b × c: the products are exact (float32 significands).
        V n0, t0, n1, t1, n2, t2;
        two_sum(by * cz, hn::Neg(bz * cy), n0, t0);
        two_sum(bz * cx, hn::Neg(bx * cz), n1, t1);
        two_sum(bx * cy, hn::Neg(by * cx), n2, t2);
        // a · (b × c) as h + l.
        V P0, Q0, P1, Q1, P2, Q2;
        two_prod(ax, n0, P0, Q0);
        two_prod(ay, n1, P1, Q1);
        two_prod(az, n2, P2, Q2);
        V h1, g1, h, g2;
        two_sum(P0, P1, h1, g1);
        two_sum(h1, P2, h, g2);
        const V l = ((g1 + g2) + ((Q0 + Q1) + Q2)) + ((ax * t0 + ay * t1) + az * t2);
        if (g == 0) {
            s.S[q] = h;
            s.E[q] = l;
        } else {
            sum2_add(s.S[q], s.E[q], h, l);
        }
        if constexpr (kM == kPlain) {
            // First moments d s_i, d = fl(h + l), s_i = fl(fl(a_i + b_i) + c_i), with Σ |d|.
            const V d = h + l;
            const V ad = hn::Abs(d);
            const V m0 = d * ((ax + bx) + cx), m1 = d * ((ay + by) + cy), m2 = d * ((az + bz) + cz);
            if (g == 0) {
                s.M[0][q] = m0, s.M[1][q] = m1, s.M[2][q] = m2, s.AD[q] = ad;
            } else {
                s.M[0][q] = s.M[0][q] + m0, s.M[1][q] = s.M[1][q] + m1, s.M[2][q] = s.M[2][q] + m2;
                s.AD[q] = s.AD[q] + ad;
            }
        }
        if constexpr (kM == kDoubleDouble) {
            // First moments: s_i = a_i + b_i + c_i as sh + sl (two two_sums),
            // (h + l)(sh + sl) as P + (Q + (h sl + l sh)).
            const V a[3] = {ax, ay, az}, b[3] = {bx, by, bz}, c[3] = {cx, cy, cz};
            for (int i = 0; i < 3; ++i) {
                V x, ex, sh, es, P, Q;
                two_sum(a[i], b[i], x, ex);
                two_sum(x, c[i], sh, es);
                const V sl = ex + es;
                two_prod(h, sh, P, Q);
                const V lo = Q + (h * sl + l * sh);
                if (g == 0) {
                    s.MS[i][q] = P;
                    s.ME[i][q] = lo;
                } else {
                    sum2_add(s.MS[i][q], s.ME[i][q], P, lo);
                }
            }
        }
        if constexpr (kM != kNoMoments) {
            // Area: |(b - a) × (c - a)|.
            const V ux = bx - ax, uy = by - ay, uz = bz - az;
            const V wx = cx - ax, wy = cy - ay, wz = cz - az;
            const V p0 = uy * wz, q0 = uz * wy, p1 = uz * wx, q1 = ux * wz, p2 = ux * wy, q2 = uy * wx;
            const V f0 = p0 - q0, f1 = p1 - q1, f2 = p2 - q2;
            const V t = hn::Sqrt((f0 * f0 + f1 * f1) + f2 * f2);
            const V x = ((hn::Abs(p0) + hn::Abs(q0)) + (hn::Abs(p1) + hn::Abs(q1))) + (hn::Abs(p2) + hn::Abs(q2));
            if (g == 0) {
                s.X[q] = x, s.T[q] = t;
            } else {
                s.X[q] = s.X[q] + x, s.T[q] = s.T[q] + t;
            }
        }
    }
}

// Σ of 8 lanes, pairwise.
HWY_INLINE double lane_sum8(const double* a) { return ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7])); }

HWY_INLINE double lanes_sum(const V (&v)[kQ]) {
    alignas(64) double a[kSumLanes];
    for (int q = 0; q < kQ; ++q) hn::Store(v[q], D(), a + q * kN);
    return lane_sum8(a);
}

#if POLYVOL_SOUP_AVX512
// Σ of each of eight vectors, in lane_sum8's order: lane k of the result is
// lane_sum8(v[k]) (8 lanes: AVX-512). Adjacent lanes added (p_b = a_2b +
// a_2b+1, two vectors interleaved), then adjacent blocks (q0 = p0 + p1, q1 =
// p2 + p3), then the 256-bit halves (q0 + q1); additions are commutative,
// so the swapped copies hold the same values.
HWY_INLINE V lane_sums8(const V (&v)[8]) {
    const D d;
    V s[4];
    for (int j = 0; j < 4; ++j) {
        const V t = hn::Add(hn::InterleaveLower(d, v[2 * j], v[2 * j + 1]), hn::InterleaveUpper(d, v[2 * j], v[2 * j + 1]));
        s[j] = hn::Add(t, hn::SwapAdjacentBlocks(t));  // blocks: q0, q0, q1, q1 of v[2j], v[2j + 1]
    }
    V w[2];
    for (int j = 0; j < 2; ++j) {
        const V u = hn::OddEvenBlocks(s[2 * j + 1], s[2 * j]);  // q0 of v[4j..4j+3] in the lower half, q1 in the upper
        w[j] = hn::Add(u, hn::ConcatLowerUpper(d, u, u));
    }
    return hn::ConcatLowerLower(d, w[1], w[0]);
}
#endif

// A block's plain sums (each lane_sum8 of its lanes).
template <Moments kM>
HWY_INLINE void finish_block(const BlockLanes& s, Pass1Block& out) {
#if POLYVOL_SOUP_AVX512
    if constexpr (kM == kPlain) {
        alignas(64) double sums[8];
        const V lanes[8] = {s.M[0][0], s.M[1][0], s.M[2][0], s.AD[0], s.X[0], s.T[0], s.T[0], s.T[0]};
        hn::Store(lane_sums8(lanes), D(), sums);
        for (int k = 0; k < 3; ++k) out.mom[k] = sums[k];
        out.abs_d = sums[3];
        out.cross = sums[4];
        out.area2 = sums[5];
        return;
    }
#endif
    out.cross = lanes_sum(s.X);
    out.area2 = lanes_sum(s.T);
    if constexpr (kM == kPlain) {
        for (int k = 0; k < 3; ++k) out.mom[k] = lanes_sum(s.M[k]);
        out.abs_d = lanes_sum(s.AD);
    }
}

// Sum2's lanes (sums s, errors e) into one pair (vs, ve): the sums by
// two_sum in lane order, their errors and the lanes' in double.
POLYVOL_INLINE void combine_lanes(const double* s, const double* e, double& vs, double& ve) {
    vs = s[0];
    ve = lane_sum8(e);
    for (int j = 1; j < kSumLanes; ++j) {
        double ns, ne;
        two_sum(vs, s[j], ns, ne);
        vs = ns;
        ve += ne;
    }
}

// The group's Sum2 lanes of one sum: each block's (S, E) taken in by Sum2,
// then the lanes into one pair.
struct GroupSum {
    V GS[kQ], GE[kQ];

    HWY_INLINE void add_block(int b, const V (&S)[kQ], const V (&E)[kQ]) {
        for (int q = 0; q < kQ; ++q) {
            if (b == 0) {
                GS[q] = S[q];
                GE[q] = E[q];
            } else {
                sum2_add(GS[q], GE[q], S[q], E[q]);
            }
        }
    }

    HWY_INLINE void finish(double& vs, double& ve) const {
        alignas(64) double s[kSumLanes], e[kSumLanes];
        for (int q = 0; q < kQ; ++q) {
            hn::Store(GS[q], D(), s + q * kN);
            hn::Store(GE[q], D(), e + q * kN);
        }
        combine_lanes(s, e, vs, ve);
    }
};

// The group's lanes: the volume's, and (kDoubleDouble) the first moments'.
template <Moments kM>
struct GroupLanes {
    GroupSum volume, moment[3];

    HWY_INLINE void add_block(int b, const BlockLanes& s) {
        volume.add_block(b, s.S, s.E);
        if constexpr (kM == kDoubleDouble)
            for (int i = 0; i < 3; ++i) moment[i].add_block(b, s.MS[i], s.ME[i]);
    }

    HWY_INLINE void finish(Pass1Group& g) const {
        volume.finish(g.vs, g.ve);
        if constexpr (kM == kDoubleDouble)
            for (int i = 0; i < 3; ++i) moment[i].finish(g.ms[i], g.me[i]);
    }
};

// Asks for the cache lines of the records kPrefetchAhead bytes past a
// block's start (bytes: the block's extent): the records stream in from
// memory (page cache, a mapping) sooner than with the hardware prefetcher
// alone. Integer arithmetic: the address may lie past the input, which a
// prefetch never faults on.
constexpr std::uintptr_t kPrefetchAhead = 8192;

HWY_INLINE void prefetch_ahead(const std::byte* block, std::size_t bytes) {
    const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(block) + kPrefetchAhead;
    for (std::size_t o = 0; o < bytes; o += 64) __builtin_prefetch(reinterpret_cast<const void*>(a + o));
}

// ---- blocks through a block of doubles (below AVX-512, or without IFMA) -------

// Coordinates of a block as doubles: c[3 v + k][i]; unused slots zero.
struct Coords {
    alignas(64) double c[9][kB];
};

// Words of a block: w[i][3 v + k] is the canonical bit pattern of coordinate
// k of vertex v of triangle i (-0.0 mapped to +0.0).
using Words = uint32_t[kB][9];

// A block's records into co (and their canonical words into w): the largest
// |coordinate| bit pattern.
HWY_INLINE uint32_t load_block_portable(const std::byte* base, std::size_t stride, int n, Coords& co, Words& w) {
    uint32_t mx = 0;
    for (int i = 0; i < n; ++i) {
        std::memcpy(w[i], base + static_cast<std::size_t>(i) * stride, 36);
        for (int k = 0; k < 9; ++k) {
            uint32_t bits = w[i][k];
            bits = bits == 0x80000000u ? 0u : bits;
            w[i][k] = bits;
            mx = std::max(mx, bits & 0x7FFFFFFFu);
            co.c[k][i] = static_cast<double>(core::bit_cast<float>(bits));
        }
    }
    for (int k = 0; k < 9; ++k)
        for (int i = n; i < kB; ++i) co.c[k][i] = 0;
    return mx;
}

// The vertex hash (x, y, z, 0) of fingerprint_aesni, one vertex at a time:
// the key k0 added, three AES rounds with k1, k2, k3, each 32-bit word cut
// to 31 bits a lane. By Highway's AESRound (AES-NI on SSE4, its emulation
// on EMU128 and NEON), on HWY_SCALAR by the scalar twin (core/aes_round.hpp).
#if HWY_TARGET != HWY_SCALAR
using D8 = hn::Full128<uint8_t>;

// The round keys as vectors (once per block, not per vertex).
HWY_INLINE void load_round_keys(const Keys& key, hn::Vec<D8> (&k)[4]) {
    for (int r = 0; r < 4; ++r) k[r] = hn::Load(D8(), reinterpret_cast<const uint8_t*>(key.aes[r]));
}

// The hash's rounds on a vertex's 16 bytes: k0 added, then AES rounds with k1, k2, k3.
HWY_INLINE hn::Vec<D8> aes_rounds(hn::Vec<D8> x, const hn::Vec<D8> (&k)[4]) {
    x = hn::Xor(x, k[0]);
    for (int r = 1; r < 4; ++r) x = hn::AESRound(x, k[r]);
    return x;
}
#endif

HWY_INLINE void aes_hash(const uint32_t* xyz, const Keys& key, uint32_t h[kFpLanes]) {
#if defined(__EMSCRIPTEN__)
    // WebAssembly has no AES instruction (a software AES was 72% of the
    // soup's time there): two keyed multiply-xor chains over the 96 bits
    // instead, each mum(mum(xy ^ k0, z ^ k1) ^ k2, k3) with xy = x | y << 32
    // (mum as in core/fingerprint.cpp; docs/numerics.md, "The closedness
    // fingerprint"); the AES keys' eight words as two chains of four.
    const uint64_t xy = xyz[0] | uint64_t{xyz[1]} << 32;
    for (int c = 0; c < 2; ++c) {
        const uint64_t* k = &key.aes[2 * c][0];  // aes[2c][0..1], aes[2c + 1][0..1]
        const uint64_t t = core::fingerprint::mum(core::fingerprint::mum(xy ^ k[0], xyz[2] ^ k[1]) ^ k[2], k[3]);
        h[2 * c] = static_cast<uint32_t>(t & kP);
        h[2 * c + 1] = static_cast<uint32_t>((t >> 32) & kP);
    }
    return;
#endif
    alignas(16) uint32_t s[4] = {xyz[0], xyz[1], xyz[2], 0};
    auto* bytes = reinterpret_cast<uint8_t*>(s);
#if HWY_TARGET == HWY_SCALAR
    const auto* k0 = reinterpret_cast<const uint8_t*>(key.aes[0]);
    for (int i = 0; i < 16; ++i) bytes[i] = static_cast<uint8_t>(bytes[i] ^ k0[i]);
    for (int r = 1; r < 4; ++r) core::aes_round(bytes, reinterpret_cast<const uint8_t*>(key.aes[r]));
#else
    hn::Vec<D8> k[4];
    load_round_keys(key, k);
    hn::Store(aes_rounds(hn::Load(D8(), bytes), k), D8(), bytes);
#endif
    for (int l = 0; l < kFpLanes; ++l) h[l] = static_cast<uint32_t>(s[l] & kP);
}

// A block's fingerprint from its canonical words, vertex by vertex.
HWY_INLINE void fingerprint_portable(const Words& w, int n, const Keys& key, uint64_t out[kFpLanes]) {
    uint64_t acc[kFpLanes] = {};
    for (int i = 0; i < n; ++i) {
        uint32_t h[3][kFpLanes];
        for (int v = 0; v < 3; ++v) aes_hash(&w[i][3 * v], key, h[v]);
        for (int l = 0; l < kFpLanes; ++l) acc[l] += vandermonde(h[0][l], h[1][l], h[2][l]);
    }
    for (int l = 0; l < kFpLanes; ++l) out[l] = reduce(acc[l]);
}

#if POLYVOL_SOUP_AVX2
// Eight floats (256 bits) and what their transposes view them as.
using DF8 = hn::CappedTag<float, 8>;
using DU8 = hn::RebindToUnsigned<DF8>;
using DD4 = hn::Repartition<double, DF8>;           // the same 256 bits as 4 doubles (64-bit interleaves)
using DW4 = hn::Rebind<double, hn::Half<DF8>>;      // 4 floats widened

// Loads a block from the records (base: first coordinate of triangle 0) into
// structure of arrays: 8 rows of coordinates 0..7 per 8 triangles, an 8x8
// transpose (32-bit interleaves, 64-bit interleaves, then the 128-bit
// halves put together), coordinate 8 apart. Returns the largest
// |coordinate| bit pattern (>= 0x7F800000: NaN or infinity).
HWY_INLINE uint32_t load_block_avx2(const std::byte* base, std::size_t stride, int n, Coords& co) {
    const DF8 df;
    const DU8 du;
    const DD4 dd;
    const DW4 dw;
    using VF = hn::Vec<DF8>;
    const auto lo64 = [&](VF a, VF b) HWY_ATTR {
        return hn::BitCast(df, hn::InterleaveLower(dd, hn::BitCast(dd, a), hn::BitCast(dd, b)));
    };
    const auto hi64 = [&](VF a, VF b) HWY_ATTR {
        return hn::BitCast(df, hn::InterleaveUpper(dd, hn::BitCast(dd, a), hn::BitCast(dd, b)));
    };
    const auto absmask = hn::Set(du, 0x7FFFFFFFu);
    auto mx = hn::Zero(du);
    for (int i0 = 0; i0 < kB; i0 += 8) {
        const int m = std::min(8, n - i0);
        VF row[8];
        alignas(32) float last[8];
        for (int j = 0; j < 8; ++j) {
            if (j < m) {
                const std::byte* r = base + static_cast<std::size_t>(i0 + j) * stride;
                row[j] = hn::LoadU(df, reinterpret_cast<const float*>(r));
                std::memcpy(&last[j], r + 32, 4);
            } else {
                row[j] = hn::Zero(df);
                last[j] = 0;
            }
        }
        const VF t0 = hn::InterleaveLower(df, row[0], row[1]), t1 = hn::InterleaveUpper(df, row[0], row[1]);
        const VF t2 = hn::InterleaveLower(df, row[2], row[3]), t3 = hn::InterleaveUpper(df, row[2], row[3]);
        const VF t4 = hn::InterleaveLower(df, row[4], row[5]), t5 = hn::InterleaveUpper(df, row[4], row[5]);
        const VF t6 = hn::InterleaveLower(df, row[6], row[7]), t7 = hn::InterleaveUpper(df, row[6], row[7]);
        const VF u0 = lo64(t0, t2), u1 = hi64(t0, t2), u2 = lo64(t1, t3), u3 = hi64(t1, t3);
        const VF u4 = lo64(t4, t6), u5 = hi64(t4, t6), u6 = lo64(t5, t7), u7 = hi64(t5, t7);
        const VF col[9] = {hn::ConcatLowerLower(df, u4, u0), hn::ConcatLowerLower(df, u5, u1),
                           hn::ConcatLowerLower(df, u6, u2), hn::ConcatLowerLower(df, u7, u3),
                           hn::ConcatUpperUpper(df, u4, u0), hn::ConcatUpperUpper(df, u5, u1),
                           hn::ConcatUpperUpper(df, u6, u2), hn::ConcatUpperUpper(df, u7, u3),
                           hn::Load(df, last)};
        for (int k = 0; k < 9; ++k) {
            // (-0.0 stays: it adds the same exact 0 to every sum as +0.0.)
            mx = hn::Max(mx, hn::And(hn::BitCast(du, col[k]), absmask));
            hn::Store(hn::PromoteTo(dw, hn::LowerHalf(col[k])), dw, &co.c[k][i0]);
            hn::Store(hn::PromoteTo(dw, hn::UpperHalf(hn::Half<DF8>(), col[k])), dw, &co.c[k][i0 + 4]);
        }
    }
    return hn::GetLane(hn::MaxOfLanes(du, mx));
}

using DV4 = hn::Full128<uint32_t>;  // a vertex (x, y, z, 0) as words, or its four hash lanes
using DV8 = hn::CappedTag<uint32_t, 8>;
using DQ4 = hn::Repartition<uint64_t, DV8>;

// The vertices of triangle r (r: its first coordinate) at bytes [0,12),
// [12,24), [24,36) as words with a zero top word, -0.0 mapped to +0.0; no
// load leaves [0, 36).
HWY_INLINE void vertices(const std::byte* r, hn::Vec<DV4> (&v)[3]) {
    const DV4 d;
    alignas(16) static constexpr uint32_t kLow96[4] = {~0u, ~0u, ~0u, 0u};
    const auto low96 = hn::Load(d, kLow96), sign = hn::Set(d, 0x80000000u);
    v[0] = hn::And(hn::LoadU(d, reinterpret_cast<const uint32_t*>(r)), low96);
    v[1] = hn::And(hn::LoadU(d, reinterpret_cast<const uint32_t*>(r + 12)), low96);
    v[2] = hn::ShiftRightLanes<1>(d, hn::LoadU(d, reinterpret_cast<const uint32_t*>(r + 20)));
    for (auto& x : v) x = hn::IfThenZeroElse(hn::Eq(x, sign), x);
}

// x ≡ fold(x) (mod p) on 64-bit lanes.
HWY_INLINE hn::Vec<DQ4> fold4(hn::Vec<DQ4> x) {
    const DQ4 d;
    return hn::Add(hn::And(x, hn::Set(d, uint64_t{kP})), hn::ShiftRight<31>(x));
}

// The odd 32-bit lanes moved to the even ones (the top halves of the 64-bit lanes).
HWY_INLINE hn::Vec<DV8> odd_lanes(hn::Vec<DV8> x) {
    return hn::BitCast(DV8(), hn::ShiftRight<32>(hn::BitCast(DQ4(), x)));
}

// Vandermonde products of two triangles at once (one per 128-bit half; four
// 31-bit lanes each), mod p: differences + p (<= 2p < 2^32), 32 x 32 -> 64-bit
// products of the even and odd lanes apart, folded mod p.
HWY_INLINE void vandermonde8(hn::Vec<DV8> A, hn::Vec<DV8> B, hn::Vec<DV8> C, hn::Vec<DQ4>& even,
                             hn::Vec<DQ4>& odd) {
    const DV8 d;
    const auto P = hn::Set(d, static_cast<uint32_t>(kP));
    const auto d1 = hn::Add(hn::Sub(B, A), P), d2 = hn::Add(hn::Sub(C, A), P), d3 = hn::Add(hn::Sub(C, B), P);
    const auto e = fold4(fold4(hn::MulEven(d1, d2)));  // < 2^31 + 8
    const auto o = fold4(fold4(hn::MulEven(odd_lanes(d1), odd_lanes(d2))));
    even = hn::Add(even, fold4(hn::MulEven(hn::BitCast(d, e), d3)));  // each < 2^31 + 2^33
    odd = hn::Add(odd, fold4(hn::MulEven(hn::BitCast(d, o), odd_lanes(d3))));
}

// The fingerprint of a block with AES-NI: each vertex through three AES
// rounds (after whitening), the four 32-bit words cut to 31 bits as lanes.
HWY_INLINE void fingerprint_aesni(const std::byte* base, std::size_t stride, int n, const Keys& key,
                                  uint64_t fp[kFpLanes]) {
    const DV4 d4;
    const DV8 d;
    const DQ4 dq;
    hn::Vec<D8> k[4];
    load_round_keys(key, k);
    const auto P = hn::Set(d4, static_cast<uint32_t>(kP));
    auto even = hn::Zero(dq), odd = hn::Zero(dq);
    for (int i = 0; i < n; i += 2) {
        hn::Vec<DV4> v[2][3];
        for (int h = 0; h < 2; ++h) {
            if (i + h < n) {
                vertices(base + static_cast<std::size_t>(i + h) * stride, v[h]);
                for (auto& x : v[h]) x = hn::And(hn::BitCast(d4, aes_rounds(hn::BitCast(D8(), x), k)), P);
            } else {
                v[h][0] = v[h][1] = v[h][2] = hn::Zero(d4);  // a degenerate triangle adds 0
            }
        }
        vandermonde8(hn::Combine(d, v[1][0], v[0][0]), hn::Combine(d, v[1][1], v[0][1]),
                     hn::Combine(d, v[1][2], v[0][2]), even, odd);
    }
    alignas(32) uint64_t ev[4], od[4];
    hn::Store(even, dq, ev);
    hn::Store(odd, dq, od);
    // 64-bit element j of `even` is lane 2 (j mod 2) of the triangle in half j / 2.
    fp[0] = reduce(ev[0] + ev[2]);
    fp[1] = reduce(od[0] + od[2]);
    fp[2] = reduce(ev[1] + ev[3]);
    fp[3] = reduce(od[1] + od[3]);
}

#endif

// Pass 1 for a group, block by block through Coords: rows loaded from it.
template <bool kFp, Moments kM>
HWY_INLINE bool group_via_coords(const std::byte* base, std::size_t stride, int n, const Keys& keys, Pass1Group& g) {
    const D d;
    for (int l = 0; l < kFpLanes; ++l) g.fp[l] = 0;
    GroupLanes<kM> lanes;
    for (int b = 0; b * kB < n; ++b) {
        const int nb = std::min(kB, n - b * kB);
        const std::byte* const bb = base + static_cast<std::size_t>(b * kB) * stride;
        prefetch_ahead(bb, kB * stride);
        Coords co;
#if POLYVOL_SOUP_AVX2
        const uint32_t mx = load_block_avx2(bb, stride, nb, co);
#else
        Words w;
        const uint32_t mx = load_block_portable(bb, stride, nb, co, w);
#endif
        if (mx >= kNonFinite) return false;
        g.mx[b] = mx;
        BlockLanes s;
        for (int set = 0; set < kSets; ++set) {
            SetRows r;
            for (int k = 0; k < 9; ++k)
                for (int q = 0; q < kQ; ++q) r.c[k][q] = hn::Load(d, &co.c[k][kSumLanes * set + kN * q]);
            add_set<kM>(set, r, s);
        }
        if constexpr (kM != kNoMoments) finish_block<kM>(s, g.block[b]);
        lanes.add_block(b, s);
        if constexpr (kFp) {
            uint64_t fp[kFpLanes];
#if POLYVOL_SOUP_AVX2
            fingerprint_aesni(bb, stride, nb, keys, fp);
#else
            fingerprint_portable(w, nb, keys, fp);
#endif
            for (int l = 0; l < kFpLanes; ++l) g.fp[l] = (g.fp[l] + fp[l]) % kP;
        }
    }
    lanes.finish(g);
    return true;
}

// ---- AVX-512 with IFMA and VAES: rows and hashes in registers -------------------

#if POLYVOL_SOUP_AVX512
// x ≡ fold(x) (mod p) on 64-bit lanes.
POLYVOL_IFMA_INLINE __m512i fold16(__m512i x) {
    return _mm512_add_epi64(_mm512_and_si512(x, _mm512_set1_epi64(static_cast<long long>(kP))), _mm512_srli_epi64(x, 31));
}

// A 128-bit round key in all four 128-bit quarters.
POLYVOL_IFMA_INLINE __m512i key512(const uint64_t k[2]) {
    return _mm512_broadcast_i32x4(_mm_load_si128(reinterpret_cast<const __m128i*>(k)));
}

// Vertex v (v = 0, 1, 2) of the four triangles at r[0..3] (first
// coordinate of each) in the four 128-bit quarters, canonical (top word 0,
// -0.0 as +0.0) and whitened with k0 (x ^ k0). words: 0x7777 (the three
// coordinates of each quarter), without the quarters that are to hold the
// point 0. Vertex 2 is loaded from bytes [20, 36) and shifted: no load
// leaves [0, 36). Quarters 1..3 come by masked broadcasts from memory, which
// spare the shuffle unit that inserts would take.
template <int v>
POLYVOL_IFMA_INLINE __m512i whitened_vertices(const std::byte* const r[4],
                                                                                       __mmask16 words, __m512i k0) {
    constexpr int off = v < 2 ? 12 * v : 20;
    __m512i x = _mm512_castsi128_si512(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r[0] + off)));
    x = _mm512_mask_broadcast_i32x4(x, 0x00F0, _mm_loadu_si128(reinterpret_cast<const __m128i*>(r[1] + off)));
    x = _mm512_mask_broadcast_i32x4(x, 0x0F00, _mm_loadu_si128(reinterpret_cast<const __m128i*>(r[2] + off)));
    x = _mm512_mask_broadcast_i32x4(x, 0xF000, _mm_loadu_si128(reinterpret_cast<const __m128i*>(r[3] + off)));
    if constexpr (v == 2) x = _mm512_bsrli_epi128(x, 4);
    // Words kept: those in `words`, unless -0.0; the others are 0, whitened: k0.
    const __mmask16 keep = _mm512_mask_cmpneq_epi32_mask(words, x, _mm512_set1_epi32(static_cast<int>(0x80000000u)));
    return _mm512_mask_xor_epi32(k0, keep, x, k0);
}

// The fingerprint with VAES: four triangles per 512-bit vector, four
// vertices per AES instruction (the same hash values as fingerprint_aesni).
// The last multiplication of each Vandermonde product uses IFMA's 52-bit
// multiplies, the product's bits 0..51 and 52..103 summed apart (2^52 ≡ 2^21).
// Bounds: hashes h <= p; d = h_y + (p - h_x) <= 2p < 2^32; e = fold(d1 d2) <
// 2^31 + 2^33 < 2^34 (d1 d2 < 2^64); e d3 < 2^66, so its low 52 bits are
// < 2^52 and its high part < 2^14; over the 32 steps of a group (4 blocks)
// the sums stay below 2^57 and 2^19, and lo + 2^21 hi < 2^58 per 64-bit element.
struct Fingerprint512 {
    __m512i k0, k1, k2, k3;
    __m512i even_lo, even_hi, odd_lo, odd_hi;

    POLYVOL_IFMA_INLINE explicit Fingerprint512(const Keys& key)
        : k0(key512(key.aes[0])), k1(key512(key.aes[1])), k2(key512(key.aes[2])), k3(key512(key.aes[3])),
          even_lo(_mm512_setzero_si512()), even_hi(even_lo), odd_lo(even_lo), odd_hi(even_lo) {}

    // Four triangles (r: their first coordinates; see whitened_vertices for words).
    POLYVOL_IFMA_INLINE void add4(const std::byte* const r[4],
                                                                             __mmask16 words) {
        __m512i w[3] = {whitened_vertices<0>(r, words, k0), whitened_vertices<1>(r, words, k0),
                        whitened_vertices<2>(r, words, k0)};
        for (__m512i& x : w) x = _mm512_aesenc_epi128(_mm512_aesenc_epi128(_mm512_aesenc_epi128(x, k1), k2), k3);
        // The hashes h = w & p, and p - h = ~w & p.
        const __m512i P = _mm512_set1_epi32(static_cast<int>(kP));
        const __m512i hb = _mm512_and_si512(w[1], P), hc = _mm512_and_si512(w[2], P);
        const __m512i na = _mm512_andnot_si512(w[0], P), nb = _mm512_andnot_si512(w[1], P);
        const __m512i d1 = _mm512_add_epi32(hb, na);
        const __m512i d2 = _mm512_add_epi32(hc, na);
        const __m512i d3 = _mm512_add_epi32(hc, nb);
        // Even and odd 32-bit lanes apart.
        const __m512i e = fold16(_mm512_mul_epu32(d1, d2));
        const __m512i o = fold16(_mm512_mul_epu32(_mm512_srli_epi64(d1, 32), _mm512_srli_epi64(d2, 32)));
        const __m512i d3e = _mm512_and_si512(d3, _mm512_set1_epi64(0xFFFFFFFFll)), d3o = _mm512_srli_epi64(d3, 32);
        even_lo = _mm512_madd52lo_epu64(even_lo, e, d3e);
        even_hi = _mm512_madd52hi_epu64(even_hi, e, d3e);
        odd_lo = _mm512_madd52lo_epu64(odd_lo, o, d3o);
        odd_hi = _mm512_madd52hi_epu64(odd_hi, o, d3o);
    }

    POLYVOL_IFMA_INLINE void finish(uint64_t fp[kFpLanes]) const {
        alignas(64) uint64_t ev[8], od[8];
        _mm512_store_si512(ev, _mm512_add_epi64(even_lo, _mm512_slli_epi64(even_hi, 21)));
        _mm512_store_si512(od, _mm512_add_epi64(odd_lo, _mm512_slli_epi64(odd_hi, 21)));
        // 64-bit element j is lane 2 (j mod 2) (ev) or 2 (j mod 2) + 1 (od) of a triangle.
        fp[0] = reduce((ev[0] + ev[2]) + (ev[4] + ev[6]));
        fp[1] = reduce((od[0] + od[2]) + (od[4] + od[6]));
        fp[2] = reduce((ev[1] + ev[3]) + (ev[5] + ev[7]));
        fp[3] = reduce((od[1] + od[3]) + (od[5] + od[7]));
    }
};

// Floats 4 (imm >> 4) .. + 3 of a's low half and b's low half, widened.
template <int imm>
HWY_INLINE __m512d column(__m512 a, __m512 b) {
    return _mm512_cvtps_pd(_mm256_permute2f128_ps(_mm512_castps512_ps256(a), _mm512_castps512_ps256(b), imm));
}

// The nine floats at r in words 0..8, the rest zero: a 256-bit load and
// the ninth float broadcast from memory into word 8 (a load with a blend;
// from a register the broadcast takes the shuffle unit, which the
// transposes below keep busy). A masked 512-bit load (0x1FF) reads the same
// words but stalls when nothing else touched the records' cache lines first.
HWY_INLINE __m512 triangle_row(const std::byte* r) {
    const __m512 x = _mm512_zextps256_ps512(_mm256_loadu_ps(reinterpret_cast<const float*>(r)));
    float ninth;
    std::memcpy(&ninth, r + 32, 4);  // any alignment
    return _mm512_mask_broadcastss_ps(x, 0x100, _mm_set_ss(ninth));
}


// One block of nb records (kFull: nb == kB) into its lanes s, the
// fingerprint going on in fpr: each set of 8 triangles' records transposed
// in registers into its rows, nothing stored in between. Returns the largest
// |coordinate| bit pattern.
template <bool kFull, bool kFp, Moments kM>
POLYVOL_IFMA_INLINE uint32_t block_in_registers(const std::byte* bb, std::size_t stride, int nb, Fingerprint512& fpr,
                                                BlockLanes& s) {
    const __m512i col8_index = _mm512_setr_epi32(8, 9, 10, 11, 24, 25, 26, 27, 8, 9, 10, 11, 24, 25, 26, 27);
    __m512 mx = _mm512_setzero_ps();
    for (int set = 0; set < kSets; ++set) {
        const int i0 = kSumLanes * set;
        // Rows: the nine floats of triangle i0 + j in words 0..8 (zero past nb).
        __m512 row[8];
        if constexpr (kFull) {
            const std::byte* const r0 = bb + static_cast<std::size_t>(i0) * stride;
            for (int j = 0; j < 8; ++j) row[j] = triangle_row(r0 + static_cast<std::size_t>(j) * stride);
            for (int q = 0; q < 8 && kFp; q += 4) {
                const std::byte* const r[4] = {r0 + static_cast<std::size_t>(q) * stride,
                                               r0 + static_cast<std::size_t>(q + 1) * stride,
                                               r0 + static_cast<std::size_t>(q + 2) * stride,
                                               r0 + static_cast<std::size_t>(q + 3) * stride};
                fpr.add4(r, 0x7777);
            }
        } else {
            for (int j = 0; j < 8; ++j)
                row[j] = i0 + j < nb ? triangle_row(bb + static_cast<std::size_t>(i0 + j) * stride)
                                     : _mm512_setzero_ps();
            // Triangles past nb: all three corners the point 0 (degenerate: adds 0).
            for (int q = i0; q < std::min(nb, i0 + 8) && kFp; q += 4) {
                const std::byte* r[4];
                for (int h = 0; h < 4; ++h) r[h] = bb + static_cast<std::size_t>(std::min(q + h, nb - 1)) * stride;
                fpr.add4(r, static_cast<__mmask16>(nb - q >= 4 ? 0x7777u : 0x7777u & ((1u << (4 * (nb - q))) - 1)));
            }
        }
        // The largest |coordinate| (range 0xB: the operand of larger
        // magnitude, its sign cleared; with a NaN operand the result
        // differs between CPUs: NaN is detected by the volume below).
        const __m512 m01 = _mm512_range_ps(row[0], row[1], 0xB), m23 = _mm512_range_ps(row[2], row[3], 0xB);
        const __m512 m45 = _mm512_range_ps(row[4], row[5], 0xB), m67 = _mm512_range_ps(row[6], row[7], 0xB);
        mx = _mm512_range_ps(mx, _mm512_range_ps(_mm512_range_ps(m01, m23, 0xB), _mm512_range_ps(m45, m67, 0xB), 0xB),
                             0xB);
        // Transposed within each 128-bit lane: lane l of u_k holds float 4 l + (k mod 4) of rows 4 (k / 4) .. + 3.
        const __m512 t0 = _mm512_unpacklo_ps(row[0], row[1]), t1 = _mm512_unpackhi_ps(row[0], row[1]);
        const __m512 t2 = _mm512_unpacklo_ps(row[2], row[3]), t3 = _mm512_unpackhi_ps(row[2], row[3]);
        const __m512 t4 = _mm512_unpacklo_ps(row[4], row[5]), t5 = _mm512_unpackhi_ps(row[4], row[5]);
        const __m512 t6 = _mm512_unpacklo_ps(row[6], row[7]), t7 = _mm512_unpackhi_ps(row[6], row[7]);
        const __m512 u0 = _mm512_shuffle_ps(t0, t2, 0x44), u1 = _mm512_shuffle_ps(t0, t2, 0xEE);
        const __m512 u2 = _mm512_shuffle_ps(t1, t3, 0x44), u3 = _mm512_shuffle_ps(t1, t3, 0xEE);
        const __m512 u4 = _mm512_shuffle_ps(t4, t6, 0x44), u5 = _mm512_shuffle_ps(t4, t6, 0xEE);
        const __m512 u6 = _mm512_shuffle_ps(t5, t7, 0x44), u7 = _mm512_shuffle_ps(t5, t7, 0xEE);
        SetRows r;
        r.c[0][0] = V{column<0x20>(u0, u4)};
        r.c[1][0] = V{column<0x20>(u1, u5)};
        r.c[2][0] = V{column<0x20>(u2, u6)};
        r.c[3][0] = V{column<0x20>(u3, u7)};
        r.c[4][0] = V{column<0x31>(u0, u4)};
        r.c[5][0] = V{column<0x31>(u1, u5)};
        r.c[6][0] = V{column<0x31>(u2, u6)};
        r.c[7][0] = V{column<0x31>(u3, u7)};
        r.c[8][0] = V{_mm512_cvtps_pd(_mm512_castps512_ps256(_mm512_permutex2var_ps(u0, col8_index, u4)))};
        add_set<kM>(set, r, s);
    }
    // Magnitudes' bit patterns order as the magnitudes (infinity above all finite ones).
    return _mm512_reduce_max_epu32(_mm512_castps_si512(mx));
}

// Pass 1 for a group with AVX-512, IFMA and VAES (block_in_registers).
template <bool kFp, Moments kM>
POLYVOL_IFMA_ATTR bool group_in_registers(const std::byte* base, std::size_t stride, int n, const Keys& key,
                                          Pass1Group& g) {
    Fingerprint512 fpr(key);
    GroupLanes<kM> lanes;
    for (int b = 0; b * kB < n; ++b) {
        const int nb = std::min(kB, n - b * kB);
        const std::byte* const bb = base + static_cast<std::size_t>(b * kB) * stride;
        prefetch_ahead(bb, kB * stride);
        BlockLanes s;
        const uint32_t m = nb == kB ? block_in_registers<true, kFp, kM>(bb, stride, nb, fpr, s)
                                    : block_in_registers<false, kFp, kM>(bb, stride, nb, fpr, s);
        if (m >= kNonFinite) return false;
        g.mx[b] = m;
        if constexpr (kM != kNoMoments) finish_block<kM>(s, g.block[b]);
        lanes.add_block(b, s);
    }
    lanes.finish(g);
    // A NaN coordinate is a factor of a product in h, which makes vs NaN;
    // finite coordinates keep vs and ve finite.
    if (std::isnan(g.vs + g.ve)) return false;
    if constexpr (kFp) {
        fpr.finish(g.fp);
    } else {
        for (int l = 0; l < kFpLanes; ++l) g.fp[l] = 0;
    }
    return true;
}
#endif

template <bool kFp, Moments kM>
HWY_INLINE bool group(const std::byte* base, std::size_t stride, int n, const Keys& keys, Pass1Group& g) {
#if POLYVOL_SOUP_AVX512
    if (simd::has_avx512_ifma_vaes()) return group_in_registers<kFp, kM>(base, stride, n, keys, g);
#endif
    return group_via_coords<kFp, kM>(base, stride, n, keys, g);
}

}  // namespace

bool RunPass1(const std::byte* base, std::size_t stride, int n, const Keys& keys, bool fingerprint, Moments moments,
              Pass1Group& g) {
    const auto with = [&]<bool kFp>() {
        switch (moments) {
            case kNoMoments: return group<kFp, kNoMoments>(base, stride, n, keys, g);
            case kPlain: return group<kFp, kPlain>(base, stride, n, keys, g);
            case kDoubleDouble: return group<kFp, kDoubleDouble>(base, stride, n, keys, g);
        }
        return false;
    };
    return fingerprint ? with.template operator()<true>() : with.template operator()<false>();
}

#undef POLYVOL_SOUP_AVX2
#undef POLYVOL_SOUP_AVX512
#undef POLYVOL_IFMA_ATTR
#undef POLYVOL_IFMA_INLINE

}  // namespace polyvol::measure::soup::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "core/hwy_dispatch.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::measure::soup {

bool pass1_group(const std::byte* base, std::size_t stride, int n, const Keys& keys, bool fingerprint,
                 Moments moments, Pass1Group& g) {
    return POLYVOL_DISPATCH(RunPass1)(base, stride, n, keys, fingerprint, moments, g);
}

}  // namespace polyvol::measure::soup
#endif  // HWY_ONCE
