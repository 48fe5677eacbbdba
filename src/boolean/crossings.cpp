// boolean/crossings.cpp — where the surfaces of two operands cross.
//
// A triangle t of A and a triangle s of B (translated by δ) cross, in general
// position, along a segment t ∩ s whose two ends are each an edge of one
// crossing the other triangle. So six edge-through-triangle tests per pair
// find everything: which edges cross (for the windings and the fractions of
// edges inside), and the cut segment with its direction N_t × N_s.
//   * edge p -> q through triangle (s0, s1, s2): p and q on opposite sides
//     of its plane, and orient(p, q, s_j, s_j+1) of one sign for j = 0, 1, 2;
//   * the crossing of edge b -> c of t is where the segment starts (along
//     N_t × N_s) iff c is in front of s and b behind: there
//     (N_t × N_s)·(N_t × (c - b)) = |N_t|² N_s·(c - b) > 0 enters t;
//   * the crossing of edge u -> v of s starts it iff u is in front of t and
//     v behind: (N_t × N_s)·(N_s × (v - u)) = -|N_s|² N_t·(v - u).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include <gmpxx.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "boolean/predicates.hpp"
#include "boolean/symbolic.hpp"
#include "core/fan_triangles.hpp"

namespace polyvol::boolean {

namespace {

// The scale of the vertices the triangles use (each once, not once per corner).
CoordinateScale used_vertex_scale(const Operand& op) {
    std::vector<uint8_t> used(op.mesh.vertex_count(), 0);
    for (const uint32_t v : op.tri) used[v] = 1;
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, used.size(), 4096), CoordinateScale{},
        [&](const auto& range, CoordinateScale scale) {
            for (std::size_t v = range.begin(); v != range.end(); ++v) {
                if (used[v] == 0) continue;
                for (int k = 0; k < 3; ++k) {
                    const double x = op.point(static_cast<uint32_t>(v))[k];
                    scale.in_range = scale.in_range && in_predicate_range(x);
                    if (x != 0) scale.e0 = std::min(scale.e0, lowest_bit_exponent(x));
                    scale.max_coordinate = std::max(scale.max_coordinate, std::fabs(x));
                }
            }
            return scale;
        },
        [](CoordinateScale x, const CoordinateScale& y) {
            x.widen(y);
            return x;
        });
}

}  // namespace

void finish_operand(Operand& op) {
    const std::size_t n = op.triangles();
    op.degenerate.resize(n);
    op.box.resize(6 * n);
    struct Extent {
        std::array<double, 6> bounds{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    };
    const Extent all = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 4096), Extent{},
        [&](const auto& range, Extent e) {
            for (std::size_t t = range.begin(); t != range.end(); ++t) {
                const double* c[3] = {op.corner(t, 0), op.corner(t, 1), op.corner(t, 2)};
                op.degenerate[t] = first_cross_sign(c[0], c[1], c[0], c[2]) == 0;
                for (int k = 0; k < 3; ++k) {
                    const double lo = std::min({c[0][k], c[1][k], c[2][k]});
                    const double hi = std::max({c[0][k], c[1][k], c[2][k]});
                    op.box[6 * t + k] = box_below(lo);
                    op.box[6 * t + 3 + k] = box_above(hi);
                    e.bounds[k] = std::min(e.bounds[k], lo);
                    e.bounds[3 + k] = std::max(e.bounds[3 + k], hi);
                }
            }
            return e;
        },
        [](Extent x, const Extent& y) {
            for (int k = 0; k < 3; ++k) {
                x.bounds[k] = std::min(x.bounds[k], y.bounds[k]);
                x.bounds[3 + k] = std::max(x.bounds[3 + k], y.bounds[3 + k]);
            }
            return x;
        });
    op.bounds = all.bounds;
    op.scale = used_vertex_scale(op);
}

