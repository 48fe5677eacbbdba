// `polyvol overlap A B`: the volumes of A, B, A ∩ B, A ∪ B, A − B and B − A,
// correctly rounded, and their boundary areas (polyvol/boolean.hpp).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace polyvol::cli {

struct OverlapArgs {
    std::string a, b;
    bool json = false;
};

CLI::App* add_overlap_command(CLI::App& app, OverlapArgs& args);

// Exit codes: 0 ok, 2 an operand unreadable, 3 an operand not a solid
// (open, inside out, overlapping itself, coordinates out of range).
int run_overlap_command(const OverlapArgs& args);

}  // namespace polyvol::cli
