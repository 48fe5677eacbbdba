// polyvol/measure.hpp — volume and mass properties of a mesh (3D).
//
// Conventions, as in Geometric Tools' mass properties:
//   * density 1 unless MeasureOptions::density says otherwise; "mass" is
//     density * volume, and moments/inertia are scaled by density.
//   * every integral is the divergence-theorem sum over the fan triangles
//     (a, b, c) of the signed tetrahedra (origin, a, b, c):
//       volume          V       = sum det(a,b,c) / 6
//       first moments   ∫x_i    = sum det * (a_i + b_i + c_i) / 24
//       second moments  ∫x_i x_j = sum det * (a_i a_j + b_i b_j + c_i c_j + s_i s_j) / 120, s = a+b+c
//   * for a closed, consistently oriented surface (no unbalanced edge, see
//     topology.hpp) these are the integrals over the enclosed solid and do not
//     depend on the origin; an inward-oriented surface gives negated values;
//     several shells and cavities add up. For an open surface the numbers are
//     still the sums above about (0,0,0) — callers decide whether to accept them.
//   * inertia (unit density): Ixx = ∫(y²+z²), Iyy = ∫(x²+z²), Izz = ∫(x²+y²),
//     Ixy = -∫xy, Iyz = -∫yz, Izx = -∫zx; about the origin and, by the
//     parallel axis theorem applied in exact arithmetic, about the centroid.
//   * symmetric 3x3 quantities are stored as {xx, yy, zz, xy, yz, zx}.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "polyvol/mesh.hpp"

namespace polyvol {

// How the volume is computed (all agree for closed meshes):
//   cone    — Allgower–Schmidt (2.1): det(a,b,c)/6 per fan triangle.
//   prism   — Allgower–Schmidt (2.2): mean z times the signed xy-projected area.
//   pyramid — Franklin: per polygon face, (vector area of its fan) · v0 / 3,
//             i.e. face area times signed distance of its plane from the origin / 3.
//   vtnb    — Franklin's local-topology formula over vertex–edge–face
//             incidences: V = -1/6 Σ (V·T)(V·N)(V·B), A = 1/2 Σ (V·T)(V·N),
//             L = -1/2 Σ V·T (valid for closed, edge-manifold surfaces).
// The method chooses only `volume` (and `mass`; for vtnb also `area` and
// `edge_length` of a closed surface, by the closedness fingerprint; an open
// one gets the direct sums, Franklin's being sums about a local origin there). Moments, centroid and inertia always come from the cone
// rule's sums, with the chosen accuracy; the centroid divides by the cone
// rule's volume. With Accuracy::correctly_rounded the volume of cone, prism
// and pyramid is the exact value of that formula on the given doubles,
// rounded once: the pyramid sum is the cone sum exactly for every mesh
// (measure/pyramid.cpp), so they give the same double; the prism sum equals
// them for a closed surface and has its own exact path (measure/prism.cpp)
// for open ones. vtnb's unit vectors make it irrational: it is computed in
// double with volume_error_bound in both accuracies.
enum class Method { cone, prism, pyramid, vtnb };

// How the sums are formed:
//   correctly_rounded — the exact value for the coordinates as given, rounded
//                       once to the nearest double (ties to even): the cone,
//                       prism and pyramid volumes, mass, first and second
//                       moments, centroid and both inertia tensors (each the exact rational function
//                       of the exact sums, rounded once). Computed by a
//                       double-double filter with a rigorous error bound, and
//                       exactly (expansions / big integers) only when the
//                       filter cannot decide the rounding (e.g. an exact zero).
//   fast              — double arithmetic per triangle (the sum across blocks is
//                       exact), with a rigorous a-posteriori error bound; when
//                       that bound exceeds kFastRelativeLimit of the moments
//                       (or of the cone volume), mass_properties computes them
//                       correctly rounded instead (MassProperties::accuracy
//                       says which).
// Meshes with a coordinate outside {0} ∪ [2^-160, 2^190] take an exact
// big-integer path for the cone rule's sums in both modes (then correctly
// rounded), and for the prism volume when correctly rounded. Area and edge
// length are computed in double in both modes (with bounds). Non-finite
// coordinates on a used vertex give NaN results.
enum class Accuracy { correctly_rounded, fast };

// Accuracy::fast's largest relative bound on the moments before they are
// computed correctly rounded instead: a bound beyond it means digits that
// may be wrong where users read them.
inline constexpr double kFastRelativeLimit = 1e-6;

std::string_view method_name(Method m);     // "cone", ...
std::string_view accuracy_name(Accuracy a); // "correctly-rounded", "fast"

struct MeasureOptions {
    Method method = Method::cone;                   // volume formula
    Accuracy accuracy = Accuracy::correctly_rounded;
    double density = 1.0;                           // scales mass, moments, inertia
    // What to compute besides volume, mass, area, first moments and centroid.
    // false leaves the fields NaN (and their bounds cover only what was
    // computed): cheaper when they are not wanted (`polyvol volume`'s table).
    bool second_moments = true;  // second_moments, inertia_origin, inertia_centroid (7 more sums)
    bool edge_length = true;     // edge_length (welds the vertices)
};

struct MassProperties {
    double volume = 0;                    // signed (negative for an inside-out surface)
    double mass = 0;                      // density * volume
    std::array<double, 3> first_moments{};   // density * ∫x, ∫y, ∫z
    std::array<double, 3> centroid{};        // ∫x_i / V (cone rule; density cancels); NaN when V == 0 exactly
    std::array<double, 6> second_moments{};  // density * ∫x_i x_j about the origin {xx,yy,zz,xy,yz,zx}
    std::array<double, 6> inertia_origin{};  // density * inertia tensor about the origin
    std::array<double, 6> inertia_centroid{};// density * inertia tensor about the centroid (NaN when V == 0)
    double area = 0;                      // Σ |(b-a)×(c-a)|/2 over fan triangles
    double edge_length = 0;               // each undirected edge (after welding bit-identical vertices) once

