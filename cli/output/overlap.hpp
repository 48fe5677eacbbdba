// cli/output/overlap.hpp — what `polyvol overlap` prints: the volumes and
// areas of A, B, A ∩ B, A ∪ B, A − B and B − A with their guarantee, as
// JSON or a table.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "polyvol/boolean.hpp"

namespace polyvol::cli {

// a, b: the operands' file names; volume_bound: 0 when the volumes are
// correctly rounded, else the bound on each (coordinates a reader computed).
nlohmann::json overlap_json(const std::string& a, const std::string& b, const BooleanVolumes& r, double volume_bound,
                            double seconds);
std::string overlap_table(const std::string& a, const std::string& b, const BooleanVolumes& r, double volume_bound,
                          double seconds);

}  // namespace polyvol::cli
