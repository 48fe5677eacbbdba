// measure/cone.cpp — the cone rule's ten sums (see cone.hpp), filtered,
// exact and big-integer.
//
// What is guaranteed, and why (u = 2^-53, safe coordinate range, see cone.hpp).
// All of it assumes the default floating-point environment: round to
// nearest, no flush-to-zero or denormals-are-zero (which e.g. -ffast-math's
// crtfastmath sets at start-up).
//
// Filtered, double-double. Per fan triangle (a, b, c):
//   u = b - a, w = c - a are split exactly (two_sum) into uh + ul, wh + wl;
//   det = a · (uh × wh) + a · (uh × wl + ul × wh + ul × wl)   (exact identity)
//   The first product is formed with two_prod/two_sum (cross product as an
//   unnormalised double-double, dot product with exact products of its high
//   parts), the second (of relative size 2u) in plain double. With
//     Perm = Σ_i |a_i| (|uh_j wh_k| + |uh_k wh_j|)   (a permanent, computed),
//   the error of det is below 96 u² Perm (the low-order parts are a sum of
//   eleven terms, g1, g2, Q_0..2, the three a_k nl_k and the three
//   a_k corr_k, of total magnitude <= 7.2 u Perm, summed with relative error
//   < 8u; the cross products' own errors are <= 3.01 u² per unit of Perm).
//   The origin form (VolumeForm::origin, the volume alone) is the same
//   computation with uh = b, wh = c and ul = wl = 0: det = a · (b × c),
//   corr = 0 and Perm = Σ_i |a_i| (|b_j c_k| + |b_k c_j|) <= 6 M^3, M the
//   largest |coordinate| the pass reads (or of any position, when the pass
//   checks every position); every bound below holds as it stands with Σ magnitude =
//   6 M^3 n (n triangles), which is what the origin form uses instead of
//   Σ Perm. It skips the six two_sums, the corr terms and the per-triangle
//   magnitudes (about 40% of the operations), but its bound grows with M^3
//   instead of |a| |b - a| |c - a|: it decides only for meshes not far from
//   the origin compared with their size (likely_volume_form guesses which).
//   s_i = a_i + b_i + c_i is formed as a double-double with error
//   <= 2.02 u² σ_i, σ_i = |a_i| + |b_i| + |c_i|; q_ij = a_i a_j + b_i b_j +
//   c_i c_j + s_i s_j with error <= 65 u² Mq_ij, Mq_ij = |a_i a_j| + |b_i b_j|
//   + |c_i c_j| + σ_i σ_j (seven low-order terms of total <= 9.1 u Mq summed
//   in double, plus the errors of s); the products det·s_i and det·q_ij
//   (two_prod of the high parts, cross terms in double) then have errors
//   <= 128 u² Perm σ_i and <= 176 u² Perm Mq_ij.
//   Terms are summed per block of 32 by Ogita–Rump–Oishi Sum2 (the high
//   parts by two_sum, the errors and low parts in plain double) in lanes of
//   B terms, with error <= 2B (1.01 B + 3.1) u² Σ|term| (the lanes' error
//   terms: <= (1.01 B + 3.1) u Σ|term|, each rounded in <= 2B additions).
//   * The volume alone in double-double (volume_block, the common call)
//     sums each triangle's (h, lo) as formed, h + lo = the approximation of
//     det above (96 u² Perm), not normalised: |h| <= 1.01 Perm and |lo| <=
//     7.21 u Perm. 8 lanes of 4 (lane j: triangles j, j + 8, j + 16, j + 24):
//     the h by two_sum (exact), their errors ne (Σ|ne| <= 3 · 1.01 u Σ|h|
//     <= 3.07 u Σ Perm) and the lo (<= 7.21 u Σ Perm) added in double, each
//     in at most 6 additions: <= γ6 · 10.3 u Σ Perm <= 61.9 u² Σ Perm, and
//     the lanes' error terms are <= 10.31 u Σ Perm. Then the lanes into one
//     pair: a two_sum tree 8 -> 4 -> 2 -> 1 (exact) whose seven errors (each
//     level's total <= u Σ|S| <= 1.013 u Σ Perm: <= 3.04 u Σ Perm) are added
//     to the lanes' error terms in double, each value in at most 6
//     additions: <= γ6 · 13.35 u Σ Perm <= 80.3 u² Σ Perm; the block's pair
//     (s_b, e_b) has |s_b| <= 1.02 Σ Perm_b and |e_b| <= 13.4 u Σ Perm_b.
//     Groups of 4 consecutive blocks of a task (the last may be shorter):
//     the s_b by two_sum (exact; three errors t, each <= 1.03 u Σ Perm of
//     the group), the e_b and t added in double, each in at most 6
//     additions: <= γ6 · (13.4 + 3.09) u Σ Perm <= 99.1 u² Σ Perm; the
//     group's pair goes exactly into a superaccumulator. Total <= (96 +
//     61.9 + 80.3 + 99.1) u² < 338 u² Σ magnitude.
//   * Everything else: 4 lanes of 8, <= 179 u² Σ magnitude, each lane's
//     (sum, error) pair exactly into a superaccumulator; totals <= 275,
//     307 and 355 u² Σ magnitude.
//   The bound used is K u² Σ magnitude (1 + 2^-10), K = 512 (volume: a
//   factor 1.51 of safety alone, 1.86 with the moments), 768 (first moments:
//   2.5), 1024 (second moments: 2.88); the factor (1 + 2^-10) covers the
//   rounding of the magnitudes (sums of non-negative doubles: in double
//   within a block and, for the volume alone, within a task's fixed range of
//   blocks; exactly across tasks; n < 2^40 terms).
//   In the safe range no operation underflows or overflows: every value is a
//   multiple of 2^-1060 (products of at most five coordinates, each a multiple
//   of 2^-212) of magnitude below 2^1000, so the relative error model above
//   holds without absolute terms.
//
// Filtered, fast (plain double): det = a · (fl(b-a) × fl(c-a)), s, q, and the
// products in double: errors <= 7.1 u Perm, 10.1 u Perm σ_i, 17.1 u Perm Mq_ij;
// lanes of 8 add <= γ_7 Σ|term|; K = 32, 40, 56 (times u, with the factor 2).
//
// Exact: det as a compressed expansion (det3_exact), s_i and q_ij as
// expansions (Grow-Expansion + Compress), every product of components by
// two_prod into the superaccumulator: exact in the safe range.
//
// Exact, as integers (tried first for each triangle): when each axis's three
// coordinates are k 2^e with |k| < 2^60, the terms are products of 64-bit
// integers in at most 384 bits, added to the superaccumulator at their
// exponent (ExactSum::add_wide). See integer_triangle.
//
// GMP: coordinates as integers times 2^E0 (E0 the lowest set bit of any used
// coordinate), sums in mpz: exact for any finite input.
//
// Range check. The filtered and exact paths need Range::safe (cone.hpp).
// The double-double volume alone checks every position when each vertex
// is read about twice or more (at least two indices per vertex) or below
// AVX-512 (extremes_of: 4 integer operations per 8 coordinates), each task
// of the pass a slice of them beside its faces (RangeCheck::positions);
// with AVX-512, a soup, or positions out of range somewhere, the pass checks
// the coordinates it reads (range_block, or the same steps on the rows in
// registers), so vertices no face uses do not matter; a mesh out of range
// thus costs a pass more than it used to (the positions' pass, then this
// one), and one below AVX-512 a pass before the exact fallback. Everything
// else calls coordinate_range (every position).
//
// Cost (one core of a shared 2-core AMD EPYC with AVX2/FMA, 2M triangles
// far from the origin, where a naive double loop takes 2.2-2.4 ns/triangle):
// filtered volume 8 ns/triangle (+1 for the range check), fast volume 4.3,
// all ten filtered sums 31 (double-double) / 15 (fast), exact volume 55,
// all ten exact 148. Blocks are processed in parallel (TBB). With AVX-512
// (the same machine class, 2 cores, polyvol_bench, a welded 1M-triangle
// sphere, the rows of each block built in registers): the double-double
// volume takes 1.8 ms around (1e6, 1e6, 1e6) (translated form) and 1.2 ms
// around the origin (origin form), about 3.4 and 2.2 ns per triangle per
// core (with the Block in between: 2.1 and 1.4 ms), where a plain double
// loop over the same arrays takes about 2.6.
#include "measure/cone.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "exact/eft.hpp"
#include "exact/expansion.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace polyvol::measure::cone {
namespace {

using exact::ExactSum;
using exact::two_prod_t;
using exact::two_sum;
using exact::two_sum_lanes;

constexpr int kLanes = 4;
constexpr int kPerLane = 8;
constexpr int kBlock = kLanes * kPerLane;  // triangles per block
constexpr double kU = 0x1p-53;

// Fan triangles of a block as structure of arrays (cone.hpp): coordinate k
// of vertex v of triangle i is c[3*v + k][i]; unused slots are zero.
static_assert(kBlock == kBlockTriangles);
using Block = TriangleBlock;

// Per-triangle terms of a block: term k of triangle i is h[k][i] + l[k][i],
// with magnitude m[k][i] (the bound is K u² Σ m, see the top of this file).
template <int N>
struct Terms {
    alignas(64) double h[N][kBlock];
    alignas(64) double l[N][kBlock];
    alignas(64) double m[N][kBlock];
};

// ---- per-triangle kernels (what is summed) -------------------------------

// The ten terms of one triangle in double-double. kTranslate false (volume
// only): the origin form, uh = b, wh = c and ul = wl = 0, so corr = 0 and
// det = a · (b × c), and no magnitude (the caller bounds Perm by 6 M_b^3 per
// triangle; see the top of this file).
template <bool kFma, int N, bool kTranslate = true>
POLYVOL_INLINE void terms_dd(const Block& b, int i, Terms<N>& t) {
    static_assert(kTranslate || N == 1);
    const double a[3] = {b.c[0][i], b.c[1][i], b.c[2][i]};
    const double bb[3] = {b.c[3][i], b.c[4][i], b.c[5][i]};
    const double cc[3] = {b.c[6][i], b.c[7][i], b.c[8][i]};
    double uh[3], ul[3] = {}, wh[3], wl[3] = {};
    #pragma GCC unroll 6
    for (int k = 0; k < 3; ++k) {
        if constexpr (kTranslate) {
            two_sum(bb[k], -a[k], uh[k], ul[k]);
            two_sum(cc[k], -a[k], wh[k], wl[k]);
        } else {
            uh[k] = bb[k];
            wh[k] = cc[k];
        }
    }
    // Cross product uh × wh: component k = uh[j] wh[l] - uh[l] wh[j].
    double ns[3], nl[3], pn[3], corr[3] = {};
    #pragma GCC unroll 6
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, l = (k + 2) % 3;
        double p1, e1, p2, e2, tt;
        two_prod_t<kFma>(uh[j], wh[l], p1, e1);
        two_prod_t<kFma>(uh[l], wh[j], p2, e2);
        two_sum(p1, -p2, ns[k], tt);
        nl[k] = (e1 - e2) + tt;
        pn[k] = std::fabs(p1) + std::fabs(p2);
        if constexpr (kTranslate) {
            corr[k] = ((uh[j] * wl[l] - uh[l] * wl[j]) + (ul[j] * wh[l] - ul[l] * wh[j])) +
                      (ul[j] * wl[l] - ul[l] * wl[j]);
        }
    }
    double P[3], Q[3];
    #pragma GCC unroll 6
    for (int k = 0; k < 3; ++k) two_prod_t<kFma>(a[k], ns[k], P[k], Q[k]);
    double h1, g1, h, g2;
    two_sum(P[0], P[1], h1, g1);
    two_sum(h1, P[2], h, g2);
    double lo = ((g1 + g2) + ((Q[0] + Q[1]) + Q[2])) + ((a[0] * nl[0] + a[1] * nl[1]) + a[2] * nl[2]);
    if constexpr (kTranslate) lo += (a[0] * corr[0] + a[1] * corr[1]) + a[2] * corr[2];
    // The volume alone keeps (h, lo) as it is (Sum2 adds lo to its error
    // terms: see the top of this file); the moments need it normalised.
    double dh = h, dl = lo;
    if constexpr (N > 1) two_sum(h, lo, dh, dl);
    const double perm = (std::fabs(a[0]) * pn[0] + std::fabs(a[1]) * pn[1]) + std::fabs(a[2]) * pn[2];
    t.h[kV][i] = dh;
    t.l[kV][i] = dl;
    if constexpr (kTranslate) t.m[kV][i] = perm;  // the origin form bounds Perm by 6 M^3 instead
    if constexpr (N > 1) {
        const exact::DD d{dh, dl};
        exact::DD s[3];
        double sigma[3];
        #pragma GCC unroll 6
        for (int k = 0; k < 3; ++k) {
            double tt, e, e2;
            two_sum(a[k], bb[k], tt, e);
            two_sum(tt, cc[k], s[k].hi, e2);
            s[k].lo = e + e2;
            sigma[k] = (std::fabs(a[k]) + std::fabs(bb[k])) + std::fabs(cc[k]);
            const exact::DD m = exact::dd_mul<kFma>(d, s[k]);
            t.h[kMx + k][i] = m.hi;
            t.l[kMx + k][i] = m.lo;
            t.m[kMx + k][i] = perm * sigma[k];
        }
        if constexpr (N <= kSxx) return;  // volume and first moments only
        constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
        #pragma GCC unroll 6
        for (int k = 0; k < 6; ++k) {
            const int x = I[k], y = J[k];
            double pa, ea, pb, eb, pc, ec;
            two_prod_t<kFma>(a[x], a[y], pa, ea);
            two_prod_t<kFma>(bb[x], bb[y], pb, eb);
            two_prod_t<kFma>(cc[x], cc[y], pc, ec);
            const exact::DD ss = exact::dd_mul<kFma>(s[x], s[y]);
            double q1, f1, q2, f2, q3, f3;
            two_sum(pa, pb, q1, f1);
            two_sum(q1, pc, q2, f2);
            two_sum(q2, ss.hi, q3, f3);
            const double qlo = ((f1 + f2) + f3) + (((ea + eb) + ec) + ss.lo);
            exact::DD q;
            two_sum(q3, qlo, q.hi, q.lo);
            const double mq = ((std::fabs(pa) + std::fabs(pb)) + std::fabs(pc)) + sigma[x] * sigma[y];
            const exact::DD m = exact::dd_mul<kFma>(d, q);
            t.h[kSxx + k][i] = m.hi;
            t.l[kSxx + k][i] = m.lo;
            t.m[kSxx + k][i] = perm * mq;
        }
    }
}

