// Private to implicit: the lattice, the cached samples of F, and the
// continuation walk that builds the PL surface as a chain.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <cstdint>
#include <vector>

#include "implicit/cone_sum.hpp"
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
//   face key    = (cube key of the owning box cube * n + axis) * 2 + (hi face)
//                 (below vertex key * 2^n: cube key < Π (N_l + 2), 2n <= 2^n)
//   point key   = vertex key * 2^n + Σ_{axes a of the edge} 2^a for the crossing
//                 on the edge from that (lower) vertex; + 0 for the vertex itself
struct Lattice {
    int n = 0;
    std::array<double, kMaxDim> lo{}, hi{}, spacing{};
    std::array<int32_t, kMaxDim> cells{};  // N_k
    std::array<uint64_t, kMaxDim> vertex_stride{}, cube_stride{};

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
    uint64_t cube_key(const Index& corner) const {
        uint64_t key = 0;
        for (int k = 0; k < n; ++k) key += static_cast<uint64_t>(corner[k] + 1) * cube_stride[k];
        return key;
    }
};

// Point (positive, negative) of a simplex with vertices v and values f: the
// vertex v[negative] itself when positive == negative, else the crossing of
// the linear interpolant with 0 on the edge, x = a + t (b - a) with
// a = v[negative], b = v[positive], t = F(a) / (F(a) - F(b)) in [0, 1) (next to
// an infinite value: at the other end). A function of the two lattice vertices
// and their two values only, so every simplex (and both the chain and the
// streaming paths) computes the same bits for the same edge. x[0 .. n-1].
void piece_point(const Lattice& lattice, const std::array<Index, kMaxDim + 1>& v,
                 const std::array<double, kMaxDim + 1>& f, int positive, int negative, double* x);

// The parts of piece_point, shared with the streaming path (cone_sum.cpp) so
// that both compute the same bits: t on the edge from a (F(a) = fa <= 0) to b
// (F(b) = fb > 0), and one coordinate of the crossing.
inline double crossing_parameter(double fa, double fb) {
    if (std::isinf(fb)) return std::isinf(fa) ? 0.5 : 0.0;  // next to an infinite value: at the other end
    if (std::isinf(fa)) return 1.0;
    return fa / (fa - fb);
}
inline double crossing_coordinate(double xa, double xb, bool moves, double t) {
    return !moves || t == 0.0 ? xa : xa + t * (xb - xa);
}

// Whether the closure pieces of a face simplex (closure_table, oriented in the
// reference face simplex) take their first two points exchanged to point out
// of the box: see docs/implicit.md, "The box".
bool closure_flip(const KuhnSimplex& face_simplex, int axis, bool hi_face, int n);

// Cells per axis for a requested spacing: N_k = 2 ceil((hi_k - lo_k) / (2h)).
std::vector<int32_t> lattice_cells(std::span<const double> lo, std::span<const double> hi, double h);

// F at lattice vertices, each evaluated at most once. Virtual vertices are
// +infinity and never evaluated. NaN throws; with BoxRule::error a boundary
// vertex with F <= 0 throws. prefetch() evaluates several vertices in one
// call of F; each is then taken in by value() when first asked for, so the
// checks and the boundary list run in the order the walk asks, as without
// prefetching (the same bits). With lookahead (F a batch function whose
// calls cost), the walk prefetches a cube's neighbourhood, not only its
// corners: more points per call, a few evaluated for nothing.
class Sampler {
public:
    // max_evaluations: ImplicitError(too_large) past this many (0: no limit).
    Sampler(const Lattice& lattice, const ImplicitBatchFunction& f, BoxRule rule, bool lookahead = false,
            std::size_t max_evaluations = 0);
    double value(const Index& v);
    // Evaluates those of vs not yet known in one call.
    void prefetch(std::span<const Index> vs);
    bool lookahead() const { return lookahead_; }
    // Sign rule: positive iff F > 0 (0 counts as negative).
    bool positive(const Index& v) { return value(v) > 0; }
    std::size_t evaluations() const { return evaluations_; }
    // Called with the evaluations so far every 2^18 of them.
    void on_evaluations(std::function<void(std::size_t)> tick) { tick_ = std::move(tick); }
    std::size_t box_vertices_inside() const { return box_inside_; }
    // Vertices on the box boundary with F <= 0, in the order met (each once):
    // the seeds of the face walks.
    std::vector<Index>& boundary_inside() { return boundary_inside_; }

private:
    const Lattice& lattice_;
    const ImplicitBatchFunction& f_;
    BoxRule rule_;
    bool lookahead_;
    std::size_t max_evaluations_;
    std::function<void(std::size_t)> tick_;
    std::size_t next_tick_ = std::size_t{1} << 18;
    void count(std::size_t evaluations);
    FlatMap<double> values_;
    FlatMap<double> prefetched_;  // evaluated, taken into values_ when first asked for
    std::vector<double> x_;
    std::vector<uint64_t> keys_;
    std::vector<double> points_, batch_;
    std::size_t evaluations_ = 0;
    std::size_t box_inside_ = 0;
    std::vector<Index> boundary_inside_;
};

