// Closed-form chains in R^n for the simplicial tests: the boundaries of the
// standard simplex (volume 1/n!), the cross-polytope (2^n/n!) and the unit
// hypercube (1, Kuhn-triangulated facets), stellar subdivisions, affine maps,
// and an exact reference volume (GMP) independent of the library's paths.
#pragma once

#include <gmpxx.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "polyvol/chain.hpp"

namespace polyvol::fixtures {

inline double factorial(int n) {
    double f = 1;
    for (int i = 2; i <= n; ++i) f *= i;
    return f;
}

// Outward: det(v_0 - p, ..., v_{n-1} - p) > 0 for p the given interior point.
inline void orient_outward(Chain& c, const std::vector<double>& p) {
    const int n = c.dimension;
    Eigen::MatrixXd m(n, n);
    for (std::size_t s = 0; s < c.simplex_count(); ++s) {
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) m(i, j) = c.coordinates[c.simplices[s * n + j] * std::size_t(n) + i] - p[i];
        if (m.determinant() < 0) std::swap(c.simplices[s * n], c.simplices[s * n + 1]);
    }
}

// Boundary of conv(0, e_1, ..., e_n): facet i is (-1)^i (v_0 .. ^v_i .. v_n).
inline Chain standard_simplex(int n) {
    Chain c;
    c.dimension = n;
    c.coordinates.assign(static_cast<std::size_t>(n) * (n + 1), 0.0);
    for (int i = 1; i <= n; ++i) c.coordinates[static_cast<std::size_t>(i) * n + (i - 1)] = 1.0;
    for (int i = 0; i <= n; ++i) {
        std::vector<uint32_t> f;
        for (int j = 0; j <= n; ++j)
            if (j != i) f.push_back(static_cast<uint32_t>(j));
        if (i % 2 == 1) std::swap(f[0], f[1]);
        c.simplices.insert(c.simplices.end(), f.begin(), f.end());
    }
    return c;
}

// Boundary of conv(±e_i): one facet per sign pattern, 2^n of them.
inline Chain cross_polytope(int n) {
    Chain c;
    c.dimension = n;
    c.coordinates.assign(static_cast<std::size_t>(2 * n) * n, 0.0);
    for (int i = 0; i < n; ++i) {
        c.coordinates[static_cast<std::size_t>(2 * i) * n + i] = 1.0;       // +e_i: vertex 2i
        c.coordinates[static_cast<std::size_t>(2 * i + 1) * n + i] = -1.0;  // -e_i: vertex 2i+1
    }
    for (uint64_t mask = 0; mask < (uint64_t{1} << n); ++mask) {
        std::vector<uint32_t> f;
        int negatives = 0;
        for (int i = 0; i < n; ++i) {
            const bool neg = (mask >> i) & 1;
            negatives += neg ? 1 : 0;
            f.push_back(static_cast<uint32_t>(2 * i + (neg ? 1 : 0)));
        }
        if (negatives % 2 == 1) std::swap(f[0], f[1]);  // det = (-1)^negatives
        c.simplices.insert(c.simplices.end(), f.begin(), f.end());
    }
    return c;
}

// Boundary of [0,1]^n: every facet x_i = 0 or 1 cut into the (n-1)! Kuhn
// simplices (paths from its lowest corner adding unit vectors in the order
// of a permutation), oriented outward: 2 n! simplices.
inline Chain hypercube(int n) {
    Chain c;
    c.dimension = n;
    for (uint32_t v = 0; v < (1u << n); ++v)
        for (int i = 0; i < n; ++i) c.coordinates.push_back((v >> i) & 1u ? 1.0 : 0.0);
    for (int i = 0; i < n; ++i) {
        std::vector<int> others;
        for (int j = 0; j < n; ++j)
            if (j != i) others.push_back(j);
        for (uint32_t side = 0; side < 2; ++side) {
            std::vector<int> perm = others;
            do {
                uint32_t v = side << i;
                c.simplices.push_back(v);
                for (int j : perm) {
                    v |= 1u << j;
                    c.simplices.push_back(v);
                }
            } while (std::next_permutation(perm.begin(), perm.end()));
        }
    }
    orient_outward(c, std::vector<double>(n, 0.5));
    return c;
}

