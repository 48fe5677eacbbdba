// implicit/eliminate.cpp — the determinants of the streaming cone volume
// with their bounds, compiled once per instruction set (Highway's
// foreach_target) and chosen at run time by the library's dispatch
// (core/hwy_dispatch.hpp).
//
// det(p_1 - O, ..., p_n - O) as det(p_1 - O, p_2 - p_1, ..., p_n - p_1) by
// Gaussian elimination with partial pivoting, and its bound (cone_sum.hpp),
// for a batch of kLanes pieces at once: the elimination's critical path
// (pivot search, row exchange, division, update) is long and a single 6 x 6
// elimination leaves the core mostly idle, so kLanes independent ones run side
// by side, the row exchanges done by selects rather than through memory. V is
// a vector of kLanes doubles (GCC vector extension, lowered to what each
// target has): every operation is elementwise and rounded on its own
// (-ffp-contract=off), so every target gives the same bits.
// N is the dimension (a template parameter: fixed-size loops unroll).
#include "core/hwy_targets.hpp"  // before Highway

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "implicit/eliminate.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <cstring>

#include "implicit/eliminate.hpp"

// Vec values cross no call boundary (lane_abs and eliminate are always
// inlined into the per-target entry points), so GCC's note that returning
// them would change the ABI without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

