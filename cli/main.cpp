// polyvol — volume, area, centroid, inertia and topology of polyhedral meshes.
//
//   polyvol volume FILE...   one row per file (or --json: an array of objects)
//   polyvol measure FILE...  every mass property, with its guarantee
//   polyvol check FILE...    the topology report
//   polyvol ndim FILE...     volume of a boundary chain in R^n
//   polyvol area FILE...     area of plane polygons with holes
//   polyvol grid MESH...     volume of the solid(s) in every cell of a grid
//   polyvol implicit EXPR    volume of {F <= 0} in R^n from a PL surface
//   polyvol overlap A B      volumes of A∩B, A∪B, A−B, B−A without building them
//   polyvol cells MESH BODY  volume of each body in every cell of an OpenFOAM mesh
//   polyvol devices          the OpenCL devices --device can name
// One file per command under cli/commands/ (volume, measure and check share
// commands/measure.cpp); this file only wires them to the grammar.
//
// Exit codes: 0 ok, 1 usage, 2 unreadable input, 3 input read but not valid
// for the request, 4 out of memory or an internal error, 5 the device asked
// for (grid --device) cannot do the work; with several files the highest of theirs, every file still
// reported. Results go to stdout, warnings and progress to stderr.
#include <iostream>
#include <new>

#include <CLI/CLI.hpp>

#include "commands/cells.hpp"
#include "commands/devices.hpp"
#include "commands/grid.hpp"
#include "commands/implicit.hpp"
#include "commands/measure.hpp"
#include "commands/ndim.hpp"
#include "commands/overlap.hpp"
#include "grammar.hpp"
#include "memory.hpp"
#include "output/format.hpp"
#include "worker_warm_up.hpp"

using namespace polyvol::cli;

int main(int argc, char** argv) {
    polyvol::cli::keep_freed_memory();
    CLI::App app{"polyvol: exact volume, area, centroid, inertia and topology of polyhedral meshes.\n"
                 "Exit codes: 0 ok, 1 usage, 2 unreadable input, 3 input read but not valid for the request "
                 "(check: not a closed 2-cycle), 4 out of memory or an internal error, 5 the --device asked for "
                 "cannot do the work."};
    app.set_version_flag("--version", "polyvol " POLYVOL_VERSION);
    app.require_subcommand(1);
    app.footer("polyvol help COMMAND: the options of one command.");
    MeasureCommands measure_commands;
    add_measure_commands(app, measure_commands);
    NdimCommands ndim_commands;
    add_ndim_commands(app, ndim_commands);
    GridArgs grid_args;
    auto* grid = add_grid_command(app, grid_args);
    ImplicitArgs implicit_args;
    auto* implicit = add_implicit_command(app, implicit_args);
    OverlapArgs overlap_args;
    auto* overlap = add_overlap_command(app, overlap_args);
    CellsArgs cells_args;
    auto* cells = add_cells_command(app, cells_args);
    DevicesArgs devices_args;
    auto* devices = add_devices_command(app, devices_args);

    if (const int code = answer_before_parse(app, argc, argv); code >= 0) return code;
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);  // --help
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return Exit::usage;
    }
    const WorkerWarmUp warm_up;  // before the first parallel loop; joined when main returns
    try {
        if (const int code = run_ndim_commands(ndim_commands); code >= 0) return code;
        if (*grid) return run_grid_command(grid_args);
        if (*implicit) return run_implicit_command(implicit_args);
        if (*overlap) return run_overlap_command(overlap_args);
        if (*cells) return run_cells_command(cells_args);
        if (*devices) return run_devices_command(devices_args);
        return run_measure_commands(measure_commands);
    } catch (const std::bad_alloc&) {
        std::cerr << "polyvol: out of memory: the input or the request needs more memory than this machine "
                     "gives (a smaller grid, fewer files at once?)\n";
        return 4;
    } catch (const std::exception& e) {
        std::cerr << "polyvol: internal error (a bug: please report it): " << e.what() << "\n";
        return 4;
    }
}
