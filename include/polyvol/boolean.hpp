// polyvol/boolean.hpp — volumes of A ∩ B, A ∪ B, A − B and B − A of two
// solids, exactly, without building the result.
//
// Conventions:
//   * A and B are closed meshes (closed 2-cycles, topology.hpp), outward
//     (counter-clockwise seen from outside), each bounding a solid: its
//     winding number is 0 or 1 everywhere (several shells and cavities are
//     fine; overlapping shells of one operand are not).
//   * The boundary of A ∩ B is the part of A's surface inside B and of B's
//     surface inside A; its pieces are summed by the cone rule like any
//     boundary (measure.hpp), and no result mesh is built. The rest follows
//     exactly: |A ∪ B| = |A| + |B| - |A ∩ B|, |A - B| = |A| - |A ∩ B|.
//   * Touching and coincident geometry (shared faces, edges, vertices,
//     identical operands) is resolved by one rule: B is translated by
//     (ε, ε², ε³), ε -> 0+. Volume is continuous, so the volumes are those of
//     the coordinates as given (docs/boolean.md).
//   * Each volume is correctly rounded: the exact volume of the solid the
//     coordinates define, rounded once to the nearest double.
//   * Areas are those of the result's boundary in the perturbed limit (where
//     faces of A and B coincide, the rule above decides whether they count),
//     computed in double with one absolute bound for all of them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "polyvol/measure.hpp"
#include "polyvol/mesh.hpp"
#include "polyvol/units.hpp"

namespace polyvol {

enum class BooleanStatus {
    ok,
    a_not_closed,        // A has an unbalanced edge: no solid
    b_not_closed,
    a_inside_out,        // A's volume is negative: it bounds the complement of a solid
    b_inside_out,
    a_overlaps_itself,   // A's winding number is not 0 or 1 at a vertex of B (overlapping shells)
    b_overlaps_itself,
    invalid_coordinates, // a coordinate is not finite, or outside 0 ∪ [2^-160, 2^180] in magnitude
    shell_crosses_itself,// solid_volume: the windings along an edge or a cut disagree, as when a shell crosses itself
    shell_touches_itself,// solid_volume resolving self-crossings: a shell that crosses itself also touches or
                         // folds onto itself (or has no clean ray for its winding): its solid is not decided
};

struct BooleanVolumes {
    BooleanStatus status = BooleanStatus::ok;
    // Correctly rounded volumes (NaN unless status == ok); after a widening
    // or a change of unit (below) each is within volume_error_bound instead.
    double volume_a = 0, volume_b = 0;
    double intersection = 0, union_volume = 0, a_minus_b = 0, b_minus_a = 0;
    double volume_error_bound = 0;  // 0: correctly rounded
    // Boundary areas, each within area_error_bound of the exact value.
    double area_a = 0, area_b = 0;
    double area_intersection = 0, area_union = 0, area_a_minus_b = 0, area_b_minus_a = 0;
    double area_error_bound = 0;
    std::size_t triangles_a = 0, triangles_b = 0;  // fan triangles
    std::size_t candidate_pairs = 0;  // triangle pairs whose boxes meet
    std::size_t crossing_pairs = 0;   // triangle pairs whose surfaces cross (cut segments)
    std::size_t rational_terms = 0;   // pieces whose contribution is a true fraction
    int refinements = 0;              // precision raises needed to decide the rounding (-1: exact rationals)
};

// The volumes above. Throws std::invalid_argument for inconsistent mesh
// arrays (an index out of range); every property of the input is a status.
BooleanVolumes boolean_volumes(const MeshView& a, const MeshView& b);

const char* boolean_status_message(BooleanStatus status);

// r's volumes for operands whose every coordinate is within a_error
// (b_error) of the value meant (LoadedMesh::coordinate_error): each result
// is a region bounded by pieces of A and B, so it moves by at most what
// their triangles sweep (perturbation_bounds' swept_volume), beside its own
// half-ulp rounding. The areas keep their bound, which is for the
// coordinates as computed.
void widen_for_coordinate_error(BooleanVolumes& r, const MeshView& a, double a_error, const MeshView& b,
                                double b_error);

// r in another length unit: volumes × f³, areas × f², their bounds widened
// by the products' rounding and the factor's own error (exact for a power
// of two meant exactly).
void scale_boolean_volumes(BooleanVolumes& r, const LengthFactor& f);

// The same volumes where A's or B's shells may overlap one another or cross
// themselves: each operand is the solid it means, the region where its
// winding number is >= 1 (solid_volume below). Every shell must be outward
// or a cavity inside an outward one (winding numbers >= 0), so that
// A ∪ B = {W_A + W_B >= 1}, the solid of both meshes together; then
// |A ∩ B| = |A| + |B| - |A ∪ B|, |A - B| = |A ∪ B| - |B|, |B - A| = |A ∪ B| - |A|,
// each formed exactly and rounded once (correctly rounded). Three solids
// are resolved, so it costs more than boolean_volumes: call it only where
// an operand needs it (polyvol/solid.hpp's MeshSolid::resolved). Areas:
// each solid's boundary, and |∂(A ∩ B)| = |∂A| + |∂B| - |∂(A ∪ B)|, within
// area_error_bound; those of A − B and B − A are not computed (NaN).
// within_shells as in solid_volume.
BooleanVolumes solid_boolean_volumes(const MeshView& a, const MeshView& b, bool within_shells = false);

// The solid a mesh whose shells may overlap or cross themselves bounds: the
// region where the winding number of all its shells is >= 1 (what a slicer
// prints; cavities, inward shells inside outward ones, subtract). The shells
// are the edge-connected components, together a closed 2-cycle. Crossings
// between different shells are always resolved; a shell crossing itself
// only when asked (within_shells: the crossing search within each shell,
// self_crossings below, about 3.5x what measure costs).
struct SolidVolume {
    BooleanStatus status = BooleanStatus::ok;  // a_not_closed (the mesh), invalid_coordinates, shell_crosses_itself,
                                               // shell_touches_itself
    // The solid |{winding >= 1}| as measure.hpp's MassProperties, density 1:
    // the volume and mass correctly rounded. With moments (SolidVolumeOptions),
    // the first and second moments correctly rounded too, the centroid within
    // 2^-51 relative, the inertia within moments_relative_error, and the area
    // of the solid's boundary (where the winding number steps from 0 to 1)
    // within area_relative_error; without moments those are NaN. The edge
    // length is NaN: the solid's edges are not formed.
    MassProperties properties;
    bool moments = false;       // properties has the moments and the area
    double winding_volume = 0;  // Σ of the shells' signed volumes = ∫ winding number (the cone rule's sum), correctly rounded
    std::size_t shells = 0;
    std::size_t overlapping_shells = 0;  // crossing another shell, or outward and inside another solid shell
    std::size_t crossing_pairs = 0;      // triangle pairs of different shells that cross
    std::size_t shells_checked = 0;      // shells whose box meets another's (the rest cost nothing)
    int refinements = 0;                 // as in BooleanVolumes
    // One crossing pair, as the faces (file order) whose fan triangles cross.
    std::optional<std::array<std::size_t, 2>> crossing_example;
    // Per face (file order), 1 when its shell crosses another shell; empty
    // when no shells cross.
    std::vector<uint8_t> face_crosses;
    // Crossings within shells (within_shells): looked for, resolved (the
    // volume is then the solid's with them), their pairs and one example.
    bool within_checked = false;
    std::size_t self_crossing_pairs = 0;
    std::size_t shells_crossing_themselves = 0;
    std::optional<std::array<std::size_t, 2>> self_crossing_example;

