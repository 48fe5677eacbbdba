// measure/soup.cpp — polyvol/soup.hpp: volume, first moments, area and a
// closedness fingerprint of float32 triangle records, in constant memory.
//
// Error analysis of pass 1 (u = 2^-53). It assumes the default
// floating-point environment: round to nearest, no flush-to-zero or
// denormals-are-zero (which e.g. -ffast-math's crtfastmath sets at start-up).
// Coordinates are float32 values widened exactly: multiples of 2^-149 below
// 2^128. The volume terms (products of three coordinates) are multiples of
// 2^-447, the first-moment and area terms (d s_i and t² = Σ_k e_k², products
// of four) multiples of 2^-596; every nonzero value in pass 1 (also t = √t²
// and the magnitudes, down to 2^-43 M^4 >= 2^-639) is at least 2^-640 and
// under 2^520, so no operation underflows or overflows and each rounding is
// relative.
//   Volume, per triangle (a, b, c), det = Σ_k a_k (b_j c_l - b_l c_j):
//     p_k = b_j c_l, q_k = b_l c_j        exact (24-bit × 24-bit significands)
//     n_k + t_k = p_k - q_k               exact (two_sum), |t_k| <= u |n_k|
//     P_k + Q_k = a_k n_k                 exact (two_prod)
//     h + g1 + g2 = P_0 + P_1 + P_2       exact (two two_sums)
//     lo = fl(g1 + g2 + Q_0 + Q_1 + Q_2 + fl(a_0 t_0) + fl(a_1 t_1) + fl(a_2 t_2))
//   With A_k = |a_k| (|p_k| + |q_k|), S = Σ A_k <= 6 M^3 (M >= every |coordinate|):
//   the eight small terms total <= 4.001 u S, so summing them costs
//   <= γ7 · 4.001 u S <= 28.1 u² S and the three products fl(a_k t_k) <= 1.01 u² S:
//     |det - (h + lo)| <= 29.2 u² S.
//   The pairs (h, lo) of a block are summed by Sum2 (Ogita–Rump–Oishi) in 8
//   lanes of 4: <= 2·4 (1.01·4 + 3.1) u² Σ S <= 57.2 u² Σ S, leaving each
//   lane an error term of <= 4.01 u Σ S of lo and <= 3.01 u Σ S of two_sum
//   errors (7.03 u Σ S with its roundings). The lanes run on across a group
//   of up to 4 consecutive blocks of a task: per lane, the blocks' sums by
//   two_sum (exact; <= 3 errors, each <= 1.02 u Σ S of the group) and the
//   blocks' error terms added in double, each value in at most 7
//   additions: <= γ7 · 10.1 u Σ S <= 70.8 u² Σ S. The group's lanes are then
//   combined by two_sum (exact) and their error terms (<= 10.2 u Σ S; seven
//   more two_sum errors <= 7.14 u Σ S) added in double (14 additions):
//   <= γ14 · 17.4 u Σ S <= 244 u² Σ S; the group's (sum, error) pair goes
//   exactly into a superaccumulator.
//   Total <= (29.2 + 57.2 + 70.8 + 244) u² Σ S < 402 u² Σ S.
//   Bound used: 512 u² (1 + 2^-10) Σ_blocks 6 M_b^3 n_b (a factor 1.27 of safety;
//   (1 + 2^-10) covers the rounding of the block magnitudes, of their sums
//   per group (at most four) and of the bound).
//   Blocks far from the origin compared with their size (M_b^3 much larger
//   than the volume they enclose) defeat this filter: pass 2 then uses
//   cone.cpp's kernel, which translates each triangle to its first vertex.
//   First moments, per triangle: d = fl(h + lo), s_i = fl(fl(a_i + b_i) + c_i),
//   m_i = fl(d s_i); with σ_i = |a_i| + |b_i| + |c_i| <= 3M,
//     |m_i - det (a_i + b_i + c_i)| <= 4.01 u σ_i |d| + 525.6 u² M^4
//   (525.6 = 3 · 29.2 · 6: σ_i <= 3M times the error of d, <= 29.2 u² · 6 M^3),
//   plus <= γ6 Σ|m_i| for the sum of a block (8 lanes of 4, then the lanes
//   pairwise: depth 6; 9.01 u is used below).
//   Bound used: 16 u (1 + 2^-10) Σ_blocks (3 M_b Σ|d| + 2^-43 M_b^4 n_b), /24.
//   Area, per triangle: t = |fl(fl(b-a) × fl(c-a))| with error <= γ5 t + γ4 X,
//   X = Σ|products| of the cross product (the analysis of area.cpp); a block's
//   sum adds <= γ6 Σ t (9 u is used below). Bound used: 15 u A + 5 u ΣX (A = Σ of block sums),
//   then halving is exact and the final rounding adds u.
//
// Fingerprint: see soup.hpp, and measure/fingerprint.hpp for its arithmetic.
// Vectorised: 32 x 32 -> 64-bit multiplies on the even and the odd 32-bit
// lanes apart (with AVX-512 IFMA, the last product in 52-bit halves:
// Fingerprint512).
#include "polyvol/soup.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

#include "core/simd.hpp"
#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "measure/cone.hpp"
#include "measure/fingerprint.hpp"
#include "measure/soup_testing.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define POLYVOL_SOUP_X86 1
#else
#define POLYVOL_SOUP_X86 0
#endif

