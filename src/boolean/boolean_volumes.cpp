// boolean/boolean_volumes.cpp — |A ∩ B| and the rest from the pieces of the
// result's boundary, summed exactly.
//
// The cone rule over the boundary of A ∩ B (A's surface inside B, B's inside
// A). For a plane region R of triangle t = (a, b, c), fanning its boundary
// cycle from a gives 6 cone(R) = Σ over the boundary segments p -> q of
// det(a, p, q); segments on the lines through a give 0. R's boundary is
//   * edge b -> c where inside the other solid: with w the other's winding
//     number (0 or 1) and λ_i the edge's crossings (sign σ_i, +1 entering),
//     its inside length is w(b) + Σ σ_i (1 - λ_i), worth that times det(a, b, c);
//   * the cut segments P -> Q along N_t × N_s where t crosses s (oriented so
//     that the inside of s is on their left; crossings.cpp).
// A cut is shared by t (region inside B) and s (inside A, run Q -> P), so
// together they give det(a_t - a_s, P, Q). Every term is linear: no sorting
// along edges, no polygons, no result mesh.
//
// Exactness. Coordinates are x = X 2^e0 with integers X. A crossing of edge
// p -> q with the plane of s is P = (D_p q - D_q p) / (D_p - D_q),
// D = orient(s, ·), an exact integer ratio; so is 1 - λ = D_q / (D_q - D_p).
// Terms whose points are input vertices (D = 0 at an end) are integers; the
// rest are fractions N / D. The sum is decided as an interval
// (exact_terms.hpp): whole triangles by measure's double-double sums with
// their bounds (exact sums if those leave a rounding open), integers
// exactly, each fraction as floor(N 2^k / D) 2^-k; k grows until the
// rounding of every result is decided, and exact rationals settle what no
// interval can (an exact double or a tie, e.g. touching boxes).
#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "exact/expansion.hpp"
#include "exact/rational.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/topology.hpp"

