// `polyvol volume`, `measure` and `check`: read each file, analyse and
// measure it (polyvol/report.hpp's measure_file), print a table, a report, JSON, CSV
// or a URDF/SDF <inertial> element.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "grammar.hpp"

namespace polyvol::cli {

// The options of one of the three commands.
struct MeasureCommandOptions {
    std::vector<std::string> files;
    bool json = false;
    bool allow_open = false;
    std::string method = "cone";
    std::string accuracy = "correctly-rounded";
    std::string density = "1";
    std::string units, to;     // --units, --to
    std::string mass_unit = "kg";  // --mass-unit (with a density that has a unit)
    std::string scale = "1";   // --scale (its text: whether it is exact)
    bool stream = false;       // volume --stream: the table's figures, a binary STL streamed whatever its size
    bool volume_only = false;  // volume --volume-only
    bool solid = false;        // volume/measure --solid: the full overlap and self-crossing check
    SolidFlags solid_flags;    // --orient, --weld-tolerance, --signed
    std::string format = "table";  // measure --format table|urdf|sdf
    int digits = 0;                // --digits
    bool verbose = false;          // --verbose
    bool csv = false;              // --csv
    CLI::Option* density_option = nullptr;
};

struct MeasureCommands {
    CLI::App* volume = nullptr;
    CLI::App* measure = nullptr;
    CLI::App* check = nullptr;
    MeasureCommandOptions volume_opts, measure_opts, check_opts;
};

// Registers the three subcommands on app (commands must outlive the parse).
void add_measure_commands(CLI::App& app, MeasureCommands& commands);

// Runs whichever was chosen: its exit code (0 ok, 1 usage, 2 unreadable, 3
// invalid; with several files the highest), or -1 when none was.
int run_measure_commands(const MeasureCommands& commands);

}  // namespace polyvol::cli
