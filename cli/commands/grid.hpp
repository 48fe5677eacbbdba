// `polyvol grid`: the volume of one or several solids in every cell of a
// rectilinear grid, written as .npy, .vti/.vtr or a JSON summary.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "grammar.hpp"

namespace polyvol::cli {

struct GridArgs {
    std::vector<std::string> files;
    SolidFlags solid_flags;  // --orient, --weld-tolerance, --signed: each body the solid it means
    UnitFlags unit_flags;    // --units, --to: the bodies in one unit, the grid's
    uint32_t cells = 128;
    bool cells_given = false;  // --cells was on the command line (not the default)
    double cell_size = 0;
    std::vector<uint32_t> dims;
    std::vector<double> bounds;
    std::vector<double> x_planes, y_planes, z_planes;
    std::string out;
    bool json = false;
    bool fractions = false;
    std::string centroids;
    std::string union_out;         // --union FILE.npy: the union's volume per cell
    std::string intersection_out;  // --intersection FILE.npy: the part inside every body
    std::string surface;  // --surface FILE.npy: wetted area and area-weighted normal per cell
    std::string png;
    std::string slice;
    std::string max_memory;  // --max-memory SIZE (default: three quarters of physical memory)
    std::string device = "auto";  // --device auto|cpu|opencl[:N] (polyvol/device.hpp)
};

// Registers the subcommand on app; its options fill args.
CLI::App* add_grid_command(CLI::App& app, GridArgs& args);

// Runs it; returns the exit code (0 ok, 1 usage — a grid larger than
// --max-memory included —, 2 unreadable mesh, 3 open mesh, bodies whose
// union is undefined, or nothing to grid, 5 the --device asked for cannot do
// the work).
int run_grid_command(const GridArgs& args);

}  // namespace polyvol::cli
