// The zero set of a linear interpolant in one Kuhn simplex as oriented
// (n-1)-simplices: the staircase triangulation of Δ^(p-1) × Δ^(q-1), one table
// per dimension (see kuhn.hpp for why it matches across facets).
#include <array>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "implicit/kuhn.hpp"

namespace polyvol::implicit {

namespace {

// The exact determinant of a small integer matrix (Bareiss' fraction-free
// elimination; every intermediate is a minor of the input, here at most
// 8! * 2^8 in magnitude, far inside int64).
int64_t bareiss_determinant(std::array<std::array<int64_t, kMaxDim>, kMaxDim> a, int n) {
    int sign = 1;
    int64_t previous = 1;
    for (int k = 0; k < n - 1; ++k) {
        if (a[k][k] == 0) {
            int r = k + 1;
            while (r < n && a[r][k] == 0) ++r;
            if (r == n) return 0;
            std::swap(a[k], a[r]);
            sign = -sign;
        }
        for (int i = k + 1; i < n; ++i)
            for (int j = k + 1; j < n; ++j) a[i][j] = (a[i][j] * a[k][k] - a[i][k] * a[k][j]) / previous;
        previous = a[k][k];
    }
    return sign * a[n - 1][n - 1];
}

// Twice the reference simplex's vertex j: u_j = Σ_{i<j} e_i.
int64_t twice_reference(int j, int k) { return k < j ? 2 : 0; }

PieceTable build_piece_table(int n) {
    PieceTable t;
    t.n = n;
    const uint32_t patterns = 1u << (n + 1);
    t.offsets.assign(patterns + 1, 0);
    for (uint32_t m = 0; m < patterns; ++m) {
        t.offsets[m] = static_cast<uint32_t>(t.vertices.size() / static_cast<std::size_t>(n));
        if (m == 0 || m == patterns - 1) continue;
        std::array<int, kMaxDim + 1> pos{}, neg{};
        int np = 0, nn = 0;
        for (int j = 0; j <= n; ++j) {
            if ((m >> j) & 1u)
                pos[np++] = j;
            else
                neg[nn++] = j;
        }
        // Monotone paths from (0, 0) to (np-1, nn-1): n-1 steps, np-1 of them
        // advancing in P. Enumerate the step sets as bit masks.
        const int steps = n - 1;
        for (uint32_t path = 0; path < (1u << steps); ++path) {
            if (__builtin_popcount(path) != np - 1) continue;
            std::array<std::array<uint8_t, 2>, kMaxDim> piece{};
            int a = 0, b = 0;
            piece[0] = {static_cast<uint8_t>(pos[0]), static_cast<uint8_t>(neg[0])};
            for (int s = 0; s < steps; ++s) {
                if ((path >> s) & 1u)
                    ++a;
                else
                    ++b;
                piece[s + 1] = {static_cast<uint8_t>(pos[a]), static_cast<uint8_t>(neg[b])};
            }
            // Orientation at the midpoints: rows 2 w_i - 2 q with q = neg[0]
            // (any point on the negative side gives the same sign).
            std::array<std::array<int64_t, kMaxDim>, kMaxDim> rows{};
            for (int i = 0; i < n; ++i)
                for (int k = 0; k < n; ++k)
                    rows[i][k] = twice_reference(piece[i][0], k) / 2 + twice_reference(piece[i][1], k) / 2 -
                                 twice_reference(neg[0], k);
            const int64_t det = bareiss_determinant(rows, n);
            if (det == 0) throw std::logic_error("implicit: degenerate staircase piece");
            if (det < 0) std::swap(piece[0], piece[1]);
            for (int i = 0; i < n; ++i) t.vertices.push_back(piece[i]);
        }
    }
    t.offsets[patterns] = static_cast<uint32_t>(t.vertices.size() / static_cast<std::size_t>(n));
    return t;
}

using Point = std::array<uint8_t, 2>;
using Simplex = std::vector<Point>;

// The staircase triangulation of Δ^(|pos|-1) × Δ^(|neg|-1): monotone paths
// from (pos[0], neg[0]) to (pos.back(), neg.back()).
std::vector<Simplex> staircase(const std::vector<int>& pos, const std::vector<int>& neg) {
    std::vector<Simplex> out;
    const int steps = static_cast<int>(pos.size() + neg.size()) - 2;
    for (uint32_t path = 0; path < (1u << steps); ++path) {
        if (__builtin_popcount(path) != static_cast<int>(pos.size()) - 1) continue;
        Simplex piece;
        std::size_t a = 0, b = 0;
        piece.push_back({static_cast<uint8_t>(pos[0]), static_cast<uint8_t>(neg[0])});
        for (int st = 0; st < steps; ++st) {
            if ((path >> st) & 1u)
                ++a;
            else
                ++b;
            piece.push_back({static_cast<uint8_t>(pos[a]), static_cast<uint8_t>(neg[b])});
        }
        out.push_back(std::move(piece));
    }
    return out;
}

// T(ρ) of closure_table for the vertex subset rho (increasing) of a simplex
// with sign pattern m.
std::vector<Simplex> pulling(const std::vector<int>& rho, uint32_t m) {
    std::vector<int> pos, neg;
    for (int j : rho) ((m >> j) & 1u ? pos : neg).push_back(j);
    if (neg.empty()) return {};
    const int v = neg[0];
    const Point apex{static_cast<uint8_t>(v), static_cast<uint8_t>(v)};
    if (rho.size() == 1) return {Simplex{apex}};
    std::vector<Simplex> out;
    std::vector<int> rest;
    for (int j : rho)
        if (j != v) rest.push_back(j);
    std::vector<Simplex> faces = pulling(rest, m);
    if (!pos.empty())
        for (Simplex& z : staircase(pos, neg)) faces.push_back(std::move(z));
    for (Simplex& f : faces) {
        f.insert(f.begin(), apex);
        out.push_back(std::move(f));
    }
    return out;
}

// Twice a point of the reference d-simplex: a vertex, or an edge midpoint.
int64_t twice_point(const Point& p, int k) { return twice_reference(p[0], k) / 2 + twice_reference(p[1], k) / 2; }

PieceTable build_closure_table(int d) {
    PieceTable t;
    t.n = d + 1;  // points per piece
    const uint32_t patterns = 1u << (d + 1);
    t.offsets.assign(patterns + 1, 0);
    std::vector<int> all;
    for (int j = 0; j <= d; ++j) all.push_back(j);
    for (uint32_t m = 0; m < patterns; ++m) {
        t.offsets[m] = static_cast<uint32_t>(t.vertices.size() / static_cast<std::size_t>(d + 1));
        for (Simplex& piece : pulling(all, m)) {
            std::array<std::array<int64_t, kMaxDim>, kMaxDim> rows{};
            for (int i = 1; i <= d; ++i)
                for (int k = 0; k < d; ++k) rows[i - 1][k] = twice_point(piece[i], k) - twice_point(piece[0], k);
            const int64_t det = bareiss_determinant(rows, d);
            if (det == 0) throw std::logic_error("implicit: degenerate closure piece");
            if (det < 0) std::swap(piece[1], piece[d == 1 ? 0 : 2]);
            for (const Point& p : piece) t.vertices.push_back(p);
        }
    }
    t.offsets[patterns] = static_cast<uint32_t>(t.vertices.size() / static_cast<std::size_t>(d + 1));
    return t;
}

}  // namespace

const PieceTable& closure_table(int d) {
    static std::array<PieceTable, kMaxDim> tables;
    static std::array<std::once_flag, kMaxDim> once;
    if (d < 1 || d >= kMaxDim) throw std::invalid_argument("implicit: dimension out of range");
    std::call_once(once[d], [d] { tables[d] = build_closure_table(d); });
    return tables[d];
}

const PieceTable& piece_table(int n) {
    static std::array<PieceTable, kMaxDim + 1> tables;
    static std::array<std::once_flag, kMaxDim + 1> once;
    if (n < 2 || n > kMaxDim) throw std::invalid_argument("implicit: dimension out of range");
    std::call_once(once[n], [n] { tables[n] = build_piece_table(n); });
    return tables[n];
}

}  // namespace polyvol::implicit
