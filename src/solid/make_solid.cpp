// solid/make_solid.cpp — polyvol/solid.hpp: weld, orient, closedness,
// inside-out shells, self-crossings and overlapping shells, in that order.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include "core/union_find.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/solid.hpp"
#include "core/charconv.hpp"

namespace polyvol {
namespace {

std::string point_text(std::span<const double, 3> p) {
    return "(" + core::shortest_text(p[0]) + ", " + core::shortest_text(p[1]) + ", " + core::shortest_text(p[2]) + ")";
}

std::string plural(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Closed but misoriented: no boundary or non-manifold edge, and some edge
// used twice in one direction (faces wound inconsistently; orient fixes it).
bool only_misoriented(const TopologyReport& t) {
    return t.boundary_edges == 0 && t.nonmanifold_edges == 0 && t.misoriented_edges > 0;
}

// The surface closes when points within a tolerance below 1e-9 of its size
// (its box's diagonal) are merged: the largest power of ten at most that,
// if welding there leaves no unbalanced edge; else 0.
double closing_tolerance(const MeshView& view) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t v = 0; v < view.vertex_count(); ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], view.positions[3 * v + k]);
            hi[k] = std::max(hi[k], view.positions[3 * v + k]);
        }
    const double size = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    if (!(size > 0) || !std::isfinite(size)) return 0;
    const double tolerance = std::pow(10.0, std::floor(std::log10(1e-9 * size)));
    Mesh copy = to_mesh(view);
    try {
        if (weld_within(copy, tolerance).moved == 0) return 0;
    } catch (const std::invalid_argument&) {
        return 0;
    }
    return check_closed(copy.view()).closed ? tolerance : 0;
}

// The part (faces joined through shared vertex indices) of every vertex, as
// a root vertex.
std::vector<uint32_t> part_roots(const MeshView& view) {
    core::UnionFind parts(view.vertex_count());
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto c = view.face(f);
        if (c.size() < 3) continue;
        for (std::size_t i = 1; i < c.size(); ++i) parts.unite(c[0], c[i]);
    }
    std::vector<uint32_t> root(view.vertex_count());
    for (uint32_t v = 0; v < root.size(); ++v) root[v] = parts.find(v);
    return root;
}

// Whether the mesh's faces form more than one part.
bool has_several_parts(const MeshView& view, const std::vector<uint32_t>& root) {
    std::optional<uint32_t> first;
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto c = view.face(f);
        if (c.size() < 3) continue;
        if (first && *first != root[c[0]]) return true;
        first = root[c[0]];
    }
    return false;
}

// Whether some part may have a negative signed volume: each part's cone sum
// 6V = Σ a · (b × c) in double, with |error| <= (n + 4) u Σ |a| (|b||c|)
// (n its fan triangles); a part whose sum is not above its bound may be
// negative, and the exact topology then decides which shells are inside out.
bool some_part_may_be_negative(const MeshView& view, const std::vector<uint32_t>& root) {
    struct Sums {
        double sum = 0, magnitude = 0;
        std::size_t n = 0;
    };
    std::vector<Sums> part(view.vertex_count());
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto c = view.face(f);
        if (c.size() < 3) continue;
        Sums& s = part[root[c[0]]];
        const double* o = view.positions.data() + 3 * std::size_t{c[0]};
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            const double* p = view.positions.data() + 3 * std::size_t{c[i]};
            const double* q = view.positions.data() + 3 * std::size_t{c[i + 1]};
            s.sum += o[0] * (p[1] * q[2] - p[2] * q[1]) + o[1] * (p[2] * q[0] - p[0] * q[2]) +
                     o[2] * (p[0] * q[1] - p[1] * q[0]);
            s.magnitude += std::fabs(o[0]) * (std::fabs(p[1] * q[2]) + std::fabs(p[2] * q[1])) +
                           std::fabs(o[1]) * (std::fabs(p[2] * q[0]) + std::fabs(p[0] * q[2])) +
                           std::fabs(o[2]) * (std::fabs(p[0] * q[1]) + std::fabs(p[1] * q[0]));
            ++s.n;
        }
    }
    return std::any_of(part.begin(), part.end(), [](const Sums& s) {
        return s.n > 0 && !(s.sum > static_cast<double>(s.n + 4) * 0x1p-53 * s.magnitude);
    });
}

