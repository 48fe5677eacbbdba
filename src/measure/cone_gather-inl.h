// measure/cone_gather-inl.h — the fan triangles of a mesh's faces as rows
// of coordinates, for the cone kernels (cone_kernels.cpp): blocks of 32 in
// structure of arrays (Block: c[3 v + k][i], coordinate k of vertex v of
// triangle i), or, on AVX2 and AVX-512, rows of kN triangles built in
// registers straight from the positions. Every way gives the same values.
//
// Included once per target by cone_kernels.cpp (Highway's foreach_target).
#if defined(POLYVOL_MEASURE_CONE_GATHER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef POLYVOL_MEASURE_CONE_GATHER_INL_H_
#undef POLYVOL_MEASURE_CONE_GATHER_INL_H_
#else
#define POLYVOL_MEASURE_CONE_GATHER_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "measure/cone_kernels.hpp"
#include "measure/cone_terms-inl.h"

#if HWY_ARCH_X86
#include <immintrin.h>
#endif

#undef POLYVOL_ROWS_AVX2
#undef POLYVOL_ROWS_AVX512

HWY_BEFORE_NAMESPACE();
namespace polyvol::measure::cone::HWY_NAMESPACE {

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
// unpacks and three lane permutations), where hardware gathers and masked
// loads of three doubles would wait on every lane.
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
    const auto put = [&](uint32_t va, uint32_t vb, uint32_t vc) HWY_ATTR {
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

}  // namespace polyvol::measure::cone::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // POLYVOL_MEASURE_CONE_GATHER_INL_H_
