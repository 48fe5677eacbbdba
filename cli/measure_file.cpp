// cli/measure_file.cpp — cli/measure_file.hpp: read, weld, orient, check
// closedness and overlap, measure, in the file's units.
#include "measure_file.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>

#include "polyvol/chain_io.hpp"
#include "polyvol/soup.hpp"
#include "units.hpp"

namespace polyvol::cli {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
    Mesh copy{std::vector<double>(view.positions.begin(), view.positions.end()),
              std::vector<uint32_t>(view.face_offsets.begin(), view.face_offsets.end()),
              std::vector<uint32_t>(view.indices.begin(), view.indices.end())};
    try {
        if (weld_within(copy, tolerance).moved == 0) return 0;
    } catch (const std::invalid_argument&) {
        return 0;
    }
    return analyze_topology(copy.view(), TopologyOptions{.shells = false}).closed_2_cycle ? tolerance : 0;
}

// --volume-only on a loaded mesh: the volume and its guarantee; the other
// fields NaN. A correctly rounded volume (cone, prism, pyramid) is
// signed_volume alone (for the cone, its origin form near the origin); vtnb
// and --accuracy fast state an error bound that only mass_properties computes.
MassProperties volume_only_properties(const MeshView& view, const MeasureOptions& o) {
    if (o.method == Method::vtnb || o.accuracy != Accuracy::correctly_rounded) return mass_properties(view, o);
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    MassProperties m;
    m.volume = signed_volume(view, o.method, Accuracy::correctly_rounded);
    m.volume_correctly_rounded = !std::isnan(m.volume);
    m.volume_error_bound = m.volume_correctly_rounded ? 0.0 : nan;
    m.mass = o.density * m.volume;
    m.first_moments = m.centroid = {nan, nan, nan};
    m.second_moments = m.inertia_origin = m.inertia_centroid = {nan, nan, nan, nan, nan, nan};
    m.area = m.edge_length = nan;
    m.moments_relative_error = m.area_relative_error = m.edge_length_relative_error = nan;
    m.method = o.method;
    m.accuracy = o.accuracy;
    return m;
}

// Whether process_file streams a binary STL for the request: what it asks
// for is what streaming computes (Request::table_only; the cone rule), and
// nothing asks for the loaded mesh (its counts in the JSON, a weld,
// orientation, units, a scale, the full overlap and self-crossing check of
// --solid, an archive member).
bool streams(const Request& q, const std::string& member) {
    return q.need_mass && q.table_only && !q.mesh_counts && q.measure.method == Method::cone && member.empty() &&
           !q.orient && q.weld_tolerance == 0 && !q.self_check_always && q.units.empty() && q.to.empty() &&
           q.scale == 1 && q.scale_typed_exactly && q.density_kg_m3 == 0 && std::isfinite(q.measure.density);
}

// The streaming route for a binary STL: nothing when the file is not binary
// STL, cannot be probed, or is not closed (the loaded route then reports it).
std::optional<FileResult> stream_binary_stl(const std::string& path, const Request& q) {
    std::optional<BinaryStlFile> file;
    try {
        file.emplace(path);
    } catch (const ReadError&) {
        return std::nullopt;
    }
    if (!file->probe().binary_stl) return std::nullopt;
    FileResult r;
    r.file = path;
    const auto t0 = std::chrono::steady_clock::now();
    SoupAccumulator acc(
        SoupWants{.closedness = true,
                  .moments_and_area = !q.volume_only,
                  .moments = q.table_moments_bounded ? Accuracy::fast : q.measure.accuracy,
                  .density = q.measure.density});
    try {
        do {
            file->for_each_window(
                [&](std::span<const std::byte> records, uint64_t first) { acc.add(stl_records(records), first); },
                StlStreamOptions{.alignment = SoupAccumulator::kBlockTriangles});
        } while (acc.next_pass());
    } catch (const ReadError& e) {
        r.exit_code = Exit::unreadable;
        r.error = e.what();
        return r;
    } catch (const std::exception&) {
        return std::nullopt;  // e.g. the file changed between passes: the loaded route reads it once
    }
    if (!acc.result().closed) return std::nullopt;
    r.streamed = true;
    r.triangles = acc.result().triangles;
    r.mass = acc.result().properties;
    r.seconds_measure = seconds_since(t0);
    return r;
}

