// The streaming cone volume: blocks of piece records reduced on oneTBB
// workers, combined in block order (the error analysis is in cone_sum.hpp).
#include "implicit/cone_sum.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include <tbb/task_arena.h>

#include "core/simd.hpp"
#include "implicit/surface.hpp"

// Vec values cross no call boundary (lane_abs and eliminate are always
// inlined into eliminate_avx2), so GCC's note that returning them would change
// the ABI without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace polyvol::implicit {

namespace {

constexpr double kUnit = 0x1p-53;
constexpr double kSlack = 1.0 + 0x1p-18;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

constexpr double rounding_gamma(double k) { return k * kUnit / (1.0 - k * kUnit); }

// det(p_1 - O, ..., p_n - O) as det(p_1 - O, p_2 - p_1, ..., p_n - p_1) by
// Gaussian elimination with partial pivoting, and its bound (cone_sum.hpp),
// for a batch of kLanes pieces at once: the elimination's critical path
// (pivot search, row exchange, division, update) is long and a single 6 x 6
// elimination leaves the core mostly idle, so kLanes independent ones run side
// by side, the row exchanges done by selects rather than through memory. V is
// the lane type: a vector of kLanes doubles (with AVX2 where the processor
// has it) or double (the portable path, one lane at a time); both run the
// same operations in the same order on every lane, so they give the same bits.
// N is the dimension (a template parameter: fixed-size loops unroll).
constexpr int kLanes = 4;
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

// The batch of pieces waiting for a kernel: matrices M in lanes.
template <int N>
struct Batch {
    alignas(32) double a[N][N][kLanes];
    double det[kLanes], bound[kLanes];
    int count = 0;
};

template <int N>
void eliminate_portable(Batch<N>& b) {
    for (int lane = 0; lane < kLanes; ++lane) {
        double a[N][N];
        for (int r = 0; r < N; ++r)
            for (int c = 0; c < N; ++c) a[r][c] = b.a[r][c][lane];
        eliminate<N, double>(a, b.det[lane], b.bound[lane]);
    }
}

#if defined(__x86_64__) && defined(__GNUC__)
template <int N>
__attribute__((target("avx2"))) void eliminate_avx2(Batch<N>& b) {
    Vec a[N][N];
    for (int r = 0; r < N; ++r)
        for (int c = 0; c < N; ++c) std::memcpy(&a[r][c], b.a[r][c], sizeof(Vec));
    Vec det, bound;
    eliminate<N, Vec>(a, det, bound);
    std::memcpy(b.det, &det, sizeof(Vec));
    std::memcpy(b.bound, &bound, sizeof(Vec));
}

// simd::level: the library's one CPU detection.
bool use_avx2() { return simd::level() >= simd::Level::avx2; }
#endif

// Runs the batch's kernel (lanes past count repeat lane 0 and are ignored).
template <int N>
void eliminate_batch(Batch<N>& b) {
    for (int lane = b.count; lane < kLanes; ++lane)
        for (int r = 0; r < N; ++r)
            for (int c = 0; c < N; ++c) b.a[r][c][lane] = b.a[r][c][0];
#if defined(__x86_64__) && defined(__GNUC__)
    if (use_avx2()) {
        eliminate_avx2<N>(b);
        return;
    }
#endif
    eliminate_portable<N>(b);
}

// The pieces of a block's records (cone_sum.hpp), summed in order.
template <int N>
ConeTotals reduce_records(const std::vector<PieceRecord>& records, const Lattice& lattice, const double* apex) {
    const PieceTable& surface = piece_table(N);
    const PieceTable& closure = closure_table(N - 1);
    ConeTotals t;
    std::array<Index, kMaxDim + 1> v;
    std::array<std::array<double, 2>, N> x;  // x[k][i]: coordinate k of the lattice plane corner_k + i
    // The points of one record, by (positive, negative) vertex pair.
    std::array<std::array<double, N>, (N + 1) * (N + 1)> points;
    std::array<uint8_t, (N + 1) * (N + 1)> known;
    std::array<const double*, kMaxDim> piece;
    Batch<N> batch;
    // Adds the batch's determinants to the totals, in piece order.
    auto flush = [&] {
        eliminate_batch<N>(batch);
        for (int lane = 0; lane < batch.count; ++lane) {
            const double det = batch.det[lane];
            t.sum += det;
            t.abs_sum += std::abs(det);
            t.bound += std::isfinite(det) && std::isfinite(batch.bound[lane]) ? batch.bound[lane] : kInfinity;
            ++t.pieces;
        }
        batch.count = 0;
    };
    for (const PieceRecord& r : records) {
        const bool surface_piece = r.axis < 0;
        kuhn_vertices(r.s, surface_piece ? N : N - 1, v);
        for (int k = 0; k < N; ++k) {
            x[k][0] = lattice.coordinate(k, r.s.corner[k]);
            x[k][1] = lattice.coordinate(k, r.s.corner[k] + 1);  // unused on a face's own axis
        }
        const PieceTable& table = surface_piece ? surface : closure;
        const bool flip = surface_piece ? permutation_odd(r.s.perm, N) : closure_flip(r.s, r.axis, r.hi_face, N);
        known.fill(0);
        for (uint32_t q = table.offsets[r.mask]; q < table.offsets[r.mask + 1]; ++q) {
            for (int i = 0; i < N; ++i) {
                const auto& e = table.vertices[static_cast<std::size_t>(q) * N + i];
                const int slot = e[0] * (N + 1) + e[1];
                if (!known[slot]) {
                    // piece_point, with the lattice coordinates looked up.
                    const Index& a = v[e[1]];
                    const Index& b = v[e[0]];
                    const double tt = e[0] == e[1] ? 0.0 : crossing_parameter(r.f[e[1]], r.f[e[0]]);
                    for (int k = 0; k < N; ++k)
                        points[slot][k] = crossing_coordinate(x[k][a[k] - r.s.corner[k]], x[k][b[k] - r.s.corner[k]],
                                                              a[k] != b[k], tt);
                    known[slot] = 1;
                }
                piece[i] = points[slot].data();
            }
            if (flip) std::swap(piece[0], piece[1]);
            // M = fl([p_1 - O, p_2 - p_1, ..., p_n - p_1]) into the next lane.
            for (int k = 0; k < N; ++k) {
                batch.a[k][0][batch.count] = piece[0][k] - apex[k];
                for (int c = 1; c < N; ++c) batch.a[k][c][batch.count] = piece[c][k] - piece[0][k];
            }
            if (++batch.count == kLanes) flush();
        }
    }
    if (batch.count > 0) flush();
    return t;
}

}  // namespace

