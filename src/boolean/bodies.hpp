// boolean/bodies.hpp — private: the bodies of one mesh for solid_volume
// and self_crossings.
#pragma once

#include <cstdint>
#include <vector>

#include "polyvol/boolean.hpp"
#include "topology/parts.hpp"
#include "topology/welded.hpp"

namespace polyvol::boolean {

// The polygons' components joined through shared edges as the file gives
// them (vertex indices), if every one is balanced on welded positions (each
// then a closed 2-cycle: parts that touch or coincide stay apart); else the
// shells joined through welded positions.
topology::ShellLabels bodies_of(const topology::WeldedMesh& wm);

// self_crossings over these bodies (labels = bodies_of(wm)); with `crossing`,
// also 1 per body that crosses itself.
SelfCrossings self_crossings_of(const MeshView& mesh, const topology::WeldedMesh& wm,
                                const topology::ShellLabels& labels, std::vector<uint8_t>* crossing);

}  // namespace polyvol::boolean
