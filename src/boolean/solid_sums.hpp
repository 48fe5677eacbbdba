// boolean/solid_sums.hpp — private: the exact sums of a solid (winding
// number >= 1) before their rounding, so that several solids' volumes can be
// combined exactly and rounded once (solid_booleans.cpp).
#pragma once

#include <vector>

#include "boolean/exact_terms.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol::boolean {

// 6 × the solid's volume (and, with moments, every cone sum) is
// pieces[k] (integers and fractions in units of 2^(degree e0)) plus the
// cone sums of `whole` (pieces[k].whole is left to the caller).
struct SolidSums {
    std::vector<PieceSum> pieces;
    Mesh whole;
    int e0 = 0;
    AreaSum area;  // SolidWants::area: twice the solid's boundary area
};

// What solid_sums computes beside the volume: the moments' sums, twice the
// boundary's area; within_shells as in solid_volume.
struct SolidWants {
    bool moments = false;
    bool area = false;
    bool within_shells = false;
};

// solid_volume's work without the rounding: the report (status, counts;
// volume, moments and area not yet set) and the sums in `out` when status
// is ok.
SolidVolume solid_sums(const MeshView& mesh, const SolidWants& wants, SolidSums& out);

}  // namespace polyvol::boolean
