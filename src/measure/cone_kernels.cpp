// measure/cone_kernels.cpp — the cone rule's passes over a face range,
// compiled once per instruction set (Highway's foreach_target) and chosen at
// run time by its dispatch: gather the fan triangles of the faces into
// blocks of 32 (structure of arrays), form their terms (cone_terms-inl.h:
// what is summed), and sum them (Sum2 in lanes, then a superaccumulator:
// how). The error analysis is in docs/numerics.md, "The cone rule's kernels".
//
// Every target forms and adds the same values in the same order, so they
// all give the same bits (tests/measure/cone_kernels_test.cpp forces each).
#include "core/hwy_targets.hpp"  // before Highway

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "measure/cone_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "core/simd.hpp"
#include "measure/cone_kernels.hpp"
#include "measure/cone_terms-inl.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <span>

#include "exact/eft.hpp"
#include "exact/expansion.hpp"

#if HWY_ARCH_X86
#include <immintrin.h>
#endif

HWY_BEFORE_NAMESPACE();
namespace polyvol::measure::cone::HWY_NAMESPACE {
namespace {

using exact::ExactSum;

// Highway's x86 targets: AVX2 and better load a vertex's (x, y, z, next)
// with one 256-bit load; AVX-512 puts two vertices in one register.
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define POLYVOL_ROWS_AVX2 1
#else
#define POLYVOL_ROWS_AVX2 0
#endif
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
#define POLYVOL_ROWS_AVX512 1
#else
#define POLYVOL_ROWS_AVX512 0
#endif

// ---- gathering fan triangles ---------------------------------------------

// Rows of kN triangles from slot i of a block: a[k] = coordinate k of vertex
// 0, b of vertex 1, c of vertex 2.
HWY_INLINE void rows_of_block(const Block& blk, int i, V (&a)[3], V (&b)[3], V (&c)[3]) {
    const D d;
    for (int k = 0; k < 3; ++k) {
        a[k] = hn::Load(d, &blk.c[k][i]);
        b[k] = hn::Load(d, &blk.c[3 + k][i]);
        c[k] = hn::Load(d, &blk.c[6 + k][i]);
    }
}

#if POLYVOL_ROWS_AVX2
// Whether every index of a block (t: its 96 indices) is below nv - 1, so
// that a 256-bit load at each vertex (one double past it) stays inside the
// positions of the nv vertices.
HWY_INLINE bool block_loads_within(std::size_t nv, const uint32_t* t) {
    if (nv == 0) return false;
    if (nv - 1 > std::numeric_limits<uint32_t>::max()) return true;
    uint32_t largest = 0;
    for (int j = 0; j < 3 * kBlock; ++j) largest = std::max(largest, t[j]);
    return largest < nv - 1;
}

// Vertex v of 4 triangles (t: their 12 indices) as rows of x, y and z: each
// vertex's (x, y, z, next) by one 256-bit load, then a 4 x 4 transpose (two
// unpacks and three lane permutations). Hardware gathers, and masked loads
// of three doubles, are much slower.
HWY_INLINE void rows4(const double* pos, const uint32_t* t, int v, __m256d (&row)[3]) {
    __m256d r[4];
    for (int i = 0; i < 4; ++i) r[i] = _mm256_loadu_pd(pos + 3 * std::size_t{t[3 * i + v]});
    const __m256d xz01 = _mm256_unpacklo_pd(r[0], r[1]);  // x0 x1 | z0 z1
    const __m256d y01 = _mm256_unpackhi_pd(r[0], r[1]);   // y0 y1 | .  .
    const __m256d xz23 = _mm256_unpacklo_pd(r[2], r[3]);
    const __m256d y23 = _mm256_unpackhi_pd(r[2], r[3]);
    row[0] = _mm256_permute2f128_pd(xz01, xz23, 0x20);
    row[1] = _mm256_permute2f128_pd(y01, y23, 0x20);
    row[2] = _mm256_permute2f128_pd(xz01, xz23, 0x31);
}
#endif

#if POLYVOL_ROWS_AVX512
// The permutations below are the _mm512_mask_ forms with every lane
// selected: the same instructions, without the plain forms' undefined
// source operand (that GCC 12 reports as used uninitialized).
constexpr __mmask8 kAllLanes = 0xFF;

// The (x, y, z, next) at p and at q in the low and high halves.
HWY_INLINE __m512d two_vertices(const double* p, const double* q) {
    const __m512d low = _mm512_castpd256_pd512(_mm256_loadu_pd(p));
    return _mm512_mask_insertf64x4(low, kAllLanes, low, _mm256_loadu_pd(q), 1);
}

// Vertex v of 8 triangles (t: their 24 indices) as rows of x, y and z, lane
// j from triangle j. Triangles j and j + 2 of each four share a register,
// the order in which per-128-bit-lane unpacks and a selection of 128-bit
// lanes put the rows back together.
HWY_INLINE void rows8(const double* pos, const uint32_t* t, int v, __m512d (&row)[3]) {
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
#endif

#if POLYVOL_ROWS_AVX2
// Rows of kN triangles (t: their 3 kN indices) straight from the positions;
// block_loads_within must hold for their block.
HWY_INLINE void rows_of_mesh(const double* pos, const uint32_t* t, V (&a)[3], V (&b)[3], V (&c)[3]) {
    V* out[3] = {a, b, c};
#if POLYVOL_ROWS_AVX512
    static_assert(kN == 8);
    for (int v = 0; v < 3; ++v) {
        __m512d row[3];
        rows8(pos, t, v, row);
        for (int k = 0; k < 3; ++k) out[v][k] = V{row[k]};
    }
#else
    static_assert(kN == 4);
    for (int v = 0; v < 3; ++v) {
        __m256d row[3];
        rows4(pos, t, v, row);
        for (int k = 0; k < 3; ++k) out[v][k] = V{row[k]};
    }
#endif
}
#endif

// A whole block of an all-triangle mesh into blk (t: its 96 indices), or
// false when its loads would leave the positions (or the target has no
// vector loads of vertices): the values of the scalar gather.
HWY_INLINE bool gather_block_in_registers(const double* pos, std::size_t nv, const uint32_t* t, Block& blk) {
#if POLYVOL_ROWS_AVX2
    if (!block_loads_within(nv, t)) return false;
    for (int g = 0; g < kBlock; g += 4) {
        for (int v = 0; v < 3; ++v) {
            __m256d row[3];
            rows4(pos, t + 3 * g, v, row);
            for (int k = 0; k < 3; ++k) _mm256_store_pd(&blk.c[3 * v + k][g], row[k]);
        }
    }
    blk.n = kBlock;
    return true;
#else
    (void)pos;
    (void)nv;
    (void)t;
    (void)blk;
    return false;
#endif
}

// Calls fn(block) for blocks of up to kBlock fan triangles of faces [f0,
// f1), in face order, the last one padded with zeros (which add exactly 0
// to every sum). On an all-triangle mesh each whole block is first offered
// to whole(t) (t: its 96 indices), which returns whether it took it.
template <class Whole, class Fn>
HWY_INLINE void walk_blocks(const MeshView& mesh, std::size_t f0, std::size_t f1, Whole&& whole, Fn&& fn) {
    Block b;
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    const auto put = [&](uint32_t va, uint32_t vb, uint32_t vc) {
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
        std::size_t f = f0;
        for (; f + kBlock <= f1; f += kBlock) {
            const uint32_t* t = idx + 3 * f;
            if (whole(t)) continue;
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

// ---- the range check ---------------------------------------------------------

using DU = hn::RebindToUnsigned<D>;
using VU = hn::Vec<DU>;

// kN coordinates into the lanes' extremes (Extremes: hi = max |x|'s
// pattern, lo = min (pattern - 1)).
HWY_INLINE void extremes_step(V x, VU& hi, VU& lo) {
    const DU du;
    const VU a = hn::And(hn::BitCast(du, x), hn::Set(du, kAbsMask));
    hi = hn::Max(a, hi);
    lo = hn::Min(hn::Sub(a, hn::Set(du, 1)), lo);
}

HWY_INLINE void merge_lanes(VU hi, VU lo, Extremes& e) {
    const DU du;
    alignas(64) uint64_t h[kN], l[kN];
    hn::Store(hi, du, h);
    hn::Store(lo, du, l);
    for (int j = 0; j < kN; ++j) e.merge(Extremes{h[j], l[j]});
}

// The extremes over n doubles, in two independent sets of lanes.
HWY_INLINE void extremes_in(const double* x, std::size_t n, Extremes& e) {
    const D d;
    const DU du;
    VU hi0 = hn::Zero(du), lo0 = hn::Set(du, ~uint64_t{0}), hi1 = hi0, lo1 = lo0;
    std::size_t i = 0;
    for (; i + 2 * kN <= n; i += 2 * kN) {
        extremes_step(hn::LoadU(d, x + i), hi0, lo0);
        extremes_step(hn::LoadU(d, x + i + kN), hi1, lo1);
    }
    merge_lanes(hi0, lo0, e);
    merge_lanes(hi1, lo1, e);
    for (; i < n; ++i) {
        const uint64_t a = std::bit_cast<uint64_t>(x[i]) & kAbsMask;
        e.merge(Extremes{a, a - 1});
    }
}

// ---- the double-double volume alone ----------------------------------------
//
// A block's 32 terms (h, lo) and magnitudes by Sum2 in 8 lanes of 4 (lane j:
// triangles j, j + 8, j + 16, j + 24), then the lanes into one (sum, error)
// pair by a two_sum tree 8 -> 4 -> 2 -> 1. The 8 lanes are kQ vectors of kN.

constexpr int kVolLanes = 8;
constexpr int kQ = kVolLanes / kN;
constexpr int kGroups = kBlock / kVolLanes;  // 4

struct VolumeSums {
    double s, e, m;
};

// The tree's levels within a vector, down to one lane.
template <class DT, class VT = hn::Vec<DT>>
HWY_INLINE VolumeSums fold_vector(DT dt, VT s, VT e, VT m) {
#if HWY_TARGET != HWY_SCALAR
    if constexpr (hn::MaxLanes(DT()) > 1) {
        const hn::Half<DT> dh;
        using VH = hn::Vec<hn::Half<DT>>;
        const VH sa = hn::LowerHalf(dh, s), sb = hn::UpperHalf(dh, s);
        VH ns, t;
        two_sum(sa, sb, ns, t);
        const VH ne = (hn::LowerHalf(dh, e) + hn::UpperHalf(dh, e)) + t;
        const VH nm = hn::LowerHalf(dh, m) + hn::UpperHalf(dh, m);
        return fold_vector(dh, ns, ne, nm);
    }
#endif
    (void)dt;
    return VolumeSums{hn::GetLane(s), hn::GetLane(e), hn::GetLane(m)};
}

template <bool kTranslate>
struct VolumeLanes {
    V S[kQ], E[kQ], M[kQ];

    // Group g's terms (h, lo, magnitude) of lanes [q kN, q kN + kN).
    HWY_INLINE void add(int g, int q, V h, V lo, V perm) {
        if (g == 0) {
            S[q] = h;
            E[q] = lo;
            M[q] = kTranslate ? perm : hn::Zero(D());
            return;
        }
        V ns, ne;
        two_sum(S[q], h, ns, ne);
        S[q] = ns;
        E[q] = E[q] + (ne + lo);
        if constexpr (kTranslate) M[q] = M[q] + perm;
    }

    HWY_INLINE VolumeSums fold() {
        for (int n = kQ; n > 1; n /= 2) {
            for (int q = 0; q < n / 2; ++q) {
                V s, t;
                two_sum(S[q], S[q + n / 2], s, t);
                S[q] = s;
                E[q] = (E[q] + E[q + n / 2]) + t;
                M[q] = M[q] + M[q + n / 2];
            }
        }
        return fold_vector(D(), S[0], E[0], M[0]);
    }
};

// The volume terms of kN triangles: det as (h, lo) and its magnitude.
template <bool kTranslate>
HWY_INLINE void volume_terms(const V (&a)[3], const V (&b)[3], const V (&c)[3], V& h, V& lo, V& perm) {
    V hh[1], ll[1], mm[1] = {hn::Zero(D())};
    terms_dd<1, kTranslate>(a, b, c, hh, ll, mm);
    h = hh[0];
    lo = ll[0];
    perm = mm[0];
}

// A gathered block's volume sums; kCheck: its coordinates into the range
// check's lanes.
template <bool kTranslate, bool kCheck>
HWY_INLINE VolumeSums volume_block(const Block& blk, VU& hi_io, VU& lo_io) {
    VolumeLanes<kTranslate> lanes;
    VU hi = hi_io, lo = lo_io;  // in registers: through the references every step is a load and a store
    for (int g = 0; g < kGroups; ++g) {
        for (int q = 0; q < kQ; ++q) {
            V a[3], b[3], c[3];
            rows_of_block(blk, kVolLanes * g + kN * q, a, b, c);
            if constexpr (kCheck) {
                for (int k = 0; k < 3; ++k) {
                    extremes_step(a[k], hi, lo);
                    extremes_step(b[k], hi, lo);
                    extremes_step(c[k], hi, lo);
                }
            }
            V h, l, m;
            volume_terms<kTranslate>(a, b, c, h, l, m);
            lanes.add(g, q, h, l, m);
        }
    }
    hi_io = hi;
    lo_io = lo;
    return lanes.fold();
}

#if POLYVOL_ROWS_AVX2
// A whole block of an all-triangle mesh (t: its 96 indices;
// block_loads_within holds) from the positions, its rows never stored:
// the same values and sums as volume_block on the gathered block.
template <bool kTranslate, bool kCheck>
HWY_INLINE VolumeSums volume_block_in_registers(const double* pos, const uint32_t* t, VU& hi_io, VU& lo_io) {
    VolumeLanes<kTranslate> lanes;
    VU hi = hi_io, lo = lo_io;  // in registers: through the references every step is a load and a store
    for (int g = 0; g < kGroups; ++g) {
        for (int q = 0; q < kQ; ++q) {
            V a[3], b[3], c[3];
            rows_of_mesh(pos, t + 3 * (kVolLanes * g + kN * q), a, b, c);
            if constexpr (kCheck) {
                for (int k = 0; k < 3; ++k) {
                    extremes_step(a[k], hi, lo);
                    extremes_step(b[k], hi, lo);
                    extremes_step(c[k], hi, lo);
                }
            }
            V h, l, m;
            volume_terms<kTranslate>(a, b, c, h, l, m);
            lanes.add(g, q, h, l, m);
        }
    }
    hi_io = hi;
    lo_io = lo;
    return lanes.fold();
}
#endif

constexpr int kGroupBlocks = 4;  // blocks per superaccumulator pair

// Faces [f0, f1) into acc: the blocks' pairs in groups of kGroupBlocks by
// two_sum and plain additions, each group's pair into the superaccumulator;
// the blocks' magnitudes (translated form) summed in double over the range
// (a fixed range: the same bits for every split of the work), then exactly.
template <bool kTranslate, RangeCheck kCheck>
HWY_INLINE void volume_faces_in(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeAccumulator& acc) {
    constexpr bool kReferenced = kCheck == RangeCheck::referenced;
    const DU du;
    VU hi = hn::Zero(du), lo = hn::Set(du, ~uint64_t{0});
    double magnitude = 0;
    std::size_t triangles = 0;
    double gs = 0, ge = 0;
    int grouped = 0;
    const auto add = [&](const VolumeSums& v, int n) {
        if (grouped == 0) {
            gs = v.s;
            ge = v.e;
        } else {
            double ns, t;
            exact::two_sum(gs, v.s, ns, t);
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
    const double* pos = mesh.positions.data();
    const std::size_t nv = mesh.vertex_count();
    walk_blocks(
        mesh, f0, f1,
        [&](const uint32_t* t) {
#if POLYVOL_ROWS_AVX2
            if (block_loads_within(nv, t)) {
                add(volume_block_in_registers<kTranslate, kReferenced>(pos, t, hi, lo), kBlock);
                return true;
            }
#endif
            (void)t;
            return false;
        },
        [&](const Block& b) { add(volume_block<kTranslate, kReferenced>(b, hi, lo), b.n); });
    if (grouped > 0) {
        acc.sum.add(gs);
        acc.sum.add(ge);
    }
    acc.magnitude.add(magnitude);
    acc.triangles += triangles;
    if constexpr (kReferenced) {
        merge_lanes(hi, lo, acc.range);
    } else if constexpr (kCheck == RangeCheck::positions) {
        // Vertices [f0 nv / nf, f1 nv / nf): the ranges' slices tile them.
        __extension__ typedef unsigned __int128 u128;
        const std::size_t nf = mesh.face_count();
        const auto v0 = static_cast<std::size_t>(u128{f0} * nv / nf), v1 = static_cast<std::size_t>(u128{f1} * nv / nf);
        Extremes e;
        extremes_in(pos + 3 * v0, 3 * (v1 - v0), e);
        acc.range.merge(e);
    } else {
        acc.range.hi = ~uint64_t{0};  // not checked: never safe()
    }
}

// ---- every other filtered sum --------------------------------------------------

// Per-triangle terms of a block: term k of triangle i is h[k][i] + l[k][i]
// (l: double-double only), with magnitude m[k][i].
template <int N>
struct Terms {
    alignas(64) double h[N][kBlock];
    alignas(64) double l[N][kBlock];
    alignas(64) double m[N][kBlock];
};

template <int N>
HWY_INLINE void block_terms(const Block& blk, bool dd, Terms<N>& t) {
    const D d;
    for (int i = 0; i < kBlock; i += kN) {
        V a[3], b[3], c[3], h[N], l[N], m[N];
        rows_of_block(blk, i, a, b, c);
        if (dd) {
            terms_dd<N>(a, b, c, h, l, m);
            for (int k = 0; k < N; ++k) hn::Store(l[k], d, &t.l[k][i]);
        } else {
            terms_fast<N>(a, b, c, h, m);
        }
        for (int k = 0; k < N; ++k) {
            hn::Store(h[k], d, &t.h[k][i]);
            hn::Store(m[k], d, &t.m[k][i]);
        }
    }
}

// Sum2 in 4 lanes of 8 (lane j: triangles j, j + 4, ...), then each lane's
// (sum, error) pair into the superaccumulator.
template <int N>
HWY_INLINE void accumulate(const Terms<N>& t, bool dd, Accumulator<N>& acc) {
    constexpr int kLanes = 4, kPerLane = kBlock / kLanes;
    for (int k = 0; k < N; ++k) {
        double s[kLanes] = {}, e[kLanes] = {}, m[kLanes] = {};
        if (dd) {
            for (int r = 0; r < kPerLane; ++r) {
                for (int j = 0; j < kLanes; ++j) {
                    const int i = r * kLanes + j;
                    double ns, ne;
                    exact::two_sum(s[j], t.h[k][i], ns, ne);
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
            acc.sum[k].add(s[j]);
            if (dd) acc.sum[k].add(e[j]);
        }
        acc.magnitude[k].add((m[0] + m[1]) + (m[2] + m[3]));
    }
}

// Calls fn(block) over the blocks of faces [f0, f1), whole blocks of an
// all-triangle mesh gathered with vector loads where the target can.
template <class Fn>
HWY_INLINE void gathered_blocks(const MeshView& mesh, std::size_t f0, std::size_t f1, Fn&& fn) {
    const double* pos = mesh.positions.data();
    const std::size_t nv = mesh.vertex_count();
    Block whole_block;
    walk_blocks(
        mesh, f0, f1,
        [&](const uint32_t* t) {
            if (!gather_block_in_registers(pos, nv, t, whole_block)) return false;
            fn(whole_block);
            return true;
        },
        fn);
}

template <int N>
HWY_INLINE void sums_in(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<N>& acc) {
    gathered_blocks(mesh, f0, f1, [&](const Block& b) {
        acc.triangles += static_cast<std::size_t>(b.n);
        Terms<N> t;
        block_terms<N>(b, dd, t);
        accumulate<N>(t, dd, acc);
    });
}

// ---- exact terms -----------------------------------------------------------------

constexpr bool kFma = HWY_NATIVE_FMA != 0;

// A compressed nonoverlapping expansion of the sum of n doubles.
HWY_INLINE int expansion_of(const double* x, int n, double* h) {
    int len = 0;
    for (int i = 0; i < n; ++i) len = exact::grow_expansion(len, h, x[i], h);
    return exact::compress(len, h, h);
}

// Every product x_i y_j into acc, exactly (two_prod).
HWY_INLINE void add_product(const double* x, int nx, const double* y, int ny, ExactSum& acc) {
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            double p, e;
            exact::two_prod_t<kFma>(x[i], y[j], p, e);
            acc.add(p);
            acc.add(e);
        }
    }
}

// The exact terms of a block: as integers where integer_triangle can, else
// det as an expansion (det3_exact), s and q as expansions, and every product
// of their components by two_prod.
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
            if (mask & (1u << (kMx + k))) add_product(d, nd, s[k], ns[k], acc[kMx + k]);
        }
        constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
        for (int k = 0; k < 6; ++k) {
            if (!(mask & (1u << (kSxx + k)))) continue;
            const int x = I[k], y = J[k];
            double raw[6 + 18];
            exact::two_prod_t<kFma>(a[x], a[y], raw[0], raw[1]);
            exact::two_prod_t<kFma>(bb[x], bb[y], raw[2], raw[3]);
            exact::two_prod_t<kFma>(cc[x], cc[y], raw[4], raw[5]);
            int n = 6;
            for (int p = 0; p < ns[x]; ++p)
                for (int r = 0; r < ns[y]; ++r, n += 2) exact::two_prod_t<kFma>(s[x][p], s[y][r], raw[n], raw[n + 1]);
            double q[32];
            const int nq = expansion_of(raw, n, q);
            add_product(d, nd, q, nq, acc[kSxx + k]);
        }
    }
}

}  // namespace

// ---- the entry points, one per target (dispatched below) ----------------------

void VolumeFaces(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeForm form, RangeCheck check,
                 VolumeAccumulator& acc) {
    const bool translate = form == VolumeForm::translated;
    switch (check) {
        case RangeCheck::none:
            return translate ? volume_faces_in<true, RangeCheck::none>(mesh, f0, f1, acc)
                             : volume_faces_in<false, RangeCheck::none>(mesh, f0, f1, acc);
        case RangeCheck::positions:
            return translate ? volume_faces_in<true, RangeCheck::positions>(mesh, f0, f1, acc)
                             : volume_faces_in<false, RangeCheck::positions>(mesh, f0, f1, acc);
        case RangeCheck::referenced:
            return translate ? volume_faces_in<true, RangeCheck::referenced>(mesh, f0, f1, acc)
                             : volume_faces_in<false, RangeCheck::referenced>(mesh, f0, f1, acc);
    }
}

void VolumeBlock(const Block& b, ExactSum& sum, ExactSum& magnitude) {
    const DU du;
    VU hi = hn::Zero(du), lo = hn::Zero(du);
    const VolumeSums v = volume_block<true, false>(b, hi, lo);
    sum.add(v.s);
    sum.add(v.e);
    magnitude.add(v.m);
}

void Sums1(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<1>& acc) {
    sums_in<1>(mesh, f0, f1, dd, acc);
}
void Sums4(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSxx>& acc) {
    sums_in<kSxx>(mesh, f0, f1, dd, acc);
}
void Sums10(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSumCount>& acc) {
    sums_in<kSumCount>(mesh, f0, f1, dd, acc);
}

void ExactFaces(const MeshView& mesh, std::size_t f0, std::size_t f1, uint32_t mask, Accumulator<kSumCount>& acc) {
    gathered_blocks(mesh, f0, f1, [&](const Block& b) {
        acc.triangles += static_cast<std::size_t>(b.n);
        exact_block(b, mask, acc.sum);
    });
}

void ExactBlock(const Block& b, uint32_t mask, ExactSum* acc) { exact_block(b, mask, acc); }

void ExtremesOf(const double* x, std::size_t n, Extremes& e) { extremes_in(x, n, e); }

bool ChecksWhatItReads() { return POLYVOL_ROWS_AVX512 != 0; }

#undef POLYVOL_ROWS_AVX2
#undef POLYVOL_ROWS_AVX512

}  // namespace polyvol::measure::cone::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace polyvol::measure::cone {

// POLYVOL_MAX_ISA, before the first dispatch.
[[maybe_unused]] const bool g_environment_applied = (simd::limit_from_environment(), true);

HWY_EXPORT(VolumeFaces);
HWY_EXPORT(VolumeBlock);
HWY_EXPORT(Sums1);
HWY_EXPORT(Sums4);
HWY_EXPORT(Sums10);
HWY_EXPORT(ExactFaces);
HWY_EXPORT(ExactBlock);
HWY_EXPORT(ExtremesOf);
HWY_EXPORT(ChecksWhatItReads);

void volume_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeForm form, RangeCheck check,
                  VolumeAccumulator& acc) {
    HWY_DYNAMIC_DISPATCH(VolumeFaces)(mesh, f0, f1, form, check, acc);
}
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<1>& acc) {
    HWY_DYNAMIC_DISPATCH(Sums1)(mesh, f0, f1, dd, acc);
}
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSxx>& acc) {
    HWY_DYNAMIC_DISPATCH(Sums4)(mesh, f0, f1, dd, acc);
}
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSumCount>& acc) {
    HWY_DYNAMIC_DISPATCH(Sums10)(mesh, f0, f1, dd, acc);
}
void exact_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, uint32_t mask, Accumulator<kSumCount>& acc) {
    HWY_DYNAMIC_DISPATCH(ExactFaces)(mesh, f0, f1, mask, acc);
}
void extremes_of(const double* x, std::size_t n, Extremes& e) { HWY_DYNAMIC_DISPATCH(ExtremesOf)(x, n, e); }
bool kernels_check_what_they_read() { return HWY_DYNAMIC_DISPATCH(ChecksWhatItReads)(); }

void filtered_volume_block(const TriangleBlock& b, exact::ExactSum& sum, exact::ExactSum& magnitude) {
    HWY_DYNAMIC_DISPATCH(VolumeBlock)(b, sum, magnitude);
}
void exact_block_sums(const TriangleBlock& b, uint32_t mask, exact::ExactSum* acc) {
    HWY_DYNAMIC_DISPATCH(ExactBlock)(b, mask, acc);
}

}  // namespace polyvol::measure::cone
#endif  // HWY_ONCE
