// boolean/solid_volume.cpp — the volume of the solid a file's shells bound
// together: the region where their winding number W is >= 1.
//
// The bodies are the file's shells (or index-connected parts, bodies_of),
// each moved by its own multiple of δ; the boundary of {W >= 1} comes from
// solid_pieces.hpp, triangle by triangle, and its cone sum is rounded once.
// Shells whose boxes overlap no other shell's are their own solid (or
// nothing, inward) and cost nothing more. A shell crossing itself is
// resolved when asked for (within_shells): its own crossings join the
// others' and its windings count its own surface.
#include <algorithm>
#include <limits>
#include <map>
#include <span>
#include <numeric>
#include <stdexcept>

#include "boolean/bodies.hpp"
#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "boolean/predicates.hpp"
#include "boolean/solid_pieces.hpp"
#include "boolean/solid_sums.hpp"
#include "measure/sums.hpp"
#include "exact/eft.hpp"
#include "exact/expansion.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"
#include "topology/parts.hpp"
#include "core/union_find.hpp"
#include "topology/welded.hpp"

namespace polyvol {
namespace boolean {
namespace {

// One group of shells whose boxes overlap (or one shell crossing itself):
// its crossings, windings and pieces (added to `pieces`), twice the area of
// its part of the solid's boundary (added to `area`, when not null), and
// what the report says of it.
void solid_group(const Operand& g, const std::vector<uint32_t>& g_face, const std::vector<uint32_t>& shells,
                 const std::vector<int>& body_sign, const Scale& scale, std::size_t faces, std::span<PieceSum> pieces,
                 Mesh& whole, AreaSum* area, SolidVolume& r) {
    const std::size_t n = g.triangles();
    Crossings cross = find_crossings(g, g);

        r.crossing_pairs += cross.cuts.size();
        std::vector<EdgeHit> hits = cross.a_hits;
        hits.insert(hits.end(), cross.b_hits.begin(), cross.b_hits.end());
        std::vector<int32_t> w = vertex_windings(g, g, hits);
        // Overlapping: crossing another shell, or an outward shell inside another solid.
        std::vector<uint8_t> overlapping(shells.size(), 0);
        for (const Cut& c : cross.cuts) overlapping[g.body(c.a)] = overlapping[g.body(c.b)] = 1;
        for (std::size_t t = 0; t < n; ++t)
            if (body_sign[g.body(t)] > 0 && w[g.tri[3 * t]] >= 1) overlapping[g.body(t)] = 1;
        r.overlapping_shells += static_cast<std::size_t>(std::count(overlapping.begin(), overlapping.end(), 1));
        if (!cross.cuts.empty()) {
            if (!r.crossing_example) r.crossing_example = {g_face[cross.cuts[0].a], g_face[cross.cuts[0].b]};
            if (r.face_crosses.empty()) r.face_crosses.assign(faces, 0);
            std::vector<uint8_t> crosses(shells.size(), 0);
            for (const Cut& c : cross.cuts) crosses[g.body(c.a)] = crosses[g.body(c.b)] = 1;
            for (std::size_t t = 0; t < n; ++t)
                if (crosses[g.body(t)]) r.face_crosses[g_face[t]] = 1;
        }
    // Bodies crossing themselves: their own crossings join the others', and
    // their windings count their own surface (operand.hpp, vertex_windings).
    // One seed for each connected piece of such a body (split_sheets cut it
    // into sheets, one fan of triangles around every vertex, and perhaps into
    // several pieces).
    std::vector<WindingSeed> seeds;
    core::UnionFind pieces_of(g.mesh.vertex_count());
    for (std::size_t t = 0; t < n; ++t)
        if (g.crosses_itself(g.body(t))) {
            pieces_of.unite(g.tri[3 * t], g.tri[3 * t + 1]);
            pieces_of.unite(g.tri[3 * t], g.tri[3 * t + 2]);
        }
    std::map<uint32_t, std::vector<uint32_t>> piece_triangles;
    for (std::size_t t = 0; t < n; ++t)
        if (g.crosses_itself(g.body(t))) piece_triangles[pieces_of.find(g.tri[3 * t])].push_back(static_cast<uint32_t>(t));
    for (const auto& [root, tris] : piece_triangles) {
        const uint32_t b = g.body(tris[0]);
        seeds.push_back(own_front_seed(g, b, body_sign[b] > 0 ? 0 : -1, tris));
    }
    if (!seeds.empty()) {
        const Crossings own = find_crossings(g, g, Pairs::self_crossing);
        cross.a_hits.insert(cross.a_hits.end(), own.a_hits.begin(), own.a_hits.end());
        cross.b_hits.insert(cross.b_hits.end(), own.b_hits.begin(), own.b_hits.end());
        cross.cuts.insert(cross.cuts.end(), own.cuts.begin(), own.cuts.end());
        hits.insert(hits.end(), own.a_hits.begin(), own.a_hits.end());
        hits.insert(hits.end(), own.b_hits.begin(), own.b_hits.end());
        w = vertex_windings(g, g, hits, seeds);
    }
    std::vector<uint32_t> whole_triangles;
    SolidPieces solid(g, cross, w, body_sign, scale);
    solid.sum(pieces, whole_triangles);
    if (area) area->merge(solid.twice_area());
    const auto base = static_cast<uint32_t>(whole.vertex_count());
    whole.positions.insert(whole.positions.end(), g.mesh.positions.begin(), g.mesh.positions.end());
    for (uint32_t t : whole_triangles) whole.add_triangle(base + g.tri[3 * t], base + g.tri[3 * t + 1], base + g.tri[3 * t + 2]);
}

}  // namespace

SolidVolume solid_sums(const MeshView& mesh, const SolidWants& wants, SolidSums& out) {
    const bool moments = wants.moments, within_shells = wants.within_shells;
    SolidVolume r;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto fail = [&](BooleanStatus s) {
        r.status = s;
        r.properties.volume = r.properties.mass = r.winding_volume = nan;
        return r;
    };
    if (!check_closed(mesh).closed) return fail(BooleanStatus::a_not_closed);

    // The bodies: the parts as the file joins them by vertex indices, when
    // each of them is a closed 2-cycle (parts that touch or coincide stay
    // apart); otherwise the shells, joined by welded positions (topology.hpp).
    const topology::WeldedMesh wm = topology::weld_polygons(mesh);
    const topology::ShellLabels labels = bodies_of(wm);
    r.shells = labels.count;
    std::vector<uint8_t> crosses_itself(labels.count, 0);
    if (within_shells) {
        const SelfCrossings self = self_crossings_of(mesh, wm, labels, &crosses_itself);
        if (self.status != BooleanStatus::ok) return fail(self.status);
        r.within_checked = true;
        r.self_crossing_pairs = self.pairs;
        r.self_crossing_example = self.example;
        r.shells_crossing_themselves = static_cast<std::size_t>(std::count(crosses_itself.begin(), crosses_itself.end(), 1));
    }
    std::vector<std::vector<std::array<uint32_t, 3>>> shell_tris(labels.count);
    std::vector<std::vector<uint32_t>> shell_faces(labels.count);  // the face of each fan triangle
    for (uint32_t f = 0, poly = 0; f < mesh.face_count(); ++f) {
        const auto c = mesh.face(f);
        if (c.size() < 3) continue;
        const uint32_t sh = labels.of_polygon[poly++];
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            shell_tris[sh].push_back({wm.id[c[0]], wm.id[c[i]], wm.id[c[i + 1]]});
            shell_faces[sh].push_back(f);
        }
    }
    int e0 = std::numeric_limits<int>::max();
    for (std::size_t d = 0; d < wm.referenced(); ++d)
        for (int k = 0; k < 3; ++k) {
            const double x = wm.position(static_cast<uint32_t>(d))[k];
            if (!in_predicate_range(x)) return fail(BooleanStatus::invalid_coordinates);
            if (x != 0) e0 = std::min(e0, lowest_bit_exponent(x));
        }
    if (e0 == std::numeric_limits<int>::max()) e0 = 0;

