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
// Why (*) holds after a fresh factorisation and after each column
// replacement, the determinant's bound from the eps, and the stability
// check: docs/numerics.md, "The rank-one LU walk's bounds".
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