// The ten terms of one triangle in plain double (Accuracy::fast).
template <int N>
POLYVOL_INLINE void terms_fast(const Block& b, int i, Terms<N>& t) {
    const double a[3] = {b.c[0][i], b.c[1][i], b.c[2][i]};
    const double bb[3] = {b.c[3][i], b.c[4][i], b.c[5][i]};
    const double cc[3] = {b.c[6][i], b.c[7][i], b.c[8][i]};
    const double u[3] = {bb[0] - a[0], bb[1] - a[1], bb[2] - a[2]};
    const double w[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
    double det = 0, perm = 0;
    #pragma GCC unroll 6
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, l = (k + 2) % 3;
        const double p1 = u[j] * w[l], p2 = u[l] * w[j];
        det += a[k] * (p1 - p2);
        perm += std::fabs(a[k]) * (std::fabs(p1) + std::fabs(p2));
    }
    t.h[kV][i] = det;
    t.m[kV][i] = perm;
    if constexpr (N > 1) {
        double s[3], sigma[3];
        #pragma GCC unroll 6
        for (int k = 0; k < 3; ++k) {
            s[k] = (a[k] + bb[k]) + cc[k];
            sigma[k] = (std::fabs(a[k]) + std::fabs(bb[k])) + std::fabs(cc[k]);
            t.h[kMx + k][i] = det * s[k];
            t.m[kMx + k][i] = perm * sigma[k];
        }
        if constexpr (N <= kSxx) return;  // volume and first moments only
        constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
        #pragma GCC unroll 6
        for (int k = 0; k < 6; ++k) {
            const int x = I[k], y = J[k];
            const double pa = a[x] * a[y], pb = bb[x] * bb[y], pc = cc[x] * cc[y];
            const double q = ((pa + pb) + pc) + s[x] * s[y];
            t.h[kSxx + k][i] = det * q;
            t.m[kSxx + k][i] = perm * (((std::fabs(pa) + std::fabs(pb)) + std::fabs(pc)) + sigma[x] * sigma[y]);
        }
    }
}

template <bool kFma, bool kDD, int N, bool kTranslate = true>
POLYVOL_INLINE void block_terms(const Block& b, Terms<N>& t) {
    for (int i = 0; i < kBlock; ++i) {
        if constexpr (kDD) {
            terms_dd<kFma, N, kTranslate>(b, i, t);
        } else {
            terms_fast<N>(b, i, t);
        }
    }
}

// The same loops compiled for AVX2 + FMA (run-time dispatch) and for the
// baseline (two_prod by Dekker's splitting, SSE2).
#if defined(__x86_64__) && defined(__GNUC__)
#define POLYVOL_HAVE_FMA_CLONE 1
// AVX-512 functions: GCC widens their loops to 512 bits only when asked
// (prefer-vector-width=512); clang has no such target feature, and its
// min_vector_width(512) attribute says the same.
#if defined(__clang__)
#define POLYVOL_AVX512_FEATURES(extra) __attribute__((target("avx512f,avx512vl,avx512dq,avx2" extra), min_vector_width(512)))
#else
#define POLYVOL_AVX512_FEATURES(extra) \
    __attribute__((target("avx512f,avx512vl,avx512dq,avx2" extra ",prefer-vector-width=512")))