namespace polyvol {
namespace boolean {
namespace {

constexpr double kU = 0x1p-53;

// A crossing point num / den (den > 0) in units of 2^e0, and its double.
struct CrossPoint {
    ExactPoint at;
    std::array<double, 3> xyz;
};

// The integers one run of terms reuses (sum_pieces keeps one per run), so
// that GMP allocates only while they grow.
struct TermScratch {
    IntPoint a, b, c, s[3], p, q, d, at, as;
    DetScratch det;
    mpz_class db, dc, dp, dq, n, den;
    CrossPoint P, Q;
};

// Where segment p -> q crosses the plane of s: D_p q - D_q p over D_p - D_q;
// exactly p (q) when D_p (D_q) is 0.
void crossing_point(CrossPoint& x, const IntPoint& p, const IntPoint& q, const IntPoint* s, const double* pd,
                    const double* qd, const Scale& scale, TermScratch& z) {
    orient_into(z.dp, s[0], s[1], s[2], p, z.det);
    orient_into(z.dq, s[0], s[1], s[2], q, z.det);
    plane_crossing_into(x.at, p, q, z.dp, z.dq);
    if (z.dp == 0 || z.dq == 0) {
        const double* v = z.dp == 0 ? pd : qd;
        x.xyz = {v[0], v[1], v[2]};
        return;
    }
    for (int k = 0; k < 3; ++k) x.xyz[k] = approx_ratio(x.at.num[k], x.at.den, scale.e0);
}

struct Inputs {
    const Operand& A;
    const Operand& B;
    const Crossings& cross;
    const std::vector<int32_t>& wa;  // A's winding at B's vertices
    const std::vector<int32_t>& wb;  // B's winding at A's vertices
    Scale scale;
    double max_coordinate;
};

// What sum_pieces gathers from a run of hits and cuts: joined in a fixed
// tree (parallel_deterministic_reduce), so every run gives the same bits.
struct PiecePart {
    PieceSum volume;
    AreaSum a_in_b, b_in_a;
    VectorAreaSum b_normal;
    void join(PiecePart& other) {
        volume.integer += other.volume.integer;
        volume.fractions.insert(volume.fractions.end(), std::make_move_iterator(other.volume.fractions.begin()),
                                std::make_move_iterator(other.volume.fractions.end()));
        a_in_b.merge(other.a_in_b);
        b_in_a.merge(other.b_in_a);
        b_normal.merge(other.b_normal);
    }
};

// A hit of edge b -> c of op's triangle through other's triangle:
// σ (1 - λ) det(a, b, c), 1 - λ = D_c / (D_c - D_b), and its area term.
void add_edge_term(const Operand& op, const Operand& other, const EdgeHit& h, const Scale& scale, PieceSum& volume,
                   AreaSum& area, VectorAreaSum* vector, TermScratch& z) {
    if (h.edge != 1) return;
    scale.set(z.a, op.corner(h.tri, 0));
    scale.set(z.b, op.corner(h.tri, 1));
    scale.set(z.c, op.corner(h.tri, 2));
    for (int i = 0; i < 3; ++i) scale.set(z.s[i], other.corner(h.other, i));
    orient_into(z.db, z.s[0], z.s[1], z.s[2], z.b, z.det);
    orient_into(z.dc, z.s[0], z.s[1], z.s[2], z.c, z.det);
    if (z.dc == 0) return;
    const Geometry g = triangle_geometry(op.corner(h.tri, 0), op.corner(h.tri, 1), op.corner(h.tri, 2));
    const double error = 8 * kU * g.normal_length + g.normal_error;
    det3_into(z.n, z.a, z.b, z.c, z.det.t);
    if (h.sign < 0) mpz_neg(z.n.get_mpz_t(), z.n.get_mpz_t());
    if (z.db == 0) {
        volume.integer += z.n;
        area.add(h.sign * g.normal_length, error);
        if (vector != nullptr) vector->add(h.sign * g.normal_length, error, g);
        return;
    }
    mpz_sub(z.den.get_mpz_t(), z.dc.get_mpz_t(), z.db.get_mpz_t());
    mpz_mul(z.n.get_mpz_t(), z.n.get_mpz_t(), z.dc.get_mpz_t());
    volume.add_fraction(z.n, z.den);
    const double term = h.sign * approx_ratio(z.dc, z.den, 0) * g.normal_length;
    area.add(term, error);
    if (vector != nullptr) vector->add(term, error, g);
}

// 2 × the area ±|(p - a) × (q - a)| of a cut's side in triangle (a, ·, ·)
// of normal g, with its bound (M: the largest coordinate magnitude).
void add_cut_area(const double* a, const std::array<double, 3>& p, const std::array<double, 3>& q, const Geometry& g,
                  double M, AreaSum& area, VectorAreaSum* vector) {
    const double u[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double v[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
    const double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = norm3(c), lu = norm3(u), lv = norm3(v);
    const double along = c[0] * g.n[0] + c[1] * g.n[1] + c[2] * g.n[2];
    double error = 6 * 16 * kU * (M * (lu + lv) + lu * lv + 4 * kU * M * M);
    if (!(g.normal_length > 4 * g.normal_error)) error += 2 * len;  // the side may be misjudged
    area.add(along >= 0 ? len : -len, error);
    if (vector != nullptr) vector->add(along >= 0 ? len : -len, error, g);
}

// A cut segment P -> Q of triangles a (A) and b (B): det(a_t - a_s, P, Q)
// and the two sides' areas.
void add_cut_term(const Inputs& in, const Cut& cut, PiecePart& part, bool with_normal, TermScratch& z) {
    const Scale& scale = in.scale;
    auto end_point = [&](const CutEnd& e, CrossPoint& x) {
        const Operand& owner = e.of_b ? in.B : in.A;
        const Operand& plane = e.of_b ? in.A : in.B;
        const uint32_t t = e.of_b ? cut.b : cut.a, s = e.of_b ? cut.a : cut.b;
        const double* pd = owner.corner(t, e.edge);
        const double* qd = owner.corner(t, (e.edge + 1) % 3);
        for (int i = 0; i < 3; ++i) scale.set(z.s[i], plane.corner(s, i));
        scale.set(z.p, pd);
        scale.set(z.q, qd);
        crossing_point(x, z.p, z.q, z.s, pd, qd, scale, z);
    };
    end_point(cut.start, z.P);
    end_point(cut.end, z.Q);
    scale.set(z.at, in.A.corner(cut.a, 0));
    scale.set(z.as, in.B.corner(cut.b, 0));
    for (int k = 0; k < 3; ++k) mpz_sub(z.d[k].get_mpz_t(), z.at[k].get_mpz_t(), z.as[k].get_mpz_t());
    det3_into(z.n, z.d, z.P.at.num, z.Q.at.num, z.det.t);
    mpz_mul(z.den.get_mpz_t(), z.P.at.den.get_mpz_t(), z.Q.at.den.get_mpz_t());
    if (z.den == 1)
        part.volume.integer += z.n;
    else
        part.volume.add_fraction(z.n, z.den);
    const double* a = in.A.corner(cut.a, 0);
    const double* b = in.B.corner(cut.b, 0);
    add_cut_area(a, z.P.xyz, z.Q.xyz, triangle_geometry(a, in.A.corner(cut.a, 1), in.A.corner(cut.a, 2)),
                 in.max_coordinate, part.a_in_b, nullptr);
    add_cut_area(b, z.Q.xyz, z.P.xyz, triangle_geometry(b, in.B.corner(cut.b, 1), in.B.corner(cut.b, 2)),
                 in.max_coordinate, part.b_in_a, with_normal ? &part.b_normal : nullptr);
}

// The pieces' volume (integers and fractions; the whole triangles are the
// caller's) and the areas of each operand's surface inside the other; with
// b_normal, also the vector area of B's surface inside A. The terms in
// parallel (their exact GMP arithmetic is most of the time), joined in a
// fixed order.
void sum_pieces(const Inputs& in, PieceSum& volume, AreaSum& area_a_in_b, AreaSum& area_b_in_a,
                VectorAreaSum* b_normal = nullptr) {
    const std::vector<EdgeHit>& ha = in.cross.a_hits;
    const std::vector<EdgeHit>& hb = in.cross.b_hits;
    const std::vector<Cut>& cuts = in.cross.cuts;
    const std::size_t n = ha.size() + hb.size() + cuts.size();
    const bool with_normal = b_normal != nullptr;
    PiecePart all = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, n, 64), PiecePart{},
        [&](const tbb::blocked_range<std::size_t>& range, PiecePart part) {
            TermScratch z;
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (i < ha.size())
                    add_edge_term(in.A, in.B, ha[i], in.scale, part.volume, part.a_in_b, nullptr, z);
                else if (i < ha.size() + hb.size())
                    add_edge_term(in.B, in.A, hb[i - ha.size()], in.scale, part.volume, part.b_in_a,
                                  with_normal ? &part.b_normal : nullptr, z);
                else
                    add_cut_term(in, cuts[i - ha.size() - hb.size()], part, with_normal, z);
            }
            return part;
        },
        [](PiecePart x, PiecePart y) {
            x.join(y);
            return x;
        });
    volume.integer += all.volume.integer;
    volume.fractions.insert(volume.fractions.end(), std::make_move_iterator(all.volume.fractions.begin()),
                            std::make_move_iterator(all.volume.fractions.end()));
    area_a_in_b.merge(all.a_in_b);
    area_b_in_a.merge(all.b_in_a);
    if (b_normal != nullptr) b_normal->merge(all.b_normal);
}

// 6 × the volume of an operand's triangles (all, or those listed in `subset`).
VolumeSum operand_volume_sum(const Operand& op, const std::vector<uint32_t>* subset, bool exactly) {
    return cone_volume_sum({op.mesh.positions, {}, subset ? std::span<const uint32_t>(*subset) : std::span<const uint32_t>(op.tri)},
                           exactly);
}

// An operand's whole triangles: their volume sums (all, and those whose
// edge b -> c starts inside the other solid, w = 1 at corner b: the whole
// triangle is inside when nothing crosses it) and Σ |N| (2 × the area) of both.
struct WholeSums {
    VolumeSum volume, volume_inside;
    AreaSum area, area_inside;
    std::vector<uint32_t> inside;  // the inside triangles' corners
};
WholeSums whole_triangles(const Operand& op, const std::vector<int32_t>& other_winding) {
    WholeSums w;
    for (std::size_t t = 0; t < op.triangles(); ++t)
        if (other_winding[op.tri[3 * t + 1]] != 0) w.inside.insert(w.inside.end(), &op.tri[3 * t], &op.tri[3 * t] + 3);
    struct Areas {
        AreaSum all, inside;
    };
    // One join tree for every run (the bounds are double sums, whose bits depend on the order).
    const Areas areas = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, op.triangles(), 4096), Areas{},
        [&](const tbb::blocked_range<std::size_t>& range, Areas sums) {
            for (std::size_t t = range.begin(); t != range.end(); ++t) {
                const Geometry g = triangle_geometry(op.corner(t, 0), op.corner(t, 1), op.corner(t, 2));
                const double error = g.normal_error + kU * g.normal_length;
                sums.all.add(g.normal_length, error);
                if (other_winding[op.tri[3 * t + 1]] != 0) sums.inside.add(g.normal_length, error);
            }
            return sums;
        },
        [](Areas x, const Areas& y) {
            x.all.merge(y.all);
            x.inside.merge(y.inside);
            return x;
        });
    w.area = areas.all;
    w.area_inside = areas.inside;
    w.volume = operand_volume_sum(op, nullptr, false);
    w.volume_inside = operand_volume_sum(op, &w.inside, false);
    return w;
}

}  // namespace
}  // namespace boolean

