// boolean/operand.hpp — private: an operand's fan triangles and what the
// crossing search finds between two operands.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "polyvol/mesh.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::boolean {

// The crossings or windings contradict each other: a body that is not a
// closed 2-cycle, or crosses itself, where that disturbs the others' windings.
struct Contradiction : std::logic_error {
    using std::logic_error::logic_error;
};

// A body that crosses itself also touches itself, or folds onto itself
// through a shared vertex or edge, where it matters: the perturbation that
// separates bodies cannot separate one body from itself, so its solid is
// not decided (docs/boolean.md, "A surface crossing itself").
struct SelfContact : std::logic_error {
    using std::logic_error::logic_error;
};

// The coordinates of an operand's triangle corners: whether all are in the
// exact predicates' range (in_predicate_range), the lowest bit exponent of
// the nonzero ones (INT_MAX when none), the largest magnitude.
struct CoordinateScale {
    bool in_range = true;
    int e0 = std::numeric_limits<int>::max();
    double max_coordinate = 0;
    void widen(const CoordinateScale& o) {
        in_range = in_range && o.in_range;
        e0 = std::min(e0, o.e0);
        max_coordinate = std::max(max_coordinate, o.max_coordinate);
    }
};

// One operand: its welded vertices and fan triangles (v0, vi, vi+1).
//   corner(t, i) = positions of vertex tri[3 t + i]
//   edge e of triangle t runs from corner e to corner (e + 1) % 3
// An operand holds one or more bodies (the shells of one file): body(t) of
// each triangle, and each body translated by shift(body) δ for the symbolic
// perturbation (predicates.hpp). Bodies share no vertex.
struct Operand {
    Mesh mesh;                       // welded(input): one vertex per position (make_operand moves
                                     // a triangle mesh's indices into tri: read tri, not mesh's faces)
    std::vector<uint32_t> tri;       // 3 per fan triangle
    std::vector<uint8_t> degenerate; // 1 where (b - a) × (c - a) == 0 exactly
    // 6 per triangle: xmin ymin zmin xmax ymax zmax, rounded outward to
    // float (box_below, box_above): a filter, half the bytes of doubles.
    std::vector<float> box;
    std::array<double, 6> bounds{};  // of the used vertices, exact (empty operand: inverted)
    CoordinateScale scale;           // of the used vertices
    std::vector<uint32_t> body_of_triangle;  // empty: every triangle in body 0
    std::vector<int32_t> body_shift{0};      // per body: the multiple of δ it is moved by
    std::vector<uint8_t> body_crosses;       // per body: 1 when it crosses itself (empty: none does)
    // Per vertex, the vertex it was split from (split_sheets: one position,
    // several sheets); empty when no vertex was split.
    std::vector<uint32_t> site;

    uint32_t body(std::size_t t) const { return body_of_triangle.empty() ? 0 : body_of_triangle[t]; }
    bool crosses_itself(uint32_t body) const { return !body_crosses.empty() && body_crosses[body] != 0; }
    int32_t shift(std::size_t t) const { return body_shift[body(t)]; }

    uint32_t site_of(uint32_t v) const { return site.empty() ? v : site[v]; }
    // Whether triangles t and s have a corner at one place (a vertex, or
    // copies of one split by split_sheets).
    bool share_corner(std::size_t t, std::size_t s) const {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (site_of(tri[3 * t + i]) == site_of(tri[3 * s + j])) return true;
        return false;
    }
    std::size_t triangles() const { return tri.size() / 3; }
    const double* point(uint32_t v) const { return mesh.positions.data() + 3 * std::size_t{v}; }
    const double* corner(std::size_t t, int i) const { return point(tri[3 * t + i]); }
};

// The largest float <= x and the smallest float >= x (x finite): a box
// rounded outward holds the triangle. One step of the float's bits moves
// it one float away from zero (or toward it, for the other sign).
inline float box_below(double x) {
    const float f = static_cast<float>(x);
    if (!(static_cast<double>(f) > x)) return f;
    if (f == 0) return -std::numeric_limits<float>::denorm_min();
    const uint32_t bits = core::bit_cast<uint32_t>(f);
    return core::bit_cast<float>(f > 0 ? bits - 1 : bits + 1);
}
inline float box_above(double x) {
    const float f = static_cast<float>(x);
    if (!(static_cast<double>(f) < x)) return f;
    if (f == 0) return std::numeric_limits<float>::denorm_min();
    const uint32_t bits = core::bit_cast<uint32_t>(f);
    return core::bit_cast<float>(f > 0 ? bits + 1 : bits - 1);
}

// Fills degenerate, box, bounds and scale from mesh and tri, in one parallel pass.
void finish_operand(Operand& op);

