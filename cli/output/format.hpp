// cli/output/format.hpp — how every command prints numbers (the library's
// polyvol/number_text.hpp) and the exit codes (polyvol/report.hpp).
#pragma once

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "polyvol/number_text.hpp"
#include "polyvol/report.hpp"

namespace polyvol::cli {

// The exit codes and json_number are polyvol/report.hpp's.
using polyvol::Exit;
using polyvol::json_number;

// How numbers are written: polyvol/number_text.hpp (the library's, for every door).
using polyvol::bound_text;
using polyvol::number_text;
using polyvol::plus_minus;
using polyvol::point_text;
using polyvol::shortest;
using polyvol::shortest_within;

}  // namespace polyvol::cli