namespace polyvol {
namespace {

using exact::ExactSum;
using exact::two_prod_t;
using exact::two_sum;
namespace cone = measure::cone;

constexpr int kB = cone::kBlockTriangles;  // triangles per block (32)
static_assert(SoupAccumulator::kBlockTriangles == kB);
using measure::fingerprint::fold;
using measure::fingerprint::kP;
using measure::fingerprint::mum;
using measure::fingerprint::reduce;
using measure::fingerprint::vandermonde;
constexpr int kFpLanes = measure::fingerprint::kLanes;
constexpr double kU = 0x1p-53;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kChunk = 8192;  // triangles per parallel task (a multiple of kB)
static_assert(kChunk % kB == 0);

// ---- the fingerprint ---------------------------------------------------------

struct Keys {
    alignas(16) uint64_t aes[4][2];  // AES: whitening key, then three round keys
    uint64_t mix[2][4];              // portable hash: four keys per lane
};

// Words of a block: w[i][3 v + k] is the canonical bit pattern of coordinate
// k of vertex v of triangle i (-0.0 mapped to +0.0).
using Words = uint32_t[kB][9];

// Portable vertex hash: two multiply-xor rounds (wyhash's mixing) for each
// 64-bit half; the four 32-bit quarters cut to 31 bits are the four lanes.
void fingerprint_portable(const Words& w, int n, const Keys& key, uint64_t out[kFpLanes]) {
    uint64_t acc[kFpLanes] = {};
    for (int i = 0; i < n; ++i) {
        uint64_t h[3][kFpLanes];
        for (int v = 0; v < 3; ++v) {
            const uint64_t w0 = w[i][3 * v] | static_cast<uint64_t>(w[i][3 * v + 1]) << 32;
            const uint64_t w1 = w[i][3 * v + 2];
            for (int half = 0; half < 2; ++half) {
                const uint64_t* k = key.mix[half];
                const uint64_t x = mum(mum(w0 ^ k[0], w1 ^ k[1]) ^ k[2], w0 ^ k[3]);
                h[v][2 * half] = x & kP;
                h[v][2 * half + 1] = (x >> 32) & kP;
            }
        }
        for (int l = 0; l < kFpLanes; ++l) acc[l] += vandermonde(h[0][l], h[1][l], h[2][l]);
    }
    for (int l = 0; l < kFpLanes; ++l) out[l] = reduce(acc[l]);
}

// ---- pass 1 arithmetic -------------------------------------------------------

// Coordinates of a block as doubles: c[3 v + k][i]; unused slots zero.
struct Coords {
    alignas(64) double c[9][kB];
};

// Per-block results of pass 1: the volume's lanes (which go on into the
// group's), the rest for the superaccumulators.
struct Pass1Block {
    alignas(64) double s[8], e[8];  // volume: Sum2 (sum, error) of 6 V in 8 lanes (lane j: triangles j mod 8)
    double mom[3];                  // Σ d s_i (24 ∫x_i)
    double abs_d;                   // Σ |d|
    double area2;                   // Σ |n| (2 A)
    double cross;                   // Σ X (the products of the cross products)
};

// Pass 1 works on groups of up to kGroupBlocks consecutive blocks of a task:
// their volume sums and fingerprints are combined before they go into the
// superaccumulators (the error analysis at the top), the rest block by block.
constexpr int kGroupBlocks = 4;

struct Pass1Group {
    Pass1Block block[kGroupBlocks];  // per block: moments and area (the lanes: see pass1_group)
    uint32_t mx[kGroupBlocks];       // per block: the largest |coordinate| bit pattern
    double vs, ve;                   // the group's Sum2 (sum, error) of 6 V
    uint64_t fp[kFpLanes];           // the group's fingerprint (mod p)
};

constexpr int kSumLanes = 8;  // lanes of the per-block sums (kB / kSumLanes terms each)
static_assert(kB == 4 * kSumLanes);

// Σ of 8 values, pairwise.
POLYVOL_INLINE double lane_sum8(const double* a) { return ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7])); }

// Eight doubles as one vector (GCC/Clang vector extension; lowered to what
// the target has: -ffp-contract=off keeps every operation a rounded IEEE one).
typedef double V8 __attribute__((vector_size(64)));
POLYVOL_INLINE void load8(V8& v, const double* p) { std::memcpy(&v, p, sizeof v); }

// One step of Sum2 in eight lanes: (S, E) takes in the pair (H, L), S by
// two_sum, its error and L into E.
POLYVOL_INLINE void sum2_add(V8& S, V8& E, const V8& H, const V8& L) {
    V8 ns, ne;
    exact::two_sum_lanes(S, H, ns, ne);
    S = ns;
    E = E + (ne + L);
}

// Σ of a block's kB values: lane j sums j, j + 8, j + 16, j + 24, then the
// lanes pairwise: depth 6.
POLYVOL_INLINE double lane_sum(const double* v) {
    V8 v0, v1, v2, v3;
    load8(v0, v);
    load8(v1, v + 8);
    load8(v2, v + 16);
    load8(v3, v + 24);
    const V8 a8 = ((v0 + v1) + v2) + v3;
    alignas(64) double a[kSumLanes];
    std::memcpy(a, &a8, sizeof a);
    return lane_sum8(a);
}

// Asks for the cache lines of the records kPrefetchAhead bytes past a
// block's start (bytes: the block's extent). The records stream in from
// memory (page cache, a mapping) faster with this than with the hardware
// prefetcher alone: 8M records in memory on one core, 42 -> 38 ms (AMD
// Zen 4); 4 KB and 16 KB ahead did less. Integer arithmetic: the address
// may lie past the input, which a prefetch never faults on.
constexpr std::uintptr_t kPrefetchAhead = 8192;

