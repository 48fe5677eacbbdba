// Private to implicit: the lattice, the cached samples of F, and the
// continuation walk that builds the PL surface as a chain.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "implicit/flat_map.hpp"
#include "implicit/kuhn.hpp"
#include "polyvol/chain.hpp"
#include "polyvol/implicit.hpp"

namespace polyvol::implicit {

// The lattice of one pass. Real vertices have 0 <= i_k <= N_k; outside the
// box F counts as +infinity, and the box's faces are closed by the face walk.
// Keys (the constructor checks that they fit below 2^63):
//   vertex key  = Σ_k (i_k + 1) vertex_stride[k],  vertex_stride[k] = Π_{l<k} (N_l + 3)
//   cube key    = Σ_k (c_k + 1) cube_stride[k],    cube_stride[k]   = Π_{l<k} (N_l + 2)
//   simplex key = cube key * n! + rank(perm)
//   point key   = vertex key * 2^n + Σ_{axes a of the edge} 2^a for the crossing
//                 on the edge from that (lower) vertex; + 0 for the vertex itself
struct Lattice {
    int n = 0;
    std::array<double, kMaxDim> lo{}, hi{}, spacing{};
    std::array<int32_t, kMaxDim> cells{};  // N_k
    std::array<uint64_t, kMaxDim> vertex_stride{}, cube_stride{};
    uint64_t permutations = 1;  // n!

    // N_k = cells[k] (each even, >= 2).
    Lattice(int dimension, std::span<const double> lo, std::span<const double> hi,
            std::span<const int32_t> cells);

