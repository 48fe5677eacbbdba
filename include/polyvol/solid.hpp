// polyvol/solid.hpp — the solid a mesh means: one policy for every entry
// point (`polyvol volume`, `measure`, `check`, `overlap`, `grid`, Python).
//
// Conventions, applied in this order to the mesh (which make_solid changes):
//   * points within weld_tolerance are merged (weld_within), when asked;
//   * faces are wound consistently and outward (orient_mesh), when asked;
//   * a surface that is not a closed 2-cycle (topology.hpp) bounds no solid:
//     refused as open (boundary or non-manifold edges) or misoriented
//     (closed, its faces wound inconsistently), unless allow_open;
//   * a closed shell facing inward and inside nothing (ShellRole::inside_out)
//     bounds the complement of a solid: its faces are reversed and a note
//     says so, unless keep_signed; cavities stay as they are;
//   * shells that overlap one another, and a shell crossing itself, mean
//     the region where the winding number is >= 1 (solid_volume): `solid`
//     then holds its volume (and moments), which every figure must use.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/mesh.hpp"
#include "polyvol/simplicial.hpp"
#include "polyvol/topology.hpp"

namespace polyvol {

enum class SolidStatus {
    ok,
    open,            // unbalanced edges (a boundary, or an edge used by three or more faces)
    misoriented,     // closed, but faces wound inconsistently (orient fixes it)
    not_orientable,  // orient asked, and a shell cannot be oriented
    bad_tolerance,   // weld_tolerance rejected by weld_within
};

// Meshes up to this many fan triangles are checked for a surface crossing
// itself by default: about 0.1 s (docs/benchmarks.md, "SelfCrossings").
inline constexpr std::size_t kSelfCheckTriangles = 250'000;

struct SolidOptions {
    double weld_tolerance = 0;  // > 0: points within it merged first
    bool orient = false;        // orient_mesh first
    bool keep_signed = false;   // inside-out shells keep their signed sums
    bool allow_open = false;    // a surface that is not closed is measured anyway (a note says how)
    // Shells that overlap: the solid (solid_volume); false: not looked for.
    bool resolve_overlaps = true;
    // A shell crossing itself is looked for (self_crossings) in meshes of at
    // most this many fan triangles; SIZE_MAX: always, 0: never.
    std::size_t self_check_triangles = kSelfCheckTriangles;
    bool solid_moments = false;  // the solid's first and second moments too
    // Closedness by fingerprint_closedness where it says closed (the cheap
    // path of `volume`'s table): the topology is then not analysed.
    bool closedness_by_fingerprint = false;
    bool shells = true;        // the topology's shells (TopologyOptions)
    bool face_shells = false;  // and each face's shell
};

// What make_solid did or found that a report must say, as data: `text` is
// one sentence without the file's name.
struct SolidNote {
    enum class Kind {
        measured_open,          // allow_open: the figures depend on the origin
        turned_outward,         // inside-out shells reversed
        no_faces,               // nothing to measure
        self_not_checked,       // the search for self-crossings could not run
        self_unresolved,        // a shell crosses and touches itself: counted by its winding number
        overlap_not_checked,    // solid_volume could not run: the shells' sum stands
        self_counted_by_winding,// crossings found but overlaps not resolved
    };
    Kind kind;
    std::string text;
};

struct MeshSolid {
    SolidStatus status = SolidStatus::ok;
    std::string message;  // status != ok: what is wrong and what fixes it
    bool closed = false;  // a closed 2-cycle (after welding and orienting)
    bool closed_by_fingerprint = false;
    std::optional<TopologyReport> topology;  // unless closed_by_fingerprint
    // A surface that is not closed but would close when points within a
    // tolerance below 1e-9 of its size were merged: that tolerance (else 0).
    double closes_at_tolerance = 0;
    std::optional<ToleranceWeld> welded;
    std::optional<OrientResult> oriented;        // orient
    std::optional<OrientResult> turned_outward;  // inside-out shells reversed (faces and shells counted)
    std::optional<SelfCrossings> self;           // when looked for
    std::string self_not_checked;                // else why not
    bool self_unresolved = false;                // crosses itself and touches itself there
    bool overlap_checked = false;
    // Where shells overlap or cross themselves, the region of winding number
    // >= 1 (status ok); empty when no shells overlap.
    std::optional<SolidVolume> solid;
    std::vector<SolidNote> notes;