// Where shells overlap, the mass properties become the solid's (winding
// number >= 1): volume and moments from solid_volume, scaled by the density
// (one more rounding unless it is 1); area and edge length stay the
// shells' sums (the reports say so).
void use_solid_properties(const SolidVolume& s, double density, MassProperties& m) {
    m.volume = s.volume;
    m.volume_correctly_rounded = true;
    m.volume_error_bound = 0;
    m.mass = density * s.volume;
    if (!s.moments) return;
    for (int i = 0; i < 3; ++i) {
        m.first_moments[i] = density * s.first_moments[i];
        m.centroid[i] = s.centroid[i];
    }
    for (int k = 0; k < 6; ++k) {
        m.second_moments[k] = density * s.second_moments[k];
        m.inertia_centroid[k] = density * s.inertia_centroid[k];
    }
    m.inertia_origin = inertia_from_second_moments(m.second_moments);
    // The centroid is within 2^-51 relative, the second moments correctly
    // rounded (before the density), the central inertia within its bound.
    m.moments_correctly_rounded = false;
    m.moments_relative_error = std::max(0x1p-51, s.inertia_relative_error) + (density != 1 ? 0x1p-52 : 0.0);
}

// The part (faces joined through shared vertex indices) of every vertex, as
// a root vertex: a union–find over the indices, one pass, no sorting.
std::vector<uint32_t> part_roots(const MeshView& view) {
    std::vector<uint32_t> parent(view.vertex_count());
    for (uint32_t v = 0; v < parent.size(); ++v) parent[v] = v;
    auto find = [&](uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto c = view.face(f);
        if (c.size() < 3) continue;
        for (std::size_t i = 1; i < c.size(); ++i) {
            const uint32_t a = find(c[0]), b = find(c[i]);
            if (a != b) parent[b] = a;
        }
    }
    for (uint32_t v = 0; v < parent.size(); ++v) parent[v] = find(v);
    return parent;
}

// Whether the mesh's faces form more than one part.
bool has_several_parts(const MeshView& view) {
    const std::vector<uint32_t> root = part_roots(view);
    std::optional<uint32_t> first;
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto c = view.face(f);
        if (c.size() < 3) continue;
        if (first && *first != root[c[0]]) return true;
        first = root[c[0]];
    }
    return false;
}

// Whether some part of a multi-part mesh has a negative signed volume, in
// double: an inside-out shell or a cavity, which the topology then tells
// apart exactly. (What `volume`'s table checks where it analyses no shells.)
bool some_part_negative(const MeshView& view) {
    const std::vector<uint32_t> root = part_roots(view);
    std::vector<double> volume(view.vertex_count(), 0.0);
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto c = view.face(f);
        if (c.size() < 3) continue;
        const double* o = view.positions.data() + 3 * std::size_t{c[0]};
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            const double* p = view.positions.data() + 3 * std::size_t{c[i]};
            const double* q = view.positions.data() + 3 * std::size_t{c[i + 1]};
            volume[root[c[0]]] += o[0] * (p[1] * q[2] - p[2] * q[1]) + o[1] * (p[2] * q[0] - p[0] * q[2]) +
                                  o[2] * (p[0] * q[1] - p[1] * q[0]);
        }
    }
    return std::any_of(volume.begin(), volume.end(), [](double v) { return v < 0; });
}

// The units of the figures for this file (Request's units, to, scale):
// sets r's length_unit, mass_unit, length_factor; returns why they cannot be
// given ("" when they can).
std::string plan_units(FileResult& r, const Request& q, double& length_error) {
    std::optional<LengthUnit> from;
    const std::string& declared = r.loaded->unit;
    if (!q.units.empty()) {
        from = length_unit(q.units);
        r.units_source = "--units";
        if (!declared.empty() && declared != from->name)
            r.warning += (r.warning.empty() ? "" : "; ") + r.file + ": the file declares its unit as " + declared +
                         "; --units " + q.units + " is used instead";
    } else if (!declared.empty()) {
        from = length_unit(declared);
        r.units_source = "declared by the file";
    }
    const std::string to = !q.to.empty()                               ? q.to
                           : q.density_kg_m3 > 0 || (q.metres_when_known && from) ? "m"
                           : from                                             ? from->name
                                                                              : "";
    if (!to.empty() && !from)
        return std::string("its length unit is not known (") + std::string(format_name(r.loaded->format)) +
               " files do not state one): --units gives it (mm, cm, m, in, ft or micron)";
    const LengthFactor f = from ? length_factor(*from, *length_unit(to), q.scale, q.scale_typed_exactly)
                                : scale_only(q.scale, q.scale_typed_exactly);
    r.length_factor = f.factor;
    length_error = f.relative_error;
    r.length_unit = to;
    r.mass_unit = q.density_kg_m3 > 0 ? "kg" : "";
    return "";
}