// F at the corners of a d-cube of the lattice (d = n for a cube of the box,
// n - 1 for a cube of a box face) spanned by axes[0 .. d-1]: corner b is
// corner + Σ_{i : bit i of b} e_{axes[i]}. reach_positive[b] (reach_negative[b])
// says some corner b' ⊇ b — componentwise above corner b — is positive
// (negative).
struct CubeSamples {
    Index corner{};
    int d = 0;
    std::array<uint8_t, kMaxDim> axes{};
    std::array<double, 1u << kMaxDim> f;
    std::array<bool, 1u << kMaxDim> positive;
    std::array<bool, 1u << kMaxDim> reach_positive, reach_negative;
    bool any_positive = false, any_negative = false;
};

// The continuation walk: visits the crossed cubes of the box through cube
// facets with both signs and hands every crossed Kuhn simplex in them to
// emit_pieces (a cube facet with both signs holds a crossed simplex facet, and
// the surface passes from cube to cube only through crossed simplex facets, so
// the walk follows the PL surface; its cost is O(crossed cubes), one hash
// probe per cube). Then the face walk closes the chain in the box's faces.
// Without a ConeSum the pieces are appended to a chain, points shared through
// a map from point keys to chain vertices; with one (the streaming path) each
// simplex with pieces is handed to the sum instead, and no chain is built.
class SurfaceBuilder {
public:
    SurfaceBuilder(const Lattice& lattice, Sampler& sampler, std::size_t max_boundary_simplices,
                   ConeSum* cone = nullptr);
    // Walks the crossed cubes connected to the cube of seed (a crossed
    // simplex of the box) unless that cube was visited before; returns
    // whether a walk was made.
    bool walk_from(const KuhnSimplex& seed);
    // Closes the chain: for every box face and every simplex of its Kuhn
    // triangulation with a vertex where F <= 0, in the face cubes reachable
    // from a boundary vertex with F <= 0 through cube facets with such a
    // vertex, the pulling triangulation of its part with F <= 0
    // (closure_table), oriented outward (out of the box). A face cube that the
    // surface crosses also starts a walk from the cube owning it, so pieces of
    // the surface joined only through the box faces are all found.
    void close_faces();
    std::size_t crossed_simplices() const { return crossed_; }
    std::size_t surface_walks() const { return surface_walks_; }
    std::size_t face_walks() const { return face_walks_; }
    std::size_t face_simplices() const { return face_simplices_; }
    // Pieces emitted (with a ConeSum: also those of faces through the apex,
    // which it drops).
    std::size_t boundary_simplices() const { return pieces_; }
    Chain take_chain() { return std::move(chain_); }

private:
    struct FaceCube {
        Index corner{};  // corner[axis] == 0 (lo face) or N_axis (hi face)
        int axis = 0;
    };
    bool walk_from_cube(const Index& corner);
    void sample(CubeSamples& cube);
    void emit_pieces(const KuhnSimplex& s, const std::array<double, kMaxDim + 1>& f, uint32_t mask);
    bool face_walk_from(const FaceCube& seed);
    // A face simplex: corner on the face, perm[0 .. n-2] the face's axes.
    void emit_closure(const KuhnSimplex& t, int axis, const std::array<double, kMaxDim + 1>& f, uint32_t mask);
    // Appends pieces [first, last) of `table` to the chain for the simplex s
    // (vertices v, F values f): piece vertex i is the point on the edge the
    // table names, keyed by the axes that edge spans; flip swaps two vertices.
    void append_pieces(const PieceTable& table, uint32_t first, uint32_t last, const KuhnSimplex& s,
                       const std::array<Index, kMaxDim + 1>& v, const std::array<double, kMaxDim + 1>& f, bool flip);
    uint64_t face_key(const FaceCube& c) const;
    void reserve_pieces(std::size_t count);
    // Chain vertex of the point (a, b) of simplex vertices v (edge a-b, a
    // positive; a == b: the vertex itself); `axes` the edge's direction bits.
    uint32_t point_vertex(const std::array<Index, kMaxDim + 1>& v, const std::array<double, kMaxDim + 1>& f,
                          int positive, int negative, uint64_t axes);

    const Lattice& lattice_;
    Sampler& sampler_;
    std::vector<Index> near_;  // a cube's neighbourhood, for the sampler's lookahead
    const PieceTable& table_;
    const PieceTable& closure_;
    std::size_t max_simplices_;
    FlatMap<uint8_t> visited_;       // cube_key of the box cubes walked
    FlatMap<uint8_t> face_visited_;  // face_key of the face cubes walked
    FlatMap<uint32_t> point_vertex_;
    std::vector<Index> cube_stack_;
    std::vector<FaceCube> face_stack_;
    std::size_t crossed_ = 0, face_simplices_ = 0;
    std::size_t boundary_done_ = 0;  // sampler_.boundary_inside() entries used as seeds
    std::size_t surface_walks_ = 0, face_walks_ = 0;
    std::size_t pieces_ = 0;
    ConeSum* cone_;
    Chain chain_;
};

// Seeding: the coarse scan (coarse_cells per axis, capped at N_k; < 0: none)
// and the seed points; each seed found starts a walk; then the box faces are
// closed (SurfaceBuilder::close_faces).
void seed_and_walk(const Lattice& lattice, Sampler& sampler, SurfaceBuilder& builder, int coarse_cells,
                   std::span<const double> seed_points);

}  // namespace polyvol::implicit