    // Whether the solid differs from the shells' sum: the figures must be the solid's.
    bool resolved() const {
        return solid && solid->status == BooleanStatus::ok && solid->differs_from_shells();
    }
    // Every note's text, "; " between them, each after `name: ` when name is given.
    std::string notes_text(const std::string& name = "") const;
};

// The solid `mesh` means under `options` (the conventions above); changes
// mesh (weld, orient, inside-out shells reversed). Throws
// std::invalid_argument for inconsistent mesh arrays.
MeshSolid make_solid(Mesh& mesh, const SolidOptions& options = {});

// The solid of a resolved mesh (MeshSolid::resolved) as a union of meshes
// that each bound a solid on their own: its shells in groups whose boxes are
// disjoint (closed boxes), so that no group overlaps itself — for the grid,
// which takes unions of bodies cell by cell. `solid` must come from
// make_solid with shells and face_shells. Throws std::invalid_argument when
// the solid cannot be had that way: a shell crossing itself, or cavities
// among overlapping shells (a cavity's group is not decided by boxes).
std::vector<Mesh> solid_as_union(const MeshView& mesh, const MeshSolid& solid);

// One body for the grid (grid.hpp's grid_union_volumes takes each body as
// the union of its parts): make_solid (with face_shells), then the solid as
// solid_as_union's parts where it was resolved, else the mesh itself.
struct SolidBody {
    MeshSolid solid;          // the policy's verdict, message and notes
    std::vector<Mesh> parts;  // the union's parts; empty: the mesh itself is the body
    std::string not_split;    // why the resolved solid is not such a union ("" when it is)
    double volume = 0;        // the body's volume: the solid's, or the mesh's signed_volume
    // A body the grid can take: status ok and, where resolved, split.
    bool ok() const { return solid.status == SolidStatus::ok && not_split.empty(); }
};
SolidBody solid_body(Mesh& mesh, SolidOptions options);

// Where the solid differs from the shells' sum (MeshSolid::resolved, with
// solid_moments): m's volume, mass and moments become the solid's (volume
// and mass correctly rounded; centroid within 2^-51, inertia within its
// bound), and its area with the solid's area bound where solid_volume gave
// one; edge length stays the shells' sum.
void use_solid_properties(const SolidVolume& solid, double density, MassProperties& m);

// The mass properties of the solid `mesh` means: make_solid (with
// solid_moments), then mass_properties of the mesh it leaves, the solid's
// where shells overlap. `mass` is empty unless solid.status is ok.
struct SolidMass {
    MeshSolid solid;
    std::optional<MassProperties> mass;
};
SolidMass measure_solid(Mesh& mesh, SolidOptions policy, const MeasureOptions& measure);

// A ∩ B and the rest of two meshes that make_solid has made solids (both
// status ok): boolean_volumes, or solid_boolean_volumes (boolean.hpp) where
// an operand's shells overlap or cross themselves (their crossings looked
// for again where make_solid found a shell crossing itself).
BooleanVolumes solid_booleans(const MeshView& a, const MeshSolid& sa, const MeshView& b, const MeshSolid& sb);

// What a mesh needs before it is a solid as it is — ready to print or
// simulate without repair — each item with its fix, from make_solid with
// keep_signed (so that inside-out shells are found, not turned): not closed,
// misoriented faces, inside-out shells, a shell crossing and touching itself
// (its solid not decided). Overlapping shells and self-crossings whose solid
// is decided need none. Empty: ready.
std::vector<std::string> repairs_needed(const MeshSolid& solid);

// Why a surface is not closed, in words (unbalanced, misoriented edges; an
// example; the weld tolerance that would close it, when known), and the
// flag that measures it anyway.
std::string unbalanced_message(const TopologyReport& t, double closes_at_tolerance = 0);
// Where a surface crosses itself within a shell, in words.
std::string self_crossing_sentence(const SelfCrossings& s);

}  // namespace polyvol