POLYVOL_INLINE void prefetch_ahead(const std::byte* block, std::size_t bytes) {
    const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(block) + kPrefetchAhead;
    for (std::size_t o = 0; o < bytes; o += 64) __builtin_prefetch(reinterpret_cast<const void*>(a + o));
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

// kMA: the first moments and t² (area) as well as the volume.
template <bool kFma, bool kMA>
POLYVOL_INLINE void pass1_arith(const Coords& co, Pass1Block& out, double* t2) {
    const auto& c = co.c;
    alignas(64) double h[kB], lo[kB], m[3][kB], ad[kB], x[kB];
    for (int i = 0; i < kB; ++i) {
        const double ax = c[0][i], ay = c[1][i], az = c[2][i];
        const double bx = c[3][i], by = c[4][i], bz = c[5][i];
        const double cx = c[6][i], cy = c[7][i], cz = c[8][i];
        // b × c: the products are exact (float32 significands).
        double n0, t0, n1, t1, n2, tt2;
        two_sum(by * cz, -(bz * cy), n0, t0);
        two_sum(bz * cx, -(bx * cz), n1, t1);
        two_sum(bx * cy, -(by * cx), n2, tt2);
        double P0, Q0, P1, Q1, P2, Q2;
        two_prod_t<kFma>(ax, n0, P0, Q0);
        two_prod_t<kFma>(ay, n1, P1, Q1);
        two_prod_t<kFma>(az, n2, P2, Q2);
        double h1, g1, hh, g2;
        two_sum(P0, P1, h1, g1);
        two_sum(h1, P2, hh, g2);
        h[i] = hh;
        lo[i] = ((g1 + g2) + ((Q0 + Q1) + Q2)) + ((ax * t0 + ay * t1) + az * tt2);
    }
    for (int i = 0; i < kB && kMA; ++i) {
        // First moments.
        const double d = h[i] + lo[i];
        ad[i] = std::fabs(d);
        m[0][i] = d * ((c[0][i] + c[3][i]) + c[6][i]);
        m[1][i] = d * ((c[1][i] + c[4][i]) + c[7][i]);
        m[2][i] = d * ((c[2][i] + c[5][i]) + c[8][i]);
    }
    for (int i = 0; i < kB && kMA; ++i) {
        // Area: |(b - a) × (c - a)|.
        const double ux = c[3][i] - c[0][i], uy = c[4][i] - c[1][i], uz = c[5][i] - c[2][i];
        const double wx = c[6][i] - c[0][i], wy = c[7][i] - c[1][i], wz = c[8][i] - c[2][i];
        const double p0 = uy * wz, q0 = uz * wy, p1 = uz * wx, q1 = ux * wz, p2 = ux * wy, q2 = uy * wx;
        const double e0 = p0 - q0, e1 = p1 - q1, e2 = p2 - q2;
        t2[i] = (e0 * e0 + e1 * e1) + e2 * e2;
        x[i] = ((std::fabs(p0) + std::fabs(q0)) + (std::fabs(p1) + std::fabs(q1))) + (std::fabs(p2) + std::fabs(q2));
    }
    // Volume: Sum2 in 8 lanes of 4 (lane j holds triangles j, j+8, j+16,
    // j+24), written with vectors of 8 doubles (elementwise IEEE operations:
    // the same results on every target), then the lanes into one pair.
    V8 S, E;
    load8(S, h);
    load8(E, lo);
    for (int r = 1; r < kB / kSumLanes; ++r) {
        V8 H, L;
        load8(H, h + r * kSumLanes);
        load8(L, lo + r * kSumLanes);
        sum2_add(S, E, H, L);
    }
    std::memcpy(out.s, &S, sizeof out.s);
    std::memcpy(out.e, &E, sizeof out.e);
    if constexpr (kMA) {
        for (int k = 0; k < 3; ++k) out.mom[k] = lane_sum(m[k]);
        out.abs_d = lane_sum(ad);
        out.cross = lane_sum(x);
    }
}


template <bool kMA>
void pass1_arith_base(const Coords& c, Pass1Block& out) {
    alignas(64) double t2[kB], t[kB];
    pass1_arith<false, kMA>(c, out, t2);
    if constexpr (kMA) {
#if POLYVOL_SOUP_X86
        for (int i = 0; i < kB; i += 2) _mm_store_pd(t + i, _mm_sqrt_pd(_mm_load_pd(t2 + i)));
#else
        for (int i = 0; i < kB; ++i) t[i] = std::sqrt(t2[i]);
#endif
        out.area2 = lane_sum(t);
    }
}

// The whole of pass 1 for one block, portable (see pass1_avx512_body). kFp: the
// fingerprint (into fp); kMA: first moments and area.
template <bool kFp, bool kMA>
uint32_t pass1_portable(const std::byte* base, std::size_t stride, int n, const Keys& key, Pass1Block& out,
                        uint64_t fp[kFpLanes]) {
    Words w;
    Coords co;
    uint32_t mx = 0;
    for (int i = 0; i < n; ++i) {
        std::memcpy(w[i], base + static_cast<std::size_t>(i) * stride, 36);
        for (int k = 0; k < 9; ++k) {
            uint32_t bits = w[i][k];
            bits = bits == 0x80000000u ? 0u : bits;
            w[i][k] = bits;
            mx = std::max(mx, bits & 0x7FFFFFFFu);
            co.c[k][i] = static_cast<double>(std::bit_cast<float>(bits));
        }
    }
    for (int k = 0; k < 9; ++k)
        for (int i = n; i < kB; ++i) co.c[k][i] = 0;
    if (mx >= 0x7F800000u) return mx;
    if constexpr (kFp) fingerprint_portable(w, n, key, fp);
    pass1_arith_base<kMA>(co, out);
    return mx;
}

#if POLYVOL_SOUP_X86
// ---- x86 kernels: AVX2 + FMA + AES-NI, and AVX-512 + IFMA + VAES where present ----

// Instruction sets (simd::level, the library's one CPU detection): 0
// portable, 1 AVX2 + FMA + AES-NI, 2 that and AVX-512 (F, VL, DQ, BW, IFMA)
// + VAES.
int isa_level() {
    if (simd::has_avx512_ifma_vaes()) return 2;
    return simd::level() >= simd::Level::avx2 ? 1 : 0;
}

// Loads a block from the records (base: first coordinate of triangle 0) into
// structure of arrays: 8 rows of coordinates 0..7 per 8 triangles, an 8x8
// transpose, coordinate 8 apart. Returns the largest
// |coordinate| bit pattern (>= 0x7F800000: NaN or infinity).
__attribute__((target("avx2"), always_inline)) inline uint32_t load_block_avx2(const std::byte* base, std::size_t stride,
                                                                            int n, Coords& co) {
    const __m256i absmask = _mm256_set1_epi32(0x7FFFFFFF);
    __m256i mx = _mm256_setzero_si256();
    for (int i0 = 0; i0 < kB; i0 += 8) {
        const int m = std::min(8, n - i0);
        __m256 row[8];
        float last[8];
        for (int j = 0; j < 8; ++j) {
            if (j < m) {
                const std::byte* r = base + static_cast<std::size_t>(i0 + j) * stride;
                row[j] = _mm256_loadu_ps(reinterpret_cast<const float*>(r));
                std::memcpy(&last[j], r + 32, 4);
            } else {
                row[j] = _mm256_setzero_ps();
                last[j] = 0;
            }
        }
        const __m256 t0 = _mm256_unpacklo_ps(row[0], row[1]), t1 = _mm256_unpackhi_ps(row[0], row[1]);
        const __m256 t2 = _mm256_unpacklo_ps(row[2], row[3]), t3 = _mm256_unpackhi_ps(row[2], row[3]);
        const __m256 t4 = _mm256_unpacklo_ps(row[4], row[5]), t5 = _mm256_unpackhi_ps(row[4], row[5]);
        const __m256 t6 = _mm256_unpacklo_ps(row[6], row[7]), t7 = _mm256_unpackhi_ps(row[6], row[7]);
        const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
        const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
        const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
        const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xEE);
        const __m256 col[9] = {_mm256_permute2f128_ps(u0, u4, 0x20), _mm256_permute2f128_ps(u1, u5, 0x20),
                               _mm256_permute2f128_ps(u2, u6, 0x20), _mm256_permute2f128_ps(u3, u7, 0x20),
                               _mm256_permute2f128_ps(u0, u4, 0x31), _mm256_permute2f128_ps(u1, u5, 0x31),
                               _mm256_permute2f128_ps(u2, u6, 0x31), _mm256_permute2f128_ps(u3, u7, 0x31),
                               _mm256_loadu_ps(last)};
        for (int k = 0; k < 9; ++k) {
            // (-0.0 stays: it adds the same exact 0 to every sum as +0.0.)
            mx = _mm256_max_epu32(mx, _mm256_and_si256(_mm256_castps_si256(col[k]), absmask));
            _mm256_store_pd(&co.c[k][i0], _mm256_cvtps_pd(_mm256_castps256_ps128(col[k])));
            _mm256_store_pd(&co.c[k][i0 + 4], _mm256_cvtps_pd(_mm256_extractf128_ps(col[k], 1)));
        }
    }
    __m128i m4 = _mm_max_epu32(_mm256_castsi256_si128(mx), _mm256_extracti128_si256(mx, 1));
    m4 = _mm_max_epu32(m4, _mm_shuffle_epi32(m4, 0x4E));
    m4 = _mm_max_epu32(m4, _mm_shuffle_epi32(m4, 0xB1));
    return static_cast<uint32_t>(_mm_cvtsi128_si32(m4));
}

// Load + arithmetic of pass 1 with AVX2 (pass1_avx512 below does the same
// with AVX-512, register-resident).
template <bool kMA>
__attribute__((target("avx2,fma"))) uint32_t arith_avx2(const std::byte* base, std::size_t stride, int n,
                                                        Pass1Block& out) {
    Coords co;
    const uint32_t mx = load_block_avx2(base, stride, n, co);
    if (mx >= 0x7F800000u) return mx;
    alignas(64) double t2[kB], t[kB];
    pass1_arith<true, kMA>(co, out, t2);
    if constexpr (kMA) {
        for (int i = 0; i < kB; i += 4) _mm256_store_pd(t + i, _mm256_sqrt_pd(_mm256_load_pd(t2 + i)));
        out.area2 = lane_sum(t);
    }
    return mx;
}