// Reverses the faces of the shells the topology finds inside out; what it did.
OrientResult turn_inside_out_shells(Mesh& mesh, const TopologyReport& shells) {
    OrientResult o;
    const MeshView view = mesh.view();
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const uint32_t sh = shells.face_shell[f];
        if (sh == TopologyReport::kNoShell || shells.shells[sh].role != ShellRole::inside_out) continue;
        const auto begin = mesh.indices.begin() + static_cast<std::ptrdiff_t>(view.face_begin(f));
        std::reverse(begin + 1, begin + static_cast<std::ptrdiff_t>(view.face_size(f)));  // (v0, vk, ..., v1)
        ++o.flipped;
    }
    o.components = shells.inside_out_shells;
    return o;
}

}  // namespace

std::string MeshSolid::notes_text(const std::string& name) const {
    std::string text;
    for (const SolidNote& n : notes) text += (text.empty() ? "" : "; ") + (name.empty() ? "" : name + ": ") + n.text;
    return text;
}

std::string unbalanced_message(const TopologyReport& t, double closes_at_tolerance) {
    if (only_misoriented(t))
        return "closed, but " + std::to_string(t.misoriented_edges) + " edge" +
               (t.misoriented_edges == 1 ? " is" : "s are") + " misoriented (faces wound inconsistently): " +
               plural(t.unbalanced_edges, "unbalanced edge", "unbalanced edges") +
               ", each used twice in the same direction; --orient winds the faces consistently and outward";
    std::string m = "not a closed surface: " + plural(t.unbalanced_edges, "unbalanced edge", "unbalanced edges") +
                    " (used a different number of times in its two directions)";
    if (t.unbalanced_example) {
        const auto& e = *t.unbalanced_example;
        m += ", e.g. " + point_text(std::span(e).first<3>()) + " - " + point_text(std::span(e).last<3>());
    }
    if (closes_at_tolerance > 0)
        m += "; merging the points within " + core::shortest_text(closes_at_tolerance) +
             " of one another (1e-9 of its size) closes it: --weld-tolerance " + core::shortest_text(closes_at_tolerance);
    m += "; its volume would depend on the origin (--allow-open gives it anyway)";
    return m;
}

std::string self_crossing_sentence(const SelfCrossings& s) {
    std::string text = "its surface crosses itself within a shell (" +
                       plural(s.pairs, "crossing triangle pair", "crossing triangle pairs");
    if (s.example) text += ", e.g. faces " + std::to_string((*s.example)[0]) + " and " + std::to_string((*s.example)[1]);
    return text + ")";
}