// welded(view) and its fan triangles, one body moved by `shift` δ.
Operand make_operand(const MeshView& view, int32_t shift = 0);

// Edge `edge` of triangle `tri` of one operand crosses triangle `other` of
// the other operand (under the perturbation, at an interior point of both).
// sign = +1 when the edge, run from its first corner, enters the other solid
// (passes from the front of `other` to its back), -1 when it leaves.
struct EdgeHit {
    uint32_t tri;
    uint32_t other;
    uint8_t edge;
    int8_t sign;
};

// An end of a cut segment: edge `edge` of operand `of_b ? B : A`'s triangle.
struct CutEnd {
    uint8_t of_b;
    uint8_t edge;
};

// Triangle a of A and triangle b of B cross along a segment, run from start
// to end in the direction N_a × N_b.
struct Cut {
    uint32_t a;
    uint32_t b;
    CutEnd start;
    CutEnd end;
};

struct Crossings {
    std::vector<EdgeHit> a_hits;  // A's edges through B's triangles
    std::vector<EdgeHit> b_hits;  // B's edges through A's triangles
    std::vector<Cut> cuts;
    std::size_t candidate_pairs = 0;  // triangle pairs whose boxes meet
};

// Which pairs of one operand's triangles find_crossings looks at.
enum class Pairs {
    other_bodies,     // triangles of different bodies
    same_body_apart,  // triangles of one body sharing no vertex (the later one moved by δ)
    self_crossing,    // triangles of one body that crosses_itself, unperturbed: pairs sharing no
                      // vertex whose crossings do not depend on a perturbation, and pairs sharing
                      // one that do not fold onto each other; anything else throws SelfContact
};

// Every crossing between A and B (each body moved by its shift δ): a
// uniform grid over the common box, each of A's triangles tested against B's
// triangles in its cells (in parallel). With &a == &b, the crossings between
// the triangles of one operand that `pairs` names, each pair once (t < s;
// a_hits and b_hits then both index that operand).
Crossings find_crossings(const Operand& a, const Operand& b, Pairs pairs = Pairs::other_bodies);

// |A ∩ B| correctly rounded (A at shift 0, B moved by δ), given B's winding
// at A's vertices (0 or 1; B need not be closed where A's box does not
// reach: every B triangle meeting A's box must be there); e0 and
// max_coordinate over both (boolean_volumes' scale); and, when `surface` is
// given, B's surface inside A (its area and vector area). boolean_volumes.cpp.
struct SurfaceInside;
double intersection_given_windings(const Operand& A, const Operand& B, const std::vector<int32_t>& wb, int e0,
                                   double max_coordinate, SurfaceInside* surface = nullptr);

// Winding number at every vertex of `self` of the other operand's bodies
// other than the vertex's own (with &self == &other: of the other bodies of
// the same operand); vertices no face uses get 0. hits: every crossing of
// self's edges with those bodies' triangles. Throws Contradiction when the
// crossings contradict each other (a body that is not a closed 2-cycle).
//
// A body that crosses itself (one operand): its vertices get the winding in
// front of the surface there, its own included, less its default front
// value (0 outward, -1 inward: `front`); hits then include its crossings of
// itself, and `seeds` hold one vertex of each such body with that value's
// own part there (own_front_seed).
struct WindingSeed {
    uint32_t vertex;
    int64_t own;  // the body's own winding in front of the surface at vertex, less its default front value
};
std::vector<int32_t> vertex_windings(const Operand& self, const Operand& other, const std::vector<EdgeHit>& hits,
                                     const std::vector<WindingSeed>& seeds = {});

// The seed of a body that crosses itself: a corner a of one of its
// triangles t and the body's own winding in front of the surface at a. From
// the centroid q of t, a ray along the axis nearest t's normal, to t's
// front, counts the body's triangles it crosses (the winding at q's front
// side), and the segment a -> q inside t the triangles it crosses on the way
// (each changes the winding in front of t by one). Exact; a triangle the
// ray or the segment only touches sends it to another t. Throws SelfContact
// when no t of the first few gives a clean count.
WindingSeed own_front_seed(const Operand& op, uint32_t body, int front, const std::vector<uint32_t>& candidates);

// Splits every body that crosses itself into sheets where its surface is not a
// 2-manifold: the triangles around an edge of four or more are paired by
// angle, each pair bounding one wedge of the solid (sheets.cpp), and each
// vertex gets one copy per fan of triangles around it (site records the
// original). Throws SelfContact where triangles around an edge lie in one
// plane.
// Call before finish_operand.
void split_sheets(Operand& op);

}  // namespace polyvol::boolean