const char* boolean_status_message(BooleanStatus status) {
    switch (status) {
        case BooleanStatus::ok: return "ok";
        case BooleanStatus::a_not_closed: return "A is not a closed surface (it has unbalanced edges)";
        case BooleanStatus::b_not_closed: return "B is not a closed surface (it has unbalanced edges)";
        case BooleanStatus::a_inside_out: return "A is inside out (negative volume)";
        case BooleanStatus::b_inside_out: return "B is inside out (negative volume)";
        case BooleanStatus::a_overlaps_itself: return "A's shells overlap (its winding number exceeds 1 somewhere)";
        case BooleanStatus::b_overlaps_itself: return "B's shells overlap (its winding number exceeds 1 somewhere)";
        case BooleanStatus::shell_crosses_itself:
            return "a shell crosses itself (the winding numbers along its edges or cuts disagree)";
        case BooleanStatus::shell_touches_itself:
            return "a shell that crosses itself also touches or folds onto itself there (its solid is not decided)";
        case BooleanStatus::invalid_coordinates:
            return "a coordinate is not finite or outside 0 and 2^-160 .. 2^180 in magnitude";
    }
    return "unknown";
}

BooleanVolumes boolean_volumes(const MeshView& a_view, const MeshView& b_view) {
    using namespace boolean;
    BooleanVolumes r;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto fail = [&](BooleanStatus s) {
        r.status = s;
        r.volume_a = r.volume_b = r.intersection = r.union_volume = r.a_minus_b = r.b_minus_a = nan;
        r.area_a = r.area_b = r.area_intersection = r.area_union = r.area_a_minus_b = r.area_b_minus_a = nan;
        r.area_error_bound = nan;
        return r;
    };
    // Closed 2-cycles first, by the one gate (it also checks the arrays: an
    // index out of range throws std::invalid_argument before anything reads it).
    if (!check_closed(a_view).closed) return fail(BooleanStatus::a_not_closed);
    if (!check_closed(b_view).closed) return fail(BooleanStatus::b_not_closed);
    const Operand A = make_operand(a_view, 0), B = make_operand(b_view, 1);
    r.triangles_a = A.triangles();
    r.triangles_b = B.triangles();

    // Coordinates: finite, in the exact kernels' range, and a common scale.
    CoordinateScale scale = A.scale;
    scale.widen(B.scale);
    if (!scale.in_range) return fail(BooleanStatus::invalid_coordinates);
    const int e0 = scale.e0 == std::numeric_limits<int>::max() ? 0 : scale.e0;
    const double max_coordinate = scale.max_coordinate;


    const Crossings cross = find_crossings(A, B);
    r.candidate_pairs = cross.candidate_pairs;
    r.crossing_pairs = cross.cuts.size();
    const std::vector<int32_t> wb = vertex_windings(A, B, cross.a_hits);
    const std::vector<int32_t> wa = vertex_windings(B, A, cross.b_hits);

    WholeSums whole_a = whole_triangles(A, wb), whole_b = whole_triangles(B, wa);
    const AreaSum& area_a = whole_a.area;
    const AreaSum& area_b = whole_b.area;
    auto volume_of = [](VolumeSum& v, const Operand& op) {
        if (auto d = exact::decided_round_div(v.sum, v.bound, 6)) return *d;
        v = operand_volume_sum(op, nullptr, true);
        return v.sum.round_div(6);
    };
    r.volume_a = volume_of(whole_a.volume, A);
    r.volume_b = volume_of(whole_b.volume, B);
    if (r.volume_a < 0) return fail(BooleanStatus::a_inside_out);
    if (r.volume_b < 0) return fail(BooleanStatus::b_inside_out);
    if (std::any_of(wb.begin(), wb.end(), [](int32_t w) { return w != 0 && w != 1; }))
        return fail(BooleanStatus::b_overlaps_itself);
    if (std::any_of(wa.begin(), wa.end(), [](int32_t w) { return w != 0 && w != 1; }))
        return fail(BooleanStatus::a_overlaps_itself);
    PieceSum pieces;
    AreaSum a_in_b = whole_a.area_inside, b_in_a = whole_b.area_inside;
    const Inputs in{A, B, cross, wa, wb, Scale{e0}, max_coordinate};
    sum_pieces(in, pieces, a_in_b, b_in_a);
    r.rational_terms = pieces.fractions.size();

    // 6 |A ∩ B| is the pieces' sum; the other results are exact combinations.
    // The whole triangles' sums come with bounds; exact sums when those
    // leave a rounding undecided.
    std::vector<double> out;
    for (bool exactly : {false, true}) {
        if (exactly) {
            whole_a.volume = operand_volume_sum(A, nullptr, true);
            whole_b.volume = operand_volume_sum(B, nullptr, true);
            whole_a.volume_inside = operand_volume_sum(A, &whole_a.inside, true);
            whole_b.volume_inside = operand_volume_sum(B, &whole_b.inside, true);
        }
        pieces.whole = whole_a.volume_inside.sum;  // sum_pieces leaves the whole part to these
        pieces.whole.merge(whole_b.volume_inside.sum);
        pieces.whole_bound = whole_a.volume_inside.bound + whole_b.volume_inside.bound;
        exact::ExactSum both = whole_a.volume.sum;
        both.merge(whole_b.volume.sum);
        const double ba = whole_a.volume.bound, bb = whole_b.volume.bound;
        const Combination combos[4] = {
            {nullptr, +1}, {&both, -1, ba + bb}, {&whole_a.volume.sum, -1, ba}, {&whole_b.volume.sum, -1, bb}};
        out = round_combinations(pieces, e0, combos, r.refinements);
        if (!out.empty()) break;
    }
    r.intersection = out[0];
    r.union_volume = out[1];
    r.a_minus_b = out[2];
    r.b_minus_a = out[3];

    // Areas: 2 × each sum; one bound for every combination.
    auto half = [](const exact::ExactSum& s) { return s.round_div(2); };
    exact::ExactSum inter = a_in_b.sum, uni = area_a.sum, amb = area_a.sum, bma = area_b.sum;
    inter.merge(b_in_a.sum);
    uni.merge(area_b.sum);
    uni.subtract(a_in_b.sum);
    uni.subtract(b_in_a.sum);
    amb.subtract(a_in_b.sum);
    amb.merge(b_in_a.sum);
    bma.subtract(b_in_a.sum);
    bma.merge(a_in_b.sum);
    r.area_a = half(area_a.sum);
    r.area_b = half(area_b.sum);
    r.area_intersection = half(inter);
    r.area_union = half(uni);
    r.area_a_minus_b = half(amb);
    r.area_b_minus_a = half(bma);
    const double largest = std::max({r.area_a + r.area_b, std::fabs(r.area_union), std::fabs(r.area_intersection)});
    r.area_error_bound = ((area_a.bound + area_b.bound + a_in_b.bound + b_in_a.bound) / 2 + kU * largest) * (1 + 0x1p-40);
    return r;
}

}  // namespace polyvol

