// polyvol — volume, area, centroid, inertia and topology of polyhedral meshes.
//
//   polyvol volume FILE...   one row per file (or --json: an array of objects)
//   polyvol measure FILE...  every mass property, with its guarantee
//   polyvol check FILE...    the topology report
//   polyvol ndim FILE        volume of a boundary chain in R^n (ndim_command.cpp)
//   polyvol area FILE        area of plane polygons with holes
//   polyvol grid MESH...     volume of the solid(s) in every cell of a grid (grid_command.cpp)
//   polyvol implicit EXPR    volume of {F <= 0} in R^n from a PL surface (implicit_command.cpp)
//   polyvol overlap A B      volumes of A∩B, A∪B, A−B, B−A without building them (overlap_command.cpp)
//
// Exit codes: 0 ok, 1 usage, 2 unreadable input, 3 input read but not valid
// for the request; with several files the highest of theirs, every file still
// reported. Results go to stdout, warnings and progress to stderr.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "grammar.hpp"
#include "ndim_command.hpp"
#include "grid_command.hpp"
#include "implicit_command.hpp"
#include "overlap_command.hpp"
#include "report.hpp"
#include "units.hpp"
#include "worker_warm_up.hpp"

namespace {

using namespace polyvol;
using namespace polyvol::cli;

struct Common {
    std::vector<std::string> files;
    bool json = false;
    bool allow_open = false;
    std::string method = "cone";
    std::string accuracy = "correctly-rounded";
    std::string density = "1";
    std::string units, to;  // --units, --to
    std::string scale = "1";  // --scale (its text: whether it is exact)
    bool stream = false;  // volume --stream: JSON from the streaming path too
    bool volume_only = false;  // volume --volume-only
    bool solid = false;        // volume/measure --solid: the full overlap and self-crossing check
    bool orient = false;       // --orient: faces wound consistently and outward before measuring
    bool keep_signed = false;  // --signed: an inside-out surface's signed sums, not turned outward
    std::string format = "table";  // measure --format table|urdf|sdf
    double weld_tolerance = 0;     // --weld-tolerance
    int digits = 0;                // --digits
    bool verbose = false;          // --verbose
    bool csv = false;              // --csv
    CLI::Option* density_option = nullptr;
};

const char* const kWeldHelp =
    "Merge points within this distance of one another (transitively) before anything else, for exports whose "
    "coordinates differ in the last digits; the report says so, and the figures are the welded mesh's";

const char* const kOrientHelp =
    "Orient the faces first: consistently within each shell (a walk over the faces), and outward, cavities "
    "inward by nesting; reports the faces flipped, then measures the oriented mesh";

void add_measure_options(CLI::App* cmd, Common& c) {
    cmd->add_option("files", c.files, "Mesh files (STL, OBJ, OFF, PLY, 3MF, AMF, optionally .gz); - reads stdin")
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
    cmd->add_flag("--orient", c.orient, kOrientHelp);
    cmd->add_option("--weld-tolerance", c.weld_tolerance, kWeldHelp)->check(positive_number());
    cmd->add_flag("--signed", c.keep_signed,
                  "Keep the signed sums of a surface that is inside out (negative volume, mass and inertia); by "
                  "default its shells are turned outward, and the report says so");
}

Request make_request(const Common& c, bool need_mass) {
    Request r;
    static const std::map<std::string, Method> methods{
        {"cone", Method::cone}, {"prism", Method::prism}, {"pyramid", Method::pyramid}, {"vtnb", Method::vtnb}};
    r.measure.method = methods.at(c.method);
    r.measure.accuracy = c.accuracy == "fast" || c.accuracy == "bounded" ? Accuracy::fast : Accuracy::correctly_rounded;
    // A density with a unit is converted to kg per output unit³ (metres by default).
    const Density d = *parse_density(c.density);
    r.measure.density = d.value;
    if (d.si) {
        const LengthUnit out = *length_unit(c.to.empty() ? "m" : c.to);
        const double metres = static_cast<double>(out.metre_num) / static_cast<double>(out.metre_den);
        r.density_kg_m3 = d.kg_per_m3;
        r.measure.density = d.kg_per_m3 * (metres * metres * metres);
    }
    r.units = c.units;
    r.to = c.to;
    r.scale = std::stod(c.scale);  // checked by positive_number()
    r.scale_typed_exactly = typed_exactly(c.scale, r.scale);
    r.allow_open = c.allow_open;
    r.need_mass = need_mass;
    r.orient = c.orient;
    r.keep_signed = c.keep_signed;
    r.weld_tolerance = c.weld_tolerance;
    r.digits = c.digits;
    r.verbose = c.verbose;
    r.density_given = c.density_option && c.density_option->count() > 0;
    return r;
}

enum class Command { volume, measure, check };

int run(Command command, const Common& c) {
    Request request = make_request(c, command != Command::check);
    request.metres_when_known = c.format != "table";
    // Binary STL through the streaming path: the table always, JSON only with
    // --stream (the streaming path has no second moments, inertia, edge
    // length or components: README).
    // Streaming gives the file's own figures: no weld, orientation, units or scale.
    request.stream = command == Command::volume && (!c.json || c.stream) && !c.solid && !c.orient &&
                     c.weld_tolerance == 0 && c.units.empty() && c.to.empty() && request.scale == 1 &&
                     request.scale_typed_exactly &&
                     request.density_kg_m3 == 0;
    request.self_check_always = command == Command::check || c.solid;
    request.volume_only = command == Command::volume && c.volume_only;
    request.table_only = command == Command::volume && (!c.json || request.volume_only);
    request.closedness_by_fingerprint = command == Command::volume && !c.json;
    if (request.table_only) {
        request.measure.second_moments = false;
        request.measure.edge_length = false;
    }
    // A zip archive of plain meshes (not a 3MF or AMF package) is its members,
    // each measured as a file of its own, "ARCHIVE:MEMBER".
    std::vector<std::pair<std::string, std::string>> inputs;  // (file, member)
    for (const std::string& f : c.files) {
        const std::vector<std::string> members = f == "-" ? std::vector<std::string>{} : mesh_archive_members(f);
        if (members.empty()) inputs.emplace_back(f, "");
        for (const std::string& m : members) inputs.emplace_back(f, m);
    }
    std::vector<FileResult> results;
    int code = Exit::ok;
    // Progress on stderr only once the run has taken more than a second.
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const auto& [file, member] = inputs[i];
        if (inputs.size() > 1 && std::chrono::steady_clock::now() - start > std::chrono::seconds(1))
            std::cerr << "[" << (i + 1) << "/" << inputs.size() << "] " << file << (member.empty() ? "" : ":" + member) << "\n";
        results.push_back(process_file(file, request, member));
        const FileResult& r = results.back();
        code = std::max(code, r.exit_code);
        if (!r.error.empty()) std::cerr << "polyvol: " << r.error << "\n";
        if (!r.warning.empty()) std::cerr << "polyvol: warning: " << r.warning << "\n";
    }
    if (c.csv && command != Command::check) {
        std::cout << csv_table(results, request, command == Command::measure);
        return code;
    }
    if (c.json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& r : results) out.push_back(to_json(r, request));
        std::cout << out.dump(2) << "\n";
        return code;
    }
    switch (command) {
        case Command::volume: std::cout << volume_table(results, request); break;
        case Command::measure:
            for (const auto& r : results)
                if (r.mass)
                    std::cout << (c.format == "table" ? measure_report(r, request)
                                                      : inertial_element(r, request, c.format == "sdf"));
            break;
        case Command::check:
            for (const auto& r : results)
                if (r.topology) std::cout << check_report(r);
            break;
    }
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"polyvol: exact volume, area, centroid, inertia and topology of polyhedral meshes.\n"
                 "Exit codes: 0 ok, 1 usage, 2 unreadable input, 3 input read but not valid for the request "
                 "(check: not a closed 2-cycle)."};
    app.set_version_flag("--version", "polyvol " POLYVOL_VERSION);
    app.require_subcommand(1);
    app.footer("polyvol help COMMAND: the options of one command.");
    Common volume_opts, measure_opts, check_opts;
    auto* volume = app.add_subcommand("volume", "Volume, area and centroid, one row per file");
    add_measure_options(volume, volume_opts);
    volume->add_flag("--stream", volume_opts.stream,
                     "With --json: measure binary STL by streaming it too (constant memory; only the keys the "
                     "streaming path computes). The table always streams binary STL.");
    volume->add_flag("--volume-only", volume_opts.volume_only,
                     "Only the volume with its guarantee (and the closedness check), in the table and the JSON: "
                     "the fastest path, e.g. a third less work per triangle for a streamed binary STL");
    const char* solid_help =
        "The full check: shells overlapping one another (where they do, the volume is the solid's: winding number "
        ">= 1) in a binary STL too (loaded instead of streamed), and a surface crossing itself within a shell in "
        "files of any size (by default up to 250000 triangles; it is reported, not resolved)";
    volume->add_flag("--solid", volume_opts.solid, solid_help);
    auto* measure = app.add_subcommand("measure", "All mass properties (volume, area, edge length, centroid, "
                                                  "second moments, inertia) with their guarantees");
    add_measure_options(measure, measure_opts);
    measure->add_flag("--solid", measure_opts.solid, solid_help);
    measure->add_option("--format", measure_opts.format,
                        "table (the report), or urdf / sdf: each file's <inertial> element (mass, origin at the "
                        "centroid, the inertia about it), in the file's units scaled by --density")
        ->check(CLI::IsMember({"table", "urdf", "sdf"}))
        ->capture_default_str();
    auto* check = app.add_subcommand("check", "Topology report: boundary, non-manifold, misoriented and "
                                              "unbalanced edges, shells and how they nest");
    check->add_option("files", check_opts.files, "Mesh files; - reads stdin")->required();
    check->add_flag("--json", check_opts.json, "Print JSON");
    check->add_flag("--orient", check_opts.orient, kOrientHelp);
    check->add_option("--weld-tolerance", check_opts.weld_tolerance, kWeldHelp)->check(positive_number());
    NdimCommands ndim_commands;
    add_ndim_commands(app, ndim_commands);
    GridArgs grid_args;
    auto* grid = add_grid_command(app, grid_args);
    ImplicitArgs implicit_args;
    auto* implicit = add_implicit_command(app, implicit_args);
    OverlapArgs overlap_args;
    auto* overlap = add_overlap_command(app, overlap_args);

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
        if (*volume) return run(Command::volume, volume_opts);
        if (*measure) return run(Command::measure, measure_opts);
        return run(Command::check, check_opts);
    } catch (const std::bad_alloc&) {
        std::cerr << "polyvol: out of memory: the input or the request needs more memory than this machine "
                     "gives (a smaller grid, fewer files at once?)\n";
        return 4;
    } catch (const std::exception& e) {
        std::cerr << "polyvol: internal error (a bug: please report it): " << e.what() << "\n";
        return 4;
    }
}
