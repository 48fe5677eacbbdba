// simplicial/lu_update.cpp — column replacement in explicit LU factors with a
// running backward-error bound (the analysis is in lu_update.hpp).
#include "simplicial/lu_update.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace polyvol::simplicial {

namespace {

constexpr double k3u = 3 * kUnit;
constexpr double kTiny = 0x1p-960;

// prod_i xs[i] * sign without spurious overflow or underflow in between:
// mantissas and exponents apart (exact scaling by powers of two).
double scaled_product(const double* xs, int n, int stride, double sign) {
    double m = sign;
    long e = 0;
    for (int i = 0; i < n; ++i) {
        int ex = 0;
        m *= std::frexp(xs[static_cast<std::size_t>(i) * stride], &ex);
        e += ex;
        int em = 0;
        m = std::frexp(m, &em);
        e += em;
        if (m == 0 || !std::isfinite(m)) return m;
    }
    if (e > 4000) e = 4000;
    if (e < -4000) e = -4000;
    return std::ldexp(m, static_cast<int>(e));
}

}  // namespace

double norm2(const double* x, int n, int stride) {
    double s = 0;
    for (int i = 0; i < n; ++i) s += x[static_cast<std::size_t>(i) * stride] * x[static_cast<std::size_t>(i) * stride];
    // No square overflowed or underflowed to nothing when the sum is in range
    // (every square is at most the sum; a sum >= 2^-800 has lost at most
    // n * 2^-1074 to underflowed squares, below its rounding error).
    if (s >= 0x1p-800 && s <= 0x1p800) return std::sqrt(s);
    double big = 0;
    for (int i = 0; i < n; ++i) big = std::max(big, std::abs(x[static_cast<std::size_t>(i) * stride]));
    if (big == 0 || !std::isfinite(big)) return big;
    int e = 0;
    std::frexp(big, &e);
    s = 0;
    for (int i = 0; i < n; ++i) {
        const double y = std::ldexp(x[static_cast<std::size_t>(i) * stride], -e);
        s += y * y;
    }
    return std::ldexp(std::sqrt(s), e);
}

ColumnLu::ColumnLu(int n)
    : n_(n),
      l_(static_cast<std::size_t>(n) * n),
      u_(static_cast<std::size_t>(n) * n),
      prow_(n),
      eps_(n),
      norm_(n),
      inv_norm_(n),
      lnorm2_(n),
      w_(n),
      fu0_(n),
      fu1_(n) {}

void ColumnLu::factor(const double* const* cols, const double* norms, const double* extra) {
    const int n = n_;
    double* m = u_.data();  // the whole working matrix, row-major
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) m[r * n + c] = cols[c][r];
    for (int r = 0; r < n; ++r) prow_[r] = static_cast<uint8_t>(r);
    sign_ = 1;
    for (int k = 0; k < n; ++k) {
        int p = k;
        double best = std::abs(m[k * n + k]);
        for (int r = k + 1; r < n; ++r)
            if (std::abs(m[r * n + k]) > best) {
                best = std::abs(m[r * n + k]);
                p = r;
            }
        if (p != k) {
            std::swap_ranges(m + k * n, m + k * n + n, m + p * n);
            std::swap(prow_[k], prow_[p]);
            sign_ = -sign_;
        }
        const double piv = m[k * n + k];
        const double* src = m + k * n;
        for (int r = k + 1; r < n; ++r) {
            double* dst = m + r * n;
            if (piv == 0 || dst[k] == 0) {
                dst[k] = 0;  // piv == 0: the column is zero below (it was the largest)
                continue;
            }
            const double lm = dst[k] / piv;
            dst[k] = lm;
            for (int c = k + 1; c < n; ++c) dst[c] -= lm * src[c];
        }
    }
    double frob2 = 0;
    for (int c = 0; c < n; ++c) {
        double s = 1;
        for (int r = 0; r < n; ++r) {
            double& x = m[r * n + c];
            if (r > c) {
                l_[c * n + r] = x;
                s += x * x;
                x = 0;
            } else {
                l_[c * n + r] = 0;
            }
        }
        lnorm2_[c] = s;
        frob2 += s;
    }
    const double g = gamma(n) * std::sqrt(frob2);
    for (int c = 0; c < n; ++c) {
        eps_[c] = g * norm2(m + c, c + 1, n) + (extra ? extra[c] : 0.0);
        norm_[c] = norms[c];
        inv_norm_[c] = norms[c] > 0 ? 1 / norms[c] : 0.0;
    }
}