// The vertices of triangle r (r: its first coordinate) at bytes [0,12),
// [12,24), [24,36) as 128-bit values with a zero top word, -0.0 mapped to
// +0.0; no load leaves [0, 36).
__attribute__((target("avx2"), always_inline)) inline void vertices(const std::byte* r, __m128i& a, __m128i& b, __m128i& c) {
    const __m128i low96 = _mm_set_epi32(0, -1, -1, -1);
    const __m128i sign = _mm_set1_epi32(static_cast<int>(0x80000000u));
    a = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r)), low96);
    b = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r + 12)), low96);
    c = _mm_srli_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r + 20)), 4);
    a = _mm_andnot_si128(_mm_cmpeq_epi32(a, sign), a);
    b = _mm_andnot_si128(_mm_cmpeq_epi32(b, sign), b);
    c = _mm_andnot_si128(_mm_cmpeq_epi32(c, sign), c);
}

// x ≡ fold(x) (mod p) on 64-bit lanes.
__attribute__((target("avx2"), always_inline)) inline __m256i fold4(__m256i x) {
    return _mm256_add_epi64(_mm256_and_si256(x, _mm256_set1_epi64x(static_cast<long long>(kP))), _mm256_srli_epi64(x, 31));
}

// Vandermonde products of two triangles at once (one per 128-bit half; four
// 31-bit lanes each), mod p: differences + p (<= 2p < 2^32), 32 x 32 -> 64-bit
// products of the even and odd lanes apart, folded mod p.
__attribute__((target("avx2"), always_inline)) inline void vandermonde8(__m256i A, __m256i B, __m256i C, __m256i& even,
                                                                      __m256i& odd) {
    const __m256i P = _mm256_set1_epi32(static_cast<int>(kP));
    const __m256i d1 = _mm256_add_epi32(_mm256_sub_epi32(B, A), P);
    const __m256i d2 = _mm256_add_epi32(_mm256_sub_epi32(C, A), P);
    const __m256i d3 = _mm256_add_epi32(_mm256_sub_epi32(C, B), P);
    __m256i e = fold4(fold4(_mm256_mul_epu32(d1, d2)));  // < 2^31 + 8
    __m256i o = fold4(fold4(_mm256_mul_epu32(_mm256_srli_epi64(d1, 32), _mm256_srli_epi64(d2, 32))));
    even = _mm256_add_epi64(even, fold4(_mm256_mul_epu32(e, d3)));  // each < 2^31 + 2^33
    odd = _mm256_add_epi64(odd, fold4(_mm256_mul_epu32(o, _mm256_srli_epi64(d3, 32))));
}

__attribute__((target("avx2"), always_inline)) inline void finish_lanes(__m256i even, __m256i odd, uint64_t fp[kFpLanes]) {
    alignas(32) uint64_t ev[4], od[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(ev), even);
    _mm256_store_si256(reinterpret_cast<__m256i*>(od), odd);
    // 64-bit element j of `even` is lane 2 (j mod 2) of the triangle in half j / 2.
    fp[0] = reduce(ev[0] + ev[2]);
    fp[1] = reduce(od[0] + od[2]);
    fp[2] = reduce(ev[1] + ev[3]);
    fp[3] = reduce(od[1] + od[3]);
}

// The fingerprint of a block with AES-NI: each vertex through three AES
// rounds (after whitening), the four 32-bit words cut to 31 bits as lanes.
__attribute__((target("avx2,aes"))) void fingerprint_aesni(const std::byte* base, std::size_t stride, int n,
                                                           const Keys& key, uint64_t fp[kFpLanes]) {
    const __m128i k0 = _mm_load_si128(reinterpret_cast<const __m128i*>(key.aes[0]));
    const __m128i k1 = _mm_load_si128(reinterpret_cast<const __m128i*>(key.aes[1]));
    const __m128i k2 = _mm_load_si128(reinterpret_cast<const __m128i*>(key.aes[2]));
    const __m128i k3 = _mm_load_si128(reinterpret_cast<const __m128i*>(key.aes[3]));
    const __m128i P = _mm_set1_epi32(static_cast<int>(kP));
    __m256i even = _mm256_setzero_si256(), odd = _mm256_setzero_si256();
    for (int i = 0; i < n; i += 2) {
        __m128i v[2][3];
        for (int h = 0; h < 2; ++h) {
            if (i + h < n) {
                vertices(base + static_cast<std::size_t>(i + h) * stride, v[h][0], v[h][1], v[h][2]);
                for (int j = 0; j < 3; ++j) {
                    __m128i x = _mm_aesenc_si128(_mm_xor_si128(v[h][j], k0), k1);
                    x = _mm_aesenc_si128(x, k2);
                    v[h][j] = _mm_and_si128(_mm_aesenc_si128(x, k3), P);
                }
            } else {
                v[h][0] = v[h][1] = v[h][2] = _mm_setzero_si128();  // a degenerate triangle adds 0
            }
        }
        vandermonde8(_mm256_set_m128i(v[1][0], v[0][0]), _mm256_set_m128i(v[1][1], v[0][1]),
                     _mm256_set_m128i(v[1][2], v[0][2]), even, odd);
    }
    finish_lanes(even, odd, fp);
}

// GCC 12's AVX-512 intrinsics pass an undefined vector as the unused
// merge operand, which -Wmaybe-uninitialized reports falsely.
#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#pragma GCC diagnostic ignored "-Wuninitialized"

// ---- AVX-512 + IFMA + VAES: the whole of pass 1 for a group in one kernel ----

#define POLYVOL_AVX512 "avx512f,avx512vl,avx512dq,avx512bw,avx512ifma,avx2,fma,aes,vaes"

// x ≡ fold(x) (mod p) on 64-bit lanes.
__attribute__((target(POLYVOL_AVX512), always_inline)) inline __m512i fold16(__m512i x) {
    return _mm512_add_epi64(_mm512_and_si512(x, _mm512_set1_epi64(static_cast<long long>(kP))), _mm512_srli_epi64(x, 31));
}

