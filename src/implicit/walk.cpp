// PL continuation (Allgower & Georg 1990, ch. 15; Allgower & Schmidt 1985):
// from a crossed simplex, step across every crossed facet to the neighbour,
// until the component of the PL surface is closed. Each crossed simplex
// contributes the oriented pieces of its zero set (zero_set.cpp). The box's
// faces are closed by a walk of the same kind in each face's own Kuhn
// triangulation (F is +infinity outside the box).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "implicit/surface.hpp"

namespace polyvol::implicit {

SurfaceBuilder::SurfaceBuilder(const Lattice& lattice, Sampler& sampler, std::size_t max_boundary_simplices)
    : lattice_(lattice),
      sampler_(sampler),
      table_(piece_table(lattice.n)),
      closure_(closure_table(lattice.n - 1)),
      max_simplices_(max_boundary_simplices),
      visited_(1 << 12),
      face_visited_(1 << 10),
      point_vertex_(1 << 12) {
    chain_.dimension = lattice.n;
}

bool SurfaceBuilder::walk_from(const KuhnSimplex& seed) {
    if (!lattice_.is_real(seed) || !visited_.insert(lattice_.simplex_key(seed), 1).second) return false;
    ++surface_walks_;
    const int n = lattice_.n;
    const uint32_t all = (1u << (n + 1)) - 1;
    stack_.push_back({seed, {}, -1});
    std::array<Index, kMaxDim + 1> v;
    while (!stack_.empty()) {
        const Pending p = stack_.back();
        stack_.pop_back();
        const KuhnSimplex& s = p.s;
        std::array<double, kMaxDim + 1> f = p.f;
        kuhn_vertices(s, n, v);
        uint32_t mask = 0;  // bit j: vertex j positive
        for (int j = 0; j <= n; ++j) {
            if (p.fresh < 0 || j == p.fresh) f[j] = sampler_.value(v[j]);
            if (f[j] > 0) mask |= 1u << j;
        }
        if (mask == 0 || mask == all) continue;  // a seed that is not crossed
        emit_pieces(s, v, f, mask);
        for (int j = 0; j <= n; ++j) {
            const uint32_t facet = all & ~(1u << j);
            if ((mask & facet) == 0 || (mask & facet) == facet) continue;  // facet not crossed
            Pending t{kuhn_neighbour(s, n, j), {}, j};
            if (!lattice_.is_real(t.s)) continue;  // a box facet: closed by close_faces
            if (!visited_.insert(lattice_.simplex_key(t.s), 1).second) continue;
            // The neighbour's vertices in order (kuhn_neighbour): j = 0 drops v_0
            // and appends one, j = n prepends one and drops v_n, otherwise v_j is
            // replaced; the n shared values come along, one is sampled.
            if (j == 0) {
                for (int i = 0; i < n; ++i) t.f[i] = f[i + 1];
                t.fresh = n;
            } else if (j == n) {
                for (int i = 0; i < n; ++i) t.f[i + 1] = f[i];
                t.fresh = 0;
            } else {
                t.f = f;
            }
            stack_.push_back(t);
        }
    }
    return true;
}

void SurfaceBuilder::reserve_pieces(std::size_t count) {
    if (chain_.simplex_count() + count > max_simplices_)
        throw ImplicitError(ImplicitError::Code::too_large, {},
                            "implicit: more than " + std::to_string(max_simplices_) +
                                " boundary simplices (h is too small, or raise max_boundary_simplices)");
}

void SurfaceBuilder::emit_pieces(const KuhnSimplex& s, const std::array<Index, kMaxDim + 1>& v,
                                 const std::array<double, kMaxDim + 1>& f, uint32_t mask) {
    const int n = lattice_.n;
    const bool odd = permutation_odd(s.perm, n);
    const uint32_t first = table_.offsets[mask], last = table_.offsets[mask + 1];
    reserve_pieces(last - first);
    std::array<uint32_t, kMaxDim> ids;
    for (uint32_t p = first; p < last; ++p) {
        for (int i = 0; i < n; ++i) {
            const auto& e = table_.vertices[static_cast<std::size_t>(p) * n + i];
            uint64_t axes = 0;
            for (int j = std::min(e[0], e[1]); j < std::max(e[0], e[1]); ++j) axes |= uint64_t{1} << s.perm[j];
            ids[i] = point_vertex(v, f, e[0], e[1], axes);
        }
        if (odd) std::swap(ids[0], ids[1]);  // the map from the reference simplex reverses orientation
        chain_.simplices.insert(chain_.simplices.end(), ids.begin(), ids.begin() + n);
    }
}

// A lattice vertex (positive == negative), or the crossing of the linear
// interpolant with 0 on the edge (negative a, positive b):
// x = a + t (b - a), t = F(a) / (F(a) - F(b)) in [0, 1), computed once per edge
// from the same two values whichever simplex reaches it.
uint32_t SurfaceBuilder::point_vertex(const std::array<Index, kMaxDim + 1>& v,
                                      const std::array<double, kMaxDim + 1>& f, int positive, int negative,
                                      uint64_t axes) {
    const int n = lattice_.n;
    const Index& a = v[negative];
    const Index& b = v[positive];
    const Index& low = positive < negative ? b : a;  // v is in increasing order
    const uint64_t key = (lattice_.vertex_key(low) << n) | axes;
    if (const uint32_t* id = point_vertex_.find(key)) return *id;

    double t = 0;
    if (positive != negative) {
        const double fa = f[negative], fb = f[positive];  // fa <= 0 < fb
        if (std::isinf(fb))
            t = std::isinf(fa) ? 0.5 : 0.0;  // next to an infinite value: at the other end
        else if (std::isinf(fa))
            t = 1.0;
        else
            t = fa / (fa - fb);
    }
    for (int k = 0; k < n; ++k) {
        const double xa = lattice_.coordinate(k, a[k]);
        if (a[k] == b[k] || t == 0.0) {
            chain_.coordinates.push_back(xa);
        } else {
            const double xb = lattice_.coordinate(k, b[k]);
            chain_.coordinates.push_back(xa + t * (xb - xa));
        }
    }
    const std::size_t id = chain_.vertex_count() - 1;
    if (id >= std::numeric_limits<uint32_t>::max())
        throw ImplicitError(ImplicitError::Code::too_large, {}, "implicit: more than 2^32 surface vertices");
    point_vertex_.insert(key, static_cast<uint32_t>(id));
    return static_cast<uint32_t>(id);
}

KuhnSimplex SurfaceBuilder::owner(const FaceSimplex& t) const {
    const int n = lattice_.n;
    KuhnSimplex s;
    s.corner = t.s.corner;
    if (t.s.corner[t.axis] == 0) {  // lo face: the facet opposite v_n
        for (int i = 0; i + 1 < n; ++i) s.perm[i] = t.s.perm[i];
        s.perm[n - 1] = static_cast<uint8_t>(t.axis);
    } else {  // hi face: the facet opposite v_0
        --s.corner[t.axis];
        s.perm[0] = static_cast<uint8_t>(t.axis);
        for (int i = 0; i + 1 < n; ++i) s.perm[i + 1] = t.s.perm[i];
    }
    return s;
}

// A simplex of the box owns at most one lo-face facet (opposite v_n) and one
// hi-face facet (opposite v_0).
uint64_t SurfaceBuilder::face_key(const FaceSimplex& t) const {
    return 2 * lattice_.simplex_key(owner(t)) + (t.s.corner[t.axis] == 0 ? 0 : 1);
}

bool SurfaceBuilder::face_walk_from(const FaceSimplex& seed) {
    const int n = lattice_.n, d = n - 1;
    if (!face_visited_.insert(face_key(seed), 1).second) return false;
    ++face_walks_;
    face_stack_.push_back(seed);
    std::array<Index, kMaxDim + 1> v;
    std::array<double, kMaxDim + 1> f;
    const uint32_t all = (1u << n) - 1;  // the face simplex's n vertices
    while (!face_stack_.empty()) {
        const FaceSimplex t = face_stack_.back();
        face_stack_.pop_back();
        kuhn_vertices(t.s, d, v);
        uint32_t mask = 0;
        for (int j = 0; j < n; ++j) {
            f[j] = sampler_.value(v[j]);
            if (f[j] > 0) mask |= 1u << j;
        }
        if (mask == all) continue;
        emit_closure(t, v, f, mask);
        if (mask != 0) walk_from(owner(t));  // the surface crosses this face simplex
        for (int j = 0; j < n; ++j) {
            if ((mask | (1u << j)) == all) continue;  // no vertex with F <= 0 on that facet
            FaceSimplex u{kuhn_neighbour(t.s, d, j), t.axis};
            bool inside = true;
            for (int k = 0; k < n; ++k)
                if (k != t.axis && (u.s.corner[k] < 0 || u.s.corner[k] >= lattice_.cells[k])) inside = false;
            if (!inside) continue;  // a ridge of the box: the other face's walk closes it
            if (face_visited_.insert(face_key(u), 1).second) face_stack_.push_back(u);
        }
    }
    return true;
}

void SurfaceBuilder::emit_closure(const FaceSimplex& t, const std::array<Index, kMaxDim + 1>& v,
                                  const std::array<double, kMaxDim + 1>& f, uint32_t mask) {
    const int n = lattice_.n, d = n - 1;
    // The table's pieces have det(w_i - w_0) > 0 in the reference face simplex;
    // the face simplex is its image under a map of sign (-1)^parity(perm). Out
    // of the box means (see docs/implicit.md) sign = -side (-1)^axis in the
    // face's coordinates, side = +1 on the lo face and -1 on the hi face.
    const int side = t.s.corner[t.axis] == 0 ? 1 : -1;
    const int wanted = -side * ((t.axis & 1) ? -1 : 1);
    const int have = permutation_odd(t.s.perm, d) ? -1 : 1;
    const bool flip = wanted != have;
    const uint32_t first = closure_.offsets[mask], last = closure_.offsets[mask + 1];
    reserve_pieces(last - first);
    std::array<uint32_t, kMaxDim> ids;
    for (uint32_t p = first; p < last; ++p) {
        for (int i = 0; i < n; ++i) {
            const auto& e = closure_.vertices[static_cast<std::size_t>(p) * n + i];
            uint64_t axes = 0;
            for (int j = std::min(e[0], e[1]); j < std::max(e[0], e[1]); ++j) axes |= uint64_t{1} << t.s.perm[j];
            ids[i] = point_vertex(v, f, e[0], e[1], axes);
        }
        if (flip) std::swap(ids[0], ids[1]);
        chain_.simplices.insert(chain_.simplices.end(), ids.begin(), ids.begin() + n);
    }
}

void SurfaceBuilder::close_faces() {
    const int n = lattice_.n;
    auto& seeds = sampler_.boundary_inside();
    while (boundary_done_ < seeds.size()) {
        const Index u = seeds[boundary_done_++];  // a copy: walks append to seeds
        for (int axis = 0; axis < n; ++axis) {
            if (u[axis] != 0 && u[axis] != lattice_.cells[axis]) continue;
            // The face simplex with vertex u: corner min(u, N - 1) off the face
            // axis, the clamped axes first in perm.
            FaceSimplex t;
            t.axis = axis;
            t.s.corner = u;
            int i = 0;
            for (int k = 0; k < n; ++k)
                if (k != axis && u[k] == lattice_.cells[k]) {
                    --t.s.corner[k];
                    t.s.perm[i++] = static_cast<uint8_t>(k);
                }
            for (int k = 0; k < n; ++k)
                if (k != axis && u[k] != lattice_.cells[k]) t.s.perm[i++] = static_cast<uint8_t>(k);
            face_walk_from(t);
        }
    }
}

}  // namespace polyvol::implicit