#endif
__attribute__((target("avx2,fma"))) void block_dd10_fma(const Block& b, Terms<kSumCount>& t) {
    block_terms<true, true, kSumCount>(b, t);
}
__attribute__((target("avx2,fma"))) void block_fast1_fma(const Block& b, Terms<1>& t) { block_terms<true, false, 1>(b, t); }
__attribute__((target("avx2,fma"))) void block_dd4_fma(const Block& b, Terms<kSxx>& t) { block_terms<true, true, kSxx>(b, t); }
__attribute__((target("avx2,fma"))) void block_fast4_fma(const Block& b, Terms<kSxx>& t) { block_terms<true, false, kSxx>(b, t); }
__attribute__((target("avx2,fma"))) void block_fast10_fma(const Block& b, Terms<kSumCount>& t) {
    block_terms<true, false, kSumCount>(b, t);
}
// The double-double kernels once more for AVX-512 (8 triangles per
// instruction). Every operation is elementwise and rounded on its own
// (-ffp-contract=off), so the terms are the same bits on every target.
#define POLYVOL_AVX512 POLYVOL_AVX512_FEATURES(",fma")
POLYVOL_AVX512 void block_dd4_avx512(const Block& b, Terms<kSxx>& t) { block_terms<true, true, kSxx>(b, t); }
POLYVOL_AVX512 void block_dd10_avx512(const Block& b, Terms<kSumCount>& t) { block_terms<true, true, kSumCount>(b, t); }
#undef POLYVOL_AVX512
std::atomic<int> g_level_cap{2};  // cap_kernel_level
bool cpu_has_fma() {
    static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return has && g_level_cap.load(std::memory_order_relaxed) >= 1;
}
bool cpu_has_avx512() {
    static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                            __builtin_cpu_supports("avx512dq");
    return has && cpu_has_fma() && g_level_cap.load(std::memory_order_relaxed) >= 2;
}
#else
#define POLYVOL_HAVE_FMA_CLONE 0
#endif
void block_dd10(const Block& b, Terms<kSumCount>& t) { block_terms<false, true, kSumCount>(b, t); }
void block_fast1(const Block& b, Terms<1>& t) { block_terms<false, false, 1>(b, t); }
void block_fast10(const Block& b, Terms<kSumCount>& t) { block_terms<false, false, kSumCount>(b, t); }
void block_dd4(const Block& b, Terms<kSxx>& t) { block_terms<false, true, kSxx>(b, t); }
void block_fast4(const Block& b, Terms<kSxx>& t) { block_terms<false, false, kSxx>(b, t); }

// N == 1: the plain double volume only (the double-double volume alone has
// its own pass, volume_pass below).
template <int N>
void compute_terms(const Block& b, Terms<N>& t, bool dd) {
#if POLYVOL_HAVE_FMA_CLONE
    if constexpr (N > 1) {
        if (dd && cpu_has_avx512()) {
            if constexpr (N == kSxx) {
                block_dd4_avx512(b, t);
            } else {
                block_dd10_avx512(b, t);
            }
            return;
        }
    }
    if (cpu_has_fma()) {
        if constexpr (N == 1) {
            block_fast1_fma(b, t);
        } else if constexpr (N == kSxx) {
            dd ? block_dd4_fma(b, t) : block_fast4_fma(b, t);
        } else {
            dd ? block_dd10_fma(b, t) : block_fast10_fma(b, t);
        }
        return;
    }
#endif
    if constexpr (N == 1) {
        block_fast1(b, t);
    } else if constexpr (N == kSxx) {
        dd ? block_dd4(b, t) : block_fast4(b, t);
    } else {
        dd ? block_dd10(b, t) : block_fast10(b, t);
    }
}

// ---- how it is summed ----------------------------------------------------

// Per task: the exact sums of the blocks' results, and of their magnitudes
// (also exact, so that bounds do not depend on how the work was split).
template <int N>
struct Accumulator {
    ExactSum sum[N];
    ExactSum magnitude[N];
    std::size_t triangles = 0;
    void merge(const Accumulator& o) {
        for (int k = 0; k < N; ++k) {
            sum[k].merge(o.sum[k]);
            magnitude[k].merge(o.magnitude[k]);
        }
        triangles += o.triangles;
    }
};

// Sum2 in 4 lanes of 8, then each lane's (sum, error) into the superaccumulator.
template <int N>
void accumulate_into(const Terms<N>& t, bool dd, ExactSum* sum, ExactSum* magnitude) {
    for (int k = 0; k < N; ++k) {
        double s[kLanes] = {}, e[kLanes] = {}, m[kLanes] = {};
        if (dd) {
            for (int r = 0; r < kPerLane; ++r) {
                for (int j = 0; j < kLanes; ++j) {
                    const int i = r * kLanes + j;
                    double ns, ne;
                    two_sum(s[j], t.h[k][i], ns, ne);
                    s[j] = ns;
                    e[j] += ne + t.l[k][i];
                    m[j] += t.m[k][i];
                }
            }
        } else {
            for (int r = 0; r < kPerLane; ++r) {
                for (int j = 0; j < kLanes; ++j) {
                    const int i = r * kLanes + j;
                    s[j] += t.h[k][i];
                    m[j] += t.m[k][i];
                }
            }
        }
        for (int j = 0; j < kLanes; ++j) {
            sum[k].add(s[j]);
            if (dd) sum[k].add(e[j]);
        }
        magnitude[k].add((m[0] + m[1]) + (m[2] + m[3]));
    }
}

template <int N>
void accumulate(const Terms<N>& t, bool dd, Accumulator<N>& acc) {
    accumulate_into<N>(t, dd, acc.sum, acc.magnitude);
}

// ---- walking the fan triangles --------------------------------------------

// Calls fn(block) for blocks of up to kBlock fan triangles of faces
// [f0, f1) (all-triangle meshes: triangles [f0, f1)).
#if POLYVOL_HAVE_FMA_CLONE
// Whether every index of a block (t: its 96 indices) is below nv - 1, so
// that a 256-bit load at each vertex (one double past it) stays inside the
// nv vertices' positions.
__attribute__((target("avx2"))) inline bool block_loads_within(std::size_t nv, const uint32_t* t) {
    if (nv == 0) return false;
    if (nv - 1 > std::numeric_limits<uint32_t>::max()) return true;  // every index is below nv - 1
    // Some index >= nv - 1: max(index, nv - 1) == index (unsigned).
    const __m256i last = _mm256_set1_epi32(static_cast<int>(static_cast<uint32_t>(nv - 1)));
    __m256i far = _mm256_setzero_si256();
    for (int j = 0; j < 3 * kBlock; j += 8) {
        const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(t + j));
        far = _mm256_or_si256(far, _mm256_cmpeq_epi32(_mm256_max_epu32(x, last), x));
    }
    return _mm256_testz_si256(far, far);
}

// A whole block of an all-triangle mesh (t: its 96 indices, pos: the
// positions of nv vertices) with AVX2: per 4 triangles and vertex, each
// vertex's (x, y, z, next) by one 256-bit load, then a 4 x 4 transpose
// (two unpacks and three lane permutations) gives 4 slots of the rows of x,
// y and z: 4 loads and 3 stores where the scalar gather has 12 and 12. The
// load reads one double past the vertex, so a block that uses the last
// vertex (or an index out of range) is left to the caller (false).
// Measured on AMD Zen 5 against other ways: as fast as 512-bit registers
// (vertex i and i + 4 in one register, permutations across 512 bits) when
// the rows still go through the Block; hardware gathers, and masked loads
// of exactly three doubles, are much slower than this. With AVX-512 the
// volume pass builds the rows in registers instead and never stores them
// (volume_block_in_registers); this one serves the volume pass on AVX2
// and, from AVX2 up, the other passes over blocks (reduce_blocks).
__attribute__((target("avx2"))) inline bool gather_block_avx2(const double* pos, std::size_t nv, const uint32_t* t,
                                                                Block& b) {
    if (!block_loads_within(nv, t)) return false;
    for (int g = 0; g < kBlock; g += 4) {
        for (int v = 0; v < 3; ++v) {
            __m256d r[4];
            for (int i = 0; i < 4; ++i) r[i] = _mm256_loadu_pd(pos + 3 * std::size_t{t[3 * (g + i) + v]});
            const __m256d xz01 = _mm256_unpacklo_pd(r[0], r[1]);  // x0 x1 | z0 z1
            const __m256d y01 = _mm256_unpackhi_pd(r[0], r[1]);   // y0 y1 | .  .
            const __m256d xz23 = _mm256_unpacklo_pd(r[2], r[3]);
            const __m256d y23 = _mm256_unpackhi_pd(r[2], r[3]);
            _mm256_store_pd(&b.c[3 * v][g], _mm256_permute2f128_pd(xz01, xz23, 0x20));
            _mm256_store_pd(&b.c[3 * v + 1][g], _mm256_permute2f128_pd(y01, y23, 0x20));
            _mm256_store_pd(&b.c[3 * v + 2][g], _mm256_permute2f128_pd(xz01, xz23, 0x31));
        }
    }
    return true;
}
#endif

