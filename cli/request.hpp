// cli/measure_file.hpp — one mesh file read, checked and measured, for
// `polyvol volume`, `measure` and `check` and for the Python package's
// measure_file: the route (a binary STL streamed, or the file loaded) is
// chosen here from what the request asks for, and the result is the same
// type either way, each figure with its guarantee: the same ones, except
// the table's centroid (table_moments_bounded). Never prints; its messages
// are fields.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "output/format.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/simplicial.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/topology.hpp"

namespace polyvol::cli {

struct FileResult {
    std::string file;
    int exit_code = Exit::ok;
    std::string error;                       // set when exit_code != ok
    std::optional<LoadedMesh> loaded;        // when the file was read
    std::optional<TopologyReport> topology;  // when read (not when closed_by_fingerprint)
    // Request::closedness_by_fingerprint: the fingerprint found the loaded
    // mesh closed, so analyze_topology was not run.
    bool closed_by_fingerprint = false;
    std::optional<MassProperties> mass;      // when measured
    std::string warning;                     // e.g. the origin dependence with --allow-open
    double seconds_read = 0, seconds_measure = 0;
    // The route process_file chose: a binary STL streamed (polyvol/soup.hpp:
    // constant memory, nothing loaded or welded; loaded and topology stay
    // empty) or the file loaded. mass is a MassProperties either way.
    bool streamed = false;
    uint64_t triangles = 0;                  // the fan triangles measured (either route)
    // The solid of overlapping shells, or of a shell crossing itself
    // (polyvol/boolean.hpp's solid_volume), computed when the loaded mesh has
    // more than one part or self_crossings found pairs.
    std::optional<SolidVolume> solid;
    // A loaded mesh whose shells were checked for overlap (also when it has one
    // part, which cannot overlap another); false when streamed.
    bool overlap_checked = false;
    // Where the surface crosses itself within one shell (self_crossings), when
    // looked for (Request::self_check_always); else why not.
    std::optional<SelfCrossings> self;
    std::string self_not_checked;
    // The surface crosses itself and also touches itself there: not resolved.
    bool self_unresolved = false;
    // Request::orient: what orienting the loaded mesh did (before any measure).
    std::optional<OrientResult> oriented;
    // A closed surface found inside out and turned outward (not --signed):
    // what orient_mesh did; the figures are the turned mesh's.
    std::optional<OrientResult> turned_outward;
    // Request::weld_tolerance: what merging the points within it did.
    std::optional<ToleranceWeld> welded;
    double weld_tolerance = 0;
    // The units the figures are in: lengths in `length_unit` ("" when not
    // known: the file's own), mass in `mass_unit` ("kg", or "" for density ×
    // volume); `length_factor` multiplied every coordinate (1: none).
    std::string length_unit, mass_unit, units_source;
    double length_factor = 1;
    // measure and --json: each shell's (in the order of topology's shells,
    // the first kMaxPieces) and each named part's own figures (their
    // surfaces' sums: volume, area, centroid with their bounds), in the units
    // of the figures.
    struct Piece {
        std::string name;
        std::size_t faces = 0;
        MassProperties m;
    };
    std::vector<Piece> shell_figures, part_figures;
    // `check`: what the file needs before it is a solid as it is (repairs_needed); empty: ready.
    std::vector<std::string> repairs;
    // A surface that is not closed but would close when points within a
    // tolerance below 1e-9 of its size were merged: that tolerance (else 0).
    double closes_at_tolerance = 0;
};

// Per-shell figures are given for at most this many shells (the largest).
inline constexpr std::size_t kMaxPieces = 1000;

struct Request {
    MeasureOptions measure;
    bool allow_open = false;
    bool need_mass = true;  // false for `check`
    // `volume`'s table, --volume-only and --stream: only the volume, area,
    // centroid and the closedness they need: topology without shells, no
    // second moments, no edge length. process_file then streams a binary STL
    // (polyvol/soup.hpp: constant memory, the same figures) when nothing
    // asks for the loaded mesh (mesh_counts, method cone, no weld,
    // orientation, units or scale, not --solid); a surface the fingerprint
    // finds open, or inside out, is loaded to be reported.
    bool table_only = false;
    // The JSON without --stream reports the loaded mesh's counts (vertices,
    // faces, edges; with --volume-only the edge counts that decide
    // closedness), which a streamed binary STL does not have: it is loaded.
    bool mesh_counts = false;
    // `volume`'s table: a loaded mesh's closedness by fingerprint_closedness
    // (topology.hpp; the streamed binary STL's check, on the loaded mesh);
    // analyze_topology runs only when it does not say closed, to name the
    // unbalanced edges.
    bool closedness_by_fingerprint = false;
    // `volume`'s table prints the centroid to the digits its bound supports:
    // a streamed binary STL's first moments keep pass 1's bound (SoupWants::
    // moments fast, no exact pass for a part centred on the origin); the
    // loaded route computes them as `measure` says.
    bool table_moments_bounded = false;
    // `volume --volume-only`: the volume, its guarantee and the closedness
    // check, nothing else (table and JSON; the JSON keeps the edge counts,
    // not the shells): the streamed pass skips area and first moments, the
    // full path calls signed_volume when the volume is correctly rounded
    // (cone, prism, pyramid).
    bool volume_only = false;
    // Shells that overlap: the volume is the solid's (winding number >= 1).
    // `volume --solid` loads a binary STL instead of streaming it, to check it too.
    bool check_overlap = true;
    // A surface crossing itself within one shell: looked for in closed files
    // up to kSelfCheckTriangles, or in every closed file (`check`, `--solid`).
    bool self_check_always = false;
    // --orient: the loaded mesh's faces wound consistently and outward
    // (orient_mesh) before it is analysed and measured.
    bool orient = false;
    // --signed: a closed surface that is inside out keeps its signed sums
    // (negative volume); by default its shells are turned outward.
    bool keep_signed = false;
    // --weld-tolerance: points within it merged (weld_within) before
    // anything is analysed or measured; 0: only equal coordinates are one point.
    double weld_tolerance = 0;
    // Tables: --digits (at most this many significant digits; 0: those the
    // guarantee supports), --verbose (the guarantees in full), and a mass
    // column when --density was given.
    int digits = 0;
    bool verbose = false;
    bool density_given = false;
    // Units. The coordinates' unit: `units` (--units), else the file's own
    // (3MF, AMF), else unknown. The figures are printed in `to` (--to; with a
    // density in kg/m³, metres by default; else the coordinates' unit), every
    // coordinate times `scale` (--scale) first. A density with a unit
    // (density_kg_m3 > 0) gives the mass in `mass_unit` (kg, g or lb): the
    // density used is then mass_unit per `to`³.
    std::string units, to;
    double scale = 1;
    bool scale_typed_exactly = true;  // the scale's text is its double's own decimal
    double density_kg_m3 = 0;
    double density_relative_error = 0;  // of measure.density against the density typed (density_in)
    std::string mass_unit = "kg";
    // URDF and SDF want SI: metres by default when the coordinates' unit is known.
    bool metres_when_known = false;
};

// Reads, analyses and measures one file; never throws.
// member: one mesh of a zip archive of meshes (mesh_archive_members),
// reported as "FILE:MEMBER"; empty for the file itself.
FileResult process_file(const std::string& file, const Request& request, const std::string& member = "");

}  // namespace polyvol::cli