ConeSum::ConeSum(const Lattice& lattice) : lattice_(lattice), block_size_(2048) {
    for (int k = 0; k < lattice.n; ++k) apex_[k] = lattice.lo[k];
    current_ = take_block();
}

ConeSum::~ConeSum() {
    try {
        group_.wait();
    } catch (...) {  // an exception from a worker is already being dropped with this object
    }
}

ConeSum::Block* ConeSum::take_block() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!free_.empty()) {
            Block* b = free_.back();
            free_.pop_back();
            return b;
        }
    }
    blocks_.push_back(std::make_unique<Block>());
    blocks_.back()->records.reserve(block_size_);
    return blocks_.back().get();
}

void ConeSum::add(const PieceRecord& record) {
    // A closure piece in a lo face lies in the hyperplane x_axis = lo_axis,
    // which holds the apex: its determinant has a zero row.
    if (record.axis >= 0 && !record.hi_face) return;
    current_->records.push_back(record);
    if (current_->records.size() >= block_size_) submit();
}

// Hands the current block to a worker; with too many blocks in flight (the
// walk outruns the workers) the walk's thread reduces it itself, which keeps
// memory bounded.
void ConeSum::submit() {
    if (current_->records.empty()) return;
    totals_.emplace_back();
    current_->totals = &totals_.back();  // std::deque: push_back keeps references valid
    const int limit = 4 * tbb::this_task_arena::max_concurrency();
    if (in_flight_.load() >= limit) {
        reduce(*current_);
        current_->records.clear();
        return;
    }
    ++in_flight_;
    Block* block = current_;
    group_.run([this, block] {
        reduce(*block);
        block->records.clear();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            free_.push_back(block);
        }
        --in_flight_;
    });
    current_ = take_block();
}

void ConeSum::reduce(const Block& block) const {
    static_assert(kMaxDim == 8, "reduce dispatches n = 2 .. 8");
    ConeTotals t;
    switch (lattice_.n) {
        case 2: t = reduce_records<2>(block.records, lattice_, apex_.data()); break;
        case 3: t = reduce_records<3>(block.records, lattice_, apex_.data()); break;
        case 4: t = reduce_records<4>(block.records, lattice_, apex_.data()); break;
        case 5: t = reduce_records<5>(block.records, lattice_, apex_.data()); break;
        case 6: t = reduce_records<6>(block.records, lattice_, apex_.data()); break;
        case 7: t = reduce_records<7>(block.records, lattice_, apex_.data()); break;
        default: t = reduce_records<8>(block.records, lattice_, apex_.data()); break;
    }
    *block.totals = t;
}

void ConeSum::finish() {
    if (finished_) return;
    submit();
    group_.wait();
    finished_ = true;
    // Σ_b S_b in block order; the summation errors (cone_sum.hpp).
    double sum = 0, block_bounds = 0, abs_blocks = 0;
    std::size_t pieces = 0;
    for (const ConeTotals& t : totals_) {
        sum += t.sum;
        abs_blocks += std::abs(t.sum);
        block_bounds += t.bound + rounding_gamma(static_cast<double>(t.pieces)) * t.abs_sum;
        pieces += t.pieces;
    }
    const double blocks = static_cast<double>(totals_.size());
    // The bound's own rounding: sums of at most `pieces` non-negative terms.
    const double slack = kSlack + 4 * static_cast<double>(pieces + totals_.size()) * kUnit;
    const double n_factorial = static_cast<double>(factorial(lattice_.n));  // exact for n <= 18
    volume_ = sum / n_factorial;
    bound_ = slack * ((block_bounds + rounding_gamma(blocks) * abs_blocks) / n_factorial + kUnit * std::abs(volume_));
    if (!std::isfinite(volume_)) bound_ = kInfinity;
}

}  // namespace polyvol::implicit