// Always inlined: the fused volume pass (volume_faces) inlines it, and fn,
// into code compiled for each instruction-set level (kGather >= 1: AVX2 or
// better, whole blocks of all-triangle meshes by gather_block_avx2 where it
// can; the same values as the scalar gather).
template <int kGather = 0, class Fn>
POLYVOL_INLINE void for_each_block(const MeshView& mesh, std::size_t f0, std::size_t f1, Fn&& fn) {
    Block b;
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    auto put = [&](uint32_t va, uint32_t vb, uint32_t vc) __attribute__((always_inline)) {
        const double* pa = pos + 3 * std::size_t{va};
        const double* pb = pos + 3 * std::size_t{vb};
        const double* pc = pos + 3 * std::size_t{vc};
        for (int k = 0; k < 3; ++k) {
            b.c[k][b.n] = pa[k];
            b.c[3 + k][b.n] = pb[k];
            b.c[6 + k][b.n] = pc[k];
        }
        if (++b.n == kBlock) {
            fn(b);
            b.n = 0;
        }
    };
    if (mesh.all_triangles()) {
        // Whole blocks with a fixed trip count (the count and the slot index
        // stay in registers), then the rest through put().
        std::size_t f = f0;
        for (; f + kBlock <= f1; f += kBlock) {
            const uint32_t* t = idx + 3 * f;
#if POLYVOL_HAVE_FMA_CLONE
            if constexpr (kGather >= 1) {
                if (gather_block_avx2(pos, mesh.vertex_count(), t, b)) {
                    b.n = kBlock;
                    fn(b);
                    b.n = 0;
                    continue;
                }
            }
#endif
            for (int i = 0; i < kBlock; ++i) {
                const double* pa = pos + 3 * std::size_t{t[3 * i]};
                const double* pb = pos + 3 * std::size_t{t[3 * i + 1]};
                const double* pc = pos + 3 * std::size_t{t[3 * i + 2]};
                for (int k = 0; k < 3; ++k) {
                    b.c[k][i] = pa[k];
                    b.c[3 + k][i] = pb[k];
                    b.c[6 + k][i] = pc[k];
                }
            }
            b.n = kBlock;
            fn(b);
            b.n = 0;
        }
        for (; f < f1; ++f) put(idx[3 * f], idx[3 * f + 1], idx[3 * f + 2]);
    } else {
        const uint32_t* off = mesh.face_offsets.data();
        for (std::size_t f = f0; f < f1; ++f) {
            const uint32_t begin = off[f], end = off[f + 1];
            for (uint32_t i = begin + 1; i + 1 < end; ++i) put(idx[begin], idx[i], idx[i + 1]);
        }
    }
    if (b.n > 0) {
        for (int r = 0; r < 9; ++r)
            for (int i = b.n; i < kBlock; ++i) b.c[r][i] = 0;
        fn(b);
    }
}

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

// Acc: as above, with a triangles count. With AVX2, whole blocks come from
// gather_block_avx2 (called, not inlined: this code is compiled for the
// baseline), the same values as the scalar gather's.
template <class Acc, class PerBlock>
Acc reduce_blocks(const MeshView& mesh, PerBlock per_block) {
#if POLYVOL_HAVE_FMA_CLONE
    const bool avx2 = cpu_has_fma();
#else
    const bool avx2 = false;
#endif
    return reduce_face_ranges<Acc>(mesh, [&](std::size_t f0, std::size_t f1, Acc& acc) {
        const auto fn = [&](const Block& b) {
            acc.triangles += static_cast<std::size_t>(b.n);
            per_block(b, acc);
        };
        if (avx2) {
            for_each_block<1>(mesh, f0, f1, fn);
        } else {
            for_each_block<0>(mesh, f0, f1, fn);
        }
    });
}

// ---- the double-double volume alone ------------------------------------------
//
// The common call (signed_volume, correctly rounded) in one pass: per block
// the terms (block_terms; with AVX-512, volume_terms8 on rows built in
// registers), Sum2 in 8 lanes of 4 and the lanes combined into one (sum,
// error) pair, written with vectors of 8 doubles (GCC vector extensions:
// elementwise IEEE operations, -ffp-contract=off, so the same bits on every
// target), and the range check (RangeCheck below). Compiled once per
// instruction-set level like the kernels above, with the gather of the
// triangles inside.

typedef double V8 __attribute__((vector_size(64)));
typedef double V4 __attribute__((vector_size(32)));
typedef double V2 __attribute__((vector_size(16)));
typedef uint64_t U8 __attribute__((vector_size(64)));

constexpr int kVolLanes = 8;
constexpr int kVolPerLane = kBlock / kVolLanes;  // 4
static_assert(kVolLanes * kVolPerLane == kBlock);

template <class V>
POLYVOL_INLINE void vload(V& v, const void* p) {
    std::memcpy(&v, p, sizeof v);
}
template <class V, class W>
POLYVOL_INLINE void halves(const W& w, V& lo, V& hi) {
    static_assert(2 * sizeof(V) == sizeof(W));
    std::memcpy(&lo, &w, sizeof lo);
    std::memcpy(&hi, reinterpret_cast<const char*>(&w) + sizeof lo, sizeof hi);
}
// One level of the lane tree: the (sum, error, magnitude) lanes of W folded
// into half as many: the sums' halves by two_sum, its error added to the
// halves' error terms.
template <class V, class W>
POLYVOL_INLINE void fold_lanes(const W& S, const W& E, const W& M, V& s, V& e, V& m) {
    V sa, sb, ea, eb, ma, mb, t;
    halves(S, sa, sb);
    halves(E, ea, eb);
    halves(M, ma, mb);
    two_sum_lanes(sa, sb, s, t);
    e = (ea + eb) + t;
    m = ma + mb;
}

// One block's volume terms summed: s + e approximates Σ det (see the top of
// this file for the error), m = Σ magnitude.
struct VolumeSums {
    double s, e, m;
};

// A block's 32 (h, lo) pairs and magnitudes (translated form) summed:
// H[r], L[r], P[r] hold triangles 8r .. 8r + 7, so lane j takes triangles
// j, j + 8, j + 16, j + 24 (Sum2 in 8 lanes of 4; see the top of this file).
// Shared by volume_block and the AVX-512 kernel that forms the terms in
// registers (volume_block_in_registers): the same additions in the same
// order, hence the same bits.
template <bool kTranslate>
POLYVOL_INLINE void sum_volume_lanes(const V8 (&H)[kVolPerLane], const V8 (&L)[kVolPerLane],
                                     const V8 (&P)[kVolPerLane], VolumeSums& out) {
    // The origin form has no per-triangle magnitudes (out.m = 0;
    // volume_sums bounds them).
    V8 S = H[0], E = L[0], M = {};
    if constexpr (kTranslate) M = P[0];
    #pragma GCC unroll 4
    for (int r = 1; r < kVolPerLane; ++r) {
        V8 ns, ne;
        two_sum_lanes(S, H[r], ns, ne);
        S = ns;
        E += ne + L[r];
        if constexpr (kTranslate) M += P[r];
    }
    // The lanes into one pair: a two_sum tree (8 -> 4 -> 2 -> 1), the errors
    // of each level added to the lanes' error terms.
    V4 s4, e4, m4;
    fold_lanes(S, E, M, s4, e4, m4);
    V2 s2, e2, m2;
    fold_lanes(s4, e4, m4, s2, e2, m2);
    double s1, t1;
    two_sum(s2[0], s2[1], s1, t1);
    out.s = s1;
    out.e = (e2[0] + e2[1]) + t1;
    out.m = m2[0] + m2[1];
}

template <bool kFma, bool kTranslate = true>
POLYVOL_INLINE void volume_block(const Block& b, VolumeSums& out) {
    Terms<1> t;
    block_terms<kFma, true, 1, kTranslate>(b, t);
    V8 H[kVolPerLane], L[kVolPerLane], P[kVolPerLane] = {};
    for (int r = 0; r < kVolPerLane; ++r) {
        vload(H[r], t.h[kV] + r * kVolLanes);
        vload(L[r], t.l[kV] + r * kVolLanes);
        if constexpr (kTranslate) vload(P[r], t.m[kV] + r * kVolLanes);
    }
    sum_volume_lanes<kTranslate>(H, L, P, out);
}

// The range check of a block's coordinates (zero slots pass): over the bit
// patterns a = |x| (monotone in |x|; NaN and infinity above every finite
// value), hi = max a and lo = min (a - 1) (0 wraps to the largest value).
// The coordinates are in the safe range iff hi <= pattern(2^190) and
// lo + 1 >= pattern(2^-160): exactly coordinate_range's Range::safe, applied
// to the coordinates the sums read. Vertices that no face uses never enter
// a block, so their coordinates no longer matter here (coordinate_range
// still looks at every position).
constexpr uint64_t kAbsMask = ~(uint64_t{1} << 63);
constexpr uint64_t kSafeHi = 0x4BD0000000000000ull;  // 2^190
constexpr uint64_t kSafeLo = 0x35F0000000000000ull;  // 2^-160
static_assert(std::bit_cast<double>(kSafeHi) == exact::kSafeMax && std::bit_cast<double>(kSafeLo) == exact::kSafeMin);

// Extremes of some coordinates' patterns (hi, lo as above).
struct Extremes {
    uint64_t hi = 0, lo = ~uint64_t{0};
    void merge(const Extremes& o) {
        hi = std::max(hi, o.hi);
        lo = std::min(lo, o.lo);
    }
    // Folds the lanes of a vector step (extremes_step).
    void merge(const U8& lanes_hi, const U8& lanes_lo) {
        for (int j = 0; j < kVolLanes; ++j) merge(Extremes{lanes_hi[j], lanes_lo[j]});
    }
    bool safe() const { return hi <= kSafeHi && lo >= kSafeLo - 1; }
    double largest() const { return std::bit_cast<double>(hi); }
};

// One vector of 8 coordinates into the lanes' extremes.
POLYVOL_INLINE void extremes_step(const U8& x, U8& hi, U8& lo) {
    const U8 a = x & kAbsMask;
    hi = a > hi ? a : hi;
    const U8 am = a - 1;
    lo = am < lo ? am : lo;
}

POLYVOL_INLINE void range_block(const Block& b, U8& hi, U8& lo) {
    #pragma GCC unroll 36
    for (int r = 0; r < 9; ++r)
        for (int i = 0; i < kBlock; i += kVolLanes) {
            U8 x;
            vload(x, &b.c[r][i]);
            extremes_step(x, hi, lo);
        }
}

