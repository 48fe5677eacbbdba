// `polyvol overlap A B`: the volumes of A, B, A ∩ B, A ∪ B, A − B and B − A,
// correctly rounded, and their boundary areas (polyvol/boolean.hpp).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "grammar.hpp"

namespace polyvol::cli {

struct OverlapArgs {
    std::string a, b;
    bool json = false;
    SolidFlags solid_flags;  // --orient, --weld-tolerance, --signed, as for `volume`
    UnitFlags unit_flags;    // --units, --to
};

CLI::App* add_overlap_command(CLI::App& app, OverlapArgs& args);

// Each operand is the solid it means (polyvol/solid.hpp, as for `volume`):
// inside-out shells turned outward, overlapping and self-crossing shells
// resolved. Exit codes: 0 ok, 2 an operand unreadable, 3 an operand not a
// solid (open, misoriented, inside out with --signed, coordinates out of range).
int run_overlap_command(const OverlapArgs& args);

}  // namespace polyvol::cli
