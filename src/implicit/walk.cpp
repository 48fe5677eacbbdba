// PL continuation (Allgower & Georg 1990, ch. 15; Allgower & Schmidt 1985):
// from a crossed cube, step across every cube facet with both signs to the
// neighbour, until the component of the PL surface is closed; every crossed
// Kuhn simplex of a visited cube contributes the oriented pieces of its zero
// set (zero_set.cpp). The box's faces are closed by a walk of the same kind
// over each face's own cubes and Kuhn triangulation (F is +infinity outside
// the box).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "implicit/surface.hpp"

namespace polyvol::implicit {

namespace {

// Calls visit(s, f, mask) for every Kuhn simplex of the cube (corner
// cube.corner, perm over cube.axes) with a negative vertex and, when
// need_positive, a positive one, in a fixed order: depth first over the
// prefixes perm[0 .. j-1], which fix v_0 .. v_j (v_j is the corner whose bits
// are those axes). A prefix whose vertices share one sign is abandoned when no
// corner above v_j has the other, so the work is about that of the simplices
// visited.
template <class Visit>
class SimplexEnumerator {
public:
    SimplexEnumerator(const CubeSamples& cube, bool need_positive, Visit& visit)
        : cube_(cube), need_positive_(need_positive), visit_(visit) {
        s_.corner = cube.corner;
        f_[0] = cube.f[0];
        prefix(0, 0, cube.positive[0] ? 1u : 0u);
    }

private:
    void prefix(int j, uint32_t bits, uint32_t mask) {
        const uint32_t all = (2u << j) - 1;  // v_0 .. v_j
        if (mask == all && !cube_.reach_negative[bits]) return;
        if (need_positive_ && mask == 0 && !cube_.reach_positive[bits]) return;
        if (j == cube_.d) {
            visit_(s_, f_, mask);
            return;
        }
        for (int i = 0; i < cube_.d; ++i) {
            if ((bits >> i) & 1u) continue;
            const uint32_t next = bits | (1u << i);
            s_.perm[j] = cube_.axes[i];
            f_[j + 1] = cube_.f[next];
            prefix(j + 1, next, mask | (cube_.positive[next] ? 2u << j : 0u));
        }
    }