// A 128-bit round key in all four 128-bit quarters.
__attribute__((target(POLYVOL_AVX512), always_inline)) inline __m512i key512(const uint64_t k[2]) {
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
__attribute__((target(POLYVOL_AVX512), always_inline)) inline __m512i whitened_vertices(const std::byte* const r[4],
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

    __attribute__((target(POLYVOL_AVX512), always_inline)) inline explicit Fingerprint512(const Keys& key)
        : k0(key512(key.aes[0])), k1(key512(key.aes[1])), k2(key512(key.aes[2])), k3(key512(key.aes[3])),
          even_lo(_mm512_setzero_si512()), even_hi(even_lo), odd_lo(even_lo), odd_hi(even_lo) {}

    // Four triangles (r: their first coordinates; see whitened_vertices for words).
    __attribute__((target(POLYVOL_AVX512), always_inline)) inline void add4(const std::byte* const r[4],
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

    __attribute__((target(POLYVOL_AVX512), always_inline)) inline void finish(uint64_t fp[kFpLanes]) const {
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

// Σ of each of eight vectors, in lane_sum8's order: {lane_sum8(v[0]), ..., lane_sum8(v[7])}.
__attribute__((target(POLYVOL_AVX512), always_inline)) inline __m512d lane_sums8(const __m512d v[8]) {
    // [a0+a1, b0+b1, a2+a3, b2+b3, a4+a5, b4+b5, a6+a7, b6+b7] for the pairs (a, b).
    __m512d t[4];
    for (int j = 0; j < 4; ++j)
        t[j] = _mm512_add_pd(_mm512_unpacklo_pd(v[2 * j], v[2 * j + 1]), _mm512_unpackhi_pd(v[2 * j], v[2 * j + 1]));
    // [a0..3, b0..3, a4..7, b4..7, c0..3, d0..3, c4..7, d4..7] for the quadruples (a, b, c, d).
    __m512d u[2];
    for (int j = 0; j < 2; ++j)
        u[j] = _mm512_add_pd(_mm512_shuffle_f64x2(t[2 * j], t[2 * j + 1], 0x88),
                             _mm512_shuffle_f64x2(t[2 * j], t[2 * j + 1], 0xDD));
    return _mm512_add_pd(_mm512_shuffle_f64x2(u[0], u[1], 0x88), _mm512_shuffle_f64x2(u[0], u[1], 0xDD));
}

// Floats 4 (imm >> 4) .. + 3 of a's low half and b's low half, widened.
template <int imm>
__attribute__((target(POLYVOL_AVX512), always_inline)) inline __m512d column(__m512 a, __m512 b) {
    return _mm512_cvtps_pd(_mm256_permute2f128_ps(_mm512_castps512_ps256(a), _mm512_castps512_ps256(b), imm));
}

// The nine floats at r in words 0..8, the rest zero: a 256-bit load and
// the ninth float broadcast from memory into word 8 (a load with a blend;
// from a register the broadcast takes the shuffle unit, which the
// transposes below keep busy: 5% of the block's time). (A masked 512-bit load, 0x1FF,
// reads the same words but was 3-4x slower for the whole block on AMD
// Zen 4 when nothing else touched the records' cache lines first.)
__attribute__((target(POLYVOL_AVX512), always_inline)) inline __m512 triangle_row(const std::byte* r) {
    const __m512 x = _mm512_zextps256_ps512(_mm256_loadu_ps(reinterpret_cast<const float*>(r)));
    float ninth;
    std::memcpy(&ninth, r + 32, 4);  // any alignment
    return _mm512_mask_broadcastss_ps(x, 0x100, _mm_set_ss(ninth));
}

// two_sum(a, b) on eight lanes.
__attribute__((target(POLYVOL_AVX512), always_inline)) inline void two_sum8(__m512d a, __m512d b, __m512d& s,
                                                                              __m512d& e) {
    s = _mm512_add_pd(a, b);
    const __m512d bb = _mm512_sub_pd(s, a);
    e = _mm512_add_pd(_mm512_sub_pd(a, _mm512_sub_pd(s, bb)), _mm512_sub_pd(b, bb));
}

// sum2_add on eight lanes (the same operations).
__attribute__((target(POLYVOL_AVX512), always_inline)) inline void sum2_add8(__m512d& S, __m512d& E, __m512d h,
                                                                               __m512d l) {
    __m512d ns, ne;
    two_sum8(S, h, ns, ne);
    S = ns;
    E = _mm512_add_pd(E, _mm512_add_pd(ne, l));
}

// Pass 1 for one block of a group (see pass1_portable and pass1_avx512). The
// arithmetic is pass1_arith's, operation for operation and lane for lane
// (the same bits): the block in four sets of eight triangles, each set's
// coordinates in nine registers (lane j of set g is triangle 8 g + j, which
// is lane j of the block's Sum2 lanes S, E), nothing stored in between; the
// fingerprint goes on in fpr. Returns the largest |coordinate| bit pattern;
// kMA: the moments and area into out. kFp, kMA: as pass1_portable.
template <bool kFull, bool kFp, bool kMA>  // kFull: n == kB
__attribute__((target(POLYVOL_AVX512), always_inline)) inline uint32_t pass1_avx512_body(
    const std::byte* base, std::size_t stride, int n, Fingerprint512& fpr, __m512d& S, __m512d& E, Pass1Block& out) {
    const __m512d neg = _mm512_set1_pd(-0.0);
    const __m512i col8_index = _mm512_setr_epi32(8, 9, 10, 11, 24, 25, 26, 27, 8, 9, 10, 11, 24, 25, 26, 27);
    __m512 mx = _mm512_setzero_ps();
    __m512d M0 = _mm512_setzero_pd(), M1 = M0, M2 = M0, AD = M0, X = M0, T = M0;
    for (int g = 0; g < kB / 8; ++g) {
        const int i0 = 8 * g;
        // Rows: the nine floats of triangle i0 + j in words 0..8 (zero past n).
        __m512 row[8];
        if (kFull) {
            const std::byte* const r0 = base + static_cast<std::size_t>(i0) * stride;
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
                row[j] = i0 + j < n ? triangle_row(base + static_cast<std::size_t>(i0 + j) * stride)
                                    : _mm512_setzero_ps();
            // Triangles past n: all three corners the point 0 (degenerate: adds 0).
            for (int q = i0; q < std::min(n, i0 + 8) && kFp; q += 4) {
                const std::byte* r[4];
                for (int h = 0; h < 4; ++h) r[h] = base + static_cast<std::size_t>(std::min(q + h, n - 1)) * stride;
                fpr.add4(r, static_cast<__mmask16>(n - q >= 4 ? 0x7777u : 0x7777u & ((1u << (4 * (n - q))) - 1)));
            }
        }
        // The largest |coordinate| (range 0xB: the operand of larger magnitude, its
        // sign cleared; with a NaN operand the result differs between CPUs: NaN
        // is detected below).
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
        const __m512d ax = column<0x20>(u0, u4), ay = column<0x20>(u1, u5), az = column<0x20>(u2, u6);
        const __m512d bx = column<0x20>(u3, u7), by = column<0x31>(u0, u4), bz = column<0x31>(u1, u5);
        const __m512d cx = column<0x31>(u2, u6), cy = column<0x31>(u3, u7);
        const __m512d cz = _mm512_cvtps_pd(_mm512_castps512_ps256(_mm512_permutex2var_ps(u0, col8_index, u4)));
        // Volume: b × c from exact products, then a · (b × c) in double-double.
        __m512d n0, e0, n1, e1, n2, e2;
        two_sum8(_mm512_mul_pd(by, cz), _mm512_xor_pd(_mm512_mul_pd(bz, cy), neg), n0, e0);
        two_sum8(_mm512_mul_pd(bz, cx), _mm512_xor_pd(_mm512_mul_pd(bx, cz), neg), n1, e1);
        two_sum8(_mm512_mul_pd(bx, cy), _mm512_xor_pd(_mm512_mul_pd(by, cx), neg), n2, e2);
        const __m512d P0 = _mm512_mul_pd(ax, n0), Q0 = _mm512_fmsub_pd(ax, n0, P0);
        const __m512d P1 = _mm512_mul_pd(ay, n1), Q1 = _mm512_fmsub_pd(ay, n1, P1);
        const __m512d P2 = _mm512_mul_pd(az, n2), Q2 = _mm512_fmsub_pd(az, n2, P2);
        __m512d h1, g1, h, g2;
        two_sum8(P0, P1, h1, g1);
        two_sum8(h1, P2, h, g2);
        const __m512d l = _mm512_add_pd(
            _mm512_add_pd(_mm512_add_pd(g1, g2), _mm512_add_pd(_mm512_add_pd(Q0, Q1), Q2)),
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(ax, e0), _mm512_mul_pd(ay, e1)), _mm512_mul_pd(az, e2)));
        // Into the lanes: Sum2 for the volume.
        if (g == 0) {
            S = h, E = l;
        } else {
            sum2_add8(S, E, h, l);
        }
        if constexpr (kMA) {
            // First moments.
            const __m512d d = _mm512_add_pd(h, l);
            const __m512d ad = _mm512_abs_pd(d);
            const __m512d m0 = _mm512_mul_pd(d, _mm512_add_pd(_mm512_add_pd(ax, bx), cx));
            const __m512d m1 = _mm512_mul_pd(d, _mm512_add_pd(_mm512_add_pd(ay, by), cy));
            const __m512d m2 = _mm512_mul_pd(d, _mm512_add_pd(_mm512_add_pd(az, bz), cz));
            // Area.
            const __m512d ux = _mm512_sub_pd(bx, ax), uy = _mm512_sub_pd(by, ay), uz = _mm512_sub_pd(bz, az);
            const __m512d wx = _mm512_sub_pd(cx, ax), wy = _mm512_sub_pd(cy, ay), wz = _mm512_sub_pd(cz, az);
            const __m512d p0 = _mm512_mul_pd(uy, wz), q0 = _mm512_mul_pd(uz, wy);
            const __m512d p1 = _mm512_mul_pd(uz, wx), q1 = _mm512_mul_pd(ux, wz);
            const __m512d p2 = _mm512_mul_pd(ux, wy), q2 = _mm512_mul_pd(uy, wx);
            const __m512d f0 = _mm512_sub_pd(p0, q0), f1 = _mm512_sub_pd(p1, q1), f2 = _mm512_sub_pd(p2, q2);
            const __m512d t = _mm512_sqrt_pd(
                _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(f0, f0), _mm512_mul_pd(f1, f1)), _mm512_mul_pd(f2, f2)));
            const __m512d x = _mm512_add_pd(_mm512_add_pd(_mm512_add_pd(_mm512_abs_pd(p0), _mm512_abs_pd(q0)),
                                                          _mm512_add_pd(_mm512_abs_pd(p1), _mm512_abs_pd(q1))),
                                            _mm512_add_pd(_mm512_abs_pd(p2), _mm512_abs_pd(q2)));
            // Plain sums.
            if (g == 0) {
                M0 = m0, M1 = m1, M2 = m2, AD = ad, X = x, T = t;
            } else {
                M0 = _mm512_add_pd(M0, m0), M1 = _mm512_add_pd(M1, m1), M2 = _mm512_add_pd(M2, m2);
                AD = _mm512_add_pd(AD, ad), X = _mm512_add_pd(X, x), T = _mm512_add_pd(T, t);
            }
        }
    }
    // Magnitudes' bit patterns order as the magnitudes (inf above all finite ones).
    const uint32_t m = _mm512_reduce_max_epu32(_mm512_castps_si512(mx));
    if (m >= 0x7F800000u) return m;
    if constexpr (kMA) {
        alignas(64) double sums[8];
        const __m512d lanes[8] = {M0, M1, M2, AD, X, T, T, T};
        _mm512_store_pd(sums, lane_sums8(lanes));
        // A NaN coordinate makes one of the differences b - a, c - a NaN; each
        // of the six is a factor of a product in X, so Σ X is then NaN (and it is
        // finite when the coordinates are).
        if (std::isnan(sums[4])) return 0x7FC00000u;
        for (int k = 0; k < 3; ++k) out.mom[k] = sums[k];
        out.abs_d = sums[3];
        out.cross = sums[4];
        out.area2 = sums[5];
    }
    return m;
}