    // Whether the solid differs from the shells' sum: shells overlap, or a
    // shell's own crossings were resolved.
    bool differs_from_shells() const { return overlapping_shells > 0 || shells_crossing_themselves > 0; }
};

// Touching and coincident shells are resolved by moving shell k of each
// group by k (ε, ε², ε³) (docs/boolean.md). Throws std::invalid_argument for
// inconsistent mesh arrays.
// Without within_shells a shell that crosses itself is not looked for: where
// its windings disagree the status says so (shell_crosses_itself), where
// they happen to agree the volume counts its self-overlap as winding. With
// it, such a shell's crossings are resolved exactly; one body cannot be
// perturbed against itself, so a shell that also touches itself, or folds
// onto itself through a shared vertex or edge, gets shell_touches_itself.
struct SolidVolumeOptions {
    bool moments = false;        // centroid, moments and the boundary's area too (else NaN)
    bool within_shells = false;  // a shell crossing itself resolved (above)
};
SolidVolume solid_volume(const MeshView& mesh, const SolidVolumeOptions& options = {});

// Where a mesh's surface crosses itself within one of solid_volume's bodies
// (the parts the file joins through shared edges when each is closed, else
// the shells): the pairs of its fan triangles that share no vertex (after
// welding) and cross along a segment, decided by exact predicates (touching
// is resolved by moving each pair's later triangle by (ε, ε², ε³): a vertex
// merely lying on another triangle does not count). Triangles that share a
// vertex are not examined, so a surface that folds through one of its own
// vertices is not found. solid_volume does not resolve these crossings:
// where they exist its volume counts the body's self-overlap as winding.
struct SelfCrossings {
    BooleanStatus status = BooleanStatus::ok;  // or invalid_coordinates (nothing examined)
    std::size_t pairs = 0;            // crossing triangle pairs
    std::size_t candidate_pairs = 0;  // pairs whose boxes meet and share no vertex
    // The first crossing pair (lowest fan triangles), as faces in file order.
    std::optional<std::array<std::size_t, 2>> example;
};
// Throws std::invalid_argument for a face index out of range.
SelfCrossings self_crossings(const MeshView& mesh);

}  // namespace polyvol
