// topology/parts.hpp — topology's internal interface for boolean (with
// topology/welded.hpp): which polygons form one shell.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/union_find.hpp"
#include "topology/welded.hpp"

namespace polyvol::topology {

struct ShellLabels {
    std::vector<uint32_t> of_polygon;  // shell of polygon p; shells numbered by their first polygon
    std::size_t count = 0;
};

// Reads the polygon sets joined by build_edge_table.
ShellLabels label_shells(core::UnionFind& polygon_sets);

// The shells: the polygons joined through the edges between welded
// positions (build_edge_table's polygon sets, read by label_shells).
ShellLabels edge_connected_shells(const WeldedMesh& mesh);

}  // namespace polyvol::topology