// Pass 1 for a group of up to kGroupBlocks blocks (n triangles) with
// AVX-512: the volume's lanes and the fingerprint's sums run on across the
// blocks (the error analysis at the top), so the lanes are combined and the
// fingerprint reduced once a group.
template <bool kFp, bool kMA>
__attribute__((target(POLYVOL_AVX512))) bool pass1_avx512(const std::byte* base, std::size_t stride, int n,
                                                            const Keys& key, Pass1Group& g) {
    Fingerprint512 fpr(key);
    __m512d GS = _mm512_setzero_pd(), GE = GS;
    for (int b = 0; b * kB < n; ++b) {
        const int nb = std::min(kB, n - b * kB);
        const std::byte* const bb = base + static_cast<std::size_t>(b * kB) * stride;
        prefetch_ahead(bb, kB * stride);
        __m512d S, E;
        const uint32_t m = nb == kB ? pass1_avx512_body<true, kFp, kMA>(bb, stride, nb, fpr, S, E, g.block[b])
                                    : pass1_avx512_body<false, kFp, kMA>(bb, stride, nb, fpr, S, E, g.block[b]);
        if (m >= 0x7F800000u) return false;
        g.mx[b] = m;
        if (b == 0) {
            GS = S, GE = E;
        } else {
            sum2_add8(GS, GE, S, E);
        }
    }
    alignas(64) double s[kSumLanes], e[kSumLanes];
    _mm512_store_pd(s, GS);
    _mm512_store_pd(e, GE);
    double vs, ve;
    combine_lanes(s, e, vs, ve);
    // Without the area: every coordinate is a factor of a product in h (a
    // NaN one makes vs NaN), and finite coordinates keep vs and ve finite.
    if (!kMA && std::isnan(vs + ve)) return false;
    g.vs = vs;
    g.ve = ve;
    if constexpr (kFp) {
        fpr.finish(g.fp);
    } else {
        for (int l = 0; l < kFpLanes; ++l) g.fp[l] = 0;
    }
    return true;
}

#undef POLYVOL_AVX512
#pragma GCC diagnostic pop
#endif

// ---- per-thread sums ------------------------------------------------------------

struct Partial {
    ExactSum vol, vol_mag;        // 6 V: the current pass's sum and magnitudes
    ExactSum mom[3], mom_mag;     // pass 1: 24 ∫x_i and the bound's magnitudes
    ExactSum area2, cross;        // pass 1: 2 A and Σ X
    uint64_t fp[kFpLanes] = {};   // mod p
    uint64_t triangles = 0;
    bool nonfinite = false;