    // Each shell's volume sign and box, and the shells' sum (the winding
    // integral): measure's double-double sums, exact where they cannot decide.
    std::vector<uint32_t> flat;  // every shell's triangles, shell after shell
    std::vector<std::size_t> first(labels.count + 1, 0);
    std::vector<std::array<double, 6>> box(labels.count, {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY});
    for (std::size_t sh = 0; sh < labels.count; ++sh) {
        for (const auto& tr : shell_tris[sh]) {
            flat.insert(flat.end(), tr.begin(), tr.end());
            for (uint32_t v : tr)
                for (int k = 0; k < 3; ++k) {
                    box[sh][k] = std::min(box[sh][k], wm.position(v)[k]);
                    box[sh][3 + k] = std::max(box[sh][3 + k], wm.position(v)[k]);
                }
        }
        first[sh + 1] = flat.size();
    }
    auto volume_sum = [&](std::span<const uint32_t> tris, bool exactly) {
        return cone_volume_sum({wm.xyz, {}, tris}, exactly);
    };
    std::vector<int> shell_sign(labels.count, 1);
    for (std::size_t sh = 0; sh < labels.count; ++sh) {
        const std::span<const uint32_t> tris(flat.data() + first[sh], first[sh + 1] - first[sh]);
        VolumeSum v = volume_sum(tris, false);
        if (!(std::fabs(v.sum.round()) > 2 * v.bound)) v = volume_sum(tris, true);
        shell_sign[sh] = v.sum.sign() >= 0 ? +1 : -1;
    }
    {
        const VolumeSum all = volume_sum(flat, false);
        const auto decided = exact::decided_round_div(all.sum, all.bound, 6);
        r.winding_volume = decided ? *decided : volume_sum(flat, true).sum.round_div(6);
    }