    const CubeSamples& cube_;
    bool need_positive_;
    Visit& visit_;
    KuhnSimplex s_;
    std::array<double, kMaxDim + 1> f_;
};

// Whether the corners of the cube's facet x_{axes[i]} = corner + side hold
// a positive and a negative one.
bool facet_signs(const CubeSamples& cube, int i, uint32_t side, bool& positive, bool& negative) {
    positive = negative = false;
    for (uint32_t b = 0; b < (1u << cube.d); ++b)
        if (((b >> i) & 1u) == side) (cube.positive[b] ? positive : negative) = true;
    return positive && negative;
}

}  // namespace

SurfaceBuilder::SurfaceBuilder(const Lattice& lattice, Sampler& sampler, std::size_t max_boundary_simplices,
                               ConeSum* cone)
    : lattice_(lattice),
      sampler_(sampler),
      table_(piece_table(lattice.n)),
      closure_(closure_table(lattice.n - 1)),
      max_simplices_(max_boundary_simplices),
      visited_(1 << 10),
      face_visited_(1 << 10),
      point_vertex_(cone ? 16 : 1 << 12),
      cone_(cone) {
    chain_.dimension = lattice.n;
}

void SurfaceBuilder::sample(CubeSamples& cube) {
    const uint32_t corners = 1u << cube.d;
    cube.any_positive = cube.any_negative = false;
    std::array<Index, 1u << kMaxDim> u;
    for (uint32_t b = 0; b < corners; ++b) {
        u[b] = cube.corner;
        for (int i = 0; i < cube.d; ++i) u[b][cube.axes[i]] += static_cast<int32_t>((b >> i) & 1u);
    }
    if (sampler_.lookahead() && cube.d <= 4) {
        // The 4^d vertices from corner - 1 to corner + 2: the corners of this
        // cube and of its neighbours, which the walk visits next.
        near_.resize(std::size_t{1} << (2 * cube.d));
        for (uint32_t c = 0; c < near_.size(); ++c) {
            near_[c] = cube.corner;
            for (int i = 0; i < cube.d; ++i) near_[c][cube.axes[i]] += static_cast<int32_t>((c >> (2 * i)) & 3u) - 1;
        }
        sampler_.prefetch(near_);
    } else {
        sampler_.prefetch(std::span<const Index>(u.data(), corners));
    }
    for (uint32_t b = 0; b < corners; ++b) {
        cube.f[b] = sampler_.value(u[b]);
        cube.positive[b] = cube.f[b] > 0;
        (cube.positive[b] ? cube.any_positive : cube.any_negative) = true;
    }
    // reach[b] = sign(b) or reach[b + e_i] for some i not in b, from the top corner down.
    for (uint32_t b = corners; b-- > 0;) {
        bool p = cube.positive[b], q = !cube.positive[b];
        for (int i = 0; i < cube.d && !(p && q); ++i)
            if (!((b >> i) & 1u)) {
                p = p || cube.reach_positive[b | (1u << i)];
                q = q || cube.reach_negative[b | (1u << i)];
            }
        cube.reach_positive[b] = p;
        cube.reach_negative[b] = q;
    }
}

bool SurfaceBuilder::walk_from(const KuhnSimplex& seed) {
    return lattice_.is_real(seed) && walk_from_cube(seed.corner);
}

bool SurfaceBuilder::walk_from_cube(const Index& start) {
    if (!visited_.insert(lattice_.cube_key(start), 1).second) return false;
    ++surface_walks_;
    const int n = lattice_.n;
    cube_stack_.push_back(start);
    CubeSamples cube;
    cube.d = n;
    for (int k = 0; k < n; ++k) cube.axes[k] = static_cast<uint8_t>(k);
    auto crossed = [this](const KuhnSimplex& s, const std::array<double, kMaxDim + 1>& f, uint32_t mask) {
        ++crossed_;
        emit_pieces(s, f, mask);
    };
    while (!cube_stack_.empty()) {
        cube.corner = cube_stack_.back();
        cube_stack_.pop_back();
        sample(cube);
        if (!cube.any_positive || !cube.any_negative) continue;  // a seed's cube that is not crossed
        SimplexEnumerator<decltype(crossed)>(cube, true, crossed);
        for (int k = 0; k < n; ++k) {
            for (uint32_t side = 0; side < 2; ++side) {
                bool positive, negative;
                if (!facet_signs(cube, k, side, positive, negative)) continue;  // no crossed simplex facet in it
                Index next = cube.corner;
                next[k] += side ? 1 : -1;
                if (next[k] < 0 || next[k] >= lattice_.cells[k]) continue;  // a box facet: closed by close_faces
                if (visited_.insert(lattice_.cube_key(next), 1).second) cube_stack_.push_back(next);
            }
        }
    }
    return true;
}

void SurfaceBuilder::reserve_pieces(std::size_t count) {
    pieces_ += count;
    if (pieces_ > max_simplices_)
        throw ImplicitError(ImplicitError::Code::too_large, {},
                            "implicit: more than " + std::to_string(max_simplices_) +
                                " boundary simplices (h is too small, or raise max_boundary_simplices)");
}

void SurfaceBuilder::emit_pieces(const KuhnSimplex& s, const std::array<double, kMaxDim + 1>& f, uint32_t mask) {
    const int n = lattice_.n;
    const uint32_t first = table_.offsets[mask], last = table_.offsets[mask + 1];
    reserve_pieces(last - first);
    if (cone_) {
        cone_->add({s, f, mask, -1, false});
        return;
    }
    std::array<Index, kMaxDim + 1> v;
    kuhn_vertices(s, n, v);
    // An odd permutation: the map from the reference simplex reverses orientation.
    append_pieces(table_, first, last, s, v, f, permutation_odd(s.perm, n));
}

void SurfaceBuilder::append_pieces(const PieceTable& table, uint32_t first, uint32_t last, const KuhnSimplex& s,
                                   const std::array<Index, kMaxDim + 1>& v, const std::array<double, kMaxDim + 1>& f,
                                   bool flip) {
    const int n = lattice_.n;
    std::array<uint32_t, kMaxDim> ids;
    for (uint32_t p = first; p < last; ++p) {
        for (int i = 0; i < n; ++i) {
            const auto& e = table.vertices[static_cast<std::size_t>(p) * n + i];
            uint64_t axes = 0;
            for (int j = std::min(e[0], e[1]); j < std::max(e[0], e[1]); ++j) axes |= uint64_t{1} << s.perm[j];
            ids[i] = point_vertex(v, f, e[0], e[1], axes);
        }
        if (flip) std::swap(ids[0], ids[1]);
        chain_.simplices.insert(chain_.simplices.end(), ids.begin(), ids.begin() + n);
    }
}

void piece_point(const Lattice& lattice, const std::array<Index, kMaxDim + 1>& v,
                 const std::array<double, kMaxDim + 1>& f, int positive, int negative, double* x) {
    const Index& a = v[negative];
    const Index& b = v[positive];
    const double t = positive == negative ? 0.0 : crossing_parameter(f[negative], f[positive]);
    for (int k = 0; k < lattice.n; ++k)
        x[k] = crossing_coordinate(lattice.coordinate(k, a[k]), lattice.coordinate(k, b[k]), a[k] != b[k], t);
}

// The chain vertex of a piece point, created once per point key.
uint32_t SurfaceBuilder::point_vertex(const std::array<Index, kMaxDim + 1>& v,
                                      const std::array<double, kMaxDim + 1>& f, int positive, int negative,
                                      uint64_t axes) {
    const int n = lattice_.n;
    const Index& low = positive < negative ? v[positive] : v[negative];  // v is in increasing order
    const uint64_t key = (lattice_.vertex_key(low) << n) | axes;
    if (const uint32_t* id = point_vertex_.find(key)) return *id;
    const std::size_t id = chain_.vertex_count();
    chain_.coordinates.resize(chain_.coordinates.size() + static_cast<std::size_t>(n));
    piece_point(lattice_, v, f, positive, negative, chain_.coordinates.data() + id * static_cast<std::size_t>(n));
    if (id >= std::numeric_limits<uint32_t>::max())
        throw ImplicitError(ImplicitError::Code::too_large, {}, "implicit: more than 2^32 surface vertices");
    point_vertex_.insert(key, static_cast<uint32_t>(id));
    return static_cast<uint32_t>(id);
}

// A face cube's key: its owning box cube, the face's axis and side.
uint64_t SurfaceBuilder::face_key(const FaceCube& c) const {
    Index owner = c.corner;
    const bool hi = owner[c.axis] != 0;
    if (hi) --owner[c.axis];
    return (lattice_.cube_key(owner) * static_cast<uint64_t>(lattice_.n) + static_cast<uint64_t>(c.axis)) * 2 +
           (hi ? 1 : 0);
}

bool SurfaceBuilder::face_walk_from(const FaceCube& seed) {
    const int n = lattice_.n;
    if (!face_visited_.insert(face_key(seed), 1).second) return false;
    ++face_walks_;
    face_stack_.push_back(seed);
    CubeSamples cube;
    cube.d = n - 1;
    while (!face_stack_.empty()) {
        const FaceCube c = face_stack_.back();
        face_stack_.pop_back();
        cube.corner = c.corner;
        for (int k = 0, i = 0; k < n; ++k)
            if (k != c.axis) cube.axes[i++] = static_cast<uint8_t>(k);
        sample(cube);
        if (!cube.any_negative) continue;
        auto inside = [this, &c](const KuhnSimplex& t, const std::array<double, kMaxDim + 1>& f, uint32_t mask) {
            ++face_simplices_;
            emit_closure(t, c.axis, f, mask);
        };
        SimplexEnumerator<decltype(inside)>(cube, false, inside);
        if (cube.any_positive) {  // the surface crosses this face cube: walk from the cube owning it
            Index owner = c.corner;
            if (owner[c.axis] != 0) --owner[c.axis];
            walk_from_cube(owner);
        }
        for (int i = 0; i < cube.d; ++i) {
            for (uint32_t side = 0; side < 2; ++side) {
                bool positive, negative;
                facet_signs(cube, i, side, positive, negative);
                if (!negative) continue;  // no vertex with F <= 0 on that facet
                FaceCube next = c;
                const int k = cube.axes[i];
                next.corner[k] += side ? 1 : -1;
                // Beyond a ridge of the box: the other face's walk closes it.
                if (next.corner[k] < 0 || next.corner[k] >= lattice_.cells[k]) continue;
                if (face_visited_.insert(face_key(next), 1).second) face_stack_.push_back(next);
            }
        }
    }
    return true;
}

bool closure_flip(const KuhnSimplex& face_simplex, int axis, bool hi_face, int n) {
    // The table's pieces have det(w_i - w_0) > 0 in the reference face simplex;
    // the face simplex is its image under a map of sign (-1)^parity(perm). Out
    // of the box means (see docs/implicit.md) sign = -side (-1)^axis in the
    // face's coordinates, side = +1 on the lo face and -1 on the hi face.
    const int side = hi_face ? -1 : 1;
    const int wanted = -side * ((axis & 1) ? -1 : 1);
    const int have = permutation_odd(face_simplex.perm, n - 1) ? -1 : 1;
    return wanted != have;
}

void SurfaceBuilder::emit_closure(const KuhnSimplex& t, int axis, const std::array<double, kMaxDim + 1>& f,
                                  uint32_t mask) {
    const int n = lattice_.n;
    const bool hi_face = t.corner[axis] != 0;
    const uint32_t first = closure_.offsets[mask], last = closure_.offsets[mask + 1];
    reserve_pieces(last - first);
    if (cone_) {
        cone_->add({t, f, mask, static_cast<int8_t>(axis), hi_face});
        return;
    }
    std::array<Index, kMaxDim + 1> v;
    kuhn_vertices(t, n - 1, v);
    append_pieces(closure_, first, last, t, v, f, closure_flip(t, axis, hi_face, n));
}

void SurfaceBuilder::close_faces() {
    const int n = lattice_.n;
    auto& seeds = sampler_.boundary_inside();
    while (boundary_done_ < seeds.size()) {
        const Index u = seeds[boundary_done_++];  // a copy: walks append to seeds
        for (int axis = 0; axis < n; ++axis) {
            if (u[axis] != 0 && u[axis] != lattice_.cells[axis]) continue;
            // The face cube with corner u, clamped to N_k - 1 off the face axis.
            FaceCube c{u, axis};
            for (int k = 0; k < n; ++k)
                if (k != axis && u[k] == lattice_.cells[k]) --c.corner[k];
            face_walk_from(c);
        }
    }
}

}  // namespace polyvol::implicit
