// Kuhn simplices: vertices, pivoting, permutation rank and parity.
#include "implicit/kuhn.hpp"

namespace polyvol::implicit {

void kuhn_vertices(const KuhnSimplex& s, int n, std::array<Index, kMaxDim + 1>& out) {
    out[0] = s.corner;
    for (int j = 0; j < n; ++j) {
        out[j + 1] = out[j];
        ++out[j + 1][s.perm[j]];
    }
}

KuhnSimplex kuhn_neighbour(const KuhnSimplex& s, int n, int j) {
    KuhnSimplex t = s;
    if (j == 0) {
        ++t.corner[s.perm[0]];
        for (int i = 0; i + 1 < n; ++i) t.perm[i] = s.perm[i + 1];
        t.perm[n - 1] = s.perm[0];
    } else if (j == n) {
        --t.corner[s.perm[n - 1]];
        t.perm[0] = s.perm[n - 1];
        for (int i = 1; i < n; ++i) t.perm[i] = s.perm[i - 1];
    } else {
        t.perm[j - 1] = s.perm[j];
        t.perm[j] = s.perm[j - 1];
    }
    return t;
}

KuhnSimplex kuhn_simplex_with_edge(const Index& u, int n, int axis, const std::array<int32_t, kMaxDim>& cells) {
    KuhnSimplex s;
    s.corner = u;
    int i = 0;
    for (int k = 0; k < n; ++k)
        if (k != axis && u[k] == cells[k]) {
            --s.corner[k];
            s.perm[i++] = static_cast<uint8_t>(k);
        }
    s.perm[i++] = static_cast<uint8_t>(axis);
    for (int k = 0; k < n; ++k)
        if (k != axis && u[k] != cells[k]) s.perm[i++] = static_cast<uint8_t>(k);
    return s;
}

uint32_t permutation_rank(const std::array<uint8_t, kMaxDim>& perm, int n) {
    // Lehmer code: rank = Σ_i (number of j > i with perm[j] < perm[i]) (n-1-i)!
    uint32_t rank = 0;
    for (int i = 0; i < n; ++i) {
        uint32_t smaller = 0;
        for (int j = i + 1; j < n; ++j) smaller += perm[j] < perm[i] ? 1u : 0u;
        rank = rank * static_cast<uint32_t>(n - i) + smaller;
    }
    return rank;
}

bool permutation_odd(const std::array<uint8_t, kMaxDim>& perm, int n) {
    int inversions = 0;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) inversions += perm[j] < perm[i] ? 1 : 0;
    return (inversions & 1) != 0;
}

uint64_t factorial(int n) {
    uint64_t f = 1;
    for (int i = 2; i <= n; ++i) f *= static_cast<uint64_t>(i);
    return f;
}

}  // namespace polyvol::implicit