    void merge(const Partial& o) {
        vol.merge(o.vol);
        vol_mag.merge(o.vol_mag);
        for (int k = 0; k < 3; ++k) mom[k].merge(o.mom[k]);
        mom_mag.merge(o.mom_mag);
        area2.merge(o.area2);
        cross.merge(o.cross);
        for (int l = 0; l < kFpLanes; ++l) {
            fp[l] += o.fp[l];
            if (fp[l] >= kP) fp[l] -= kP;
        }
        triangles += o.triangles;
        nonfinite = nonfinite || o.nonfinite;
    }
};

// Pass 1 for one block below AVX-512: the largest |coordinate| bit pattern
// (>= 0x7F800000: NaN or infinity, and then nothing else is set).
template <bool kFp, bool kMA>
uint32_t pass1_block(const std::byte* base, std::size_t stride, int n, const Keys& keys, Pass1Block& r,
                     uint64_t fp[kFpLanes]) {
#if POLYVOL_SOUP_X86
    if (isa_level() == 1) {
        const uint32_t mx = arith_avx2<kMA>(base, stride, n, r);
        if (kFp && mx < 0x7F800000u) fingerprint_aesni(base, stride, n, keys, fp);
        return mx;
    }
#endif
    return pass1_portable<kFp, kMA>(base, stride, n, keys, r, fp);
}

// Pass 1 for a group (n <= kGroupBlocks kB triangles) at the best
// instruction-set level; false when a coordinate is NaN or infinite (then
// nothing else is set). Below AVX-512 block by block, the blocks' Sum2
// lanes then combined as pass1_avx512 combines them (the same operations,
// so the same bits; the error analysis at the top).
template <bool kFp, bool kMA>
bool pass1_group(const std::byte* base, std::size_t stride, int n, const Keys& keys, Pass1Group& g) {
#if POLYVOL_SOUP_X86
    if (isa_level() == 2) return pass1_avx512<kFp, kMA>(base, stride, n, keys, g);
#endif
    for (int l = 0; l < kFpLanes; ++l) g.fp[l] = 0;
    V8 GS = {}, GE = {};  // set by the first block (n >= 1)
    for (int b = 0; b * kB < n; ++b) {
        uint64_t fp[kFpLanes] = {};
        Pass1Block& r = g.block[b];
        const std::byte* const bb = base + static_cast<std::size_t>(b * kB) * stride;
        prefetch_ahead(bb, kB * stride);
        g.mx[b] = pass1_block<kFp, kMA>(bb, stride, std::min(kB, n - b * kB), keys, r, fp);
        if (g.mx[b] >= 0x7F800000u) return false;
        V8 S, E;
        load8(S, r.s);
        load8(E, r.e);
        if (b == 0) {
            GS = S, GE = E;
        } else {
            sum2_add(GS, GE, S, E);
        }
        for (int l = 0; l < kFpLanes; ++l) g.fp[l] = (g.fp[l] + fp[l]) % kP;
    }
    alignas(64) double s[kSumLanes], e[kSumLanes];
    std::memcpy(s, &GS, sizeof s);
    std::memcpy(e, &GE, sizeof e);
    combine_lanes(s, e, g.vs, g.ve);
    return true;
}

using Pass1Fn = bool (*)(const std::byte*, std::size_t, int, const Keys&, Pass1Group&);

Pass1Fn pass1_for(SoupWants w) {
    if (w.closedness) return w.moments_and_area ? pass1_group<true, true> : pass1_group<true, false>;
    return w.moments_and_area ? pass1_group<false, true> : pass1_group<false, false>;
}

double up(double x) { return std::nextafter(x, kInf); }

}  // namespace


namespace {
std::atomic<measure::SoupPass1Sums*> g_pass1_record{nullptr};  // record_soup_pass1
}  // namespace

void measure::record_soup_pass1(SoupPass1Sums* out) { g_pass1_record.store(out, std::memory_order_relaxed); }

struct SoupAccumulator::State {
    Keys keys{};
    SoupWants wants;
    Pass1Fn pass1;
    int pass = 1;
    bool done = false;
    tbb::enumerable_thread_specific<Partial> tls;
    uint64_t pass1_triangles = 0;
    SoupResult result;

    State(uint64_t seed, SoupWants w) : wants(w), pass1(pass1_for(w)) {
        uint64_t s = seed;
        for (auto& k : keys.aes)
            for (auto& x : k) x = measure::fingerprint::splitmix(s);
        for (auto& k : keys.mix)
            for (auto& x : k) x = measure::fingerprint::splitmix(s) | 1;
    }

    // Pass 1 over a group: triangles [first, first + n) of t, n <= kGroupBlocks
    // kB, relative index (first is a multiple of kB in the whole input).
    void group(const Float32Triangles& t, std::size_t first, int n, Partial& p) const {
        p.triangles += static_cast<uint64_t>(n);
        Pass1Group g;
        if (!pass1(t.data + first * t.stride + t.offset, t.stride, n, keys, g)) {
            p.nonfinite = true;  // NaN or infinity: nothing else is meaningful
            return;
        }
        for (int l = 0; l < kFpLanes; ++l) {
            p.fp[l] += g.fp[l];
            if (p.fp[l] >= kP) p.fp[l] -= kP;
        }
        p.vol.add(g.vs);
        p.vol.add(g.ve);
        double magnitude = 0;
        for (int b = 0; b * kB < n; ++b) {
            const double M = static_cast<double>(std::bit_cast<float>(g.mx[b]));
            const double nb = static_cast<double>(std::min(kB, n - b * kB));
            magnitude += 6 * (M * M * M) * nb;
            if (!wants.moments_and_area) continue;
            const Pass1Block& r = g.block[b];
            for (int k = 0; k < 3; ++k) p.mom[k].add(r.mom[k]);
            p.mom_mag.add(3 * M * r.abs_d + 0x1p-43 * ((M * M) * (M * M)) * nb);
            p.area2.add(r.area2);
            p.cross.add(r.cross);
        }
        p.vol_mag.add(magnitude);
    }

    // Passes 2 and 3 over one block: triangles [first, first + n) of t, n <= kB.
    void block(const Float32Triangles& t, std::size_t first, int n, Partial& p) const {
        const std::byte* base = t.data + first * t.stride + t.offset;
        cone::TriangleBlock b;
        for (int i = 0; i < n; ++i) {
            float f[9];
            std::memcpy(f, base + static_cast<std::size_t>(i) * t.stride, 36);
            for (int k = 0; k < 9; ++k) b.c[k][i] = static_cast<double>(f[k]);
        }
        for (int k = 0; k < 9; ++k)
            for (int i = n; i < kB; ++i) b.c[k][i] = 0;
        b.n = n;
        p.triangles += static_cast<uint64_t>(n);
        if (pass == 2) {
            cone::filtered_volume_block(b, p.vol, p.vol_mag);
        } else {
            cone::exact_block_sums(b, 1u << cone::kV, &p.vol);
        }
    }

    void range(const Float32Triangles& t, std::size_t begin, std::size_t end) {
        Partial& p = tls.local();
        const std::size_t step = pass == 1 ? kGroupBlocks * kB : kB;
        for (std::size_t i = begin; i < end; i += step) {
            const int n = static_cast<int>(std::min(step, end - i));
            if (pass == 1) group(t, i, n, p);
            else block(t, i, n, p);
        }
    }
};

