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

#include "implicit/eliminate.hpp"
#include "implicit/surface.hpp"

namespace polyvol::implicit {

namespace {

constexpr double kUnit = 0x1p-53;
constexpr double kSlack = 1.0 + 0x1p-18;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

constexpr double rounding_gamma(double k) { return k * kUnit / (1.0 - k * kUnit); }

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
        eliminate_batch(batch);
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