// The extremes of the bit patterns of |x| over n doubles (as range_block),
// in 8 independent lanes (one running max/min would serialise on its
// latency). Inlined into each level's volume pass (a task's slice of the
// positions) and into position_extremes (chunks on oneTBB), also compiled
// for AVX-512, where the 64-bit minimum and maximum are single instructions.
POLYVOL_INLINE void extremes_of(const double* x, std::size_t n, Extremes& e) {
    U8 hi = {}, lo = ~U8{};
    std::size_t i = 0;
    for (; i + kVolLanes <= n; i += kVolLanes) {
        U8 v;
        vload(v, x + i);
        extremes_step(v, hi, lo);
    }
    e.merge(hi, lo);
    for (; i < n; ++i) {
        const uint64_t a = std::bit_cast<uint64_t>(x[i]) & kAbsMask;
        e.merge(Extremes{a, a - 1});
    }
}

// The origin form's magnitude: 6 M^3 n >= Σ Perm over n triangles whose
// coordinates are at most M in magnitude (Perm = Σ_i |a_i| (|b_j c_k| +
// |b_k c_j|) <= 6 M^3 per triangle). Rounded three times (relative error
// < 4u, within the factor 1 + 2^-10 of the bound). Cheaper than Perm per
// triangle, and for a mesh not far from the origin compared with its size
// still far below what deciding the rounding needs (likely_volume_form).
double origin_magnitude(double M, std::size_t n) { return (M * M) * (M * (6.0 * static_cast<double>(n))); }

#if POLYVOL_HAVE_FMA_CLONE
// ---- the AVX-512 volume pass in registers ----------------------------------
//
// With AVX-512 a whole block of an all-triangle mesh goes from the positions
// to its VolumeSums without the Block in between: each group of 8
// triangles' rows of coordinates is built in registers (rows_of_vertex),
// its terms formed there (volume_terms8: terms_dd's operations, lane by
// lane) and the 4 groups summed by sum_volume_lanes, as volume_block sums
// the Block's. Every operation is the scalar code's, elementwise (FMA only
// where two_prod has one), so the bits are the same as on every other path.
// What it saves is the Block's stores and reloads (9 rows of 32 doubles a
// block): 0.81 of the time with the Block around the origin, 0.84 far
// from it (polyvol_bench, welded 1M-triangle sphere, 2 cores, with the
// range check's slices below); on a soup, where each position is read once
// and memory bounds the pass, about the same time.
#define POLYVOL_AVX512_INLINE \
    __attribute__((always_inline)) POLYVOL_AVX512_FEATURES(",fma") inline

// The permutations below are the _mm512_mask_ forms with every lane
// selected: the same instructions, without the plain forms' undefined
// source operand (that GCC 12 reports as used uninitialized).
constexpr __mmask8 kAllLanes = 0xFF;

// The (x, y, z, next) at p and at q in the low and high halves.
POLYVOL_AVX512_INLINE __m512d two_vertices(const double* p, const double* q) {
    const __m512d low = _mm512_castpd256_pd512(_mm256_loadu_pd(p));
    return _mm512_mask_insertf64x4(low, kAllLanes, low, _mm256_loadu_pd(q), 1);
}

// Vertex v (0, 1, 2) of 8 triangles (t: their 24 indices) as rows of x, y
// and z, lane j from triangle j. Triangles j and j + 2 of each four share a
// register, the order in which per-128-bit-lane unpacks and a selection of
// 128-bit lanes put the rows back together. Each load reads one double past
// its vertex (block_loads_within).
POLYVOL_AVX512_INLINE void rows_of_vertex(const double* pos, const uint32_t* t, int v, V8 (&row)[3]) {
    const double* p[8];
    for (int i = 0; i < 8; ++i) p[i] = pos + 3 * std::size_t{t[3 * i + v]};
    const __m512d r0 = two_vertices(p[0], p[2]), r1 = two_vertices(p[1], p[3]);
    const __m512d r2 = two_vertices(p[4], p[6]), r3 = two_vertices(p[5], p[7]);
    const __m512d lo01 = _mm512_mask_unpacklo_pd(r0, kAllLanes, r0, r1);  // x0 x1 | z0 z1 | x2 x3 | z2 z3
    const __m512d hi01 = _mm512_mask_unpackhi_pd(r0, kAllLanes, r0, r1);  // y0 y1 | .  .  | y2 y3 | .  .
    const __m512d lo23 = _mm512_mask_unpacklo_pd(r2, kAllLanes, r2, r3);  // x4 x5 | z4 z5 | x6 x7 | z6 z7
    const __m512d hi23 = _mm512_mask_unpackhi_pd(r2, kAllLanes, r2, r3);
    row[0] = _mm512_mask_shuffle_f64x2(lo01, kAllLanes, lo01, lo23, 0x88);  // 128-bit lanes 0 and 2 of each
    row[1] = _mm512_mask_shuffle_f64x2(hi01, kAllLanes, hi01, hi23, 0x88);
    row[2] = _mm512_mask_shuffle_f64x2(lo01, kAllLanes, lo01, lo23, 0xDD);  // lanes 1 and 3
}

// x y - p with one rounding (std::fma(x, y, -p) in each lane).
POLYVOL_AVX512_INLINE V8 fms_lanes(const V8& x, const V8& y, const V8& p) { return _mm512_fmsub_pd(x, y, p); }
POLYVOL_AVX512_INLINE V8 abs_lanes(const V8& x) { return (V8)((U8)x & kAbsMask); }

// terms_dd<true, 1, kTranslate> for 8 triangles (a, b, c: rows of x, y, z):
// the same operations in the same order, in each lane. A twin rather than
// one template over double and V8: GCC has no fma on generic vectors, and
// a template without the AVX-512 target cannot inline the intrinsic.
template <bool kTranslate>
POLYVOL_AVX512_INLINE void volume_terms8(const V8 (&a)[3], const V8 (&bb)[3], const V8 (&cc)[3], V8& h, V8& lo,
                                         V8& perm) {
    V8 uh[3], ul[3] = {}, wh[3], wl[3] = {};
    for (int k = 0; k < 3; ++k) {
        if constexpr (kTranslate) {
            two_sum_lanes(bb[k], -a[k], uh[k], ul[k]);
            two_sum_lanes(cc[k], -a[k], wh[k], wl[k]);
        } else {
            uh[k] = bb[k];
            wh[k] = cc[k];
        }
    }
    V8 ns[3], nl[3], pn[3], corr[3];
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, l = (k + 2) % 3;
        const V8 p1 = uh[j] * wh[l], e1 = fms_lanes(uh[j], wh[l], p1);
        const V8 p2 = uh[l] * wh[j], e2 = fms_lanes(uh[l], wh[j], p2);
        V8 tt;
        two_sum_lanes(p1, -p2, ns[k], tt);
        nl[k] = (e1 - e2) + tt;
        if constexpr (kTranslate) {
            pn[k] = abs_lanes(p1) + abs_lanes(p2);
            corr[k] = ((uh[j] * wl[l] - uh[l] * wl[j]) + (ul[j] * wh[l] - ul[l] * wh[j])) +
                      (ul[j] * wl[l] - ul[l] * wl[j]);
        }
    }
    V8 P[3], Q[3];
    for (int k = 0; k < 3; ++k) {
        P[k] = a[k] * ns[k];
        Q[k] = fms_lanes(a[k], ns[k], P[k]);
    }
    V8 h1, g1, g2;
    two_sum_lanes(P[0], P[1], h1, g1);
    two_sum_lanes(h1, P[2], h, g2);
    lo = ((g1 + g2) + ((Q[0] + Q[1]) + Q[2])) + ((a[0] * nl[0] + a[1] * nl[1]) + a[2] * nl[2]);
    if constexpr (kTranslate) {
        lo += (a[0] * corr[0] + a[1] * corr[1]) + a[2] * corr[2];
        perm = (abs_lanes(a[0]) * pn[0] + abs_lanes(a[1]) * pn[1]) + abs_lanes(a[2]) * pn[2];
    }
}

// One whole block (t: its 96 indices; block_loads_within holds) into out,
// as volume_block on the gathered Block; kCheck: its coordinates into the
// range check's lanes hi_out, lo_out, as range_block (the same values, so
// the same extremes). The lanes are copied in and out: updated through the
// references, each step was a load and a store (a 1M-triangle soup, every
// corner its own vertex: 3.1 ms against the Block's 2.6; copied: 2.4).
template <bool kTranslate, bool kCheck>
POLYVOL_AVX512_FEATURES(",fma") inline void
volume_block_in_registers(const double* pos, const uint32_t* t, VolumeSums& out, U8& hi_out, U8& lo_out) {
    V8 H[kVolPerLane], L[kVolPerLane], P[kVolPerLane] = {};
    U8 hi = hi_out, lo = lo_out;
    for (int r = 0; r < kVolPerLane; ++r) {
        V8 x[3][3];  // [vertex][axis]
        for (int v = 0; v < 3; ++v) rows_of_vertex(pos, t + 3 * kVolLanes * r, v, x[v]);
        if constexpr (kCheck) {
            for (int v = 0; v < 3; ++v)
                for (int k = 0; k < 3; ++k) extremes_step((U8)x[v][k], hi, lo);
        }
        volume_terms8<kTranslate>(x[0], x[1], x[2], H[r], L[r], P[r]);
    }
    hi_out = hi;
    lo_out = lo;
    sum_volume_lanes<kTranslate>(H, L, P, out);
}
#undef POLYVOL_AVX512_INLINE
#endif

