// cli/request.hpp — what `polyvol volume`, `measure` and `check` ask of the
// library for each file (polyvol/report.hpp: the library measures it and
// chooses the route) and how their tables print the report.
#pragma once

#include "polyvol/report.hpp"

namespace polyvol::cli {

// FileOptions, and how the tables print: --digits (at most this many
// significant digits; 0: those the guarantee supports), --verbose (the
// guarantees in full), and a mass column when --density was given.
struct Request : FileOptions {
    int digits = 0;
    bool verbose = false;
    bool density_given = false;
};

using FileResult = FileReport;

}  // namespace polyvol::cli