    // x_k of lattice coordinate i (real: 0 <= i <= N_k): lo + i h (hi at N_k).
    double coordinate(int k, int32_t i) const {
        return i == cells[k] ? hi[k] : lo[k] + static_cast<double>(i) * spacing[k];
    }
    // A simplex of the box's cubes: 0 <= c_k < N_k.
    bool is_real(const KuhnSimplex& s) const {
        for (int k = 0; k < n; ++k)
            if (s.corner[k] < 0 || s.corner[k] >= cells[k]) return false;
        return true;
    }
    bool is_virtual(const Index& v) const {
        for (int k = 0; k < n; ++k)
            if (v[k] < 0 || v[k] > cells[k]) return true;
        return false;
    }
    bool on_boundary(const Index& v) const {
        for (int k = 0; k < n; ++k)
            if (v[k] == 0 || v[k] == cells[k]) return true;
        return false;
    }
    uint64_t vertex_key(const Index& v) const {
        uint64_t key = 0;
        for (int k = 0; k < n; ++k) key += static_cast<uint64_t>(v[k] + 1) * vertex_stride[k];
        return key;
    }
    uint64_t simplex_key(const KuhnSimplex& s) const {
        uint64_t key = 0;
        for (int k = 0; k < n; ++k) key += static_cast<uint64_t>(s.corner[k] + 1) * cube_stride[k];
        return key * permutations + permutation_rank(s.perm, n);
    }
};

// Cells per axis for a requested spacing: N_k = 2 ceil((hi_k - lo_k) / (2h)).
std::vector<int32_t> lattice_cells(std::span<const double> lo, std::span<const double> hi, double h);

// F at lattice vertices, each evaluated at most once. Virtual vertices are
// +infinity and never evaluated. NaN throws; with BoxRule::error a boundary
// vertex with F <= 0 throws.
class Sampler {
public:
    Sampler(const Lattice& lattice, const ImplicitFunction& f, BoxRule rule);
    double value(const Index& v);
    // Sign rule: positive iff F > 0 (0 counts as negative).
    bool positive(const Index& v) { return value(v) > 0; }
    std::size_t evaluations() const { return evaluations_; }
    std::size_t box_vertices_inside() const { return box_inside_; }
    // Vertices on the box boundary with F <= 0, in the order met (each once):
    // the seeds of the face walks.
    std::vector<Index>& boundary_inside() { return boundary_inside_; }

private:
    const Lattice& lattice_;
    const ImplicitFunction& f_;
    BoxRule rule_;
    FlatMap<double> values_;
    std::vector<double> x_;
    std::size_t evaluations_ = 0;
    std::size_t box_inside_ = 0;
    std::vector<Index> boundary_inside_;
};

// The continuation walk: visits the crossed simplices of the box through
// crossed facets and appends each one's oriented pieces to `chain`; then the
// face walk closes the chain in the box's faces. Points are shared through a
// map from point keys to chain vertices.
class SurfaceBuilder {
public:
    SurfaceBuilder(const Lattice& lattice, Sampler& sampler, std::size_t max_boundary_simplices);
    // Walks the component containing seed (a crossed simplex of the box)
    // unless its simplex was visited before; returns whether a walk was made.
    bool walk_from(const KuhnSimplex& seed);
    // Closes the chain: for every box face and every simplex of its Kuhn
    // triangulation reachable from a boundary vertex with F <= 0 through faces
    // with such a vertex, the pulling triangulation of its part with F <= 0
    // (closure_table), oriented outward (out of the box). A face simplex that
    // the surface crosses also starts a walk from the simplex owning it, so
    // pieces of the surface joined only through the box faces are all found.
    void close_faces();
    std::size_t crossed_simplices() const { return visited_.size(); }
    std::size_t surface_walks() const { return surface_walks_; }
    std::size_t face_walks() const { return face_walks_; }
    std::size_t face_simplices() const { return face_visited_.size(); }
    Chain take_chain() { return std::move(chain_); }

private:
    struct Pending {
        KuhnSimplex s;
        std::array<double, kMaxDim + 1> f;  // F at its vertices, except vertex `fresh`
        int fresh;                          // the vertex to sample; -1: all of them
    };
    struct FaceSimplex {
        KuhnSimplex s;  // corner on the face; perm[0 .. n-2] the face's axes
        int axis = 0;   // the face is x_axis = lo (corner[axis] == 0) or hi (== N_axis)
    };
    void emit_pieces(const KuhnSimplex& s, const std::array<Index, kMaxDim + 1>& v,
                     const std::array<double, kMaxDim + 1>& f, uint32_t mask);
    bool face_walk_from(const FaceSimplex& seed);
    void emit_closure(const FaceSimplex& t, const std::array<Index, kMaxDim + 1>& v,
                      const std::array<double, kMaxDim + 1>& f, uint32_t mask);
    // The simplex of the box whose facet is the face simplex t.
    KuhnSimplex owner(const FaceSimplex& t) const;
    uint64_t face_key(const FaceSimplex& t) const;
    void reserve_pieces(std::size_t count);
    // Chain vertex of the point (a, b) of simplex vertices v (edge a-b, a
    // positive; a == b: the vertex itself); `axes` the edge's direction bits.
    uint32_t point_vertex(const std::array<Index, kMaxDim + 1>& v, const std::array<double, kMaxDim + 1>& f,
                          int positive, int negative, uint64_t axes);

    const Lattice& lattice_;
    Sampler& sampler_;
    const PieceTable& table_;
    const PieceTable& closure_;
    std::size_t max_simplices_;
    FlatMap<uint8_t> visited_;
    FlatMap<uint8_t> face_visited_;  // face_key
    FlatMap<uint32_t> point_vertex_;
    std::vector<Pending> stack_;
    std::vector<FaceSimplex> face_stack_;
    std::size_t boundary_done_ = 0;
    std::size_t surface_walks_ = 0, face_walks_ = 0;  // sampler_.boundary_inside() entries used as seeds
    Chain chain_;
};

// Seeding: the coarse scan (coarse_cells per axis, capped at N_k; < 0: none)
// and the seed points; each seed found starts a walk; then the box faces are
// closed (SurfaceBuilder::close_faces).
void seed_and_walk(const Lattice& lattice, Sampler& sampler, SurfaceBuilder& builder, int coarse_cells,
                   std::span<const double> seed_points);

}  // namespace polyvol::implicit