constexpr int kGroupBlocks = 4;  // blocks per superaccumulator pair (volume_faces)

// Per task: the exact sum of the blocks' pairs, of their magnitudes
// (translated form), and the extremes of what the pass checked (RangeCheck:
// the coordinates it read, or its slice of the positions; with no check, hi
// is the largest pattern, so safe() is false).
struct VolumeAccumulator {
    ExactSum sum;
    ExactSum magnitude;
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

// What a volume pass checks of the coordinates' range (acc.range):
//   none: nothing (the caller has; acc.range is never safe());
//   referenced: the coordinates the pass reads (range_block; AVX-512 only:
//     before it there are no 64-bit integer minimum and maximum, and a
//     check in floating point (7 operations per vector) cost more than a
//     separate pass over the positions: AVX2 + FMA +19% against +15%,
//     baseline +25% against +4%, measured);
//   positions: every position, each task a slice of them in proportion to
//     its faces (extremes_of), read while the task's blocks are computed,
//     where a separate pass before (position_extremes) read them alone.
enum class RangeCheck { none, referenced, positions };

// Faces [f0, f1) into acc. The blocks' magnitudes (translated form) are
// summed in double over the range (a fixed range: the same bits for every
// split of the work), then added exactly; kCheck as above. Everything is
// inlined into the per-level entry points below.
template <bool kFma, int kLevel, bool kTranslate, RangeCheck kCheck>
POLYVOL_INLINE void volume_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeAccumulator& acc) {
    static_assert(kCheck != RangeCheck::referenced || kLevel >= 2);
    U8 hi = {}, lo = ~U8{};
    double magnitude = 0;
    std::size_t triangles = 0;
    // The blocks' pairs in groups of kGroupBlocks: (gs, ge) by two_sum and
    // plain additions, then into the superaccumulator (two exact additions
    // per group instead of per block; see the top of this file).
    double gs = 0, ge = 0;
    int grouped = 0;
    const auto add = [&](const VolumeSums& v, int n) __attribute__((always_inline)) {
        if (grouped == 0) {
            gs = v.s;
            ge = v.e;
        } else {
            double ns, t;
            two_sum(gs, v.s, ns, t);
            gs = ns;
            ge = (ge + v.e) + t;
        }
        if (++grouped == kGroupBlocks) {
            acc.sum.add(gs);
            acc.sum.add(ge);
            grouped = 0;
        }
        if constexpr (kTranslate) magnitude += v.m;
        triangles += static_cast<std::size_t>(n);
    };
    const auto per_block = [&](const Block& b) __attribute__((always_inline)) {
        VolumeSums v;
        volume_block<kFma, kTranslate>(b, v);
        if constexpr (kCheck == RangeCheck::referenced) range_block(b, hi, lo);
        add(v, b.n);
    };
    bool walked = false;
#if POLYVOL_HAVE_FMA_CLONE
    if constexpr (kLevel >= 2) {
        if (mesh.all_triangles()) {
            // Whole blocks in registers where their loads stay inside the
            // positions, else through the Block (the scalar gather); then
            // the rest as one partial block: the blocks of for_each_block.
            const double* pos = mesh.positions.data();
            const uint32_t* idx = mesh.indices.data();
            const std::size_t nv = mesh.vertex_count();
            std::size_t f = f0;
            for (; f + kBlock <= f1; f += kBlock) {
                const uint32_t* t = idx + 3 * f;
                if (block_loads_within(nv, t)) {
                    VolumeSums v;
                    volume_block_in_registers<kTranslate, kCheck == RangeCheck::referenced>(pos, t, v, hi, lo);
                    add(v, kBlock);
                } else {
                    for_each_block<0>(mesh, f, f + kBlock, per_block);
                }
            }
            if (f < f1) for_each_block<0>(mesh, f, f1, per_block);
            walked = true;
        }
    }
#endif
    if (!walked) for_each_block<kLevel>(mesh, f0, f1, per_block);
    if (grouped > 0) {
        acc.sum.add(gs);
        acc.sum.add(ge);
    }
    acc.magnitude.add(magnitude);
    acc.triangles += triangles;
    if constexpr (kCheck == RangeCheck::referenced) {
        acc.range.merge(hi, lo);
    } else if constexpr (kCheck == RangeCheck::positions) {
        // Vertices [f0 nv / nf, f1 nv / nf): the ranges' slices tile them.
        __extension__ typedef unsigned __int128 u128;
        const std::size_t nv = mesh.vertex_count(), nf = mesh.face_count();
        const auto v0 = static_cast<std::size_t>(u128{f0} * nv / nf), v1 = static_cast<std::size_t>(u128{f1} * nv / nf);
        Extremes e;
        extremes_of(mesh.positions.data() + 3 * v0, 3 * (v1 - v0), e);
        acc.range.merge(e);
    } else {
        acc.range.hi = ~uint64_t{0};  // not checked: never safe()
    }
}

#if POLYVOL_HAVE_FMA_CLONE
#define POLYVOL_AVX512 POLYVOL_AVX512_FEATURES(",fma")
template <bool kTranslate, RangeCheck kCheck>
POLYVOL_AVX512 void volume_faces_avx512(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeAccumulator& acc) {
    volume_faces<true, 2, kTranslate, kCheck>(mesh, f0, f1, acc);
}
POLYVOL_AVX512 void volume_block_avx512(const Block& b, VolumeSums& out) { volume_block<true>(b, out); }
#undef POLYVOL_AVX512
template <bool kTranslate, RangeCheck kCheck>
__attribute__((target("avx2,fma"))) void volume_faces_fma(const MeshView& mesh, std::size_t f0, std::size_t f1,
                                                          VolumeAccumulator& acc) {
    volume_faces<true, 1, kTranslate, kCheck>(mesh, f0, f1, acc);
}
__attribute__((target("avx2,fma"))) void volume_block_fma(const Block& b, VolumeSums& out) { volume_block<true>(b, out); }
#endif
template <bool kTranslate, RangeCheck kCheck>
void volume_faces_base(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeAccumulator& acc) {
    volume_faces<false, 0, kTranslate, kCheck>(mesh, f0, f1, acc);
}
void volume_block_base(const Block& b, VolumeSums& out) { volume_block<false>(b, out); }

// The instruction-set level for a volume pass (0, 1, 2 as in
// cap_kernel_level). Read once per call: the cap may change meanwhile, and
// whether the range check can run in the pass depends on the level.
int volume_level() {
#if POLYVOL_HAVE_FMA_CLONE
    if (cpu_has_avx512()) return 2;
    if (cpu_has_fma()) return 1;
#endif
    return 0;
}

void volume_block_any(const Block& b, VolumeSums& out) {
#if POLYVOL_HAVE_FMA_CLONE
    switch (volume_level()) {
        case 2: return volume_block_avx512(b, out);
        case 1: return volume_block_fma(b, out);
        default: break;
    }
#endif
    volume_block_base(b, out);
}

using VolumeFacesFn = void (*)(const MeshView&, std::size_t, std::size_t, VolumeAccumulator&);

// The per-level entry point of volume_faces for a form and a check.
template <RangeCheck kCheck>
VolumeFacesFn volume_faces_of(int level, bool translate) {
#if POLYVOL_HAVE_FMA_CLONE
    if (level == 2) return translate ? volume_faces_avx512<true, kCheck> : volume_faces_avx512<false, kCheck>;
    if constexpr (kCheck != RangeCheck::referenced) {
        if (level == 1) return translate ? volume_faces_fma<true, kCheck> : volume_faces_fma<false, kCheck>;
    }
#else
    (void)level;
#endif
    if constexpr (kCheck == RangeCheck::referenced) {
        return nullptr;  // level 2 only
    } else {
        return translate ? volume_faces_base<true, kCheck> : volume_faces_base<false, kCheck>;
    }
}

// The pass with the kernels of `level` (from volume_level()) in the given
// form and with the given check (referenced: level 2 only).
VolumeAccumulator volume_pass(const MeshView& mesh, int level, VolumeForm form, RangeCheck check) {
    const bool translate = form == VolumeForm::translated;
    const VolumeFacesFn fn = check == RangeCheck::none        ? volume_faces_of<RangeCheck::none>(level, translate)
                             : check == RangeCheck::positions ? volume_faces_of<RangeCheck::positions>(level, translate)
                                                              : volume_faces_of<RangeCheck::referenced>(level, translate);
    return reduce_face_ranges<VolumeAccumulator>(
        mesh, [&](std::size_t f0, std::size_t f1, VolumeAccumulator& acc) { fn(mesh, f0, f1, acc); });
}

// The sums of a pass; M (origin form): the largest |coordinate| it read.
ConeSums volume_sums(const VolumeAccumulator& acc, VolumeForm form, double M) {
    ConeSums out;
    out.count = 1;
    out.triangles = acc.triangles;
    out.sum[kV] = acc.sum;
    const double magnitude = form == VolumeForm::origin ? origin_magnitude(M, acc.triangles) : acc.magnitude.round();
    out.bound[kV] = filtered_bound(kV, Precision::double_double, magnitude);
    return out;
}

