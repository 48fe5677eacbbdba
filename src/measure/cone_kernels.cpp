// measure/cone_kernels.cpp — the cone rule's passes over a face range,
// compiled once per instruction set (Highway's foreach_target) and chosen at
// run time by the library's dispatch (core/hwy_dispatch.hpp): gather the fan triangles of the faces
// (cone_gather-inl.h), form their terms (cone_terms-inl.h: what is summed),
// and sum them (Sum2 in lanes, then a superaccumulator: how). The error analysis is in docs/numerics.md, "The cone rule's kernels".
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
#include "measure/cone_gather-inl.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <span>

#include "exact/eft.hpp"
#include "exact/expansion.hpp"

HWY_BEFORE_NAMESPACE();
namespace polyvol::measure::cone::HWY_NAMESPACE {
namespace {

using exact::ExactSum;

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
        const uint64_t a = core::bit_cast<uint64_t>(x[i]) & kAbsMask;
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
        sum2_add(S[q], E[q], h, lo);
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

// A block's volume sums, its rows of kN triangles from rows(i, a, b, c)
// (triangles i .. i + kN - 1); kCheck: its coordinates into the range
// check's lanes.
template <bool kTranslate, bool kCheck, class Rows>
HWY_INLINE VolumeSums volume_block_of(Rows&& rows, VU& hi_io, VU& lo_io) {
    VolumeLanes<kTranslate> lanes;
    VU hi = hi_io, lo = lo_io;  // in registers: through the references every step is a load and a store
    for (int g = 0; g < kGroups; ++g) {
        for (int q = 0; q < kQ; ++q) {
            V a[3], b[3], c[3];
            rows(kVolLanes * g + kN * q, a, b, c);
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

// A gathered block's volume sums.
template <bool kTranslate, bool kCheck>
HWY_INLINE VolumeSums volume_block(const Block& blk, VU& hi, VU& lo) {
    return volume_block_of<kTranslate, kCheck>(
        [&](int i, V(&a)[3], V(&b)[3], V(&c)[3]) HWY_ATTR { rows_of_block(blk, i, a, b, c); }, hi, lo);
}

#if POLYVOL_ROWS_AVX2
// A whole block of an all-triangle mesh (t: its 96 indices;
// block_loads_within holds) from the positions, its rows never stored:
// the same values and sums as volume_block on the gathered block.
template <bool kTranslate, bool kCheck>
HWY_INLINE VolumeSums volume_block_in_registers(const double* pos, const uint32_t* t, VU& hi, VU& lo) {
    return volume_block_of<kTranslate, kCheck>(
        [&](int i, V(&a)[3], V(&b)[3], V(&c)[3]) HWY_ATTR { rows_of_mesh(pos, t + 3 * i, a, b, c); }, hi, lo);
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
    const auto add = [&](const VolumeSums& v, int n) HWY_ATTR {
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
        [&](const uint32_t* t) HWY_ATTR {
#if POLYVOL_ROWS_AVX2
            if (block_loads_within(nv, t)) {
                add(volume_block_in_registers<kTranslate, kReferenced>(pos, t, hi, lo), kBlock);
                return true;
            }
#endif
            (void)t;
            return false;
        },
        [&](const Block& b) HWY_ATTR { add(volume_block<kTranslate, kReferenced>(b, hi, lo), b.n); });
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
HWY_INLINE void accumulate(const Terms<N>& t, bool dd, ExactSum* sum, ExactSum* magnitude) {
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
            sum[k].add(s[j]);
            if (dd) sum[k].add(e[j]);
        }
        magnitude[k].add((m[0] + m[1]) + (m[2] + m[3]));
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
        [&](const uint32_t* t) HWY_ATTR {
            if (!gather_block_in_registers(pos, nv, t, whole_block)) return false;
            fn(whole_block);
            return true;
        },
        fn);
}

template <int N>
HWY_INLINE void sums_in(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<N>& acc) {
    gathered_blocks(mesh, f0, f1, [&](const Block& b) HWY_ATTR {
        acc.triangles += static_cast<std::size_t>(b.n);
        Terms<N> t;
        block_terms<N>(b, dd, t);
        accumulate<N>(t, dd, acc.sum, acc.magnitude);
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

void FirstMomentsBlock(const Block& b, ExactSum* sum, ExactSum* magnitude) {
    Terms<kSxx> t;
    block_terms<kSxx>(b, true, t);
    accumulate<kSxx>(t, true, sum, magnitude);
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
    gathered_blocks(mesh, f0, f1, [&](const Block& b) HWY_ATTR {
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
#include "core/hwy_dispatch.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::measure::cone {

void volume_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, VolumeForm form, RangeCheck check,
                  VolumeAccumulator& acc) {
    POLYVOL_DISPATCH(VolumeFaces)(mesh, f0, f1, form, check, acc);
}
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<1>& acc) {
    POLYVOL_DISPATCH(Sums1)(mesh, f0, f1, dd, acc);
}
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSxx>& acc) {
    POLYVOL_DISPATCH(Sums4)(mesh, f0, f1, dd, acc);
}
void sums_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, bool dd, Accumulator<kSumCount>& acc) {
    POLYVOL_DISPATCH(Sums10)(mesh, f0, f1, dd, acc);
}
void exact_faces(const MeshView& mesh, std::size_t f0, std::size_t f1, uint32_t mask, Accumulator<kSumCount>& acc) {
    POLYVOL_DISPATCH(ExactFaces)(mesh, f0, f1, mask, acc);
}
void extremes_of(const double* x, std::size_t n, Extremes& e) { POLYVOL_DISPATCH(ExtremesOf)(x, n, e); }
bool kernels_check_what_they_read() { return POLYVOL_DISPATCH(ChecksWhatItReads)(); }

void filtered_volume_block(const TriangleBlock& b, exact::ExactSum& sum, exact::ExactSum& magnitude) {
    POLYVOL_DISPATCH(VolumeBlock)(b, sum, magnitude);
}
void filtered_first_moments_block(const TriangleBlock& b, exact::ExactSum* sum, exact::ExactSum* magnitude) {
    POLYVOL_DISPATCH(FirstMomentsBlock)(b, sum, magnitude);
}

void exact_block_sums(const TriangleBlock& b, uint32_t mask, exact::ExactSum* acc) {
    POLYVOL_DISPATCH(ExactBlock)(b, mask, acc);
}

}  // namespace polyvol::measure::cone
#endif  // HWY_ONCE