// x -> s A x + b on every vertex; returns det(s A) (volume factor, signed).
inline double transform(Chain& c, std::mt19937_64& rng, double s) {
    const int n = c.dimension;
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) a(i, j) += 0.3 * u(rng);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = 10 * u(rng);
    for (std::size_t v = 0; v < c.vertex_count(); ++v) {
        Eigen::Map<Eigen::VectorXd> x(&c.coordinates[v * n], n);
        const Eigen::VectorXd y = s * (a * x) + b;
        x = y;
    }
    return std::pow(s, n) * a.determinant();
}

// Replaces random simplices by the cone from a new point slightly outside
// their centroid (stellar subdivision): the chain stays closed.
inline void subdivide(Chain& c, std::mt19937_64& rng, std::size_t target_simplices, double push = 0.05) {
    const int n = c.dimension;
    std::uniform_real_distribution<double> u(0, 1);
    while (c.simplex_count() + n - 1 <= target_simplices) {
        const std::size_t s = std::uniform_int_distribution<std::size_t>(0, c.simplex_count() - 1)(rng);
        std::vector<uint32_t> f(c.simplices.begin() + s * n, c.simplices.begin() + (s + 1) * n);
        std::vector<double> p(n, 0.0);
        for (uint32_t v : f)
            for (int i = 0; i < n; ++i) p[i] += c.coordinates[std::size_t{v} * n + i] / n;
        const double scale = 1 + push * u(rng);
        const auto nv = static_cast<uint32_t>(c.vertex_count());
        for (int i = 0; i < n; ++i) c.coordinates.push_back(p[i] * scale);
        // Simplex s becomes f with f[0] replaced; the others are appended.
        for (int j = 0; j < n; ++j) {
            std::vector<uint32_t> g = f;
            g[j] = nv;
            if (j == 0) {
                std::copy(g.begin(), g.end(), c.simplices.begin() + s * n);
            } else {
                c.simplices.insert(c.simplices.end(), g.begin(), g.end());
            }
        }
    }
}

// Random perturbation of every coordinate by a relative amount.
inline void perturb(Chain& c, std::mt19937_64& rng, double amount) {
    std::uniform_real_distribution<double> u(-amount, amount);
    for (double& x : c.coordinates) x *= 1 + u(rng);
}

// Exact cone-rule volume with gmpxx (mpq Gaussian elimination): independent of
// the library's Bareiss code.
inline mpq_class exact_volume(const Chain& c) {
    const int n = c.dimension;
    mpq_class sum = 0;
    std::vector<mpq_class> m(static_cast<std::size_t>(n) * n);
    for (std::size_t s = 0; s < c.simplex_count(); ++s) {
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) m[i * n + j] = c.coordinates[std::size_t{c.simplices[s * n + j]} * n + i];
        mpq_class det = 1;
        for (int k = 0; k < n && det != 0; ++k) {
            int p = k;
            while (p < n && m[p * n + k] == 0) ++p;
            if (p == n) {
                det = 0;
                break;
            }
            if (p != k) {
                for (int j = 0; j < n; ++j) std::swap(m[k * n + j], m[p * n + j]);
                det = -det;
            }
            det *= m[k * n + k];
            for (int r = k + 1; r < n; ++r) {
                const mpq_class l = m[r * n + k] / m[k * n + k];
                for (int j = k; j < n; ++j) m[r * n + j] -= l * m[k * n + j];
            }
        }
        sum += det;
    }
    mpq_class f = 1;
    for (int i = 2; i <= n; ++i) f *= i;
    return sum / f;
}

}  // namespace polyvol::fixtures
