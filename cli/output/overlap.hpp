// cli/output/overlap.hpp — `polyvol overlap`'s table: the volumes and areas
// of A, B, A ∩ B, A ∪ B, A − B and B − A with their guarantee (its JSON is
// the library's overlap_json, polyvol/report.hpp).
#pragma once

#include <string>

#include "polyvol/boolean.hpp"

namespace polyvol::cli {

// a, b: the operands' file names; unit: the lengths' ("" when not known).
// The volumes are correctly rounded where r.volume_error_bound is 0, else
// each within it (coordinates a reader computed, a change of unit).
std::string overlap_table(const std::string& a, const std::string& b, const BooleanVolumes& r, const std::string& unit,
                          double seconds);

}  // namespace polyvol::cli
