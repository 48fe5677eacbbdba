// grid/clip.hpp — private: clipping a triangle into its pieces, one per grid
// cell, such that pieces of neighbouring triangles meet exactly.
//
// Sources: I. E. Sutherland and G. W. Hodgman, "Reentrant polygon clipping",
// CACM 17 (1974) — the split of a polygon by a plane; D. Powell and
// T. Abel, "An exact general remeshing scheme applied to physically
// conservative voxelization", J. Comput. Phys. 297 (2015) (r3d) — splitting
// by grid planes in sequence.
//
// Exactness of the seams. Every vertex a split creates is the crossing of a
// grid plane with a straight segment, its *support*: an edge of the input
// triangle (shared with the neighbouring triangle, or a fan diagonal shared
// with the next fan triangle) or a cut line along an earlier plane (shared
// with the piece on its other side). crossing() computes it from the
// support's two end points in lexicographic order, so the two polygons that
// share an edge compute bit-identical points, whatever their orientation or
// the order of earlier splits: the pieces of a closed mesh form a closed
// surface. Each polygon edge carries its support (not just its end points),
// so crossings along an input edge are interpolated from the input vertices,
// not from earlier crossings, and errors do not accumulate along the edge.
// A vertex exactly on a plane goes to both sides and is never interpolated:
// planes through vertices, edges and faces need no special case.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "grid/axis.hpp"