Operand make_operand(const MeshView& view, int32_t shift) {
    Operand op;
    op.body_shift = {shift};
    op.mesh = welded(view);
    const MeshView m = op.mesh.view();
    if (m.all_triangles()) {
        op.tri = std::move(op.mesh.indices);  // the fan triangles are the faces
        op.mesh.indices.clear();
    } else {
        core::append_fan_triangles(m, op.tri);
    }
    finish_operand(op);
    return op;
}

namespace {

template <class P, class Q>
bool boxes_meet(const P* p, const Q* q) {
    return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5];
}

// Whether segment p -> q crosses triangle s (whose plane separates p and q):
// `shift` is the translation of s relative to p q (+1: s in B).
bool line_through(const double* p, const double* q, const double* const s[3], int shift) {
    const int o0 = perturbed_orient_edges(p, q, s[0], s[1], shift);
    const int o1 = perturbed_orient_edges(p, q, s[1], s[2], shift);
    if (o0 != o1) return false;
    return perturbed_orient_edges(p, q, s[2], s[0], shift) == o0;
}

// All crossings between triangle ta of A and triangle tb of B (B's body
// moved by `shift` δ relative to A's: only its sign matters).
void cross_pair(const Operand& A, uint32_t ta, const Operand& B, uint32_t tb, int shift, Crossings& out) {
    const double* const T[3] = {A.corner(ta, 0), A.corner(ta, 1), A.corner(ta, 2)};
    const double* const S[3] = {B.corner(tb, 0), B.corner(tb, 1), B.corner(tb, 2)};
    const bool t_flat = A.degenerate[ta] != 0, s_flat = B.degenerate[tb] != 0;
    if (t_flat && s_flat) return;
    int side_t[3] = {0, 0, 0}, side_s[3] = {0, 0, 0};  // of t's corners w.r.t. s, of s's w.r.t. t
    if (!s_flat) {
        for (int i = 0; i < 3; ++i) side_t[i] = perturbed_side(S[0], S[1], S[2], T[i], -shift);
        if (side_t[0] == side_t[1] && side_t[1] == side_t[2]) return;
    }
    if (!t_flat) {
        for (int j = 0; j < 3; ++j) side_s[j] = perturbed_side(T[0], T[1], T[2], S[j], shift);
        if (side_s[0] == side_s[1] && side_s[1] == side_s[2]) return;
    }
    CutEnd ends[6];
    bool starts[6];
    int n = 0;
    if (!s_flat) {
        for (int i = 0; i < 3; ++i) {
            const int i1 = (i + 1) % 3;
            if (side_t[i] == side_t[i1] || !line_through(T[i], T[i1], S, shift)) continue;
            out.a_hits.push_back({ta, tb, static_cast<uint8_t>(i), static_cast<int8_t>(side_t[i])});
            ends[n] = {0, static_cast<uint8_t>(i)};
            starts[n++] = side_t[i] < 0;
        }
    }
    if (!t_flat) {
        for (int j = 0; j < 3; ++j) {
            const int j1 = (j + 1) % 3;
            if (side_s[j] == side_s[j1] || !line_through(S[j], S[j1], T, -shift)) continue;
            out.b_hits.push_back({tb, ta, static_cast<uint8_t>(j), static_cast<int8_t>(side_s[j])});
            ends[n] = {1, static_cast<uint8_t>(j)};
            starts[n++] = side_s[j] > 0;
        }
    }
    if (t_flat || s_flat || n == 0) return;
    if (n != 2 || starts[0] == starts[1])
        throw Contradiction("boolean: a triangle pair crosses in other than one segment");
    out.cuts.push_back({ta, tb, starts[0] ? ends[0] : ends[1], starts[0] ? ends[1] : ends[0]});
}

void append(Crossings& to, const Crossings& from) {
    to.a_hits.insert(to.a_hits.end(), from.a_hits.begin(), from.a_hits.end());
    to.b_hits.insert(to.b_hits.end(), from.b_hits.begin(), from.b_hits.end());
    to.cuts.insert(to.cuts.end(), from.cuts.begin(), from.cuts.end());
    to.candidate_pairs += from.candidate_pairs;
}

bool hit_order(const EdgeHit& x, const EdgeHit& y) {
    return std::tie(x.tri, x.edge, x.other) < std::tie(y.tri, y.edge, y.other);
}


