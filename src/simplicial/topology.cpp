// simplicial/topology.cpp — welding, face matching, components (see topology.hpp).
#include "simplicial/topology.hpp"
#include "core/bit_cast.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

namespace polyvol::simplicial {

namespace {

uint64_t mix64(uint64_t x) {  // splitmix64's finaliser
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

struct UnionFind {
    std::vector<uint32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t x) {
        while (parent[x] != x) {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        return x;
    }
    void unite(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

// One use of a face: the face of simplex s omitting its listed position p,
// identified by two keyed 64-bit sums over its vertices (below).
struct FaceUse {
    uint64_t hash;
    uint64_t hash2;
    uint32_t s;
    uint8_t p;
    int8_t sign;
};

// Grouping needs equal hashes together, not a full order: a stable LSD radix
// sort by the top kPrefixBits bits of the hash, 11 bits a pass (a stable
// comparison sort for small inputs). Records made in (s, p) order stay in that
// order among equal prefixes, so the groups come out the same for every key.
constexpr int kPrefixShift = 31;  // the top 33 bits
inline uint64_t prefix(const FaceUse& u) { return u.hash >> kPrefixShift; }

void sort_by_hash(std::vector<FaceUse>& a) {
    if (a.size() < (std::size_t{1} << 15)) {
        std::stable_sort(a.begin(), a.end(), [](const FaceUse& x, const FaceUse& y) { return prefix(x) < prefix(y); });
        return;
    }
    std::vector<FaceUse> b(a.size());
    std::vector<std::size_t> count(1u << 11);
    for (int shift = kPrefixShift; shift < 64; shift += 11) {
        std::fill(count.begin(), count.end(), 0);
        for (const FaceUse& u : a) ++count[(u.hash >> shift) & 0x7FFu];
        std::size_t sum = 0;
        for (std::size_t& c : count) {
            const std::size_t t = c;
            c = sum;
            sum += t;
        }
        for (const FaceUse& u : a) b[count[(u.hash >> shift) & 0x7FFu]++] = u;
        a.swap(b);
    }
}

// The keys of the face hashes: random per process, so that no input can be
// built to make two different faces collide.
std::array<uint64_t, 2> hash_keys() {
    static const std::array<uint64_t, 2> keys = [] {
        uint64_t a = 0, b = 0;
        try {
            std::random_device rd;
            a = (uint64_t{rd()} << 32) ^ rd();
            b = (uint64_t{rd()} << 32) ^ rd();
        } catch (...) {  // no entropy source: the clock and an address
        }
        const auto t = static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
        a = mix64(a ^ t);
        b = mix64(b ^ reinterpret_cast<uintptr_t>(&a) ^ 0x5851F42D4C957F2Dull);
        return std::array<uint64_t, 2>{a, b};
    }();
    return keys;
}

}  // namespace

void check_arrays(const ChainView& c) {
    const int n = c.dimension;
    if (n < 2 || n > kMaxDimension)
        throw std::invalid_argument("chain dimension " + std::to_string(n) + " outside 2.." +
                                    std::to_string(kMaxDimension));
    if (c.coordinates.size() % static_cast<std::size_t>(n) != 0)
        throw std::invalid_argument("chain coordinates: size not a multiple of the dimension");
    if (c.simplices.size() % static_cast<std::size_t>(n) != 0)
        throw std::invalid_argument("chain simplices: size not a multiple of the dimension");
    if (c.simplex_count() >= kNone) throw std::invalid_argument("chain: 2^32 - 1 simplices or more");
    if (c.vertex_count() >= kNone) throw std::invalid_argument("chain: 2^32 - 1 vertices or more");
    const std::size_t m = c.vertex_count();
    for (uint32_t v : c.simplices)
        if (v >= m) throw std::invalid_argument("chain: vertex index " + std::to_string(v) + " >= vertex count");
}

std::vector<uint32_t> weld(const ChainView& c) {
    const int n = c.dimension;
    const std::size_t m = c.vertex_count();
    std::vector<uint64_t> hash(m);
    for (std::size_t v = 0; v < m; ++v) {
        uint64_t h = 0x243F6A8885A308D3ull;
        for (int i = 0; i < n; ++i) h = mix64(h ^ core::bit_cast<uint64_t>(c.coordinates[n * v + i] + 0.0));
        hash[v] = h;
    }
    std::vector<uint32_t> order(m);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return hash[a] != hash[b] ? hash[a] < hash[b] : a < b;
    });
    std::vector<uint32_t> canon(m);
    std::iota(canon.begin(), canon.end(), 0u);
    auto equal = [&](uint32_t a, uint32_t b) {
        for (int i = 0; i < n; ++i)
            if (!(c.coordinates[n * std::size_t{a} + i] == c.coordinates[n * std::size_t{b} + i])) return false;
        return true;
    };
    for (std::size_t i = 0; i < m;) {
        std::size_t j = i + 1;
        while (j < m && hash[order[j]] == hash[order[i]]) ++j;
        // Within a run (increasing index), each vertex welds to the first equal one.
        for (std::size_t a = i; a < j; ++a) {
            if (canon[order[a]] != order[a]) continue;
            for (std::size_t b = a + 1; b < j; ++b)
                if (canon[order[b]] == order[b] && equal(order[a], order[b])) canon[order[b]] = order[a];
        }
        i = j;
    }
    return canon;
}

Topology analyze(const ChainView& c, bool want_graph) {
    check_arrays(c);
    const int n = c.dimension;
    const std::size_t k = c.simplex_count();
    Topology t;
    t.n = n;
    t.canon = weld(c);
    ChainReport& r = t.report;
    r.dimension = n;
    r.simplices = k;
    r.vertices = c.vertex_count();
    for (std::size_t v = 0; v < r.vertices; ++v) r.vertices_welded += t.canon[v] == v ? 1 : 0;

    // Faces. With the welded ids of a simplex sorted by a permutation pi, the
    // face omitting listed position p (sorted position q) has the induced sign
    // sgn(pi) (-1)^q (topology.hpp). It is identified by the pair of sums
    // sum_v mix(v ^ key) over its vertices: the simplex's sums minus the
    // omitted vertex's, O(1) per face. Two different faces share both 64-bit
    // sums with probability about 2^-128 per pair for random keys; that is
    // the only assumption (no input can aim at it: the keys are secret).
    const auto keys = hash_keys();
    t.degenerate.assign(k, 0);
    std::vector<FaceUse> uses;
    uses.reserve(k * n);
    std::array<std::pair<uint32_t, uint8_t>, kMaxDimension> d{};  // (welded id, listed position)
    for (std::size_t s = 0; s < k; ++s) {
        for (int i = 0; i < n; ++i) d[i] = {t.canon[c.simplices[s * n + i]], static_cast<uint8_t>(i)};
        int swaps = 0;
        for (int i = 1; i < n; ++i)  // insertion sort: n <= 64
            for (int j = i; j > 0 && d[j - 1].first > d[j].first; --j) {
                std::swap(d[j - 1], d[j]);
                ++swaps;
            }
        bool degenerate = false;
        for (int i = 1; i < n; ++i) degenerate |= d[i - 1].first == d[i].first;
        if (degenerate) {
            t.degenerate[s] = 1;
            ++r.degenerate_simplices;
            continue;
        }
        const int parity = (swaps & 1) ? -1 : 1;
        uint64_t total = 0, total2 = 0;
        for (int i = 0; i < n; ++i) {
            total += mix64(d[i].first ^ keys[0]);
            total2 += mix64(d[i].first ^ keys[1]);
        }
        for (int q = 0; q < n; ++q)
            uses.push_back({total - mix64(d[q].first ^ keys[0]), total2 - mix64(d[q].first ^ keys[1]),
                            static_cast<uint32_t>(s), d[q].second, static_cast<int8_t>((q & 1) ? -parity : parity)});
    }
    sort_by_hash(uses);

    if (want_graph) {
        t.nb.assign(k * n, kNone);
        t.same.assign(k * n, 0);
    }
    UnionFind uf(k);
    std::size_t example_simplex = kNone;
    // One face and all its uses (indices into uses, in (s, p) order).
    auto face = [&](const std::size_t* group, std::size_t size) {
        ++r.faces;
        std::size_t pos = 0;
        for (std::size_t g = 0; g < size; ++g) pos += uses[group[g]].sign > 0 ? 1 : 0;
        const std::size_t neg = size - pos;
        const FaceUse& u = uses[group[0]];  // the use in the lowest simplex
        for (std::size_t g = 1; g < size; ++g) uf.unite(u.s, uses[group[g]].s);
        if (size == 1) ++r.boundary_faces;
        if (size == 2 && pos != neg) ++r.misoriented_faces;
        if (size > 2) ++r.nonmanifold_faces;
        if (pos != neg) {
            ++r.unmatched_faces;
            if (u.s < example_simplex) {
                example_simplex = u.s;
                UnmatchedFace e;
                e.simplex = u.s;
                for (int v = 0; v < n; ++v)
                    if (v != u.p) e.vertices.push_back(c.simplices[std::size_t{u.s} * n + v]);
                e.same = u.sign > 0 ? pos : neg;
                e.opposite = u.sign > 0 ? neg : pos;
                r.unmatched_example = std::move(e);
            }
        }
        if (want_graph && size == 2) {
            const FaceUse& w = uses[group[1]];
            const std::size_t iu = std::size_t{u.s} * n + u.p;
            const std::size_t iw = std::size_t{w.s} * n + w.p;
            t.nb[iu] = w.s;
            t.nb[iw] = u.s;
            t.same[iu] = t.same[iw] = u.sign == w.sign ? 1 : 0;
        }
    };
    std::vector<uint8_t> taken;
    std::vector<std::size_t> group;
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i + 1;
        while (j < uses.size() && prefix(uses[j]) == prefix(uses[i])) ++j;
        if (j - i == 1 || (j - i == 2 && uses[i].hash == uses[i + 1].hash && uses[i].hash2 == uses[i + 1].hash2)) {
            const std::size_t g[2] = {i, i + 1};
            face(g, j - i);
        } else {
            taken.assign(j - i, 0);
            for (std::size_t a2 = i; a2 < j; ++a2) {
                if (taken[a2 - i]) continue;
                group.clear();
                group.push_back(a2);
                for (std::size_t b2 = a2 + 1; b2 < j; ++b2)
                    if (!taken[b2 - i] && uses[a2].hash == uses[b2].hash && uses[a2].hash2 == uses[b2].hash2) {
                        taken[b2 - i] = 1;
                        group.push_back(b2);
                    }
                face(group.data(), group.size());
            }
        }
        i = j;
    }

    // Components, numbered in order of their first simplex.
    std::vector<uint32_t> id_of_root(k, kNone);
    if (want_graph) t.component.assign(k, kNone);
    for (std::size_t s = 0; s < k; ++s) {
        if (t.degenerate[s]) continue;
        const uint32_t root = uf.find(static_cast<uint32_t>(s));
        if (id_of_root[root] == kNone) id_of_root[root] = static_cast<uint32_t>(r.components++);
        if (want_graph) t.component[s] = id_of_root[root];
    }
    return t;
}

}  // namespace polyvol::simplicial
