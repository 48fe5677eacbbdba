// `polyvol ndim` (volume of a boundary chain in R^n: .chain or qhull's OFF
// output) and `polyvol area` (plane polygons with holes and islands).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace polyvol::cli {

struct NdimOptions {
    std::vector<std::string> files;
    std::string formula = "cone";        // cone | prism
    std::string accuracy = "auto";       // auto | bounded | exact
    std::string traversal = "rank-one";  // rank-one | refactor
    bool json = false;
    bool orient = false;
    bool allow_open = false;
};

struct NdimCommands {
    CLI::App* ndim = nullptr;
    CLI::App* area = nullptr;
    NdimOptions ndim_options, area_options;
};

// Registers both subcommands on app (commands must outlive the parse).
void add_ndim_commands(CLI::App& app, NdimCommands& commands);

// Runs whichever of the two was chosen and returns its exit code (0 ok,
// 1 usage, 2 unreadable, 3 unmatched faces); -1 when neither was chosen.
int run_ndim_commands(const NdimCommands& commands);

}  // namespace polyvol::cli