bool same_crossings(const Crossings& x, const Crossings& y) {
    auto hit = [](const EdgeHit& h) { return std::tie(h.tri, h.other, h.edge, h.sign); };
    auto cut = [](const Cut& c) { return std::tie(c.a, c.b, c.start.of_b, c.start.edge, c.end.of_b, c.end.edge); };
    auto equal = [](const auto& u, const auto& v, auto key) {
        return u.size() == v.size() && std::equal(u.begin(), u.end(), v.begin(), [&](const auto& p, const auto& q) {
                   return key(p) == key(q);
               });
    };
    return equal(x.a_hits, y.a_hits, hit) && equal(x.b_hits, y.b_hits, hit) && equal(x.cuts, y.cuts, cut);
}

// Triangles t and s of one body sharing one or two vertices meet only there
// (or along the shared edge) unless the surface folds onto itself: then
// they overlap along a segment from a shared vertex, which no cut between
// edge crossings represents. Throws SelfContact for such a pair.
//   * Two shared (edge u w; a, c the others): a fold iff c lies in t's plane
//     on a's side of the line u w.
//   * One shared (v; t = (v, a, b), s = (v, c, d)): t meets the plane of s
//     only at v when a and b are strictly on one side of it (likewise s and
//     t). Otherwise t ∩ plane(s) runs from v along u_t = |o_b|(a - v) + |o_a|(b - v)
//     (o = orient(s, ·)) and s ∩ plane(t) along u_s; both lie on the line
//     where the planes meet, and the triangles overlap beyond v iff
//     u_t · u_s > 0. Coplanar: iff no boundary line of one corner at v
//     separates it from the other.
void check_fold(const Operand& op, uint32_t t, uint32_t s) {
    if (op.degenerate[t] || op.degenerate[s]) return;
    int ti[3], si[3], shared = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (op.site_of(op.tri[3 * std::size_t{t} + i]) == op.site_of(op.tri[3 * std::size_t{s} + j])) {
                ti[shared] = i;
                si[shared++] = j;
            }
    if (shared == 0) return;
    if (shared == 3) throw SelfContact("boolean: two triangles of a body that crosses itself coincide");
    const double* const T[3] = {op.corner(t, 0), op.corner(t, 1), op.corner(t, 2)};
    const double* const S[3] = {op.corner(s, 0), op.corner(s, 1), op.corner(s, 2)};
    // A projection that keeps t's plane 2D: axis k with N_t[k] != 0, (i, j, k) cyclic.
    int pi = 1, pj = 2, nk = 0;
    for (const auto& [i, j] : {std::pair{1, 2}, std::pair{2, 0}, std::pair{0, 1}}) {
        if ((nk = cross_component_sign(T[0], T[1], T[0], T[2], i, j)) != 0) {
            pi = i;
            pj = j;
            break;
        }
    }
    // The orientation of (o, x, y) within t's plane, positive for t itself.
    auto o2 = [&](const double* o, const double* x, const double* y) {
        return nk * cross_component_sign(o, x, o, y, pi, pj);
    };
    if (shared == 2) {
        const double* u = T[ti[0]];
        const double* w = T[ti[1]];
        const double* a = T[3 - ti[0] - ti[1]];
        const double* c = S[3 - si[0] - si[1]];
        if (orient3d_sign(T[0], T[1], T[2], c) != 0) return;
        const int side_a = o2(u, w, a), side_c = o2(u, w, c);
        if (side_a != 0 && side_a == side_c) throw SelfContact("boolean: a body that crosses itself folds onto itself across an edge");
        return;
    }
    const double* v = T[ti[0]];
    const double* a = T[(ti[0] + 1) % 3];
    const double* b = T[(ti[0] + 2) % 3];
    const double* c = S[(si[0] + 1) % 3];
    const double* d = S[(si[0] + 2) % 3];
    const int sa = orient3d_sign(S[0], S[1], S[2], a), sb = orient3d_sign(S[0], S[1], S[2], b);
    const int sc = orient3d_sign(T[0], T[1], T[2], c), sd = orient3d_sign(T[0], T[1], T[2], d);
    if (sa * sb > 0 || sc * sd > 0) return;
    if (sa == 0 && sb == 0 && sc == 0 && sd == 0) {
        if (o2(v, c, d) < 0) std::swap(c, d);
        const bool apart = (o2(v, a, c) <= 0 && o2(v, a, d) <= 0) || (o2(v, b, c) >= 0 && o2(v, b, d) >= 0) ||
                           (o2(v, c, a) <= 0 && o2(v, c, b) <= 0) || (o2(v, d, a) >= 0 && o2(v, d, b) >= 0);
        if (!apart) throw SelfContact("boolean: a body that crosses itself folds onto itself at a vertex");
        return;
    }
    using Q3 = RationalPoint;
    auto q3 = rational_point;
    auto sub = [](const Q3& x, const Q3& y) { return Q3{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; };
    auto orient_q = [&](const double* const P[3], const double* x) {
        return orient_of<mpq_class>(q3(P[0]), q3(P[1]), q3(P[2]), q3(x));
    };
    auto along = [&](const double* x, const double* y, const mpq_class& ox, const mpq_class& oy) {
        const Q3 vv = q3(v), dx = sub(q3(x), vv), dy = sub(q3(y), vv);
        const mpq_class fx = abs(oy), fy = abs(ox);
        return Q3{fx * dx[0] + fy * dy[0], fx * dx[1] + fy * dy[1], fx * dx[2] + fy * dy[2]};
    };
    const Q3 ut = along(a, b, orient_q(S, a), orient_q(S, b));
    const Q3 us = along(c, d, orient_q(T, c), orient_q(T, d));
    if (ut[0] * us[0] + ut[1] * us[1] + ut[2] * us[2] > 0)
        throw SelfContact("boolean: a body that crosses itself folds onto itself at a vertex");
}

// A uniform grid over a box: about `target` cells, cubic where the box allows.
struct CellGrid {
    std::array<double, 6> box{};
    std::array<uint32_t, 3> dims{1, 1, 1};
    std::array<double, 3> per_unit{};  // cells per unit length along each axis

    CellGrid(const std::array<double, 6>& b, std::size_t target) : box(b) {
        const double ext[3] = {b[3] - b[0], b[4] - b[1], b[5] - b[2]};
        const double longest = std::max({ext[0], ext[1], ext[2]});
        if (!(longest > 0)) return;
        double h = longest / std::cbrt(static_cast<double>(std::max<std::size_t>(target, 1)));
        for (;;) {
            std::size_t total = 1;
            for (int k = 0; k < 3; ++k) {
                dims[k] = static_cast<uint32_t>(std::clamp(std::ceil(ext[k] / h), 1.0, 1024.0));
                total *= dims[k];
            }
            if (total <= 8 * std::max<std::size_t>(target, 1)) break;
            h *= 1.5;
        }
        for (int k = 0; k < 3; ++k) {
            const double d = ext[k] > 0 ? dims[k] / ext[k] : 0;
            per_unit[k] = std::isfinite(d) ? d : 0;  // a subnormal extent: one cell along k
        }
    }
    // Cell k-index of coordinate x: floor((x - lo) · dims / extent), clamped
    // to the grid (a truncation, which is the floor where it is not clamped).
    uint32_t index(int k, double x) const {
        const double f = (x - box[k]) * per_unit[k];
        if (!(f > 0)) return 0;
        if (f >= dims[k]) return dims[k] - 1;
        return static_cast<uint32_t>(f);
    }
    std::size_t cells() const { return std::size_t{dims[0]} * dims[1] * dims[2]; }
    std::size_t cell(uint32_t i, uint32_t j, uint32_t k) const { return (std::size_t{i} * dims[1] + j) * dims[2] + k; }
    // Calls f(cell) for every cell a box {xmin..zmax} overlaps.
    template <class F>
    void for_cells(const float* b, F&& f) const {
        const uint32_t lo[3] = {index(0, b[0]), index(1, b[1]), index(2, b[2])};
        const uint32_t hi[3] = {index(0, b[3]), index(1, b[4]), index(2, b[5])};
        for (uint32_t i = lo[0]; i <= hi[0]; ++i)
            for (uint32_t j = lo[1]; j <= hi[1]; ++j)
                for (uint32_t k = lo[2]; k <= hi[2]; ++k) f(cell(i, j, k));
    }
};

}  // namespace

