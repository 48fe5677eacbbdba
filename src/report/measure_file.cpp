// src/report/measure_file.cpp — polyvol/report.hpp's measure_file: read,
// the solid policy (weld, orient, closedness, overlap), measure, in the
// units asked for; the route chosen once (streams).
#include "polyvol/report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>

#include "core/progress.hpp"
#include "polyvol/chain_io.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/soup.hpp"
#include "polyvol/units.hpp"

namespace polyvol {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

// FileOptions::progress, where the caller asked for it.
void tell(const FileOptions& q, FileStage stage, double fraction) {
    if (q.progress) q.progress(stage, fraction);
}

// The route, decided here only: a binary STL of more than
// kStreamAboveTriangles triangles (any size with stream_any_size) is streamed (constant memory, nothing
// loaded or welded) when what is wanted is what streaming computes
// (FileOptions::table_only; the cone rule) and nothing asks for the loaded
// mesh (its counts, a weld, orientation, units, a scale, the full overlap
// and self-crossing check, an archive member). A streamed file the
// fingerprint finds open, or inside out, is loaded after all, to be
// reported or turned (measure_file).
bool streams(const FileOptions& q, const std::string& member) {
    return q.need_mass && q.table_only && !q.mesh_counts && q.measure.method == Method::cone && member.empty() &&
           !q.orient && q.weld_tolerance == 0 && !q.self_check_always && q.units.empty() && q.to.empty() &&
           q.scale == 1 && q.scale_typed_exactly && q.density_kg_m3 == 0 && std::isfinite(q.measure.density);
}

// The streamed windows: natively StlStreamOptions' (L2-sized, one buffer per
// thread); in a browser's worker each read of a File is a call to the
// browser's file system costing milliseconds, so its windows are 8 MiB.
#ifdef __EMSCRIPTEN__
constexpr std::size_t kWindowBytes = std::size_t{8} << 20;
#else
constexpr std::size_t kWindowBytes = StlStreamOptions{}.window_bytes;
#endif
constexpr std::size_t kSliceTriangles = 4096;  // a multiple of SoupAccumulator::kBlockTriangles
static_assert(kSliceTriangles % SoupAccumulator::kBlockTriangles == 0);

// The streaming route for a binary STL: nothing when the file is not binary
// STL, cannot be probed, or is not closed (the loaded route then reports it).
std::optional<FileReport> stream_binary_stl(const std::string& path, const FileOptions& q) {
    std::optional<BinaryStlFile> file;
    try {
        file.emplace(path);
    } catch (const ReadError&) {
        return std::nullopt;
    }
    if (!file->probe().binary_stl) return std::nullopt;
    if (file->probe().triangles <= kStreamAboveTriangles && !q.stream_any_size) return std::nullopt;  // checked in full
    FileReport r;
    r.file = path;
    const auto t0 = std::chrono::steady_clock::now();
    SoupAccumulator acc(
        SoupWants{.closedness = true,
                  .moments_and_area = !q.volume_only,
                  .moments = q.moments_bounded ? Accuracy::fast : q.measure.accuracy,
                  .density = q.measure.density});
    try {
        do {
            // Pass 1 reads and measures (reading, 0 to 1); passes 2 and 3
            // decide the first moments (soup.hpp): measuring, 0 to 1/2 and
            // 1/2 to 1, so that a skipped pass only jumps ahead.
            const bool first_pass = acc.pass() == 1;
            const FileStage stage = first_pass ? FileStage::reading : FileStage::measuring;
            const double from = first_pass ? 0 : 0.5 * (acc.pass() - 2), width = first_pass ? 1 : 0.5;
            tell(q, stage, from);
            core::ProgressCounter records(
                q.progress ? std::function<void(double)>([&](double f) { q.progress(stage, from + width * f); })
                           : nullptr,
                file->probe().triangles);
            // A window in slices of kSliceTriangles, so that progress moves within it.
            file->for_each_window(
                [&](std::span<const std::byte> window, uint64_t first) {
                    const Float32Triangles all = stl_records(window);
                    for (std::size_t k = 0; k < all.count; k += kSliceTriangles) {
                        Float32Triangles slice = all;
                        slice.data += k * all.stride;
                        slice.count = std::min(all.count - k, kSliceTriangles);
                        acc.add(slice, first + k);
                        records.add(slice.count);
                    }
                },
                StlStreamOptions{.window_bytes = kWindowBytes, .alignment = SoupAccumulator::kBlockTriangles});
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

// The units of the figures for this file (FileOptions' units, to, scale):
// sets r's length_unit, mass_unit, length_factor; returns why they cannot be
// given ("" when they can).
std::string plan_units(FileReport& r, const FileOptions& q, double& length_error) {
    const bool stated = !r.loaded->unit.empty();
    const UnitsPlan p = plan_units(r.loaded->unit, UnitsRequest{.units = q.units_where_unstated && stated ? "" : q.units,
                                                               .to = q.to,
                                                               .scale = q.scale,
                                                               .scale_typed_exactly = q.scale_typed_exactly,
                                                               .density_si = q.density_kg_m3 > 0,
                                                               .metres_when_known = q.metres_when_known});
    if (!p.error.empty()) {
        if (p.error.find("not known") != std::string::npos)
            return std::string("its length unit is not known (") + std::string(format_name(r.loaded->format)) +
                   " files do not state one): --units gives it (" + kLengthUnitNames + ")";
        return p.error;
    }
    r.units_source = p.source;
    if (!p.warning.empty())
        r.warning += (r.warning.empty() ? "" : "; ") + r.file + ": " + p.warning + " (--units " + q.units + ")";
    r.length_factor = p.length.factor;
    length_error = p.length.relative_error;
    r.length_unit = p.length_unit;
    r.mass_unit = q.density_kg_m3 > 0 ? q.mass_unit : "";
    return "";
}

// The figures of a set of faces of the file (their own surface's sums):
// volume, area, first moments and centroid, widened for computed coordinates.
MassProperties figures_of(const MeshView& view, const std::vector<uint32_t>& faces, const FileOptions& q, double delta) {
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
void piece_figures(FileReport& r, const FileOptions& q, const MeshView& view) {
    const TopologyReport& t = *r.policy.topology;
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

namespace {

// Reads the file (or archive member) into r.loaded; false with r's error and
// exit code 2 when it cannot be read.
bool load(FileReport& r, const std::string& file, const std::string& member) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
        r.loaded = member.empty() ? read_mesh_file(file) : read_archive_member(file, member);
    } catch (const ReadError& e) {
        r.exit_code = Exit::unreadable;
        r.error = e.what();
        if (member.empty() && file != "-" && reads_as_chain(file))
            r.error += "; it reads as a boundary chain (.chain or qhull's output): `polyvol ndim` measures it";
        return false;
    } catch (const std::bad_alloc&) {
        r.exit_code = Exit::unreadable;
        r.error = r.file + ": out of memory while reading";
        return false;
    }
    r.seconds_read = seconds_since(t0);
    r.triangles = r.loaded->mesh.view().triangle_count();
    return true;
}

// The solid policy for what is wanted (polyvol/solid.hpp): `check` judges
// the file as it is (inside-out shells reported, not turned); the table's
// figures need the closedness alone, not the shells.
SolidOptions policy_for(const FileOptions& q) {
    return SolidOptions{.weld_tolerance = q.weld_tolerance,
                        .orient = q.orient,
                        .keep_signed = q.keep_signed || !q.need_mass,
                        .allow_open = q.allow_open,
                        .resolve_overlaps = q.check_overlap,
                        .self_check_triangles = q.self_check_always ? SIZE_MAX : kSelfCheckTriangles,
                        .solid_moments = q.need_mass && !q.volume_only,
                        .closedness_by_fingerprint = !q.edge_counts,
                        .shells = !q.table_only,
                        .face_shells = q.need_mass && !q.table_only};
}

// What the policy found, into the report; false (exit 3) when the mesh is
// not a solid. `check` reports an open or misoriented surface in its table;
// every other refusal is said in r.error.
bool take_solid(FileReport& r, const FileOptions& q) {
    const MeshSolid& solid = r.policy;
    if (!q.need_mass) r.repairs = repairs_needed(solid);
    if (solid.welded) r.weld_tolerance = q.weld_tolerance;
    const std::string notes = solid.notes_text(r.file);
    if (!notes.empty()) r.warning += (r.warning.empty() ? "" : "; ") + notes;
    if (solid.status == SolidStatus::ok) {
        if (!r.repairs.empty()) r.exit_code = Exit::invalid;  // `check`: a file that needs a repair is not a solid as it is
        return true;
    }
    r.exit_code = Exit::invalid;
    if (q.need_mass || !solid.topology) r.error = r.file + ": " + solid.message;
    return false;
}

// The figures: the mesh's (the solid's where shells overlap), widened for
// coordinates a reader computed, per shell and part, in the units asked for.
void measure_figures(FileReport& r, const FileOptions& q, double length_error) {
    const MeshSolid& solid = r.policy;
    const MeshView view = r.loaded->mesh.view();
    r.mass = q.volume_only ? volume_only_properties(view, q.measure) : mass_properties(view, q.measure);
    if (solid.resolved()) use_solid_properties(*r.policy.solid, q.measure.density, *r.mass);
    // Coordinates a reader computed (3MF transforms): every guarantee widened
    // to hold for the coordinates the file defines.
    if (r.loaded->coordinate_error > 0)
        widen_for_coordinate_error(view, r.loaded->coordinate_error, q.measure.density, solid.closed, solid.resolved(),
                                   *r.mass);
    if (!q.table_only && r.policy.topology) piece_figures(r, q, view);
    // Every figure times its power of the length factor.
    const double density_error = q.density_relative_error;  // polyvol::density_in's
    if (r.length_factor != 1 || length_error > 0 || density_error > 0) {
        scale_mass_properties(*r.mass, r.length_factor, length_error, density_error);
        for (auto* list : {&r.shell_figures, &r.part_figures})
            for (FileReport::Piece& p : *list) scale_mass_properties(p.m, r.length_factor, length_error, density_error);
        if (r.policy.solid) r.policy.solid->winding_volume *= r.length_factor * r.length_factor * r.length_factor;
    }
}

}  // namespace

// The route (streams), then read → units → the solid policy → the figures.
FileReport measure_file(const std::string& file, const FileOptions& request, const std::string& member) {
    // A streamed file found open or inside out is loaded below: its stages begin again.
    if (streams(request, member))
        if (auto s = stream_binary_stl(file, request))
            if (request.keep_signed || !s->mass || s->mass->volume >= 0) {
                if (s->exit_code == Exit::ok) tell(request, FileStage::measuring, 1);
                return std::move(*s);
            }
    FileReport r;
    r.file = member.empty() ? file : file + ":" + member;  // the name in every message
    tell(request, FileStage::reading, 0);
    if (!load(r, file, member)) return r;
    const auto t0 = std::chrono::steady_clock::now();
    double length_error = 0;
    if (const std::string why = plan_units(r, request, length_error); !why.empty()) {
        r.exit_code = Exit::invalid;
        r.error = r.file + ": " + why;
        return r;
    }
    tell(request, FileStage::checking, 0);
    r.policy = make_solid(r.loaded->mesh, policy_for(request));
    if (!take_solid(r, request)) return r;
    tell(request, FileStage::measuring, 0);
    if (request.need_mass) measure_figures(r, request, length_error);
    r.seconds_measure = seconds_since(t0);
    tell(request, FileStage::measuring, 1);
    return r;
}

std::vector<std::pair<std::string, std::string>> file_inputs(const std::vector<std::string>& paths) {
    std::vector<std::pair<std::string, std::string>> inputs;
    for (const std::string& f : paths) {
        std::vector<std::string> members;
        try {
            if (f != "-") members = mesh_archive_members(f);
        } catch (const ReadError&) {
            // Not a readable archive: read as one file, whose reader says what is wrong (exit 2).
        }
        if (members.empty()) inputs.emplace_back(f, "");
        for (const std::string& m : members) inputs.emplace_back(f, m);
    }
    return inputs;
}

}  // namespace polyvol