MeshSolid make_solid(Mesh& mesh, const SolidOptions& o) {
    MeshSolid r;
    auto note = [&](SolidNote::Kind kind, std::string text) { r.notes.push_back({kind, std::move(text)}); };
    if (o.weld_tolerance > 0) {
        try {
            r.welded = weld_within(mesh, o.weld_tolerance);
        } catch (const std::invalid_argument& e) {
            r.status = SolidStatus::bad_tolerance;
            r.message = e.what();
            return r;
        }
    }
    if (o.orient) {
        r.oriented = orient_mesh(mesh);
        if (!r.oriented->orientable) {
            r.status = SolidStatus::not_orientable;
            r.message = "cannot orient the faces: a shell is not orientable (an edge used twice in one "
                        "direction that no flip fixes, or by three or more faces)";
            return r;
        }
    }
    const MeshView view = mesh.view();
    const TopologyOptions topology_options{.shells = o.shells, .face_shells = o.shells && o.face_shells};
    ClosednessCheck closedness =
        check_closed(view, ClosednessOptions{.fingerprint = o.closedness_by_fingerprint, .report = topology_options});
    r.closed = closedness.closed;
    r.closed_by_fingerprint = closedness.by_fingerprint;
    r.topology = std::move(closedness.topology);
    if (!r.closed) {
        const TopologyReport& t = *r.topology;
        if (o.allow_open) {
            note(SolidNote::Kind::measured_open,
                 std::to_string(t.unbalanced_edges) +
                     " unbalanced edges: the surface is not closed, so the figures depend on the origin (they are "
                     "the sums about (0,0,0))");
        } else {
            r.closes_at_tolerance = closing_tolerance(view);
            r.status = only_misoriented(t) ? SolidStatus::misoriented : SolidStatus::open;
            r.message = unbalanced_message(t, r.closes_at_tolerance);
            r.self_not_checked = "not a closed surface";
            return r;
        }
    }
    // Inside out: a closed shell facing inward and inside nothing bounds the
    // complement of a solid (negative volume, mass, inertia): its faces are
    // reversed. With the topology's shells at hand their roles say which;
    // otherwise a part whose cone sum may be negative asks for them.
    const std::vector<uint32_t> roots = r.closed ? part_roots(view) : std::vector<uint32_t>{};
    const bool several_parts = r.closed && has_several_parts(view, roots);
    if (r.closed && !o.keep_signed && !o.orient) {
        const bool have_shells = r.topology && o.shells;
        if (have_shells ? r.topology->inside_out_shells > 0 : some_part_may_be_negative(view, roots)) {
            std::optional<TopologyReport> own;
            if (!have_shells || r.topology->face_shell.empty())
                own = analyze_topology(view, TopologyOptions{.shells = true, .face_shells = true});
            const OrientResult turned = turn_inside_out_shells(mesh, own ? *own : *r.topology);
            if (turned.flipped > 0) {
                r.turned_outward = turned;
                if (r.topology) r.topology = analyze_topology(view, topology_options);
                note(SolidNote::Kind::turned_outward,
                     "inside out: " + plural(turned.components, "shell", "shells") + " turned outward (" +
                         plural(turned.flipped, "face", "faces") + " reversed); --signed keeps the signed sums");
            }
        }
    }
    if (view.triangle_count() == 0)
        note(SolidNote::Kind::no_faces,
             "no faces (a point cloud, or an empty file?): there is nothing to measure, every figure is 0");
    if (!r.closed) {
        r.self_not_checked = "not a closed surface";
    } else if (view.triangle_count() > o.self_check_triangles) {
        r.self_not_checked = o.self_check_triangles == 0
                                 ? "not looked for"
                                 : "not looked for: more than " + std::to_string(o.self_check_triangles) +
                                       " triangles (--solid looks)";
    } else {
        r.self = self_crossings(view);
        if (r.self->status != BooleanStatus::ok) {
            r.self_not_checked = std::string("not looked for: ") + boolean_status_message(r.self->status);
            note(SolidNote::Kind::self_not_checked,
                 std::string("not checked for a surface crossing itself: ") + boolean_status_message(r.self->status));
            r.self.reset();
        }
    }
    // The solid: where shells overlap, or a shell crosses itself, the region
    // where the winding number is >= 1 (solid_volume resolves both).
    const bool crosses_itself = r.self && r.self->pairs > 0;
    if (o.resolve_overlaps && r.closed) {
        r.overlap_checked = true;
        if (several_parts || crosses_itself) r.solid = solid_volume(view, {.moments = o.solid_moments, .within_shells = crosses_itself});
        if (r.solid && r.solid->status == BooleanStatus::shell_touches_itself) {
            note(SolidNote::Kind::self_unresolved,
                 self_crossing_sentence(*r.self) +
                     " and also touches or folds onto itself there: its solid is not decided, so the volume counts "
                     "the region it wraps by its winding number");
            r.self_unresolved = true;
            r.solid.reset();
            if (several_parts) r.solid = solid_volume(view, {.moments = o.solid_moments});
        }
        if (r.solid && r.solid->status != BooleanStatus::ok) {
            note(SolidNote::Kind::overlap_not_checked,
                 std::string("shells not checked for overlap: ") + boolean_status_message(r.solid->status) +
                     "; the volume is the sum of the shells' volumes");
            r.overlap_checked = false;
            r.solid.reset();
        }
    } else if (crosses_itself) {
        note(SolidNote::Kind::self_counted_by_winding,
             self_crossing_sentence(*r.self) +
                 ": the volume counts the region it wraps by its winding number there, not as the solid");
    }
    return r;
}

void use_solid_properties(const SolidVolume& s, double density, MassProperties& m) {
    const MassProperties& p = s.properties;
    m.volume = p.volume;
    m.volume_correctly_rounded = true;
    m.volume_error_bound = 0;
    m.mass = density * p.volume;
    if (!s.moments) return;
    for (int i = 0; i < 3; ++i) {
        m.first_moments[i] = density * p.first_moments[i];
        m.centroid[i] = p.centroid[i];
    }
    for (int k = 0; k < 6; ++k) {
        m.second_moments[k] = density * p.second_moments[k];
        m.inertia_origin[k] = density * p.inertia_origin[k];
        m.inertia_centroid[k] = density * p.inertia_centroid[k];
    }
    // A density other than 1 rounds each product once more.
    m.moments_correctly_rounded = false;
    m.moments_relative_error = p.moments_relative_error + (density != 1 ? 0x1p-52 : 0.0);
    if (std::isfinite(p.area)) {
        m.area = p.area;
        m.area_relative_error = p.area_relative_error;
    }
}

SolidMass measure_solid(Mesh& mesh, SolidOptions policy, const MeasureOptions& measure) {
    policy.solid_moments = true;
    SolidMass r{make_solid(mesh, policy), std::nullopt};
    if (r.solid.status != SolidStatus::ok) return r;
    r.mass = mass_properties(mesh.view(), measure);
    if (r.solid.resolved()) use_solid_properties(*r.solid.solid, measure.density, *r.mass);
    return r;
}