namespace polyvol::boolean {

double intersection_given_windings(const Operand& A, const Operand& B, const std::vector<int32_t>& wb, int e0,
                                   double max_coordinate, SurfaceInside* surface) {
    const Crossings cross = find_crossings(A, B);
    const std::vector<int32_t> wa = vertex_windings(B, A, cross.b_hits);
    WholeSums whole_a = whole_triangles(A, wb), whole_b = whole_triangles(B, wa);
    PieceSum pieces;
    AreaSum a_in_b = whole_a.area_inside, b_in_a = whole_b.area_inside;
    VectorAreaSum b_normal;
    if (surface != nullptr)  // B's whole triangles inside A: their full vector area
        for (std::size_t i = 0; i < whole_b.inside.size(); i += 3) {
            const Geometry g = triangle_geometry(B.mesh.positions.data() + 3 * std::size_t{whole_b.inside[i]},
                                                 B.mesh.positions.data() + 3 * std::size_t{whole_b.inside[i + 1]},
                                                 B.mesh.positions.data() + 3 * std::size_t{whole_b.inside[i + 2]});
            b_normal.add(g.normal_length, g.normal_error + kU * g.normal_length, g);
        }
    sum_pieces(Inputs{A, B, cross, wa, wb, Scale{e0}, max_coordinate}, pieces, a_in_b, b_in_a,
               surface != nullptr ? &b_normal : nullptr);
    if (surface != nullptr) {
        surface->area = b_in_a;
        surface->normal = b_normal;
    }
    // 6 |A ∩ B| is the pieces' sum, the whole triangles' part filtered first.
    int refinements = 0;
    for (bool exactly : {false, true}) {
        if (exactly) {
            whole_a.volume_inside = operand_volume_sum(A, &whole_a.inside, true);
            whole_b.volume_inside = operand_volume_sum(B, &whole_b.inside, true);
        }
        pieces.whole = whole_a.volume_inside.sum;
        pieces.whole.merge(whole_b.volume_inside.sum);
        pieces.whole_bound = whole_a.volume_inside.bound + whole_b.volume_inside.bound;
        const Combination intersection[1] = {{nullptr, +1}};
        const std::vector<double> out = round_combinations(pieces, e0, intersection, refinements);
        if (!out.empty()) return out[0];
    }
    throw std::logic_error("intersection_given_windings: the exact sums left the rounding undecided");
}

}  // namespace polyvol::boolean
