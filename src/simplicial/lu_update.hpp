// simplicial/lu_update.hpp — private: an LU factorisation with row pivoting,
// updated by column replacement in O(n^2), that carries a rigorous bound on
// its own backward error, column by column.
//
// Sources:
//   R. H. Bartels and G. H. Golub, "The simplex method of linear programming
//     using LU decomposition", Comm. ACM 12 (1969) — replace a column, move it
//     last, restore triangularity of the upper Hessenberg part by eliminations
//     between adjacent rows, choosing the larger pivot of each pair;
//   R. Fletcher and S. P. J. Matthews, "Stable modification of explicit LU
//     factors for simplex updates", Math. Programming 30 (1984) — keep L and U
//     explicit and dense; when the pair's rows are interchanged, restore the
//     triangularity of L with one column operation: O(n^2) per update, no
//     growing file of eta factors;
//   N. J. Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed.
//     (2002): Thm 8.5 (substitution), Thm 9.3 (LU), gamma_k = k u / (1 - k u),
//     u = 2^-53.
//
// State. For the n x n matrix A whose column c is the column of the vertex at
// "position" c, we keep P (a row permutation), L (unit lower triangular,
// column-major: L[r + n c]) and U (upper triangular, row-major: U[n r + c])
// and, for every position c, a number eps[c] such that
//     L U = P A + E   with   ||E e_c||_2 <= eps[c]                        (*)
// where L and U are the stored (computed) factors and the equation is exact.
// A is the exact matrix the caller means; when a column is itself rounded
// (the caller forms v - o in floating point), the caller passes a bound on
// that rounding, which starts that column's eps (factor/replace `extra`).
//
// Fresh factorisation (Gaussian elimination with partial pivoting): Higham
// 9.3 gives |E| <= gamma_n |L||U|, so ||E e_c|| <= gamma_n || |L| |U e_c| ||
// <= gamma_n ||L||_F ||U e_c||_2.
//
// Column replacement at position j by a: w = L^{-1} P a by forward
// substitution satisfies (L + dL) w = P a, |dL| <= gamma_n |L| (Higham 8.5),
// so L w = P a + d with ||d|| <= gamma_n ||L||_F ||w||. U with column j
// replaced by w, and that column moved last (every position > j moves down
// one), gives L H = P A' + E' with H upper Hessenberg from column j and E'
// the old columns of E (shifted) plus d in the last place: (*) holds for H.
//
// Restoring triangularity, for k = j .. n-2, with d = H[k][k], h = H[k+1][k],
// l = L[k+1][k] (the 2x2 block of L is [1 0; l 1], so the pair's local
// product has column (d, l d + h)):
//   keep (|d| >= |l d + h|):  g = h/d; row k+1 of U -= g row k; column k of L
//       += g column k+1. The new L[k+1][k] = (l d + h)/d has modulus <= 1.
//   swap (otherwise): rows k, k+1 of L and P are interchanged, and with
//       s = l d + h, x = d/s the exact 2x2 transformation
//         U rows:    row_k' = l row_k + row_{k+1},  row_{k+1}' = row_k - x row_k'
//         L columns: col_{k+1}' = col_k - l col_{k+1},  col_k' = col_{k+1} + x col_{k+1}'
//       leaves the block of L exactly [1 0; x 1] with |x| <= 1 and H[k+1][k] = 0.
// Both are L U = (L G^-1)(G U) exactly for an invertible G (times a row
// interchange in the swap case, which permutes the rows of E and keeps its
// column norms). In floating point each computed entry is fl(y ± fl(b c)),
// whose error is <= 3u (|y| + |fl(b c)|); the zeroed entry H[k+1][k] has
// error <= u|h| (keep: h - fl(h/d) d = -h delta) resp. <= u|d| + |x| f (swap).
// With F_U, F_L the differences between the computed new factors L', U' and
// the exact transforms, L'U' - (L G^-1)(G U) = L' F_U + F_L U' - F_L F_U; F_U
// lives in rows k, k+1 and F_L in columns k, k+1, so column c of the new error
// is bounded by
//   ||L' e_k|| f_U[k][c] + ||L' e_{k+1}|| f_U[k+1][c]
//     + |F_L e_k|_1 (|U'[k][c]| + f_U[k][c]) + |F_L e_{k+1}|_1 (|U'[k+1][c]| + f_U[k+1][c])
// which is added to eps[c] for c >= k (columns < k are untouched). The swap
// case's second row/column use the first's computed values, so their bounds
// carry |x| times the first's (see lu_update.cpp).
//
// Determinant. det(L U) = prod U[i][i] exactly (L has an exact unit
// diagonal) and det(P A + E) - det(P A) = sum over nonempty sets S of columns
// of det(A with the columns in S taken from E), so by Hadamard's inequality
//   |det(L U) - det(P A)| <= prod_c (||a_c|| + eps_c) - prod_c ||a_c||
//                         <= prod_c ||a_c|| * expm1(sum_c eps_c / ||a_c||)
// (1 + t <= e^t; the first form when some a_c = 0), plus gamma_n |det| for the
// rounded product of the diagonal. The bounds themselves are computed in
// floating point from non-negative quantities: each is a sum of fewer than
// 2^30 terms (the caller refactors at least every 2^20 updates, and an update
// adds at most n <= 65 terms to an eps) of products of at most 8 computed
// factors, so its relative error is below 2^-20; the results are multiplied
// by kSlack = 1 + 2^-18 to cover it (also the rounding of the norms ||a_c||
// and of 1/||a_c||). This assumes no underflow: a determinant below 2^-960
// in magnitude gets 2^-960 added to its bound, and non-finite values make the
// bound infinite.
//
// The stability check is the bound itself: eta = sum_c eps_c / ||a_c|| (the
// relative backward error, columns with a_c = 0 excepted: their U column is
// exactly zero and stays so) is compared by the caller against a multiple of
// its value after the last fresh factorisation (volume.cpp adds a test on the
// columns' lengths).
#pragma once