void ColumnLu::replace(int j, const double* col, double norm, double extra) {
    const int n = n_;
    double* w = w_.data();
    for (int r = 0; r < n; ++r) w[r] = col[prow_[r]];
    // w = L^-1 P a, column-oriented forward substitution (each w[r] is still
    // the sequential inner product of Higham 8.5).
    for (int c = 0; c + 1 < n; ++c) {
        const double wc = w[c];
        if (wc == 0) continue;
        const double* __restrict lc = &l_[static_cast<std::size_t>(c) * n];
        double* __restrict wr = w;
        for (int r = c + 1; r < n; ++r) wr[r] -= lc[r] * wc;
    }
    double frob2 = 0;
    for (int c = 0; c < n; ++c) frob2 += lnorm2_[c];
    const double e_new = gamma(n) * std::sqrt(frob2) * norm2(w, n) + extra;
    // Column j out, the others down one place, w last.
    const std::size_t tail = static_cast<std::size_t>(n - 1 - j);
    for (int r = 0; r < n; ++r) {
        double* row = &u_[static_cast<std::size_t>(r) * n];
        std::memmove(row + j, row + j + 1, tail * sizeof(double));
        row[n - 1] = w[r];
    }
    std::memmove(&eps_[j], &eps_[j + 1], tail * sizeof(double));
    std::memmove(&norm_[j], &norm_[j + 1], tail * sizeof(double));
    std::memmove(&inv_norm_[j], &inv_norm_[j + 1], tail * sizeof(double));
    eps_[n - 1] = e_new;
    norm_[n - 1] = norm;
    inv_norm_[n - 1] = norm > 0 ? 1 / norm : 0.0;
    for (int k = j; k + 1 < n; ++k) eliminate(k);
}

void ColumnLu::eliminate(int k) {
    const int n = n_;
    double* rk = &u_[static_cast<std::size_t>(k) * n];
    double* rk1 = &u_[static_cast<std::size_t>(k + 1) * n];
    const double d = rk[k];
    const double h = rk1[k];
    if (h == 0) return;  // already triangular here: nothing computed, no error
    double* lk = &l_[static_cast<std::size_t>(k) * n];
    double* lk1 = &l_[static_cast<std::size_t>(k + 1) * n];
    const double l = lk[k + 1];
    const double ld = l * d;
    const double s = ld + h;
    if (std::abs(d) >= std::abs(s)) {
        // keep: row k+1 -= g row k; column k of L += g column k+1.
        const double g = h / d;
        double fl = 0, n0 = 1;
        {
            const double y = lk[k + 1];  // times L[k+1][k+1] = 1: the product is exact
            const double v = y + g;
            lk[k + 1] = v;
            fl += std::abs(y) + std::abs(g);
            n0 += v * v;
        }
        for (int r = k + 2; r < n; ++r) {
            const double t = g * lk1[r];
            const double y = lk[r];
            const double v = y + t;
            lk[r] = v;
            fl += std::abs(y) + std::abs(t);
            n0 += v * v;
        }
        fl *= k3u;
        lnorm2_[k] = n0;
        const double nl1 = std::sqrt(lnorm2_[k + 1]);
        rk1[k] = 0;
        eps_[k] += nl1 * (kUnit * std::abs(h)) + fl * std::abs(d);
        // Column c gains nl1 f_U[k+1][c] + |F_L e_k|_1 |U[k][c]|, f_U = 3u (|y| + |t|).
        const double cu = nl1 * k3u;
        const double* __restrict a_row = rk;
        double* __restrict b_row = rk1;
        double* __restrict e = eps_.data();
        for (int c = k + 1; c < n; ++c) {
            const double a = a_row[c];
            const double t = g * a;
            const double y = b_row[c];
            b_row[c] = y - t;
            e[c] += cu * (std::abs(y) + std::abs(t)) + fl * std::abs(a);
        }
        return;
    }
    // swap: interchange rows k, k+1 of L (columns < k) and of P, then the
    // exact 2x2 transformation of lu_update.hpp.
    for (int c = 0; c < k; ++c) std::swap(l_[static_cast<std::size_t>(c) * n + k], l_[static_cast<std::size_t>(c) * n + k + 1]);
    std::swap(prow_[k], prow_[k + 1]);
    sign_ = -sign_;
    const double x = d / s;
    const double ax = std::abs(x);
    double fl0 = 0, fl1 = 0, n0 = 1 + x * x, n1 = 1;
    lk[k + 1] = x;
    for (int r = k + 2; r < n; ++r) {
        const double a = lk[r];   // column k
        const double b = lk1[r];  // column k+1
        const double t = l * b;
        const double c1 = a - t;
        const double f1 = k3u * (std::abs(a) + std::abs(t));
        const double t2 = x * c1;
        const double c0 = b + t2;
        const double f0 = ax * f1 + k3u * (std::abs(b) + std::abs(t2));
        lk[r] = c0;
        lk1[r] = c1;
        fl0 += f0;
        fl1 += f1;
        n0 += c0 * c0;
        n1 += c1 * c1;
    }
    lnorm2_[k] = n0;
    lnorm2_[k + 1] = n1;
    const double nl0 = std::sqrt(n0), nl1 = std::sqrt(n1);
    {
        const double f0 = k3u * (std::abs(ld) + std::abs(h));
        const double f1 = ax * f0 + k3u * (std::abs(d) + std::abs(x * s));
        rk[k] = s;
        rk1[k] = 0;
        eps_[k] += nl0 * f0 + nl1 * f1 + fl0 * (std::abs(s) + f0) + fl1 * f1;
    }
    for (int c = k + 1; c < n; ++c) {
        const double a = rk[c];
        const double b = rk1[c];
        const double t1 = l * a;
        const double v0 = t1 + b;
        const double f0 = k3u * (std::abs(t1) + std::abs(b));
        const double t2 = x * v0;
        const double v1 = a - t2;
        const double f1 = ax * f0 + k3u * (std::abs(a) + std::abs(t2));
        rk[c] = v0;
        rk1[c] = v1;
        eps_[c] += nl0 * f0 + nl1 * f1 + fl0 * (std::abs(v0) + f0) + fl1 * (std::abs(v1) + f1);
    }
}

