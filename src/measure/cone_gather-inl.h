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

#undef POLYVOL_ROWS_AVX2
#undef POLYVOL_ROWS_AVX512

HWY_BEFORE_NAMESPACE();
namespace polyvol::measure::cone::HWY_NAMESPACE {

// Highway's x86 targets: AVX2 and better load a vertex's (x, y, z, next)
// with one 256-bit load; AVX-512 puts two vertices in one register. (Written
// in Highway operations; only the load width is x86's.)
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

// Vertex v of triangles i and, on AVX-512, i + 4 (t: their indices): each
// (x, y, z, next) by one 256-bit load, the second in the upper half.
HWY_INLINE V vertex_quads(const double* pos, const uint32_t* t, int v, int i) {
#if POLYVOL_ROWS_AVX512
    const hn::Half<D> dh;
    return hn::Combine(D(), hn::LoadU(dh, pos + 3 * std::size_t{t[3 * (i + 4) + v]}),
                       hn::LoadU(dh, pos + 3 * std::size_t{t[3 * i + v]}));
#else
    return hn::LoadU(D(), pos + 3 * std::size_t{t[3 * i + v]});
#endif
}

// Vertex v of kN triangles (t: their 3 kN indices) as rows of x, y and z,
// lane j from triangle j, where hardware gathers and masked loads of three
// doubles would wait on every lane. Registers r_i hold triangles i (and
// i + 4) as (x, y, z, next); per 128-bit block, interleaving r_0 with r_1
// gives (x0 x1 | z0 z1), r_2 with r_3 (x2 x3 | z2 z3). The x row is then
// the lower halves of both (AVX2), or, with a second pair of triangles in
// the upper 256 bits (AVX-512), the even blocks of the first and the odd
// of the second swapped.
HWY_INLINE void rows_of_vertex(const double* pos, const uint32_t* t, int v, V (&row)[3]) {
    const D d;
    V r[4];
    for (int i = 0; i < 4; ++i) r[i] = vertex_quads(pos, t, v, i);
    const V xz01 = hn::InterleaveLower(d, r[0], r[1]), y01 = hn::InterleaveUpper(d, r[0], r[1]);
    const V xz23 = hn::InterleaveLower(d, r[2], r[3]), y23 = hn::InterleaveUpper(d, r[2], r[3]);
    if constexpr (kN == 4) {
        row[0] = hn::ConcatLowerLower(d, xz23, xz01);
        row[1] = hn::ConcatLowerLower(d, y23, y01);
        row[2] = hn::ConcatUpperUpper(d, xz23, xz01);
    } else {
        row[0] = hn::OddEvenBlocks(hn::SwapAdjacentBlocks(xz23), xz01);
        row[1] = hn::OddEvenBlocks(hn::SwapAdjacentBlocks(y23), y01);
        row[2] = hn::OddEvenBlocks(xz23, hn::SwapAdjacentBlocks(xz01));
    }
}

// Rows of kN triangles (t: their 3 kN indices) straight from the positions;
// block_loads_within must hold for their block.
HWY_INLINE void rows_of_mesh(const double* pos, const uint32_t* t, V (&a)[3], V (&b)[3], V (&c)[3]) {
    rows_of_vertex(pos, t, 0, a);
    rows_of_vertex(pos, t, 1, b);
    rows_of_vertex(pos, t, 2, c);
}
#endif

// A whole block of an all-triangle mesh into blk (t: its 96 indices), or
// false when its loads would leave the positions (or the target has no
// vector loads of vertices): the values of the scalar gather.
HWY_INLINE bool gather_block_in_registers(const double* pos, std::size_t nv, const uint32_t* t, Block& blk) {
#if POLYVOL_ROWS_AVX2
    if (!block_loads_within(nv, t)) return false;
    const D d;
    for (int g = 0; g < kBlock; g += kN)
        for (int v = 0; v < 3; ++v) {
            V row[3];
            rows_of_vertex(pos, t + 3 * g, v, row);
            for (int k = 0; k < 3; ++k) hn::Store(row[k], d, &blk.c[3 * v + k][g]);
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