    // Guarantees. volume_correctly_rounded (then volume_error_bound == 0)
    // means the volume is the exact value rounded once to nearest.
    bool volume_correctly_rounded = false;
    double volume_error_bound = 0;        // absolute bound on |volume - exact|
    // moments_correctly_rounded: mass (cone, and pyramid when correctly
    // rounded), first/second moments, centroid and inertia are each the
    // exact value rounded once to nearest;
    // moments_relative_error is then 2^-53 (half an ulp, for results >= 2^-1022).
    bool moments_correctly_rounded = false;
    double moments_relative_error = 0;    // bound on the error of moments, centroid, inertia, relative to the largest magnitude in the same array (inf when the volume may be 0)
    double area_relative_error = 0;       // bound, relative
    double edge_length_relative_error = 0;// bound, relative
    Method method = Method::cone;
    Accuracy accuracy = Accuracy::correctly_rounded;  // as computed: fast may have become correctly_rounded
};

// All mass properties in one pass over the mesh.
MassProperties mass_properties(const MeshView& mesh, const MeasureOptions& options = {});

// Signed volume only, by the chosen method and accuracy.
double signed_volume(const MeshView& mesh, Method method = Method::cone,
                     Accuracy accuracy = Accuracy::correctly_rounded);

// Σ |(b-a)×(c-a)|/2 over the fan triangles.
double surface_area(const MeshView& mesh);

// Σ |b-a| over the undirected edges of the polygon faces, each counted once
// after welding vertices with bit-identical coordinates (-0.0 == +0.0).
double total_edge_length(const MeshView& mesh);

// The principal moments of inertia (the eigenvalues of a symmetric tensor
// {xx, yy, zz, xy, yz, zx}, increasing) and axes (axes[k] the unit axis of
// moments[k], right-handed), with bounds that hold when every entry is
// within relative_error of the largest entry's magnitude:
//   * each moment within moment_error of the exact tensor's: the residual
//     |A v - λ v| of the computed pair bounds the distance to an eigenvalue
//     of the computed tensor, and Weyl's inequality moves each eigenvalue by
//     at most |E|_2 <= |E|_F <= 3 relative_error max|A_ij|;
//   * each axis within axis_angle[k] radians (Davis–Kahan: sin θ <= error /
//     gap to the other moments); infinite where the gap does not exceed
//     twice the error (equal moments: that axis is not determined).
struct PrincipalInertia {
    std::array<double, 3> moments{};
    std::array<std::array<double, 3>, 3> axes{};
    double moment_error = 0;
    std::array<double, 3> axis_angle{};
};
PrincipalInertia principal_inertia(const std::array<double, 6>& tensor, double relative_error);
// An absolute bound on each entry of one of m's moment quantities (the
// centroid, the first or second moments, an inertia tensor): the relative
// bound times the largest entry's magnitude; 0 when they are correctly
// rounded (each is then the exact value rounded once).
double moments_error_bound(const MassProperties& m, std::span<const double> entries);

// Of m's inertia about the centroid, with m's own guarantee on it (each
// entry correctly rounded: within u of the largest entry).
PrincipalInertia principal_inertia(const MassProperties& m);

// The figures of the mesh with every coordinate multiplied by length_factor
// (a change of unit, or a scale), from those of the mesh as read: each
// quantity times its power of the factor, with its guarantee widened for the
// rounding of that product. length_error bounds the factor's relative error
// against the one meant (0.001 for mm to m is not a double; 0 for an exact
// factor), density_error the density's (a density converted between units),
// which touches the mass and the moments. A power of two with both errors 0
// scales exactly and keeps every guarantee. Derivation: docs/numerics.md,
// "Units and scale".
void scale_mass_properties(MassProperties& m, double length_factor, double length_error = 0,
                           double density_error = 0);

// How far the measures of a closed mesh can move when every coordinate moves
// by at most delta (coordinates a reader computed, say: io.hpp's
// LoadedMesh::coordinate_error). Absolute bounds, density 1: on |ΔV|, on
// every |ΔF_i| (first moments), every |ΔS_ij| (second moments about the
// origin), |Δarea| and |Δedge length| (each edge of each face counted).
// closed: the surface is a closed 2-cycle (its volume does not depend on the
// origin, which tightens that bound). Formulas and proof: docs/numerics.md,
// "Coordinates within delta".
struct PerturbationBounds {
    double volume = 0, first_moments = 0, second_moments = 0, area = 0, edge_length = 0;
    // For a region bounded by pieces of the surface (the solid {W >= 1} of
    // overlapping shells): the same from what each triangle sweeps.
    double swept_volume = 0, swept_first_moments = 0, swept_second_moments = 0;
};
PerturbationBounds perturbation_bounds(const MeshView& mesh, double delta, bool closed);

// Widens m's guarantees to hold for the coordinates within delta of those
// m was computed from (perturbation_bounds, scaled by the density): volume,
// area and edge length by absolute bounds, centroid, moments and inertia by
// one relative bound (MassProperties::moments_relative_error's meaning).
// region: m holds the figures of a region bounded by pieces of the surface
// (solid_volume's solid), not the surface's own sums.
void widen_for_coordinate_error(const MeshView& mesh, double delta, double density, bool closed, bool region,
                                MassProperties& m);

// Inertia tensor {xx,yy,zz,xy,yz,zx} from second moments {xx,yy,zz,xy,yz,zx}.
std::array<double, 6> inertia_from_second_moments(const std::array<double, 6>& m);

}  // namespace polyvol
