// The column-replacement LU (src/simplicial/lu_update.hpp): after any
// sequence of replacements its determinant is within the stated bound of the
// exact determinant (GMP), and the bound stays near that of a fresh
// factorisation — also for matrices built to need row interchanges and for
// nearly singular ones.
#include "simplicial/lu_update.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <vector>

#include "simplicial/exact_det.hpp"

using namespace polyvol;
using namespace polyvol::simplicial;

namespace {

struct Matrix {
    int n;
    std::vector<std::vector<double>> cols;  // in position order
    std::vector<const double*> ptrs() const {
        std::vector<const double*> p;
        for (const auto& c : cols) p.push_back(c.data());
        return p;
    }
    std::vector<double> norms() const {
        std::vector<double> r;
        for (const auto& c : cols) r.push_back(norm2(c.data(), n));
        return r;
    }
};

double norm(const std::vector<double>& c) { return norm2(c.data(), static_cast<int>(c.size())); }

// n × n standard normal entries, drawn column by column from g.
Matrix random_matrix(int n, std::mt19937_64& rng, std::normal_distribution<double>& g) {
    Matrix m{n, {}};
    for (int c = 0; c < n; ++c) {
        m.cols.emplace_back(n);
        for (double& x : m.cols.back()) x = g(rng);
    }
    return m;
}

// Replaces column j of lu by col, and of m the way ColumnLu orders its
// columns: the new one goes last.
void replace_column(ColumnLu& lu, Matrix& m, int j, const std::vector<double>& col) {
    lu.replace(j, col.data(), norm(col));
    m.cols.erase(m.cols.begin() + j);
    m.cols.push_back(col);
}

// |det - exact| <= bound, checked in exact arithmetic.
void expect_within(const ColumnLu& lu, const Matrix& m) {
    const double d = lu.det();
    const double b = lu.det_bound(d);
    ASSERT_TRUE(std::isfinite(b)) << "n=" << m.n;
    const auto p = m.ptrs();
    const exact::Rational ex = exact_det(m.n, p.data());
    exact::Rational diff = exact::Rational(d) - ex;
    if (diff.sign() < 0) diff = -diff;
    EXPECT_FALSE(exact::Rational(b) < diff) << "n=" << m.n << " det=" << d << " exact=" << ex.to_double()
                                              << " bound=" << b;
}

}  // namespace

TEST(ColumnLu, FreshFactorisationMatchesEigenAndExact) {
    std::mt19937_64 rng(1);
    std::normal_distribution<double> g;
    for (int n : {2, 3, 4, 7, 12, 20, 32}) {
        Matrix m = random_matrix(n, rng, g);
        ColumnLu lu(n);
        lu.factor(m.ptrs().data(), m.norms().data());
        Eigen::MatrixXd e(n, n);
        for (int c = 0; c < n; ++c)
            for (int r = 0; r < n; ++r) e(r, c) = m.cols[c][r];
        EXPECT_NEAR(lu.det(), e.determinant(), 1e-10 * std::abs(e.determinant()));
        expect_within(lu, m);
    }
}

TEST(ColumnLu, ReplacementsStayWithinTheBound) {
    std::mt19937_64 rng(2);
    std::normal_distribution<double> g;
    for (int n : {2, 3, 4, 5, 8, 13, 20}) {
        Matrix m = random_matrix(n, rng, g);
        ColumnLu lu(n);
        lu.factor(m.ptrs().data(), m.norms().data());
        const double fresh = lu.backward_error();
        for (int step = 0; step < 200; ++step) {
            const int j = std::uniform_int_distribution<int>(0, n - 1)(rng);
            std::vector<double> col(n);
            for (double& x : col) x = g(rng);
            // Every tenth column nearly parallel to another: ill-conditioned steps.
            if (step % 10 == 9) {
                col = m.cols[(j + 1) % n];
                for (double& x : col) x *= 1 + 1e-9 * g(rng);
            }
            replace_column(lu, m, j, col);
            if (step % 7 == 0 || step == 199) expect_within(lu, m);
        }
        // The bound grows linearly with the number of updates, not worse.
        EXPECT_LT(lu.backward_error(), 400 * fresh + 1e-10) << n;
    }
}

TEST(ColumnLu, RowInterchangesAreExercised) {
    // Columns with tiny leading entries force the "swap" branch of the
    // elimination; the determinant still matches.
    std::mt19937_64 rng(3);
    std::normal_distribution<double> g;
    const int n = 6;
    Matrix m{n, {}};
    for (int c = 0; c < n; ++c) {
        m.cols.emplace_back(n);
        for (int r = 0; r < n; ++r) m.cols.back()[r] = (r == c ? 1e-8 : 1.0) * g(rng);
    }
    ColumnLu lu(n);
    lu.factor(m.ptrs().data(), m.norms().data());
    for (int step = 0; step < 50; ++step) {
        std::vector<double> col(n);
        for (int r = 0; r < n; ++r) col[r] = (r == step % n ? 1e6 : 1.0) * g(rng);
        const int j = step % 3;
        replace_column(lu, m, j, col);
        expect_within(lu, m);
    }
}

TEST(ColumnLu, ZeroAndSingularColumns) {
    const int n = 4;
    Matrix m{n, {{0, 0, 0, 0}, {1, 2, 3, 4}, {0, 1, 0, 1}, {2, 0, 1, 0}}};
    ColumnLu lu(n);
    lu.factor(m.ptrs().data(), m.norms().data());
    EXPECT_EQ(lu.det(), 0.0);
    expect_within(lu, m);
    std::vector<double> col{1, 2, 3, 4};  // equal to column 1: singular
    replace_column(lu, m, 0, col);
    expect_within(lu, m);
    col = {0.5, -1, 2, 7};
    replace_column(lu, m, 0, col);
    EXPECT_NE(lu.det(), 0.0);
    expect_within(lu, m);
}

TEST(ColumnLu, HugeAndTinyScalesDoNotOverflowTheProduct) {
    const int n = 4;
    Matrix m{n, {{1e200, 0, 0, 0}, {0, 1e200, 0, 0}, {0, 0, 1e-200, 0}, {0, 0, 0, 1e-200}}};
    ColumnLu lu(n);
    lu.factor(m.ptrs().data(), m.norms().data());
    EXPECT_DOUBLE_EQ(lu.det(), 1.0);
    expect_within(lu, m);
}