double ColumnLu::det() const {
    const int n = n_;
    const std::size_t diag = static_cast<std::size_t>(n) + 1;
    double p = sign_;
    double smallest = std::numeric_limits<double>::infinity();
    bool zero_factor = false;
    for (int i = 0; i < n; ++i) {
        const double x = u_[i * diag];
        zero_factor |= x == 0;
        p *= x;
        smallest = std::min(smallest, std::abs(p));
    }
    if (zero_factor) return 0.0;  // exact
    if (std::isfinite(p) && smallest >= kTiny) return p;
    // An overflow or underflow on the way: mantissas and exponents apart.
    return scaled_product(u_.data(), n, n + 1, sign_);
}

double ColumnLu::backward_error() const {
    // 1/||a_c|| is rounded: the relative error (<= 2u) is within kSlack.
    double s = 0;
    for (int c = 0; c < n_; ++c) s += eps_[c] * inv_norm_[c];
    return s;
}

double ColumnLu::det_bound(double det_value, double eta) const {
    const int n = n_;
    if (!std::isfinite(det_value) || !std::isfinite(eta)) return std::numeric_limits<double>::infinity();
    double p0 = 1;
    bool zero_column = false;
    for (int c = 0; c < n; ++c) {
        p0 *= norm_[c];
        zero_column |= norm_[c] == 0;
    }
    double b;
    if (zero_column) {
        // prod (||a_c|| + eps_c) - prod ||a_c|| with the second product 0.
        std::vector<double> t(static_cast<std::size_t>(n));
        for (int c = 0; c < n; ++c) t[c] = norm_[c] + eps_[c];
        b = scaled_product(t.data(), n, 1, 1.0);
    } else {
        if (!(p0 < std::numeric_limits<double>::infinity()) || p0 < kTiny)
            p0 = scaled_product(norm_.data(), n, 1, 1.0);
        b = p0 * std::expm1(eta);
    }
    b = (b + gamma(n) * std::abs(det_value)) * kSlack;
    if (std::abs(det_value) < kTiny || b < kTiny) b += kTiny;
    return std::isnan(b) ? std::numeric_limits<double>::infinity() : b;
}

}  // namespace polyvol::simplicial
