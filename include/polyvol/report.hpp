// polyvol/report.hpp — the library measures a file: read it, turn it into
// the solid it means (polyvol/solid.hpp), measure what is wanted, in the
// units asked for; one typed report per file, each figure with its
// guarantee, never throwing (what went wrong is its fields), never
// printing. `polyvol volume`, `measure` and `check` print this report, and
// Python's measure_file is its JSON (report_json: the keys, declared once).
// The route (a binary STL streamed in constant memory, or the file loaded)
// is chosen in one place, measure_file, from what is wanted
// (docs/architecture.md, "Measuring a file").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/simplicial.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/topology.hpp"

namespace polyvol {

// The outcome of a file as the command line's exit codes state it (once):
// 0 ok, 1 usage, 2 unreadable input, 3 input read but not valid for the
// request (an open surface asked for a volume, say); 5 (grid, cells) the
// device asked for by --device cannot do the work (4 is the command line's
// own: out of memory or an internal error).
enum Exit : int { ok = 0, usage = 1, unreadable = 2, invalid = 3, device_failed = 5 };

// What measure_file is doing, for a caller that shows progress: reading the
// file (a streamed binary STL: its first pass, which measures as it reads),
// turning it into the solid it means (the topology, overlapping and
// crossing shells), measuring the figures (a streamed file's later passes).
enum class FileStage { reading, checking, measuring };

// What is wanted of a file and how it is to be taken. The quantities first
// (they choose the route), then the solid policy, then the units.
struct FileOptions {
    MeasureOptions measure;
    // Quantities. need_mass false: `check` (the topology and whether the
    // file is a solid as it is: FileReport::repairs).
    bool need_mass = true;
    // Only the table's figures (volume, area, centroid and the closedness
    // they need): no second moments, edge length, shells or per-piece
    // figures. A binary STL is then streamed (polyvol/soup.hpp: constant
    // memory, the same figures) when nothing asks for the loaded mesh.
    bool table_only = false;
    // With table_only: a binary STL streamed whatever its size (by default
    // only above kStreamAboveTriangles); its shells are then not checked for
    // overlap, and the report says so.
    bool stream_any_size = false;
    // Only the volume with its guarantee and the closedness check: the
    // streamed pass skips area and first moments, the loaded route calls
    // signed_volume when the volume is correctly rounded.
    bool volume_only = false;
    // The loaded mesh's counts (vertices, faces, edges; with volume_only the
    // edge counts that decide closedness): a binary STL is loaded for them.
    bool mesh_counts = false;
    // The edge counts of analyze_topology even where the fingerprint finds
    // the surface closed (false: closedness by fingerprint_closedness, the
    // edges analysed only to name what is open).
    bool edge_counts = true;
    // The centroid to the digits the double sums' bound supports (no exact
    // pass for the first moments of a streamed binary STL).
    bool moments_bounded = false;
    // The solid policy (polyvol/solid.hpp's SolidOptions).
    bool allow_open = false;
    bool check_overlap = true;      // overlapping shells resolved (winding number >= 1)
    bool self_check_always = false; // shells crossing themselves looked for at any size (else up to kSelfCheckTriangles)
    bool orient = false;            // faces wound consistently and outward first (orient_mesh)
    bool keep_signed = false;       // an inside-out surface keeps its signed sums
    double weld_tolerance = 0;      // points within it merged first (weld_within)
    // Units (polyvol/units.hpp). The coordinates' unit: `units`, else the
    // file's own (3MF, AMF), else unknown. The figures are in `to` (with a
    // density in kg/m³, metres by default; else the coordinates' unit),
    // every coordinate times `scale` first. A density with a unit
    // (density_kg_m3 > 0, measure.density then in mass_unit per `to`³, from
    // density_in) gives the mass in `mass_unit` (kg, g or lb).
    std::string units, to;
    bool units_where_unstated = false;  // `units` only for a file that states no unit (else it overrides, with a note)
    double scale = 1;
    bool scale_typed_exactly = true;  // the scale's text is its double's own decimal
    double density_kg_m3 = 0;
    double density_relative_error = 0;  // of measure.density against the density typed (density_in)
    std::string mass_unit = "kg";
    bool metres_when_known = false;     // SI whenever the unit is known (URDF, SDF)
    // Progress, for a caller that shows it (empty: none; the library never
    // prints): each stage with fraction 0 as it begins, a streamed file's
    // passes by whole percents of their records (pass 1 reading; passes 2
    // and 3 measuring, each half of it), and (measuring, 1) at the end of a
    // file measured. Within a stage the fraction never falls; a streamed
    // file found open or inside out is then loaded, its stages begun again.
    std::function<void(FileStage, double)> progress{};
};

// A request as a person words it, the same on every door (the command
// line's flags, Python's arguments, the web page's fields and the npm
// package's options): file_options reads it once for all of them.
struct RequestWords {
    std::string method = "cone";      // cone, prism, pyramid or vtnb
    std::string accuracy = "exact";   // exact (also correctly-rounded) or fast (also bounded)
    std::string density = "1";        // a number (mass per output unit³), or with kg/m3 or g/cm3
    std::string mass_unit = "kg";     // kg, g or lb (a density with a unit only)
    std::string units, to;            // the coordinates' unit; the figures' unit (length_unit names)
    bool units_where_unstated = false;  // units only where the file states none (3MF, AMF, glTF state theirs)
    std::string scale = "1";          // every coordinate times this first (> 0)
    bool allow_open = false, solid = false, orient = false, keep_signed = false;
    double weld_tolerance = 0;        // >= 0
    bool stream = false;       // volume: a binary STL streamed whatever its size (--stream)
    bool volume_only = false;  // volume: the volume, its guarantee and the closedness check only (--volume-only)
};

// What a report is of: the command, and (file_options' json) whether it is
// the JSON report (`--json`, Python's measure_file, the npm package) or a
// table for people (`volume`'s table streams a large binary STL and bounds
// the centroid; `measure`'s and `check`'s tables, CSV).
enum class ReportOf { volume, measure, check };

// FileOptions for a report of `command`, the route's flags included, or the
// sentence that says which word is not understood (exit code 1).
struct ReadRequest {
    std::optional<FileOptions> options;
    std::string error;
};
ReadRequest file_options(const RequestWords& words, ReportOf command, bool json);

// `overlap`'s words: each operand's solid policy and the units (the others
// of RequestWords do not apply).
struct OverlapWords {
    std::string units, to;  // the coordinates' unit; the figures'
    bool units_where_unstated = false;  // units only for an operand that states none
    bool orient = false, keep_signed = false;
    double weld_tolerance = 0;
};

// The library measures two files' overlap: each read, both put in one unit
// (B converted into A's where they differ), each made the solid it means
// (polyvol/solid.hpp, as for `volume`), then the volumes of A ∩ B, A ∪ B,
// A − B and B − A (polyvol/boolean.hpp). Throws only std::bad_alloc. `messages` are what
// the command line prints on stderr, in order, without its "polyvol: "
// (warnings begin "warning: "); exit_code 2 an operand unreadable, 3 not a
// solid or units that cannot be put together.
struct OverlapReport {
    int exit_code = Exit::ok;
    std::vector<std::string> messages;
    std::optional<BooleanVolumes> volumes;  // when computed
    std::string unit;                       // the figures' unit ("" when not known)
    double seconds = 0;                     // the solids and the booleans (not the reading)
};
OverlapReport overlap_files(const std::string& a, const std::string& b, const OverlapWords& words);

// `polyvol overlap --json`'s object (its keys, once).
nlohmann::json overlap_json(const std::string& a, const std::string& b, const OverlapReport& report);

// A binary STL is streamed (FileOptions::table_only) only above this many
// triangles: up to it the file is loaded and checked in full, as every other
// file is (shells overlapping one another resolved, a shell crossing itself
// looked for), so that a multi-part print gives its solid's volume through
// the table too. Above it the stream's figures are the shells' sum, and the
// report says the shells were not checked (--solid loads and checks).
inline constexpr uint64_t kStreamAboveTriangles = kSelfCheckTriangles;

// Per-shell figures are given for at most this many shells.
inline constexpr std::size_t kMaxPieces = 1000;

struct FileReport {
    std::string file;                        // "FILE" or "ARCHIVE:MEMBER"
    int exit_code = Exit::ok;
    std::string error;                       // set when exit_code != ok
    std::string warning;                     // what the figures assume or what was repaired
    std::optional<LoadedMesh> loaded;        // when the file was read (not when streamed)
    std::optional<MassProperties> mass;      // when measured (of the solid where shells overlap)
    double seconds_read = 0, seconds_measure = 0;
    // The route: a binary STL streamed (loaded and topology stay empty) or the file loaded.
    bool streamed = false;
    uint64_t triangles = 0;                  // the fan triangles measured (either route)
    // What the solid policy found (polyvol/solid.hpp's MeshSolid, for a file
    // loaded): the topology (unless closed by the fingerprint), the solid of
    // overlapping or self-crossing shells when resolved, whether shells were
    // checked for overlap, self-crossings looked for (or why not), what
    // orienting, turning outward and welding (at weld_tolerance) did.
    MeshSolid policy;
    double weld_tolerance = 0;
    // The units of the figures: lengths in `length_unit` ("" when not
    // known), mass in `mass_unit` ("" for density × volume); every
    // coordinate was multiplied by `length_factor`.
    std::string length_unit, mass_unit, units_source;
    double length_factor = 1;
    // Each shell's (the first kMaxPieces) and each named part's own figures
    // (their surfaces' sums: volume, area, centroid with their bounds).
    struct Piece {
        std::string name;
        std::size_t faces = 0;
        MassProperties m;
    };
    std::vector<Piece> shell_figures, part_figures;
    std::vector<std::string> repairs;  // `check`: what the file needs to be a solid as it is; empty: ready
};

// Reads, analyses and measures one file (member: one mesh of a zip archive
// of meshes, mesh_archive_members; "" for the file itself); never throws.
FileReport measure_file(const std::string& file, const FileOptions& options, const std::string& member = "");

// The files to measure: each path, or a zip archive of plain meshes (not a
// 3MF or AMF package) as its members, (path, member) each.
std::vector<std::pair<std::string, std::string>> file_inputs(const std::vector<std::string>& paths);

// The report as JSON (`polyvol measure --json`'s object; Python's
// measure_file): the keys of every report are written here, once. Non-finite
// numbers are null.
nlohmann::json report_json(const FileReport& report, const FileOptions& options);
// A finite number for JSON (never -0), else null.
nlohmann::json json_number(double v);
// The box of the loaded mesh's faces in the units of the figures (each
// bound times the length factor, rounded once more when it is not 1).
std::array<double, 6> report_bounds(const FileReport& report);

// The length and mass units every measured report shares ("" for a unit
// they do not share, or that none knows), for the headers of tables.
std::pair<std::string, std::string> common_units(const std::vector<FileReport>& reports);

// The CSV of `polyvol volume --csv` (measure --csv with `inertia`): one row
// per file (RFC 4180, CRLF, a header row first), every number in full or to
// the digits its bound supports, empty where a file has none; `inertia` adds
// the tensor about the centroid, its bound, the edge length and the bounding
// box. density_error: the density's relative error (RequestWords' density
// read by file_options), for the mass's digits.
std::string csv_table(const std::vector<FileReport>& reports, bool inertia, double density_error);

}  // namespace polyvol