SoupAccumulator::SoupAccumulator(SoupWants wants) {
    std::random_device rd;
    uint64_t seed = 0;
    for (int i = 0; i < 4; ++i) seed = (seed << 16) ^ (static_cast<uint64_t>(rd()) * 0x9E3779B97F4A7C15ull) ^ (seed >> 7);
    // More entropy than one 64-bit seed for the keys themselves.
    s_ = std::make_unique<State>(seed, wants);
    for (auto& k : s_->keys.aes)
        for (auto& x : k) x ^= measure::fingerprint::random_word(rd);
    for (auto& k : s_->keys.mix)
        for (auto& x : k) x ^= measure::fingerprint::random_word(rd);
}

SoupAccumulator::SoupAccumulator(uint64_t seed, SoupWants wants) : s_(std::make_unique<State>(seed, wants)) {}

SoupAccumulator::~SoupAccumulator() = default;

int SoupAccumulator::pass() const { return s_->pass; }

void SoupAccumulator::add(const Float32Triangles& t, uint64_t first_triangle) {
    if (first_triangle % kB != 0)
        throw std::invalid_argument("SoupAccumulator::add: first_triangle " + std::to_string(first_triangle) +
                                    " is not a multiple of " + std::to_string(kB));
    if (t.count > 0 && (t.data == nullptr || t.stride < 36))
        throw std::invalid_argument("SoupAccumulator::add: no data, or a stride below 36 bytes");
    if (s_->done) throw std::logic_error("SoupAccumulator::add after the last pass");
    const std::size_t n = t.count;
    if (n <= kChunk) {
        s_->range(t, 0, n);
        return;
    }
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t c = r.begin(); c < r.end(); ++c) s_->range(t, c * kChunk, std::min(n, (c + 1) * kChunk));
        },
        tbb::simple_partitioner());
}

bool SoupAccumulator::next_pass() {
    State& s = *s_;
    if (s.done) return false;
    Partial all;
    for (const Partial& p : s.tls) all.merge(p);
    s.tls.clear();
    SoupResult& r = s.result;
    if (s.pass == 1) {
        if (measure::SoupPass1Sums* rec = g_pass1_record.load(std::memory_order_relaxed))
            *rec = {all.vol, all.vol_mag, {all.mom[0], all.mom[1], all.mom[2]}, all.mom_mag, all.area2, all.cross};
        s.pass1_triangles = all.triangles;
        r.computed = s.wants;
        r.triangles = all.triangles;
        r.nonfinite = all.nonfinite;
        r.fingerprint = {all.fp[0], all.fp[1], all.fp[2], all.fp[3]};
        r.closed = s.wants.closedness && !all.nonfinite && all.fp[0] == 0 && all.fp[1] == 0 && all.fp[2] == 0 &&
                   all.fp[3] == 0;
        if (all.nonfinite || !s.wants.moments_and_area) {  // NaN unless computed below
            r.area = kNaN;
            r.first_moments = r.centroid = {kNaN, kNaN, kNaN};
            r.first_moments_error_bound = r.centroid_error_bound = r.area_relative_error = kNaN;
        }
        if (all.nonfinite) {
            r.volume = kNaN;
            r.passes = 1;
            s.done = true;
            return false;
        }
        if (s.wants.moments_and_area) {
            // Area.
            const double a2 = all.area2.round();
            const double cross = all.cross.round();
            r.area = a2 / 2;
            r.area_relative_error =
                a2 > 0 ? up(up(up(up(15 * kU * a2) + up(5 * kU * cross)) / a2) + kU) : (cross > 0 ? kInf : 0.0);
            // First moments (the centroid needs the volume: below).
            const double mom_bound = up(up(16 * kU * up(all.mom_mag.round() * (1 + 0x1p-10))) / 24);
            double emax = 0;
            for (int k = 0; k < 3; ++k) {
                r.first_moments[k] = all.mom[k].round_div(24);
                emax = std::max(emax, up(mom_bound + up(kU * std::fabs(r.first_moments[k]))));
            }
            r.first_moments_error_bound = emax;
        }
        const double bound = up(512 * kU * kU * up(all.vol_mag.round() * (1 + 0x1p-10)));
        if (const auto v = exact::decided_round_div(all.vol, bound, 6)) {
            r.volume = *v;
        } else {
            s.pass = 2;
            return true;
        }
    } else {
        if (all.triangles != s.pass1_triangles)
            throw std::logic_error("SoupAccumulator: pass " + std::to_string(s.pass) + " saw " +
                                   std::to_string(all.triangles) + " triangles, pass 1 saw " +
                                   std::to_string(s.pass1_triangles));
        const double bound =
            s.pass == 2 ? cone::filtered_bound(cone::kV, cone::Precision::double_double, all.vol_mag.round()) : 0.0;
        if (const auto v = exact::decided_round_div(all.vol, bound, 6)) {
            r.volume = *v;
        } else {
            s.pass = 3;  // only from pass 2: the exact sum always decides
            return true;
        }
    }
    r.volume_correctly_rounded = true;
    r.passes = s.pass;
    if (!s.wants.moments_and_area) {
        s.done = true;
        return false;
    }
    // Centroid c_i = F_i / V with F_i ± E (first moments) and V correctly
    // rounded (|V - V*| <= u |V|): |c - c*| <= (E + 1.01 u (|F| + E)) / |V| + u |c|.
    const double V = r.volume;
    double cmax = 0;
    for (int k = 0; k < 3; ++k) {
        if (V == 0) {
            r.centroid[k] = kNaN;
            continue;
        }
        const double F = r.first_moments[k], E = r.first_moments_error_bound;
        r.centroid[k] = F / V;
        const double num = up(E + up(1.01 * kU * up(std::fabs(F) + E)));
        cmax = std::max(cmax, up(up(num / std::fabs(V)) + up(kU * std::fabs(r.centroid[k]))));
    }
    r.centroid_error_bound = V == 0 ? kInf : cmax;
    s.done = true;
    return false;
}

const SoupResult& SoupAccumulator::result() const {
    if (!s_->done) throw std::logic_error("SoupAccumulator::result before the last pass ended");
    return s_->result;
}

namespace {
SoupResult run_all(SoupAccumulator& acc, const Float32Triangles& t) {
    do {
        acc.add(t, 0);
    } while (acc.next_pass());
    return acc.result();
}
}  // namespace

SoupResult soup_properties(const Float32Triangles& t, SoupWants wants) {
    SoupAccumulator acc(wants);
    return run_all(acc, t);
}

SoupResult soup_properties(const Float32Triangles& t, uint64_t seed, SoupWants wants) {
    SoupAccumulator acc(seed, wants);
    return run_all(acc, t);
}

double soup_volume(const Float32Triangles& t) {
    // No keys are needed without the fingerprint: a fixed seed spares
    // std::random_device.
    SoupAccumulator acc(0, SoupWants{.closedness = false, .moments_and_area = false});
    return run_all(acc, t).volume;
}

}  // namespace polyvol