    // Groups of shells whose boxes overlap (closed boxes: touching counts).
    std::vector<uint32_t> order(labels.count);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return box[x][0] < box[y][0]; });
    core::UnionFind groups(labels.count);
    for (std::size_t i = 0; i < order.size(); ++i)
        for (std::size_t j = i + 1; j < order.size() && box[order[j]][0] <= box[order[i]][3]; ++j) {
            const auto &p = box[order[i]], &q = box[order[j]];
            if (p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5]) groups.unite(order[i], order[j]);
        }
    std::map<uint32_t, std::vector<uint32_t>> members;
    for (uint32_t sh = 0; sh < labels.count; ++sh) members[groups.find(sh)].push_back(sh);

    std::vector<PieceSum> pieces(moments ? kSums : 1);
    Mesh whole;  // whole triangles of the solid's boundary, summed at the end
    const Scale scale{e0};
    for (const auto& [root, shells] : members) {
        if (shells.size() == 1 && !crosses_itself[shells[0]]) {
            if (shell_sign[shells[0]] < 0) continue;  // inward alone: no solid
            const auto base = static_cast<uint32_t>(whole.vertex_count());
            std::map<uint32_t, uint32_t> local;
            for (const auto& tr : shell_tris[shells[0]]) {
                uint32_t v[3];
                for (int i = 0; i < 3; ++i) {
                    auto [it, fresh] = local.try_emplace(tr[i], static_cast<uint32_t>(local.size()));
                    if (fresh) {
                        const double* p = wm.position(tr[i]);
                        whole.add_vertex(p[0], p[1], p[2]);
                    }
                    v[i] = base + it->second;
                }
                whole.add_triangle(v[0], v[1], v[2]);
                if (wants.area) {  // a shell alone: its own surface bounds the solid
                    const Geometry geo = triangle_geometry(wm.position(tr[0]), wm.position(tr[1]), wm.position(tr[2]));
                    out.area.add(geo.normal_length, geo.normal_error + 0x1p-53 * geo.normal_length);
                }
            }
            continue;
        }
        r.shells_checked += shells.size();
        Operand g;
        std::vector<uint32_t> g_face;
        g.body_shift.clear();
        std::vector<int> body_sign;
        std::vector<uint32_t> new_id(wm.referenced(), UINT32_MAX);
        for (uint32_t b = 0; b < shells.size(); ++b) {
            const uint32_t sh = shells[b];
            g.body_shift.push_back(static_cast<int32_t>(b + 1));
            g.body_crosses.push_back(crosses_itself[sh]);
            body_sign.push_back(shell_sign[sh]);
            const uint32_t first_vertex = static_cast<uint32_t>(g.mesh.vertex_count());
            g_face.insert(g_face.end(), shell_faces[sh].begin(), shell_faces[sh].end());
            for (const auto& tr : shell_tris[sh]) {
                for (uint32_t v : tr) {
                    if (new_id[v] == UINT32_MAX || new_id[v] < first_vertex) {  // each body its own vertices
                        const double* p = wm.position(v);
                        new_id[v] = g.mesh.add_vertex(p[0], p[1], p[2]);
                    }
                    g.tri.push_back(new_id[v]);
                }
                g.body_of_triangle.push_back(b);
            }
        }
        try {
            if (std::count(g.body_crosses.begin(), g.body_crosses.end(), 1) > 0) split_sheets(g);
            finish_operand(g);
            solid_group(g, g_face, shells, body_sign, scale, mesh.face_count(), pieces, whole,
                        wants.area ? &out.area : nullptr, r);
        } catch (const Contradiction&) {
            return fail(BooleanStatus::shell_crosses_itself);
        } catch (const SelfContact&) {
            return fail(BooleanStatus::shell_touches_itself);
        }
    }
    out.pieces = std::move(pieces);
    out.whole = std::move(whole);
    out.e0 = e0;
    return r;
}

}  // namespace boolean