// The figures of a set of faces of the file (their own surface's sums):
// volume, area, first moments and centroid, widened for computed coordinates.
MassProperties figures_of(const MeshView& view, const std::vector<uint32_t>& faces, const Request& q, double delta) {
    std::vector<uint32_t> offsets{0}, indices;
    offsets.reserve(faces.size() + 1);
    for (uint32_t f : faces) {
        const std::size_t b = view.face_begin(f), n = view.face_size(f);
        indices.insert(indices.end(), view.indices.begin() + static_cast<std::ptrdiff_t>(b),
                       view.indices.begin() + static_cast<std::ptrdiff_t>(b + n));
        offsets.push_back(static_cast<uint32_t>(indices.size()));
    }
    const MeshView piece{view.positions, offsets, indices};
    MeasureOptions o = q.measure;
    o.second_moments = false;
    o.edge_length = false;
    MassProperties m = mass_properties(piece, o);
    if (delta > 0) widen_for_coordinate_error(piece, delta, o.density, false, false, m);
    return m;
}

// Each shell's (the first kMaxPieces) and each named part's figures.
void piece_figures(FileResult& r, const Request& q, const MeshView& view) {
    const TopologyReport& t = *r.topology;
    const double delta = r.loaded->coordinate_error;
    if (t.shells.size() > 1 && !t.face_shell.empty()) {
        const std::size_t n = std::min(t.shells.size(), kMaxPieces);
        std::vector<std::vector<uint32_t>> faces(n);
        for (uint32_t f = 0; f < t.face_shell.size(); ++f)
            if (t.face_shell[f] < n) faces[t.face_shell[f]].push_back(f);
        for (std::size_t s = 0; s < n; ++s)
            r.shell_figures.push_back({"shell " + std::to_string(s + 1), faces[s].size(), figures_of(view, faces[s], q, delta)});
    }
    for (const MeshPart& p : r.loaded->parts) {
        std::vector<uint32_t> faces(p.faces);
        for (std::size_t i = 0; i < p.faces; ++i) faces[i] = static_cast<uint32_t>(p.first_face + i);
        r.part_figures.push_back({p.name, p.faces, figures_of(view, faces, q, p.coordinate_error)});
    }
}