#if POLYVOL_HAVE_FMA_CLONE
POLYVOL_AVX512_FEATURES("") void extremes_avx512(
    const double* x, std::size_t n, Extremes& e) {
    extremes_of(x, n, e);
}
#endif

Extremes position_extremes(std::span<const double> x) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, x.size(), std::size_t{1} << 16), Extremes{},
        [&](const tbb::blocked_range<std::size_t>& r, Extremes acc) {
#if POLYVOL_HAVE_FMA_CLONE
            if (cpu_has_avx512()) {
                extremes_avx512(x.data() + r.begin(), r.size(), acc);
                return acc;
            }
#endif
            extremes_of(x.data() + r.begin(), r.size(), acc);
            return acc;
        },
        [](Extremes a, const Extremes& b) {
            a.merge(b);
            return a;
        });
}

// ---- every other filtered sum (accumulate_into: 4 lanes of 8) ----------------

template <int N>
ConeSums filtered_impl(const MeshView& mesh, bool dd) {
    if constexpr (N == 1) {
        if (dd) {
            return volume_sums(volume_pass(mesh, volume_level(), VolumeForm::translated, RangeCheck::none),
                               VolumeForm::translated, 0);
        }
    }
    const Accumulator<N> acc = reduce_blocks<Accumulator<N>>(mesh, [dd](const Block& b, Accumulator<N>& a) {
        Terms<N> t;
        compute_terms<N>(b, t, dd);
        accumulate<N>(t, dd, a);
    });
    ConeSums out;
    out.count = N;
    out.triangles = acc.triangles;
    for (int k = 0; k < N; ++k) {
        out.sum[k] = acc.sum[k];
        out.bound[k] = filtered_bound(k, dd ? Precision::double_double : Precision::fast, acc.magnitude[k].round());
    }
    return out;
}

// ---- exact terms as integers ------------------------------------------------

__extension__ typedef unsigned __int128 u128;
__extension__ typedef __int128 i128;

// out[0 .. nx+ny) = x * y (magnitudes).
POLYVOL_INLINE void wide_mul(const uint64_t* x, int nx, const uint64_t* y, int ny, uint64_t* out) {
    for (int i = 0; i < nx + ny; ++i) out[i] = 0;
    for (int i = 0; i < nx; ++i) {
        u128 c = 0;
        for (int j = 0; j < ny; ++j) {
            c += static_cast<u128>(x[i]) * y[j] + out[i + j];
            out[i + j] = static_cast<uint64_t>(c);
            c >>= 64;
        }
        out[i + ny] = static_cast<uint64_t>(c);
    }
}

POLYVOL_INLINE void split_i128(i128 v, uint64_t* mag, bool& negative) {
    negative = v < 0;
    const u128 m = negative ? static_cast<u128>(0) - static_cast<u128>(v) : static_cast<u128>(v);
    mag[0] = static_cast<uint64_t>(m);
    mag[1] = static_cast<uint64_t>(m >> 64);
}

// Coordinate x = k 2^e with an integer k: the exponent of x's lowest set bit
// and of its highest (x != 0, finite).
POLYVOL_INLINE void bit_range(double x, int& lowest, int& highest) {
    const uint64_t bits = std::bit_cast<uint64_t>(x);
    const int ex = static_cast<int>((bits >> 52) & 0x7FF);
    const uint64_t frac = bits & ((uint64_t{1} << 52) - 1);
    const uint64_t mant = ex != 0 ? (frac | (uint64_t{1} << 52)) : frac;
    const int e = (ex != 0 ? ex : 1) - 1075;  // x = mant 2^e
    lowest = e + std::countr_zero(mant);
    highest = e + 63 - std::countl_zero(mant);
}

// One triangle's exact terms as integers, when each axis's three
// coordinates are k 2^e_axis with |k| < 2^60 (the usual case: a triangle's
// coordinates share their leading exponents). det is then an integer times
// 2^(ex+ey+ez), det s_i one times 2^(ex+ey+ez+e_i), det q_ij one times
// 2^(ex+ey+ez+e_i+e_j) (det is trilinear with one coordinate of each axis
// per term). Bounds: |det| < 2^183, |s| < 2^62, |q| < 2^125, |det q| < 2^308.
// Returns false (nothing added) when some axis spans more than 60 bits.
bool integer_triangle(const double* a, const double* b, const double* c, uint32_t mask, ExactSum* acc) {
    int e[3];
    for (int k = 0; k < 3; ++k) {
        int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
        for (double x : {a[k], b[k], c[k]}) {
            if (x == 0) continue;
            int l, h;
            bit_range(x, l, h);
            lo = std::min(lo, l);
            hi = std::max(hi, h);
        }
        if (lo == std::numeric_limits<int>::max()) {
            lo = 0;  // all three zero
        } else if (hi + 1 - lo > 60) {
            return false;
        }
        e[k] = lo;
    }
    int64_t A[3], B[3], C[3];
    for (int k = 0; k < 3; ++k) {  // exact: |x 2^-e| < 2^60; 2^-e is a normal double in the safe range
        const double scale = std::bit_cast<double>(static_cast<uint64_t>(1023 - e[k]) << 52);
        A[k] = static_cast<int64_t>(a[k] * scale);
        B[k] = static_cast<int64_t>(b[k] * scale);
        C[k] = static_cast<int64_t>(c[k] * scale);
    }
    // det = Σ A_k x_k, x_k = B_j C_l - B_l C_j (|x_k| < 2^121), as
    // hi 2^64 + lo: with x_k = xh_k 2^64 + xl_k (xl_k unsigned, |xh_k| <=
    // 2^57), Σ A_k xl_k (|.| < 3 2^124) and Σ A_k xh_k (< 2^119) in 128-bit
    // integers, the first's high word carried into the second (|hi| < 2^120).
    i128 lo_sum = 0, hi = 0;
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, l = (k + 2) % 3;
        const i128 x = static_cast<i128>(B[j]) * C[l] - static_cast<i128>(B[l]) * C[j];
        lo_sum += static_cast<i128>(A[k]) * static_cast<i128>(static_cast<uint64_t>(x));
        hi += static_cast<i128>(A[k]) * static_cast<int64_t>(x >> 64);
    }
    hi += lo_sum >> 64;  // arithmetic shift: lo_sum = (lo_sum >> 64) 2^64 + its low word
    uint64_t lo = static_cast<uint64_t>(lo_sum);
    if (hi == 0 && lo == 0) return true;  // det == 0: every term is 0
    const bool dn = hi < 0;
    if (dn) {  // |det| = -(hi 2^64 + lo)
        hi = -hi - (lo != 0 ? 1 : 0);
        lo = static_cast<uint64_t>(0) - lo;
    }
    const uint64_t d[3] = {lo, static_cast<uint64_t>(hi), static_cast<uint64_t>(hi >> 64)};  // |det| < 2^183
    const int ev = e[0] + e[1] + e[2];
    if (mask & (1u << kV)) acc[kV].add_wide(d, 3, dn, ev);
    int64_t s[3];
    for (int k = 0; k < 3; ++k) s[k] = A[k] + B[k] + C[k];  // |s| < 2^62
    for (int k = 0; k < 3; ++k) {
        if (!(mask & (1u << (kMx + k)))) continue;
        const uint64_t sm[1] = {s[k] < 0 ? static_cast<uint64_t>(0) - static_cast<uint64_t>(s[k])
                                         : static_cast<uint64_t>(s[k])};
        uint64_t p[4];
        wide_mul(d, 3, sm, 1, p);
        acc[kMx + k].add_wide(p, 4, dn != (s[k] < 0), ev + e[k]);
    }
    constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
    for (int k = 0; k < 6; ++k) {
        if (!(mask & (1u << (kSxx + k)))) continue;
        const int x = I[k], y = J[k];
        const i128 q = static_cast<i128>(A[x]) * A[y] + static_cast<i128>(B[x]) * B[y] +
                       static_cast<i128>(C[x]) * C[y] + static_cast<i128>(s[x]) * s[y];  // |q| < 2^125
        uint64_t qm[2], p[5];
        bool qn;
        split_i128(q, qm, qn);
        wide_mul(d, 3, qm, 2, p);
        acc[kSxx + k].add_wide(p, 5, dn != qn, ev + e[x] + e[y]);
    }
    return true;
}

// ---- exact terms ------------------------------------------------------------

// Builds a compressed nonoverlapping expansion of the sum of n doubles.
int expansion_of(const double* x, int n, double* h) {
    int len = 0;
    for (int i = 0; i < n; ++i) len = exact::grow_expansion(len, h, x[i], h);
    return exact::compress(len, h, h);
}

template <bool kFma>
POLYVOL_INLINE void add_product(const double* x, int nx, const double* y, int ny, ExactSum& acc) {
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            double p, e;
            two_prod_t<kFma>(x[i], y[j], p, e);
            acc.add(p);
            acc.add(e);
        }
    }
}

