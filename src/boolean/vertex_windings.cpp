// boolean/vertex_windings.cpp — the other operand's winding number at every
// vertex of one operand.
//
// Along an edge x -> y the winding number w of a closed surface changes by
// the signed count of its triangles the edge crosses (+1 entering the solid):
// w(y) = w(x) + k(x, y). A union–find with offsets collects these relations
// per connected part of the operand; each part then needs one value: 0 for a
// vertex outside the other operand's box, else the signed crossings of a ray
// from the vertex to a point beyond that box (where w = 0).
#include <climits>
#include <cstdint>
#include <stdexcept>

#include "boolean/operand.hpp"
#include "boolean/predicates.hpp"

namespace polyvol::boolean {
namespace {

// Union–find in which every vertex knows w(v) - w(parent(v)).
class OffsetForest {
public:
    explicit OffsetForest(std::size_t n) : parent_(n), offset_(n, 0), size_(n, 1) {
        for (std::size_t v = 0; v < n; ++v) parent_[v] = static_cast<uint32_t>(v);
    }
    // The root of v, with w(v) - w(root) in `offset`.
    uint32_t find(uint32_t v, int64_t& offset) {
        int64_t total = 0;
        uint32_t r = v;
        while (parent_[r] != r) {
            total += offset_[r];
            r = parent_[r];
        }
        // Path compression: every vertex on the path points at r directly.
        int64_t remaining = total;
        while (parent_[v] != v) {
            const uint32_t next = parent_[v];
            const int64_t step = offset_[v];
            parent_[v] = r;
            offset_[v] = remaining;
            remaining -= step;
            v = next;
        }
        offset = total;
        return r;
    }
    // Records w(y) - w(x) == k; false when it contradicts what is known.
    bool relate(uint32_t x, uint32_t y, int64_t k) {
        int64_t ox, oy;
        uint32_t rx = find(x, ox), ry = find(y, oy);
        if (rx == ry) return oy - ox == k;
        // w(ry) = w(y) - oy = w(x) + k - oy = w(rx) + ox + k - oy
        int64_t d = ox + k - oy;
        if (size_[rx] < size_[ry]) {
            std::swap(rx, ry);
            d = -d;
        }
        parent_[ry] = rx;
        offset_[ry] = d;
        size_[rx] += size_[ry];
        return true;
    }

private:
    std::vector<uint32_t> parent_;
    std::vector<int64_t> offset_;
    std::vector<uint32_t> size_;
};

bool strictly_outside(const double* p, const std::array<double, 6>& box) {
    for (int k = 0; k < 3; ++k)
        if (p[k] < box[k] || p[k] > box[3 + k]) return true;
    return false;
}

// The winding number at p (a vertex of self's body `body`, moved by
// `shift` δ) of the other operand's bodies but that one: minus the signed
// crossings of the segment from p to a point beyond the other's box.
int64_t ray_winding(const double* p, uint32_t body, int32_t shift, const Operand& other, bool same) {
    const double reach = other.bounds[3] + (other.bounds[3] - other.bounds[0]) + 1.0;
    const double far[3] = {reach, p[1], p[2]};
    int64_t crossings = 0;
    for (std::size_t s = 0; s < other.triangles(); ++s) {
        const double* box = &other.box[6 * s];
        if (other.degenerate[s] || (same && other.body(s) == body) || box[3] < p[0] || box[1] > p[1] ||
            box[4] < p[1] || box[2] > p[2] || box[5] < p[2])
            continue;
        const int point_shift = shift > other.shift(s) ? 1 : -1;  // p relative to the triangle
        const double* const S[3] = {other.corner(s, 0), other.corner(s, 1), other.corner(s, 2)};
        const int from = perturbed_side(S[0], S[1], S[2], p, point_shift);
        const int to = perturbed_side(S[0], S[1], S[2], far, point_shift);
        if (from == to) continue;
        const int o0 = perturbed_orient_edges(p, far, S[0], S[1], -point_shift);
        if (o0 != perturbed_orient_edges(p, far, S[1], S[2], -point_shift) ||
            o0 != perturbed_orient_edges(p, far, S[2], S[0], -point_shift))
            continue;
        crossings += from;  // +1: entering the other solid
    }
    return -crossings;
}

}  // namespace

std::vector<int32_t> vertex_windings(const Operand& self, const Operand& other, const std::vector<EdgeHit>& hits) {
    const std::size_t nv = self.mesh.vertex_count();
    const bool same = &self == &other;
    std::vector<int64_t> k(self.tri.size(), 0);  // per triangle edge: signed crossings
    for (const EdgeHit& h : hits) k[3 * std::size_t{h.tri} + h.edge] += h.sign;
    OffsetForest forest(nv);
    std::vector<uint8_t> used(nv, 0);
    std::vector<uint32_t> triangle_of(nv, 0);  // one triangle using the vertex (its body)
    for (std::size_t t = 0; t < self.triangles(); ++t) {
        for (int e = 0; e < 3; ++e) {
            const uint32_t x = self.tri[3 * t + e], y = self.tri[3 * t + (e + 1) % 3];
            used[x] = 1;
            triangle_of[x] = static_cast<uint32_t>(t);
            if (!forest.relate(x, y, k[3 * t + e]))
                throw Contradiction("boolean: winding numbers along edges disagree (an operand is not closed)");
        }
    }
    constexpr int64_t kUnknown = INT64_MIN;
    std::vector<int64_t> root_value(nv, kUnknown);
    const bool far_away_exists = other.triangles() > 0;
    for (uint32_t v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        int64_t off;
        const uint32_t r = forest.find(v, off);
        if (root_value[r] == kUnknown && (!far_away_exists || (!same && strictly_outside(self.point(v), other.bounds))))
            root_value[r] = -off;  // w(v) = 0
    }
    std::vector<int32_t> w(nv, 0);
    for (uint32_t v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        int64_t off;
        const uint32_t r = forest.find(v, off);
        if (root_value[r] == kUnknown) {
            const uint32_t t = triangle_of[v];
            root_value[r] = ray_winding(self.point(v), self.body(t), self.shift(t), other, same) - off;
        }
        w[v] = static_cast<int32_t>(root_value[r] + off);
    }
    return w;
}

}  // namespace polyvol::boolean