namespace polyvol::grid {

struct Point {
    double v[3];
};

inline bool lex_less(const Point& a, const Point& b) {
    if (a.v[0] != b.v[0]) return a.v[0] < b.v[0];
    if (a.v[1] != b.v[1]) return a.v[1] < b.v[1];
    return a.v[2] < b.v[2];
}

// A straight segment with a <= b lexicographically.
struct Segment {
    Point a, b;
};
inline Segment make_segment(const Point& p, const Point& q) { return lex_less(q, p) ? Segment{q, p} : Segment{p, q}; }

// A polygon: vertices p[0..n) in the triangle's orientation; edge i runs from
// p[i] to p[(i+1) % n] and lies on the segment s[i]. pos[] is scratch for
// split(). Polygons that stay convex up to rounding (all of ours) never come
// near the capacity; exceeding it throws std::length_error.
inline constexpr int kMaxVertices = 96;
struct Polygon {
    int n = 0;
    Point p[kMaxVertices];
    Segment s[kMaxVertices];
    int pos[kMaxVertices];
};

// The point where the plane {coordinate `axis` = c} crosses the edge (p, q)
// lying on support s, given p and q strictly on opposite sides:
//     t = (c - a_axis) / (b_axis - a_axis),   r_k = a_k + t (b_k - a_k)  (k != axis),
//     r_axis = c exactly,
// with (a, b) = s in lexicographic order, and r_k clamped to the range of the
// edge's end points (so the point stays on the edge's side of every other
// plane). Symmetric in (p, q): both polygons sharing the edge get the same bits.
inline Point crossing(const Segment& s, int axis, double c, const Point& p, const Point& q) {
    const double t = (c - s.a.v[axis]) / (s.b.v[axis] - s.a.v[axis]);
    Point r;
    for (int k = 0; k < 3; ++k) {
        if (k == axis) {
            r.v[k] = c;
            continue;
        }
        const double x = s.a.v[k] + t * (s.b.v[k] - s.a.v[k]);
        const double lo = std::min(p.v[k], q.v[k]), hi = std::max(p.v[k], q.v[k]);
        r.v[k] = std::clamp(x, lo, hi);
    }
    return r;
}

namespace detail {
inline void push(Polygon& out, const Point& p, int pos) {
    if (out.n == kMaxVertices) throw std::length_error("polyvol grid: clipped polygon exceeds capacity");
    out.p[out.n] = p;
    out.pos[out.n] = pos;
    ++out.n;
}
// Supports of the output edges. out's vertices came from `in` at positions
// pos = 2i (vertex i) or 2i + 1 (crossing on edge i). An output edge follows
// input edge i when it runs vertex i -> crossing i, crossing i -> vertex i+1,
// or vertex i -> vertex i+1; any other output edge runs along the plane (a
// cut line) and is its own support.
inline void assign_supports(const Polygon& in, Polygon& out) {
    if (out.n < 3) {
        out.n = 0;  // nothing of positive extent on this side
        return;
    }
    const int n2 = 2 * in.n;
    for (int j = 0; j < out.n; ++j) {
        const int jn = j + 1 == out.n ? 0 : j + 1;
        const int a = out.pos[j];
        int d = out.pos[jn] - a;
        if (d <= 0) d += n2;
        if (d == 1 || (d == 2 && (a & 1) == 0))
            out.s[j] = in.s[a >> 1];
        else
            out.s[j] = make_segment(out.p[j], out.p[jn]);
    }
}
}  // namespace detail

// Splits `in` by the plane {coordinate `axis` = c} into the part below (lo)
// and the part above (hi) — Sutherland–Hodgman: a vertex on the plane goes to
// both, an edge with its ends strictly on opposite sides gets its crossing in
// both. `in` must not alias lo or hi.
inline void split(const Polygon& in, int axis, double c, Polygon& lo, Polygon& hi) {
    lo.n = hi.n = 0;
    const int n = in.n;
    auto side = [&](const Point& p) { return p.v[axis] < c ? -1 : (p.v[axis] > c ? 1 : 0); };
    int sa = side(in.p[0]);
    const int s0 = sa;
    for (int i = 0; i < n; ++i) {
        const int inext = i + 1 == n ? 0 : i + 1;
        const int sb = inext == 0 ? s0 : side(in.p[inext]);
        if (sa <= 0) detail::push(lo, in.p[i], 2 * i);
        if (sa >= 0) detail::push(hi, in.p[i], 2 * i);
        if (sa * sb < 0) {
            const Point x = crossing(in.s[i], axis, c, in.p[i], in.p[inext]);
            detail::push(lo, x, 2 * i + 1);
            detail::push(hi, x, 2 * i + 1);
        }
        sa = sb;
    }
    detail::assign_supports(in, lo);
    detail::assign_supports(in, hi);
}

// Three polygons of scratch for split_into_slabs.
struct SplitBuffers {
    Polygon a, b, c;
};

// Splits `poly` by every plane of `axis` strictly inside its extent, in
// increasing order, and calls emit(part, s) for each part with its slab s
// (see axis.hpp) for s in [keep_lo, keep_hi] (the parts below keep_lo are
// still split off first, so a part is the same whichever range is kept).
// The part handed to emit lives in buf and is valid during the call only.
template <class Emit>
void split_into_slabs(const Polygon& poly, int axis, const Axis& ax, int keep_lo, int keep_hi, SplitBuffers& buf,
                      Emit&& emit) {
    double mn = poly.p[0].v[axis], mx = mn;
    for (int i = 1; i < poly.n; ++i) {
        mn = std::min(mn, poly.p[i].v[axis]);
        mx = std::max(mx, poly.p[i].v[axis]);
    }
    int first, last;
    ax.slab_range(mn, mx, first, last);
    if (last < keep_lo || first > keep_hi) return;
    const Polygon* cur = &poly;
    Polygon* lo = &buf.a;
    Polygon* hi = &buf.b;
    Polygon* spare = &buf.c;
    for (int m = first + 1; m <= last; ++m) {
        split(*cur, axis, ax.plane(m), *lo, *hi);
        if (m - 1 >= keep_lo && lo->n > 0) emit(static_cast<const Polygon&>(*lo), m - 1);
        if (m - 1 >= keep_hi) return;
        // the part above becomes the polygon to split next
        Polygon* done = cur == &poly ? spare : const_cast<Polygon*>(cur);
        cur = hi;
        hi = done;
        if (cur->n == 0) return;
    }
    emit(*cur, last);
}

// Clips one polygon (a triangle) into its pieces, one per cell, for the
// columns i in [ix0, ix1], j in [iy0, iy1] (a tile) and every z slab from kz0
// to nz (nz: above the grid, where only the projected area matters); parts
// below z[kz0] and outside the tile are dropped. Calls piece(poly, i, j, k).
struct ClipBuffers {
    SplitBuffers x, y, z;
};
template <class Piece>
void clip_to_cells(const Polygon& tri, const Axis& ax, const Axis& ay, const Axis& az, int ix0, int ix1, int iy0,
                   int iy1, int kz0, ClipBuffers& buf, Piece&& piece) {
    split_into_slabs(tri, 0, ax, ix0, ix1, buf.x, [&](const Polygon& px, int i) {
        split_into_slabs(px, 1, ay, iy0, iy1, buf.y, [&](const Polygon& py, int j) {
            split_into_slabs(py, 2, az, kz0, az.cells(), buf.z, [&](const Polygon& pz, int k) { piece(pz, i, j, k); });
        });
    });
}

}  // namespace polyvol::grid