SolidVolume solid_volume(const MeshView& mesh, const SolidVolumeOptions& options) {
    const bool moments = options.moments, within_shells = options.within_shells;
    using namespace boolean;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    SolidSums sums;
    SolidVolume r = solid_sums(mesh, SolidWants{.moments = moments, .area = moments, .within_shells = within_shells}, sums);
    if (r.status != BooleanStatus::ok) return r;
    std::vector<PieceSum>& pieces = sums.pieces;
    const Mesh& whole = sums.whole;
    const int e0 = sums.e0;
    // The whole triangles' sums by measure's kernels (parallel): the volume
    // filtered first (an interval), exact when that leaves the rounding open.
    const Combination one[1] = {{nullptr, +1}};
    const uint32_t mask = moments ? (1u << kSums) - 1 : 1u;
    // (SolidPieces leaves every sum's whole part to these.)
    const VolumeSum whole_volume = cone_volume_sum(whole.view(), false);
    pieces[0].whole = whole_volume.sum;
    pieces[0].whole_bound = whole_volume.bound;
    std::vector<double> v = round_combinations(pieces[0], e0, one, r.refinements);
    if (v.empty() || moments) {
        measure::cone::ConeSums exact_whole;  // all sums (count = kSumCount)
        measure::cone::exact_sums(whole.view(), mask, exact_whole);
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            pieces[k].whole = exact_whole.sum[k];
            pieces[k].whole_bound = 0;
        }
        if (v.empty()) v = round_combinations(pieces[0], e0, one, r.refinements);
    }
    MassProperties& p = r.properties;
    p.volume = p.mass = v[0];
    p.volume_correctly_rounded = true;
    p.volume_error_bound = 0;
    p.edge_length = p.edge_length_relative_error = nan;
    if (!moments) {
        p.first_moments.fill(nan);
        p.centroid.fill(nan);
        p.second_moments.fill(nan);
        p.inertia_origin.fill(nan);
        p.inertia_centroid.fill(nan);
        p.area = p.area_relative_error = p.moments_relative_error = nan;
        return r;
    }
    int refinements = 0;
    for (int k = 1; k < kSums; ++k) {
        const int degree = k <= measure::cone::kMz ? 4 : 5;
        const double m = round_combinations(pieces[k], e0, one, refinements, degree, measure::cone::divisor(k))[0];
        (k <= measure::cone::kMz ? p.first_moments[k - 1] : p.second_moments[k - 4]) = m;
    }
    r.moments = true;
    // The area: the exact sum of the terms, halved and rounded once; its
    // absolute bound carried as a relative one rounded up.
    p.area = sums.area.sum.round_div(2);
    const double area_bound = (sums.area.bound / 2 + 0x1p-53 * std::fabs(p.area)) * (1 + 0x1p-40);
    p.area_relative_error = p.area > 0 ? area_bound / p.area * (1 + 0x1p-50) : (area_bound > 0 ? INFINITY : 0.0);
    // Centroid F / V in double: F and V each within half an ulp, so within
    // 1.5 ulp + rounding of the quotient: a relative error below 2^-51.
    for (int i = 0; i < 3; ++i) p.centroid[i] = p.volume != 0 ? p.first_moments[i] / p.volume : nan;
    p.inertia_origin = inertia_from_second_moments(p.second_moments);
    // Inertia about the centroid: Σ_c = S - V c c^T, then the tensor.
    std::array<double, 6> central = p.second_moments;
    static constexpr int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};
    double scale_of_terms = 0;
    for (int k = 0; k < 6; ++k) {
        const double shift = p.first_moments[kPairs[k][0]] * p.centroid[kPairs[k][1]];
        central[k] -= shift;
        scale_of_terms = std::max({scale_of_terms, std::fabs(p.second_moments[k]), std::fabs(shift)});
    }
    p.inertia_centroid = inertia_from_second_moments(central);
    double largest = 0;
    for (double x : p.inertia_centroid) largest = std::max(largest, std::fabs(x));
    // Each central moment: two terms within 2 ulp each, one subtraction, one
    // addition in the tensor: |error| <= 16 u of the largest term. The first
    // and second moments are correctly rounded, the centroid within 2^-51,
    // the inertia about the origin within 3 u of its largest entry.
    const double inertia_error = largest > 0 ? 16 * 0x1p-53 * 2 * scale_of_terms / largest : INFINITY;
    p.moments_correctly_rounded = false;
    p.moments_relative_error = std::max(0x1p-51, inertia_error);
    return r;
}

}  // namespace polyvol