HWY_BEFORE_NAMESPACE();
namespace polyvol::implicit::HWY_NAMESPACE {
namespace {

constexpr double kUnit = 0x1p-53;
constexpr double kSlack = 1.0 + 0x1p-18;

constexpr double rounding_gamma(double k) { return k * kUnit / (1.0 - k * kUnit); }

using Vec = double __attribute__((vector_size(8 * kLanes)));
using VecInt = int64_t __attribute__((vector_size(8 * kLanes)));

template <class V>
struct LaneTraits {
    using Int = int64_t;  // a pivot row per lane
};
template <>
struct LaneTraits<Vec> {
    using Int = VecInt;
};

template <class V>
[[gnu::always_inline]] inline V lane_abs(const V& x) {
    return x < 0 ? -x : x;
}

// a[r][c]: row r (a coordinate), column c (a point) of M; on return det and
// bound (before the non-finite check) per lane.
template <int N, class V>
[[gnu::always_inline]] inline void eliminate(V (&a)[N][N], V& det, V& bound) {
    using Int = typename LaneTraits<V>::Int;
    V norm1[N], alpha[N];  // ||M e_c||_1, and / (1 - u) >= ||M* e_c||_2
    for (int c = 0; c < N; ++c) {
        V s = a[0][c] - a[0][c];  // 0 in every lane
        for (int r = 0; r < N; ++r) s += lane_abs(a[r][c]);
        norm1[c] = s;
        alpha[c] = s / (1 - kUnit);
    }
    V sign = norm1[0] * 0 + 1;
    for (int k = 0; k < N; ++k) {
        Int best = Int{} + k;
        V largest = lane_abs(a[k][k]);
        for (int r = k + 1; r < N; ++r) {
            const V m = lane_abs(a[r][k]);
            best = m > largest ? Int{} + r : best;
            largest = m > largest ? m : largest;
        }
        sign = best != k ? -sign : sign;
        for (int r = k + 1; r < N; ++r) {  // exchange rows k and best, L's part too
            const auto exchange = best == r;
            for (int c = 0; c < N; ++c) {
                const V top = a[k][c];
                a[k][c] = exchange ? a[r][c] : top;
                a[r][c] = exchange ? top : a[r][c];
            }
        }
        // A zero pivot: the column below is zero too; L's column becomes 0.
        const V inverse = a[k][k] == 0 ? a[k][k] * 0 : 1 / a[k][k];
        for (int i = k + 1; i < N; ++i) {
            const V l = a[i][k] * inverse;
            a[i][k] = l;
            for (int c = k + 1; c < N; ++c) a[i][c] -= l * a[k][c];
        }
    }
    det = sign;
    for (int k = 0; k < N; ++k) det *= a[k][k];
    // ε_c = γ_{n+1} (|L| |U| e_c summed) + γ_1 ||M e_c||_1;
    // Π(α_c + ε_c) - Π α_c = Σ_c ε_c Π_{c' < c} α_c' Π_{c' > c} (α_c' + ε_c')
    // (non-negative terms, no cancellation).
    constexpr double gn = rounding_gamma(N + 1), g1 = rounding_gamma(1);
    V lcol[N];  // Σ_i |L_ik|, the unit diagonal included
    for (int k = 0; k < N; ++k) {
        V s = sign * 0 + 1;
        for (int i = k + 1; i < N; ++i) s += lane_abs(a[i][k]);
        lcol[k] = s;
    }
    V eps[N];
    for (int c = 0; c < N; ++c) {
        V lu = lcol[0] * lane_abs(a[0][c]);
        for (int k = 1; k <= c; ++k) lu += lcol[k] * lane_abs(a[k][c]);
        eps[c] = gn * lu + g1 * norm1[c];
    }
    V prefix[N];  // Π_{c' < c} α_c'
    prefix[0] = sign * 0 + 1;
    for (int c = 1; c < N; ++c) prefix[c] = prefix[c - 1] * alpha[c - 1];
    V spread = eps[N - 1] * prefix[N - 1], suffix = alpha[N - 1] + eps[N - 1];
    for (int c = N - 2; c >= 0; --c) {
        spread += eps[c] * prefix[c] * suffix;
        suffix *= alpha[c] + eps[c];
    }
    bound = kSlack * (gn * lane_abs(det) + spread);
}

template <int N>
HWY_INLINE void eliminate_in_lanes(Batch<N>& b) {
    for (int lane = b.count; lane < kLanes; ++lane)
        for (int r = 0; r < N; ++r)
            for (int c = 0; c < N; ++c) b.a[r][c][lane] = b.a[r][c][0];
    Vec a[N][N];
    for (int r = 0; r < N; ++r)
        for (int c = 0; c < N; ++c) std::memcpy(&a[r][c], b.a[r][c], sizeof(Vec));
    Vec det, bound;
    eliminate<N, Vec>(a, det, bound);
    std::memcpy(b.det, &det, sizeof(Vec));
    std::memcpy(b.bound, &bound, sizeof(Vec));
}

}  // namespace

void Eliminate2(Batch<2>& b) { eliminate_in_lanes<2>(b); }
void Eliminate3(Batch<3>& b) { eliminate_in_lanes<3>(b); }
void Eliminate4(Batch<4>& b) { eliminate_in_lanes<4>(b); }
void Eliminate5(Batch<5>& b) { eliminate_in_lanes<5>(b); }
void Eliminate6(Batch<6>& b) { eliminate_in_lanes<6>(b); }
void Eliminate7(Batch<7>& b) { eliminate_in_lanes<7>(b); }
void Eliminate8(Batch<8>& b) { eliminate_in_lanes<8>(b); }

}  // namespace polyvol::implicit::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "core/hwy_dispatch.hpp"

namespace polyvol::implicit {

void eliminate_batch(Batch<2>& b) { POLYVOL_DISPATCH(Eliminate2)(b); }
void eliminate_batch(Batch<3>& b) { POLYVOL_DISPATCH(Eliminate3)(b); }
void eliminate_batch(Batch<4>& b) { POLYVOL_DISPATCH(Eliminate4)(b); }
void eliminate_batch(Batch<5>& b) { POLYVOL_DISPATCH(Eliminate5)(b); }
void eliminate_batch(Batch<6>& b) { POLYVOL_DISPATCH(Eliminate6)(b); }
void eliminate_batch(Batch<7>& b) { POLYVOL_DISPATCH(Eliminate7)(b); }
void eliminate_batch(Batch<8>& b) { POLYVOL_DISPATCH(Eliminate8)(b); }

}  // namespace polyvol::implicit
#endif  // HWY_ONCE
