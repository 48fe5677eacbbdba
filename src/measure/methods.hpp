// Private: the volume formulas other than the cone rule, and the
// length/area sums. Each works on the fan triangles of a MeshView (see
// mesh.hpp) in plain double arithmetic and returns its sum; the caller
// (mass_properties.cpp) chooses and reports the guarantees.
#pragma once

#include "polyvol/mesh.hpp"

namespace polyvol::measure {

struct SumWithBound {
    double value = 0;        // the computed sum
    double error_bound = 0;  // a rigorous bound on |value - exact value of the formula|
};

// Allgower–Schmidt (2.2), n = 3: V = Σ (z_a+z_b+z_c)/3 · ((b-a)×(c-a))_z / 2.
SumWithBound prism_volume(const MeshView& mesh);

// The prism rule's exact sum on the given doubles, rounded once to the
// nearest double (ties to even); NaN when a used coordinate is NaN or
// infinite. A double-double filter with a rigorous bound decides almost
// always; the exact sum otherwise (prism.cpp).
double prism_volume_correctly_rounded(const MeshView& mesh);

// Franklin's pyramids: per polygon face, V_f = A_f · v0 / 3 where A_f is the
// vector area of the face's fan (= Σ (vi-v0)×(vi+1-v0) / 2).
SumWithBound pyramid_volume(const MeshView& mesh);

// Franklin's local-topology formulas over vertex–edge–face incidences of the
// fan triangles: V = -1/6 Σ (V·T)(V·N)(V·B), A = 1/2 Σ (V·T)(V·N),
// L = -1/2 Σ V·T (L counts every edge once only on closed edge-manifold meshes).
struct VtnbResult {
    SumWithBound volume, area, length;
};
VtnbResult vtnb_measures(const MeshView& mesh);

// Σ |(b-a)×(c-a)|/2 over the fan triangles.
SumWithBound fan_area(const MeshView& mesh);

// Σ |b-a| over undirected polygon edges, each once after welding.
SumWithBound welded_edge_length(const MeshView& mesh);

}  // namespace polyvol::measure