// Whether a file the mesh readers refused is one `polyvol ndim` reads.
bool reads_as_chain(const std::string& file) {
    try {
        return read_chain_file(file).chain.simplex_count() > 0;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace

std::string unbalanced_message(const TopologyReport& t, double closes_at_tolerance) {
    if (t.boundary_edges == 0 && t.nonmanifold_edges == 0 && t.misoriented_edges > 0)
        return "closed, but " + std::to_string(t.misoriented_edges) + " edge" +
               (t.misoriented_edges == 1 ? " is" : "s are") + " misoriented (faces wound inconsistently): " +
               std::to_string(t.unbalanced_edges) + " unbalanced edge" + (t.unbalanced_edges == 1 ? "" : "s") +
               ", each used twice in the same direction; --orient winds the faces consistently and outward";
    std::string m = "not a closed surface: " + std::to_string(t.unbalanced_edges) +
                    " unbalanced edge" + (t.unbalanced_edges == 1 ? "" : "s") +
                    " (used a different number of times in its two directions)";
    if (t.unbalanced_example) {
        const auto& e = *t.unbalanced_example;
        m += ", e.g. " + point_text(std::span(e).first<3>()) + " - " + point_text(std::span(e).last<3>());
    }
    if (closes_at_tolerance > 0)
        m += "; merging the points within " + shortest(closes_at_tolerance) +
             " of one another (1e-9 of its size) closes it: --weld-tolerance " + shortest(closes_at_tolerance);
    m += "; its volume would depend on the origin (--allow-open gives it anyway)";
    return m;
}

std::string self_crossing_sentence(const SelfCrossings& s) {
    std::string text = "its surface crosses itself within a shell (" + std::to_string(s.pairs) + " crossing triangle pair" +
                       (s.pairs == 1 ? "" : "s");
    if (s.example) text += ", e.g. faces " + std::to_string((*s.example)[0]) + " and " + std::to_string((*s.example)[1]);
    return text + ")";
}

FileResult process_file(const std::string& file, const Request& request, const std::string& member) {
    if (streams(request, member))
        if (auto s = stream_binary_stl(file, request))
            if (request.keep_signed || !s->mass || s->mass->volume >= 0) return std::move(*s);  // inside out: loaded below
    FileResult r;
    r.file = member.empty() ? file : file + ":" + member;
    const std::string& path = r.file;  // the name in every message
    auto t0 = std::chrono::steady_clock::now();
    try {
        r.loaded = member.empty() ? read_mesh_file(file) : read_archive_member(file, member);
    } catch (const ReadError& e) {
        r.exit_code = Exit::unreadable;
        r.error = e.what();
        if (member.empty() && file != "-" && reads_as_chain(file))
            r.error += "; it reads as a boundary chain (.chain or qhull's output): `polyvol ndim` measures it";
        return r;
    } catch (const std::bad_alloc&) {
        r.exit_code = Exit::unreadable;
        r.error = path + ": out of memory while reading";
        return r;
    }
    r.seconds_read = seconds_since(t0);
    r.triangles = r.loaded->mesh.view().triangle_count();
    t0 = std::chrono::steady_clock::now();
    double length_error = 0;
    if (const std::string why = plan_units(r, request, length_error); !why.empty()) {
        r.exit_code = Exit::invalid;
        r.error = path + ": " + why;
        return r;
    }
    if (request.weld_tolerance > 0) {
        try {
            r.welded = weld_within(r.loaded->mesh, request.weld_tolerance);
            r.weld_tolerance = request.weld_tolerance;
        } catch (const std::invalid_argument& e) {
            r.exit_code = Exit::invalid;
            r.error = path + ": " + e.what();
            return r;
        }
    }
    if (request.orient) {
        r.oriented = orient_mesh(r.loaded->mesh);
        if (!r.oriented->orientable) {
            r.exit_code = Exit::invalid;
            r.error = path + ": cannot orient the faces: a shell is not orientable (an edge used twice in one "
                             "direction that no flip fixes, or by three or more faces)";
            return r;
        }
    }
    const MeshView view = r.loaded->mesh.view();
    r.closed_by_fingerprint =
        request.closedness_by_fingerprint && fingerprint_closedness(view) == Closedness::closed;
    const bool pieces = request.need_mass && !request.table_only;  // per-shell and per-part figures
    if (!r.closed_by_fingerprint)
        r.topology = analyze_topology(view, TopologyOptions{.shells = !request.table_only, .face_shells = pieces});
    if (r.topology && !r.topology->closed_2_cycle && !request.allow_open) r.closes_at_tolerance = closing_tolerance(view);
    if (request.need_mass) {
        if (!r.closed_by_fingerprint && !r.topology->closed_2_cycle) {
            if (request.allow_open) {
                r.warning = path + ": " + std::to_string(r.topology->unbalanced_edges) +
                            " unbalanced edges: the surface is not closed, so the figures depend on "
                            "the origin (they are the sums about (0,0,0))";
            } else {
                r.exit_code = Exit::invalid;
                r.error = path + ": " + unbalanced_message(*r.topology, r.closes_at_tolerance);
            }
        }
        if (r.exit_code == Exit::ok)
            r.mass = request.volume_only ? volume_only_properties(view, request.measure)
                                         : mass_properties(view, request.measure);
    }
    const bool closed = r.closed_by_fingerprint || r.topology->closed_2_cycle;
    // Inside out: a closed shell facing inward and inside nothing (topology's
    // role inside_out, not a cavity) bounds the complement of a solid
    // (negative volume, mass, inertia). Its faces are reversed, and said so;
    // cavities and nested shells stay as they are.
    const bool several_parts = closed && (request.check_overlap || !request.table_only) && has_several_parts(view);
    if (r.mass && closed && !request.keep_signed && !request.orient &&
        (r.mass->volume < 0 || (!request.table_only ? r.topology && r.topology->inside_out_shells > 0
                                                    : several_parts && some_part_negative(view)))) {
        OrientResult o;
        // Each face's shell: the topology's own when it has them (measure, --json).
        std::optional<TopologyReport> own;
        if (!r.topology || r.topology->face_shell.empty())
            own = analyze_topology(view, TopologyOptions{.shells = true, .face_shells = true});
        const TopologyReport& shells = own ? *own : *r.topology;
        for (std::size_t f = 0; f < view.face_count(); ++f) {
            const uint32_t sh = shells.face_shell[f];
            if (sh == TopologyReport::kNoShell || shells.shells[sh].role != ShellRole::inside_out) continue;
            const auto begin = r.loaded->mesh.indices.begin() + static_cast<std::ptrdiff_t>(view.face_begin(f));
            std::reverse(begin + 1, begin + static_cast<std::ptrdiff_t>(view.face_size(f)));  // (v0, vk, ..., v1)
            ++o.flipped;
        }
        o.components = shells.inside_out_shells;
        if (o.flipped > 0) {
            r.turned_outward = o;
            if (r.topology)
                r.topology = analyze_topology(view, TopologyOptions{.shells = !request.table_only, .face_shells = pieces});
            r.mass = request.volume_only ? volume_only_properties(view, request.measure)
                                         : mass_properties(view, request.measure);
            r.warning += (r.warning.empty() ? "" : "; ") + path + ": inside out: " + std::to_string(o.components) +
                         " shell" + (o.components == 1 ? "" : "s") + " turned outward (" + std::to_string(o.flipped) +
                         " face" + (o.flipped == 1 ? "" : "s") + " reversed); --signed keeps the signed sums";
        }
    }
    // `check`: a surface that is not a closed 2-cycle exits 3 too (the report says why).
    if (!request.need_mass && !closed) r.exit_code = Exit::invalid;
    if (view.triangle_count() == 0)
        r.warning += (r.warning.empty() ? "" : "; ") + path +
                     ": no faces (a point cloud, or an empty file?): there is nothing to measure, every figure is 0";
    if (!closed) {
        r.self_not_checked = "not a closed surface";
    } else if (!request.self_check_always && view.triangle_count() > kSelfCheckTriangles) {
        r.self_not_checked = "not looked for: more than " + std::to_string(kSelfCheckTriangles) + " triangles (--solid looks)";
    } else {
        r.self = self_crossings(view);
        if (r.self->status != BooleanStatus::ok) {
            r.self_not_checked = std::string("not looked for: ") + boolean_status_message(r.self->status);
            r.warning += (r.warning.empty() ? "" : "; ") + path + ": not checked for a surface crossing itself: " +
                         boolean_status_message(r.self->status);
            r.self.reset();
        }
    }
    // The solid: where shells overlap, or a shell crosses itself, the region
    // where the winding number is >= 1 (solid_volume resolves both).
    const bool crosses_itself = r.self && r.self->pairs > 0;
    if (request.check_overlap && closed) {
        r.overlap_checked = true;
        const bool moments = request.need_mass && !request.volume_only;
        const bool several = several_parts;
        if (several || crosses_itself) r.solid = solid_volume(view, moments, crosses_itself);
        if (r.solid && r.solid->status == BooleanStatus::shell_touches_itself) {
            if (request.need_mass)
                r.warning += (r.warning.empty() ? "" : "; ") + path + ": " + self_crossing_sentence(*r.self) +
                             " and also touches or folds onto itself there: its solid is not decided, so the volume "
                             "counts the region it wraps by its winding number";
            r.self_unresolved = true;
            r.solid.reset();
            if (several) r.solid = solid_volume(view, moments);
        }
        if (r.solid && r.solid->status == BooleanStatus::ok && solid_differs(*r.solid) && r.mass)
            use_solid_properties(*r.solid, request.measure.density, *r.mass);
        if (r.solid && r.solid->status != BooleanStatus::ok) {
            r.warning += (r.warning.empty() ? "" : "; ") + path +
                         ": shells not checked for overlap: " + boolean_status_message(r.solid->status) +
                         "; the volume is the sum of the shells' volumes";
            r.overlap_checked = false;
            r.solid.reset();
        }
    } else if (crosses_itself && request.need_mass) {
        r.warning += (r.warning.empty() ? "" : "; ") + path + ": " + self_crossing_sentence(*r.self) +
                     ": the volume counts the region it wraps by its winding number there, not as the solid";
    }
    // Coordinates a reader computed (3MF transforms): every guarantee widened
    // to hold for the coordinates the file defines.
    if (r.mass && r.loaded->coordinate_error > 0)
        widen_for_coordinate_error(view, r.loaded->coordinate_error, request.measure.density, closed,
                                   r.solid && r.solid->status == BooleanStatus::ok && solid_differs(*r.solid), *r.mass);
    if (r.mass && pieces && r.topology) piece_figures(r, request, view);
    // In the units asked for: every figure times its power of the length factor.
    const double density_error = request.density_kg_m3 > 0 ? 4 * 0x1p-53 : 0.0;  // typed, × 1000, × (m per unit)³
    if (r.mass && (r.length_factor != 1 || length_error > 0 || density_error > 0)) {
        scale_mass_properties(*r.mass, r.length_factor, length_error, density_error);
        for (auto* list : {&r.shell_figures, &r.part_figures})
            for (FileResult::Piece& p : *list) scale_mass_properties(p.m, r.length_factor, length_error, density_error);
        if (r.solid) r.solid->winding_volume *= r.length_factor * r.length_factor * r.length_factor;
    }
    r.seconds_measure = seconds_since(t0);
    return r;
}

}  // namespace polyvol::cli
