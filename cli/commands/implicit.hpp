// `polyvol implicit EXPR`: the volume of {x : F(x) <= 0} in R^n for F given as
// an expression, from its piecewise-linear approximation on a Kuhn
// triangulation (implicit.hpp, docs/implicit.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace polyvol::cli {

struct ImplicitArgs {
    std::string expression;
    int dimension = 0;                // 0: the highest coordinate the expression names (at least 2)
    std::string box;                  // LO:HI, or LO:HI,LO:HI,... one per axis
    double h = 0;                     // 0: the library's default for the dimension
    int coarse_cells = 0;             // 0: default; -1: no scan
    std::vector<std::string> seeds;   // "x1,x2,...": points
    std::string box_rule = "clip";    // clip | error
    std::string formula = "cone";     // cone | prism
    bool no_estimate = false;
    bool json = false;
    std::string stl;                  // 3D: write the PL surface
    std::string max_memory;           // empty: three quarters of physical memory
};

// Registers the subcommand on app; its options fill args.
CLI::App* add_implicit_command(CLI::App& app, ImplicitArgs& args);

// Runs it; returns the exit code: 0 ok; 1 usage (bad option, --stl outside 3D);
// 2 the expression cannot be parsed (unreadable input); 3 F is NaN at a
// lattice vertex, or the solid reaches the box with --box-rule error, or the
// lattice is too large (for 64-bit keys, or for --max-memory).
int run_implicit_command(const ImplicitArgs& args);

}  // namespace polyvol::cli
