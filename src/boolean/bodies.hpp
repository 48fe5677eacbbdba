// boolean/bodies.hpp — private: the bodies of one mesh for solid_volume
// and self_crossings.
#pragma once

#include "topology/shells.hpp"
#include "topology/welded.hpp"

namespace polyvol::boolean {

// The polygons' components joined through shared edges as the file gives
// them (vertex indices), if every one is balanced on welded positions (each
// then a closed 2-cycle: parts that touch or coincide stay apart); else the
// shells joined through welded positions.
topology::ShellLabels bodies_of(const topology::WeldedMesh& wm);

}  // namespace polyvol::boolean