#include <cstdint>
#include <vector>

namespace polyvol::simplicial {

inline constexpr double kUnit = 0x1p-53;
inline constexpr double kSlack = 1.0 + 0x1p-18;
inline double gamma(int k) { return k * kUnit / (1.0 - k * kUnit); }

// ||x||_2 of x[0], x[stride], ..., without overflow or underflow of the
// squares (scaled by a power of two when the largest entry is far from 1).
double norm2(const double* x, int n, int stride = 1);

class ColumnLu {
public:
    explicit ColumnLu(int n);

    int size() const { return n_; }

    // Factorises afresh the matrix whose column c is cols[c][0..n), with
    // norms[c] = ||cols[c]||_2 as computed. extra[c] (may be null) is added to
    // eps[c]: an error the column already carries (the rounding of the
    // coordinates it was formed from), so that (*) holds for the exact matrix.
    void factor(const double* const* cols, const double* norms, const double* extra = nullptr);

    // Replaces the column at position j by col (norm as computed, extra as
    // above); positions j+1 .. n-1 move to j .. n-2 and the new column takes
    // position n-1.
    void replace(int j, const double* col, double norm, double extra = 0);

    // det(P)^-1 prod U[i][i] = det(A) up to the error bounded by det_bound().
    double det() const;
    // sum_c eps_c / ||a_c|| over columns with ||a_c|| > 0.
    double backward_error() const;
    // |det() - det(A)| <= det_bound(det(), backward_error()).
    double det_bound(double det_value, double eta) const;
    double det_bound(double det_value) const { return det_bound(det_value, backward_error()); }

private:
    void eliminate(int k);

    int n_;
    std::vector<double> l_;        // column-major, strictly lower part used, diagonal implicit 1
    std::vector<double> u_;        // row-major, upper part (lower part kept 0)
    std::vector<uint8_t> prow_;    // row r of P A is row prow_[r] of A
    std::vector<double> eps_;      // (*) per position
    std::vector<double> norm_;     // ||a_c|| per position
    std::vector<double> inv_norm_; // 1 / ||a_c|| (0 for a zero column) per position
    std::vector<double> lnorm2_;   // ||L e_c||^2 per column (diagonal included)
    std::vector<double> w_;        // scratch
    std::vector<double> fu0_, fu1_;  // scratch: error bounds of the two U rows
    int sign_ = 1;                 // det(P)
};

}  // namespace polyvol::simplicial
