// Disjoint sets over 0..n-1 (union by size, path halving): near-linear time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace polyvol::core {

class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) {
        std::iota(parent_.begin(), parent_.end(), uint32_t{0});
    }

    std::size_t size() const { return parent_.size(); }

    uint32_t find(uint32_t x) {
        while (parent_[x] != x) {
            parent_[x] = parent_[parent_[x]];  // path halving
            x = parent_[x];
        }
        return x;
    }

    // Joins the sets of a and b; true when they were different.
    bool unite(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        if (size_[a] < size_[b]) std::swap(a, b);
        parent_[b] = a;
        size_[a] += size_[b];
        return true;
    }

    // Number of sets.
    std::size_t count_roots() {
        std::size_t n = 0;
        for (uint32_t x = 0; x < parent_.size(); ++x) n += find(x) == x;
        return n;
    }

private:
    std::vector<uint32_t> parent_;
    std::vector<uint32_t> size_;
};

}  // namespace polyvol::core
