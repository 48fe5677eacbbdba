// `polyvol volume`, `measure` and `check` (commands/measure.hpp).
#include "commands/measure.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "grammar.hpp"
#include "output/measure.hpp"
#include "output/format.hpp"
#include "polyvol/units.hpp"

namespace polyvol::cli {
namespace {

void add_measure_options(CLI::App* cmd, MeasureCommandOptions& c) {
    cmd->add_option("files", c.files,
                    "Mesh files (STL, OBJ, OFF, PLY, 3MF, AMF, glTF; .gz or .bz2; zip and tar archives of them); "
                    "- reads stdin")
        ->required();
    auto* json = cmd->add_flag("--json", c.json, "Print JSON (an array with one object per file)");
    cmd->add_option("--method", c.method,
                    "Volume formula: cone (det/6 per triangle), prism (projected area x mean height), "
                    "pyramid (per polygon face), vtnb (Franklin's vertex-edge-face formula)")
        ->check(CLI::IsMember({"cone", "prism", "pyramid", "vtnb"}))
        ->capture_default_str();
    cmd->add_option("--formula", c.method, "")->check(CLI::IsMember({"cone", "prism", "pyramid", "vtnb"}))->group("");
    cmd->add_option("--accuracy", c.accuracy,
                    "correctly-rounded (exact value rounded once; also spelled exact) or fast (double, with an error "
                    "bound; also spelled bounded)")
        ->check(CLI::IsMember({"correctly-rounded", "fast", "exact", "bounded"}))
        ->capture_default_str();
    c.density_option =
        cmd->add_option("--density", c.density,
                        "Density: scales mass, moments and inertia; a number (mass per output unit³), or with a "
                        "unit, 7850kg/m3 or 7.85g/cm3: the mass in kg and the inertia in kg·(output unit)², lengths "
                        "in metres unless --to says otherwise (the coordinates' unit must be known: --units, or a "
                        "3MF or AMF file's own)")
            ->check(CLI::Validator(
                [](std::string& v) -> std::string {
                    if (parse_density(v)) return "";
                    // Why not: the number (as the other options say it), else the unit.
                    std::string number = v.substr(0, v.find_first_not_of("0123456789+-.eE"));
                    if (number.empty()) return "not a number: " + v;
                    if (const std::string why = positive_number()(number); !why.empty()) return why;
                    return "unknown density unit '" + v.substr(number.size()) + "' (kg/m3 or g/cm3)";
                },
                "D[kg/m3|g/cm3]"))
            ->capture_default_str();
    const std::vector<std::string> units{"micron", "um", "mm", "cm", "m", "in", "ft"};
    cmd->add_option("--units", c.units,
                    "The coordinates' length unit (mm, cm, m, in, ft, micron); a 3MF or AMF file states its own")
        ->check(CLI::IsMember(units));
    cmd->add_option("--to", c.to, "Print lengths, areas, volumes and moments in this unit")->check(CLI::IsMember(units));
    cmd->add_option("--mass-unit", c.mass_unit,
                    "The mass (and inertia) unit for a density with a unit: kg (default), g (what a print costs) or lb")
        ->check(CLI::IsMember({"kg", "g", "lb"}));
    cmd->add_option("--scale", c.scale, "Multiply every coordinate by this first (after --units)")
        ->check(positive_number());
    cmd->add_option("--digits", c.digits,
                    "At most this many significant digits in the table (default: the digits each figure's guarantee "
                    "supports; JSON and CSV always give every digit)")
        ->check(whole_number(1, 17));
    cmd->add_flag("--verbose", c.verbose, "The guarantees in full below the table");
    cmd->add_flag("--csv", c.csv, "Print CSV for spreadsheets (one row per file, every digit)")->excludes(json);
    cmd->add_flag("--allow-open", c.allow_open,
                  "Measure surfaces with unbalanced edges anyway (the result then depends on the origin)");
    add_solid_flags(cmd, c.solid_flags);
}

// The flags in the library's words (polyvol/report.hpp: file_options reads
// them, as for Python and the web page), then how the tables print.
// CLI11's validators have checked each flag; what file_options refuses is
// said in its words (exit 1).
std::optional<Request> make_request(const MeasureCommandOptions& c, ReportOf command, bool json) {
    RequestWords w;
    w.method = c.method;
    w.accuracy = c.accuracy;
    w.density = c.density;
    w.mass_unit = c.mass_unit;
    w.units = c.units;
    w.to = c.to;
    w.scale = c.scale;
    w.allow_open = c.allow_open;
    w.solid = c.solid;
    w.orient = c.solid_flags.orient;
    w.keep_signed = c.solid_flags.keep_signed;
    w.weld_tolerance = c.solid_flags.weld_tolerance;
    w.stream = c.stream;
    w.volume_only = c.volume_only;
    const ReadRequest read = file_options(w, command, json);
    if (!read.options) {
        std::cerr << "polyvol: " << read.error << "\n";
        return std::nullopt;
    }
    Request r;
    static_cast<FileOptions&>(r) = *read.options;
    r.digits = c.digits;
    r.verbose = c.verbose;
    r.density_given = c.density_option && c.density_option->count() > 0;
    return r;
}

int run(ReportOf command, const MeasureCommandOptions& c) {
    const std::optional<Request> read = make_request(c, command, c.json);
    if (!read) return Exit::usage;
    Request request = *read;
    if (c.format != "table" && c.mass_unit != "kg") {
        std::cerr << "polyvol: --format " << c.format << " writes SI (kg, m): --mass-unit " << c.mass_unit
                  << " does not apply\n";
        return Exit::usage;
    }
    // A simulator takes the <inertial> mass as given: no density, no guess.
    if (c.format != "table" && !request.density_given) {
        std::cerr << "polyvol: --format " << c.format
                  << " needs --density (the material's, e.g. 2700kg/m3 for aluminium, 1.24g/cm3 for PLA): a "
                     "simulator takes the mass as given\n";
        return Exit::usage;
    }
    request.metres_when_known = c.format != "table";
    // A zip archive of plain meshes (not a 3MF or AMF package) is its members,
    // each measured as a file of its own, "ARCHIVE:MEMBER".
    const std::vector<std::pair<std::string, std::string>> inputs = file_inputs(c.files);
    std::vector<FileResult> results;
    int code = Exit::ok;
    // Progress on stderr only once the run has taken more than a second.
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const auto& [file, member] = inputs[i];
        // Progress for people: on a terminal, for work longer than a second.
        if (inputs.size() > 1 && ::isatty(2) && std::chrono::steady_clock::now() - start > std::chrono::seconds(1))
            std::cerr << "[" << (i + 1) << "/" << inputs.size() << "] " << file << (member.empty() ? "" : ":" + member) << "\n";
        results.push_back(measure_file(file, request, member));
        const FileResult& r = results.back();
        code = std::max(code, r.exit_code);
        if (!r.error.empty()) std::cerr << "polyvol: " << r.error << "\n";
        if (!r.warning.empty()) std::cerr << "polyvol: warning: " << r.warning << "\n";
    }
    if (c.csv && command != ReportOf::check) {
        std::cout << csv_table(results, command == ReportOf::measure, request.density_relative_error);
        return code;
    }
    if (c.json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& r : results) out.push_back(report_json(r, request));
        std::cout << out.dump(2) << "\n";
        return code;
    }
    switch (command) {
        case ReportOf::volume: std::cout << volume_table(results, request); break;
        case ReportOf::measure:
            for (const auto& r : results)
                if (r.mass)
                    std::cout << (c.format == "table" ? measure_report(r, request)
                                                      : inertial_element(r, request, c.format == "sdf"));
            break;
        case ReportOf::check:
            for (const auto& r : results)
                if (r.policy.topology) std::cout << check_report(r);
            break;
    }
    return code;
}

}  // namespace