Crossings find_crossings(const Operand& A, const Operand& B, Pairs pairs) {
    Crossings result;
    const bool same = &A == &B;
    const bool strict = same && pairs == Pairs::self_crossing;
    const bool within = (same && pairs == Pairs::same_body_apart) || strict;
    auto examined = [&](const Operand& op, uint32_t t) { return !strict || op.crosses_itself(op.body(t)); };
    std::array<double, 6> common{};
    for (int k = 0; k < 3; ++k) {
        common[k] = std::max(A.bounds[k], B.bounds[k]);
        common[3 + k] = std::min(A.bounds[3 + k], B.bounds[3 + k]);
        if (!(common[k] <= common[3 + k])) return result;  // boxes apart (or an empty operand)
    }
    // Which sides have triangles in each cell of a uniform grid over the
    // common box (bit 0: A, bit 1: B; one operand of up to 64 bodies: bit b
    // for body b). Only a triangle in a cell holding some other side's
    // triangles can cross one: near the curves where the surfaces meet.
    const CellGrid grid(common, (A.triangles() + (same ? 0 : B.triangles())) / 2);
    const bool by_body = same && !within && A.body_shift.size() <= 64;
    auto label_a = [&](uint32_t t) { return by_body ? uint64_t{1} << A.body(t) : uint64_t{1}; };
    auto label_b = [&](uint32_t t) { return same ? label_a(t) : uint64_t{2}; };
    std::vector<std::atomic<uint64_t>> present(grid.cells());
    auto mark = [&](const Operand& op, auto label) {
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, static_cast<uint32_t>(op.triangles()), 4096),
                          [&](const auto& range) {
                              for (uint32_t t = range.begin(); t != range.end(); ++t) {
                                  if (!boxes_meet(&op.box[6 * std::size_t{t}], common.data()) || !examined(op, t)) continue;
                                  const uint64_t bit = label(t);
                                  grid.for_cells(&op.box[6 * std::size_t{t}], [&](std::size_t c) {
                                      if (!(present[c].load(std::memory_order_relaxed) & bit))
                                          present[c].fetch_or(bit, std::memory_order_relaxed);
                                  });
                              }
                          });
    };
    mark(A, label_a);
    if (!same) mark(B, label_b);
    auto near = [&](const Operand& op, auto label) {
        std::vector<uint8_t> flag(op.triangles(), 0);
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, static_cast<uint32_t>(op.triangles()), 4096),
                          [&](const auto& range) {
                              for (uint32_t t = range.begin(); t != range.end(); ++t) {
                                  if (!boxes_meet(&op.box[6 * std::size_t{t}], common.data()) || !examined(op, t)) continue;
                                  const uint64_t others = same && !by_body ? ~uint64_t{0} : ~label(t);  // all: any cell
                                  bool hit = false;
                                  grid.for_cells(&op.box[6 * std::size_t{t}], [&](std::size_t c) { hit = hit || (present[c].load(std::memory_order_relaxed) & others); });
                                  flag[t] = hit;
                              }
                          });
        std::vector<uint32_t> list;
        for (uint32_t t = 0; t < op.triangles(); ++t)
            if (flag[t]) list.push_back(t);
        return list;
    };
    const std::vector<uint32_t> a_near = near(A, label_a);
    const std::vector<uint32_t> b_near = same ? a_near : near(B, label_b);
    if (a_near.empty() || b_near.empty()) return result;

    // B's triangles near A binned into the same cells (compressed rows).
    std::vector<std::size_t> start(grid.cells() + 1, 0);
    for (uint32_t t : b_near) grid.for_cells(&B.box[6 * std::size_t{t}], [&](std::size_t c) { ++start[c + 1]; });
    for (std::size_t c = 0; c < grid.cells(); ++c) start[c + 1] += start[c];
    std::vector<uint32_t> binned(start.back());
    std::vector<float> binned_box(6 * start.back());  // each entry's box beside it: read in order
    {
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (uint32_t t : b_near)
            grid.for_cells(&B.box[6 * std::size_t{t}], [&](std::size_t c) {
                std::copy_n(&B.box[6 * std::size_t{t}], 6, &binned_box[6 * fill[c]]);
                binned[fill[c]++] = t;
            });
    }
    // One operand: only cells holding triangles of two or more bodies can
    // hold a pair (most cells hold one body's surface only).
    std::vector<uint8_t> mixed;
    if (same && !within) {
        mixed.assign(grid.cells(), 0);
        for (std::size_t c = 0; c < grid.cells(); ++c)
            for (std::size_t i = start[c] + 1; i < start[c + 1] && !mixed[c]; ++i)
                mixed[c] = B.body(binned[i]) != B.body(binned[start[c]]);
    }

    struct Local {
        Crossings found;
    };
    tbb::enumerable_thread_specific<Local> locals;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, a_near.size(), 256), [&](const auto& range) {
        Local& local = locals.local();
        for (std::size_t r = range.begin(); r != range.end(); ++r) {
            const uint32_t ta = a_near[r];
            const float* box = &A.box[6 * std::size_t{ta}];
            // Each pair once, in the cell holding the low corner of the two boxes' overlap.
            grid.for_cells(box, [&](std::size_t c) {
                if (same && !within && !mixed[c]) return;
                for (std::size_t i = start[c]; i < start[c + 1]; ++i) {
                    const uint32_t tb = binned[i];
                    if (same && tb <= ta) continue;
                    const float* other = &binned_box[6 * i];
                    if (!boxes_meet(box, other)) continue;
                    if (same && (B.body(tb) == A.body(ta)) != within) continue;
                    const bool neighbours = within && A.share_corner(ta, tb);
                    if (neighbours && !strict) continue;
                    if (grid.cell(grid.index(0, std::max(box[0], other[0])), grid.index(1, std::max(box[1], other[1])),
                                  grid.index(2, std::max(box[2], other[2]))) != c)
                        continue;
                    if (neighbours) {
                        check_fold(A, ta, tb);
                        continue;
                    }
                    ++local.found.candidate_pairs;
                    if (strict) {
                        // Unperturbed: what the pair does must not depend on
                        // which way one of them would be moved.
                        Crossings plus, minus;
                        cross_pair(A, ta, B, tb, +1, plus);
                        cross_pair(A, ta, B, tb, -1, minus);
                        if (!same_crossings(plus, minus))
                            throw SelfContact("boolean: a body that crosses itself also touches itself");
                        append(local.found, plus);
                        continue;
                    }
                    if (within) {
                        // One body: a pair crosses only if it does whichever way the
                        // later triangle is moved (touching crosses one way only).
                        Crossings plus, minus;
                        cross_pair(A, ta, B, tb, +1, plus);
                        if (plus.cuts.empty()) continue;
                        cross_pair(A, ta, B, tb, -1, minus);
                        if (minus.cuts.empty()) continue;
                        append(local.found, plus);
                        continue;
                    }
                    cross_pair(A, ta, B, tb, B.shift(tb) > A.shift(ta) ? 1 : -1, local.found);
                }
            });
        }
    });
    for (Local& local : locals) append(result, local.found);
    // In triangle order, whatever the threads did: what is built from these
    // (the grid's pieces) is then the same bits on every run.
    std::sort(result.a_hits.begin(), result.a_hits.end(), hit_order);
    std::sort(result.b_hits.begin(), result.b_hits.end(), hit_order);
    std::sort(result.cuts.begin(), result.cuts.end(),
              [](const Cut& x, const Cut& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
    return result;
}

}  // namespace polyvol::boolean
