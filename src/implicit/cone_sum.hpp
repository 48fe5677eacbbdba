// Private to implicit: the streaming volume. The pieces of the PL surface are
// not collected into a chain; each crossed simplex (and each box-face simplex
// of the closure) is recorded as it is visited, records are buffered in
// blocks, and each block is reduced on a oneTBB worker to the sum of the
// cone determinants (Allgower & Schmidt 1986, formula (2.1)) of its pieces,
//   V = Σ_pieces det(p_1 - O, ..., p_n - O) / n!,
// with a rigorous bound on the rounding error. Blocks are formed in the
// order of the (deterministic, single-threaded) walk and their sums combined
// in that order, so the result has the same bits for every thread count; the
// determinants are taken four pieces at a time (AVX2 where present, the same
// bits without: cone_sum.cpp).
//
// The points are those of the chain path bit for bit (piece_point), so the
// streamed volume and chain_volume measure the same chain; the apex O is the
// box corner lo, so the closure pieces in the lo faces of the box (whose
// hyperplanes contain O) contribute exactly 0 and are not recorded.
//
// Error analysis of one piece (N. J. Higham, Accuracy and Stability of
// Numerical Algorithms, 2nd ed., Thm 9.3; u = 2^-53, γ_k = k u / (1 - k u)):
//   M* = [p_1 - O, p_2 - p_1, ..., p_n - p_1] (exact; det M* is the cone
//   determinant, by column operations; the short columns p_c - p_1 keep
//   Hadamard's inequality below close to |det|), M = fl(M*),
//   |M - M*| <= γ_1 |M|. Gaussian elimination with partial pivoting on M
//   (multipliers formed with the pivot's reciprocal, one rounding more than
//   Thm 9.3 counts) gives L U = P M + ΔM, |ΔM| <= γ_{n+1} |L| |U|, for the
//   computed L and U (the bound below uses their actual Σ_i |L_ik|); so
//   L U = P M* + E with
//     ||E e_c||_2 <= ||E e_c||_1 <= ε_c = γ_{n+1} Σ_k (Σ_i |L_ik|) |U_kc| + γ_1 ||M e_c||_1.
//   By multilinearity and Hadamard's inequality, with α_c = ||M e_c||_1 / (1 - u)
//   >= ||M* e_c||_2,
//     |det(L U) - det(P M*)| <= Π_c (α_c + ε_c) - Π_c α_c
//                            = Σ_c ε_c Π_{c' < c} α_c' Π_{c' > c} (α_c' + ε_c'),
//   and the computed product of U's diagonal d is within γ_{n+1} |d| of det(L U).
// Summation: a block's sum of m determinants is within γ_m Σ|d| of the exact
// sum, the blocks' sum within γ_B Σ_b |S_b| (B blocks), and V = S / n! adds
// u |V|. Every bound is itself computed in floating point from non-negative
// terms (relative error far below 2^-20) and multiplied by 1 + 2^-18. The
// analysis assumes no underflow (coordinates and determinants far above
// 2^-900); a non-finite determinant makes the bound infinite.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include <tbb/task_group.h>

#include "implicit/kuhn.hpp"

namespace polyvol::implicit {

struct Lattice;

// What the walk records for one simplex that has pieces.
struct PieceRecord {
    KuhnSimplex s;                       // a Kuhn n-simplex, or a face (n-1)-simplex (corner on the face)
    std::array<double, kMaxDim + 1> f;   // F at its vertices
    uint32_t mask = 0;                   // bit j: vertex j positive
    int8_t axis = -1;                    // -1: surface pieces; else the box face x_axis = lo/hi
    bool hi_face = false;                // the face is x_axis = hi_axis
};

// The sum of the determinants and its rounding bound.
struct ConeTotals {
    double sum = 0;        // Σ det (in block order)
    double abs_sum = 0;    // Σ |det|
    double bound = 0;      // Σ per-determinant bounds
    std::size_t pieces = 0;
};

class ConeSum {
public:
    explicit ConeSum(const Lattice& lattice);
    ~ConeSum();
    ConeSum(const ConeSum&) = delete;
    ConeSum& operator=(const ConeSum&) = delete;

    // Pieces of a crossed simplex (surface) or of a face simplex (closure);
    // a face through the apex is dropped (its pieces' determinants are 0).
    void add(const PieceRecord& record);
    // Waits for every block; then volume() and bound() are final.
    void finish();
    double volume() const { return volume_; }
    // |volume() - exact volume of the chain of these pieces| <= bound().
    double bound() const { return bound_; }

private:
    struct Block {
        std::vector<PieceRecord> records;
        ConeTotals* totals = nullptr;
    };
    void submit();
    void reduce(const Block& block) const;
    Block* take_block();

    const Lattice& lattice_;
    std::array<double, kMaxDim> apex_{};
    std::size_t block_size_;
    std::vector<std::unique_ptr<Block>> blocks_;  // every block ever allocated
    std::vector<Block*> free_;                    // idle blocks (guarded by mutex_)
    std::mutex mutex_;
    Block* current_ = nullptr;
    std::deque<ConeTotals> totals_;               // one per submitted block, in order
    std::atomic<int> in_flight_{0};
    tbb::task_group group_;
    bool finished_ = false;
    double volume_ = 0, bound_ = 0;
};

}  // namespace polyvol::implicit