void add_measure_commands(CLI::App& app, MeasureCommands& c) {
    c.volume = app.add_subcommand("volume", "Volume, area and centroid, one row per file");
    add_measure_options(c.volume, c.volume_opts);
    c.volume->add_flag("--stream", c.volume_opts.stream,
                     "Only the table's figures (volume, area, centroid, closedness; with --json too), a binary STL "
                     "streamed in constant memory whatever its size (by default only above 250000 triangles): its "
                     "shells are then not checked for overlap, the figures are their sums");
    c.volume->add_flag("--volume-only", c.volume_opts.volume_only,
                     "Only the volume with its guarantee (and the closedness check), in the table and the JSON: "
                     "the fastest path, e.g. a third less work per triangle for a streamed binary STL");
    const char* solid_help =
        "The full check: shells overlapping one another (where they do, the volume is the solid's: winding number "
        ">= 1) in a binary STL too (loaded instead of streamed), and a surface crossing itself within a shell in "
        "files of any size (by default up to 250000 triangles): both are resolved, the figures the solid's";
    c.volume->add_flag("--solid", c.volume_opts.solid, solid_help);
    c.measure = app.add_subcommand("measure", "All mass properties (volume, area, edge length, centroid, "
                                                  "second moments, inertia) with their guarantees");
    add_measure_options(c.measure, c.measure_opts);
    c.measure->add_flag("--solid", c.measure_opts.solid, solid_help);
    c.measure->add_option("--format", c.measure_opts.format,
                        "table (the report), or urdf / sdf: each file's <inertial> element (mass, origin at the "
                        "centroid, the inertia about it), in the file's units scaled by --density")
        ->check(CLI::IsMember({"table", "urdf", "sdf"}))
        ->capture_default_str();
    c.check = app.add_subcommand("check", "Topology report: boundary, non-manifold, misoriented and "
                                              "unbalanced edges, shells and how they nest");
    c.check->add_option("files", c.check_opts.files, "Mesh files; - reads stdin")->required();
    c.check->add_flag("--json", c.check_opts.json, "Print JSON");
    add_solid_flags(c.check, c.check_opts.solid_flags, /*keep_signed=*/false);
}

int run_measure_commands(const MeasureCommands& c) {
    if (c.volume && *c.volume) return run(ReportOf::volume, c.volume_opts);
    if (c.measure && *c.measure) return run(ReportOf::measure, c.measure_opts);
    if (c.check && *c.check) return run(ReportOf::check, c.check_opts);
    return -1;
}

}  // namespace polyvol::cli
