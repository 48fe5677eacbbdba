// cli/output/grid.hpp — what `polyvol grid` prints: the grid and each
// body's (and the union's) figures, as JSON (also its -o .json file) or
// lines for people. The per-cell arrays go to files (io.hpp's writers).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "polyvol/grid.hpp"

namespace polyvol::cli {

// The summary; mesh_volumes are the bodies' own volumes (signed_volume),
// union_problem why the union was not computed ("" when it was), unit the
// lengths' unit ("" when not known).
nlohmann::json grid_summary_json(const std::vector<std::string>& files, const std::vector<double>& mesh_volumes,
                                 const GridAxes& g, const GridSummary& s, double seconds,
                                 const std::string& union_problem, const std::string& unit);
std::string grid_summary_text(const std::vector<std::string>& files, const std::vector<double>& mesh_volumes,
                              const GridAxes& g, const GridSummary& s, const std::string& union_problem,
                              const std::string& unit);

}  // namespace polyvol::cli
