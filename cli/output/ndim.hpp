// cli/output/ndim.hpp — what `polyvol ndim` and `polyvol area` print for a
// boundary chain or a set of polygons: JSON (one object per file) or a
// report for people.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "output/format.hpp"
#include "polyvol/simplicial.hpp"

namespace polyvol::cli {

// The exit code of one file and its messages.
struct ChainOutcome {
    int code = Exit::ok;
    std::string error, warning;
};

// The unmatched (n-2)-faces of a chain that is not closed, in words.
std::string unmatched_text(const ChainReport& r);

// v: the measured chain, or null when it is not given (not closed).
nlohmann::json chain_json(const std::string& file, const ChainVolume* v, const ChainReport& r,
                          const std::string& formula, const ChainOutcome& out);
// what: the input's format; extra: lines after the topology (e.g. --orient's).
std::string chain_report(const std::string& file, const std::string& what, const ChainVolume* v,
                         const ChainReport& r, const std::string& formula, const std::vector<std::string>& extra);

}  // namespace polyvol::cli
