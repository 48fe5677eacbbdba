#include "commands/overlap.hpp"

#include <iostream>

#include "polyvol/report.hpp"
#include "output/overlap.hpp"

namespace polyvol::cli {

CLI::App* add_overlap_command(CLI::App& app, OverlapArgs& args) {
    auto* cmd = app.add_subcommand("overlap",
                                   "Volumes of A, B, A∩B, A∪B, A−B and B−A of two closed meshes, each the solid it "
                                   "means (as for volume), correctly rounded, without building the result; boundary "
                                   "areas with a bound");
    cmd->add_option("a", args.a, "Mesh A (any format polyvol reads; - reads stdin)")->required();
    cmd->add_option("b", args.b, "Mesh B")->required();
    cmd->add_flag("--json", args.json, "Print one JSON object");
    add_solid_flags(cmd, args.solid_flags);
    add_unit_flags(cmd, args.unit_flags,
                   "Print volumes and areas in this unit (default: A's, or B's when A states none); B in another "
                   "unit than A is converted into A's");
    return cmd;
}

int run_overlap_command(const OverlapArgs& args) {
    // The route and its messages are the library's (polyvol/report.hpp).
    OverlapWords words;
    words.units = args.unit_flags.units;
    words.to = args.unit_flags.to;
    words.orient = args.solid_flags.orient;
    words.keep_signed = args.solid_flags.keep_signed;
    words.weld_tolerance = args.solid_flags.weld_tolerance;
    const OverlapReport r = overlap_files(args.a, args.b, words);
    for (const std::string& m : r.messages) std::cerr << "polyvol: " << m << "\n";
    if (!r.volumes) return r.exit_code;
    if (args.json)
        std::cout << overlap_json(args.a, args.b, r).dump(2) << "\n";
    else
        std::cout << overlap_table(args.a, args.b, *r.volumes, r.unit, r.seconds);
    return r.exit_code;
}

}  // namespace polyvol::cli
