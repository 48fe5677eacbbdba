// cli/output/implicit.hpp — what `polyvol implicit` prints: the volume of
// {F <= 0} with its error estimate and the lattice's figures, as JSON or a
// report for people.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "polyvol/implicit.hpp"

namespace polyvol::cli {

// What the command was asked, as the output repeats it.
struct ImplicitPrint {
    std::string expression, box_rule, formula;
    std::string stl;       // -o: where the surface was written ("" when not)
    bool streamed = false; // the chain was not built (cone formula, no -o)
    bool estimate = false; // the 2h pass ran: r.error_estimate holds
};

nlohmann::json implicit_json(const ImplicitVolume& r, const ImplicitPrint& p);
std::string implicit_report(const ImplicitVolume& r, const ImplicitPrint& p);

// x with three significant digits (sizes and times in messages).
std::string short_number(double x);

}  // namespace polyvol::cli