SolidBody solid_body(Mesh& mesh, SolidOptions options) {
    options.face_shells = true;  // solid_as_union groups the shells
    SolidBody b;
    b.solid = make_solid(mesh, options);
    if (b.solid.status != SolidStatus::ok) return b;
    if (!b.solid.resolved()) {
        b.volume = signed_volume(mesh.view());
        return b;
    }
    try {
        b.parts = solid_as_union(mesh.view(), b.solid);
    } catch (const std::invalid_argument& e) {
        b.not_split = e.what();
    }
    b.volume = b.solid.solid->properties.volume;
    return b;
}

BooleanVolumes solid_booleans(const MeshView& a, const MeshSolid& sa, const MeshView& b, const MeshSolid& sb) {
    if (!sa.resolved() && !sb.resolved()) return boolean_volumes(a, b);
    const bool within = (sa.self && sa.self->pairs > 0) || (sb.self && sb.self->pairs > 0);
    return solid_boolean_volumes(a, b, within);
}

std::vector<std::string> repairs_needed(const MeshSolid& s) {
    std::vector<std::string> out;
    // (A surface that is not closed always has its topology: the fingerprint decides only "closed".)
    const TopologyReport* t = s.topology ? &*s.topology : nullptr;
    if (!s.closed && only_misoriented(*t))
        out.push_back(plural(t->misoriented_edges, "misoriented edge", "misoriented edges") +
                      ", faces wound inconsistently (fix: --orient)");
    else if (!s.closed)
        out.push_back("not closed: " + plural(t->unbalanced_edges, "unbalanced edge", "unbalanced edges") +
                      (s.closes_at_tolerance > 0 ? " (fix: --weld-tolerance " + core::shortest_text(s.closes_at_tolerance) + ")"
                                                 : " (fix: close its holes in a mesh editor)"));
    else if (t && t->inside_out_shells > 0)
        out.push_back(plural(t->inside_out_shells, "inside-out shell", "inside-out shells") + " (fix: --orient)");
    if (s.self_unresolved)
        out.push_back("a shell crosses itself and touches itself there: its solid is not decided (fix: the mesh)");
    return out;
}

std::vector<Mesh> solid_as_union(const MeshView& mesh, const MeshSolid& solid) {
    if (!solid.topology || solid.topology->face_shell.size() != mesh.face_count())
        throw std::invalid_argument("solid_as_union: the topology's face shells are needed");
    if (solid.solid && solid.solid->shells_crossing_themselves > 0)
        throw std::invalid_argument("its surface crosses itself within a shell: its solid cannot be split into "
                                    "bodies that do not (the grid cannot take it yet; polyvol volume resolves it)");
    const TopologyReport& t = *solid.topology;
    if (t.cavities > 0)
        throw std::invalid_argument("its shells overlap and it has cavities: which shell holds each cavity is not "
                                    "decided here");
    // Each shell's box, then greedy groups: a shell joins the first group
    // none of whose boxes meets its own.
    using Box = std::array<double, 6>;
    std::vector<Box> box(t.shells.size(), Box{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY});
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const uint32_t sh = t.face_shell[f];
        if (sh == TopologyReport::kNoShell) continue;
        for (uint32_t v : mesh.face(f))
            for (int k = 0; k < 3; ++k) {
                box[sh][k] = std::min(box[sh][k], mesh.positions[3 * std::size_t{v} + k]);
                box[sh][3 + k] = std::max(box[sh][3 + k], mesh.positions[3 * std::size_t{v} + k]);
            }
    }
    auto meet = [](const Box& p, const Box& q) {
        return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5];
    };
    std::vector<std::vector<uint32_t>> groups;
    std::vector<uint32_t> group_of(t.shells.size());
    for (uint32_t sh = 0; sh < t.shells.size(); ++sh) {
        std::size_t g = 0;
        for (; g < groups.size(); ++g)
            if (std::none_of(groups[g].begin(), groups[g].end(), [&](uint32_t o) { return meet(box[o], box[sh]); }))
                break;
        if (g == groups.size()) groups.emplace_back();
        groups[g].push_back(sh);
        group_of[sh] = static_cast<uint32_t>(g);
    }
    std::vector<Mesh> out(groups.size());
    for (Mesh& m : out) m.positions.assign(mesh.positions.begin(), mesh.positions.end());
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const uint32_t sh = t.face_shell[f];
        if (sh == TopologyReport::kNoShell) continue;
        const auto c = mesh.face(f);
        out[group_of[sh]].add_face(c);
    }
    return out;
}

}  // namespace polyvol