template <bool kFma>
void exact_block(const Block& b, uint32_t mask, ExactSum* acc) {
    for (int i = 0; i < b.n; ++i) {
        const double a[3] = {b.c[0][i], b.c[1][i], b.c[2][i]};
        const double bb[3] = {b.c[3][i], b.c[4][i], b.c[5][i]};
        const double cc[3] = {b.c[6][i], b.c[7][i], b.c[8][i]};
        if (integer_triangle(a, bb, cc, mask, acc)) continue;
        double d[exact::kDetTerms];
        const int nd = exact::det3_exact<kFma>(a, bb, cc, d);
        if (nd == 1 && d[0] == 0) continue;
        if (mask & (1u << kV)) acc[kV].add(std::span<const double>(d, static_cast<std::size_t>(nd)));
        if ((mask >> kMx) == 0) continue;
        double s[3][3];
        int ns[3];
        for (int k = 0; k < 3; ++k) {
            const double raw[3] = {a[k], bb[k], cc[k]};
            ns[k] = expansion_of(raw, 3, s[k]);
            if (mask & (1u << (kMx + k))) add_product<kFma>(d, nd, s[k], ns[k], acc[kMx + k]);
        }
        constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
        for (int k = 0; k < 6; ++k) {
            if (!(mask & (1u << (kSxx + k)))) continue;
            const int x = I[k], y = J[k];
            double raw[6 + 18];
            int n = 0;
            two_prod_t<kFma>(a[x], a[y], raw[0], raw[1]);
            two_prod_t<kFma>(bb[x], bb[y], raw[2], raw[3]);
            two_prod_t<kFma>(cc[x], cc[y], raw[4], raw[5]);
            n = 6;
            for (int p = 0; p < ns[x]; ++p)
                for (int r = 0; r < ns[y]; ++r, n += 2) two_prod_t<kFma>(s[x][p], s[y][r], raw[n], raw[n + 1]);
            double q[32];
            const int nq = expansion_of(raw, n, q);
            add_product<kFma>(d, nd, q, nq, acc[kSxx + k]);
        }
    }
}

#if POLYVOL_HAVE_FMA_CLONE
__attribute__((target("avx2,fma"))) void exact_block_fma(const Block& b, uint32_t mask, ExactSum* acc) {
    exact_block<true>(b, mask, acc);
}
#endif

// ---- big integers -------------------------------------------------------------

struct Mpz {
    mpz_t z;
    Mpz() { mpz_init(z); }
    Mpz(const Mpz&) = delete;
    Mpz& operator=(const Mpz&) = delete;
    ~Mpz() { mpz_clear(z); }
};

// x = m 2^e with m an odd integer (x != 0, finite): returns e.
int lowest_bit_exponent(double x) {
    int e;
    const double m = std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
    auto mant = static_cast<uint64_t>(std::ldexp(std::fabs(m), 53));
    return e - 53 + std::countr_zero(mant);
}

// z = x 2^-e0 (an integer: e0 <= lowest_bit_exponent(x)).
void to_integer(double x, int e0, mpz_t z) {
    if (x == 0) {
        mpz_set_ui(z, 0);
        return;
    }
    int e;
    const double m = std::frexp(x, &e);
    mpz_set_d(z, std::ldexp(m, 53));  // exact integer, |.| < 2^53
    const int shift = e - 53 - e0;
    if (shift >= 0) {
        mpz_mul_2exp(z, z, static_cast<mp_bitcnt_t>(shift));
    } else {
        mpz_tdiv_q_2exp(z, z, static_cast<mp_bitcnt_t>(-shift));  // exact: low bits are zero
    }
}

}  // namespace

double filtered_bound(int k, Precision precision, double magnitude) {
    const bool dd = precision == Precision::double_double;
    const double K = k == kV ? (dd ? 512 : 32) : (k <= kMz ? (dd ? 768 : 40) : (dd ? 1024 : 56));
    const double unit = dd ? kU * kU : kU;
    // + 2^-1060 covers the rounding of a bound in the subnormal range (any
    // error is a multiple of 2^-1060 in the safe range).
    return magnitude > 0 ? K * unit * magnitude * (1 + 0x1p-10) + 0x1p-1060 : 0.0;
}

void filtered_volume_block(const TriangleBlock& b, ExactSum& sum, ExactSum& magnitude) {
    VolumeSums v;
    volume_block_any(b, v);
    sum.add(v.s);
    sum.add(v.e);
    magnitude.add(v.m);
}

void exact_block_sums(const TriangleBlock& b, uint32_t mask, ExactSum* acc) {
#if POLYVOL_HAVE_FMA_CLONE
    if (cpu_has_fma()) {
        exact_block_fma(b, mask, acc);
        return;
    }
#endif
    exact_block<false>(b, mask, acc);
}

void force_baseline_kernels(bool on) { cap_kernel_level(on ? 0 : 2); }

void cap_kernel_level(int level) {
#if POLYVOL_HAVE_FMA_CLONE
    g_level_cap.store(level, std::memory_order_relaxed);
#else
    (void)level;
#endif
}

Range coordinate_range(const MeshView& mesh) {
    const Extremes e = position_extremes(mesh.positions);
    // NaN and infinity: patterns above the largest finite one.
    if (e.hi > std::bit_cast<uint64_t>(std::numeric_limits<double>::max())) return Range::nonfinite;
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
    const int level = volume_level();  // once: the passes below run this level
    // Every position checked (in the pass) when that costs less than
    // checking each used coordinate (at least two indices per vertex: each
    // vertex is read about twice or more there), and always below AVX-512,
    // where the pass cannot check what it reads. The origin form's M is
    // then the largest |coordinate| of any position, else of any used one.
    if (level < 2 || 2 * mesh.vertex_count() <= mesh.indices.size()) {
        const VolumeAccumulator acc = volume_pass(mesh, level, form, RangeCheck::positions);
        if (acc.safe()) {
            safe = true;
            return volume_sums(acc, form, acc.range.largest());
        }
        if (level < 2) {  // stricter than the definition; the caller's exact fallback gives the same results
            safe = false;
            return ConeSums{.count = 1};
        }
        // Out of range somewhere, maybe only on vertices no face uses: the
        // check of what the pass reads decides.
    }
    const VolumeAccumulator acc = volume_pass(mesh, level, form, RangeCheck::referenced);
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
    const Accumulator<kSumCount> acc = reduce_blocks<Accumulator<kSumCount>>(mesh, [mask](const Block& b, Accumulator<kSumCount>& a) {
#if POLYVOL_HAVE_FMA_CLONE
        if (cpu_has_fma()) {
            exact_block_fma(b, mask, a.sum);
            return;
        }
#endif
        exact_block<false>(b, mask, a.sum);
    });
    for (int k = 0; k < sums.count; ++k) {
        if (mask & (1u << k)) {
            sums.sum[k] = acc.sum[k];
            sums.bound[k] = 0;
        }
    }
}

RationalSums gmp_sums(const MeshView& mesh, int count) {
    RationalSums out;
    // The common scale: the lowest set bit of any coordinate of a used vertex.
    int e0 = std::numeric_limits<int>::max();
    bool any = false;
    for_each_block(mesh, 0, mesh.face_count(), [&](const Block& b) {
        for (int r = 0; r < 9; ++r)
            for (int i = 0; i < b.n; ++i) {
                const double x = b.c[r][i];
                if (!std::isfinite(x)) {
                    out.ok = false;
                } else if (x != 0) {
                    e0 = std::min(e0, lowest_bit_exponent(x));
                    any = true;
                }
            }
    });
    if (!out.ok || !any) return out;  // not finite, or every sum is 0

    Mpz sums[kSumCount];
    Mpz c[9], det, s[3], t1, t2, q;
    for_each_block(mesh, 0, mesh.face_count(), [&](const Block& b) {
        for (int i = 0; i < b.n; ++i) {
            for (int r = 0; r < 9; ++r) to_integer(b.c[r][i], e0, c[r].z);
            mpz_ptr A[3] = {c[0].z, c[1].z, c[2].z}, B[3] = {c[3].z, c[4].z, c[5].z},
                    C[3] = {c[6].z, c[7].z, c[8].z};
            mpz_set_ui(det.z, 0);
            for (int k = 0; k < 3; ++k) {
                const int j = (k + 1) % 3, l = (k + 2) % 3;
                mpz_mul(t1.z, B[j], C[l]);
                mpz_submul(t1.z, B[l], C[j]);
                mpz_addmul(det.z, A[k], t1.z);
            }
            mpz_add(sums[kV].z, sums[kV].z, det.z);
            if (count == 1) continue;
            for (int k = 0; k < 3; ++k) {
                mpz_add(s[k].z, A[k], B[k]);
                mpz_add(s[k].z, s[k].z, C[k]);
                mpz_addmul(sums[kMx + k].z, det.z, s[k].z);
            }
            if (count <= kSxx) continue;
            constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
            for (int k = 0; k < 6; ++k) {
                const int x = I[k], y = J[k];
                mpz_mul(q.z, A[x], A[y]);
                mpz_addmul(q.z, B[x], B[y]);
                mpz_addmul(q.z, C[x], C[y]);
                mpz_addmul(q.z, s[x].z, s[y].z);
                mpz_addmul(sums[kSxx + k].z, det.z, q.z);
            }
        }
    });
    for (int k = 0; k < count; ++k) {
        const int degree = k == kV ? 3 : (k <= kMz ? 4 : 5);
        mpq_ptr r = out.sum[k].get();
        mpq_set_z(r, sums[k].z);
        const long shift = static_cast<long>(degree) * e0;
        if (shift >= 0) {
            mpq_mul_2exp(r, r, static_cast<mp_bitcnt_t>(shift));
        } else {
            mpq_div_2exp(r, r, static_cast<mp_bitcnt_t>(-shift));
        }
    }
    return out;
}

}  // namespace polyvol::measure::cone
