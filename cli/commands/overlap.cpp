#include "commands/overlap.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>

#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/solid.hpp"
#include "read_input.hpp"
#include "output/format.hpp"
#include "output/overlap.hpp"

namespace polyvol::cli {
namespace {

// Which operand a status is about, and the sentence for it (what the solid
// policy leaves to boolean_volumes: an inside-out operand kept by --signed,
// a shell crossing itself that was not looked for, coordinates out of range).
std::string status_text(BooleanStatus s, const OverlapArgs& args) {
    const bool about_b = s == BooleanStatus::b_not_closed || s == BooleanStatus::b_inside_out ||
                         s == BooleanStatus::b_overlaps_itself;
    const std::string text = (about_b ? args.b + " (B): " : args.a + " (A): ");
    switch (s) {
        case BooleanStatus::a_inside_out:
        case BooleanStatus::b_inside_out:
            return text + "inside out: its volume is negative (faces clockwise seen from outside); without --signed "
                          "its shells are turned outward";
        case BooleanStatus::a_overlaps_itself:
        case BooleanStatus::b_overlaps_itself:
            return text + "its surface crosses itself (winding number above 1 at a vertex of the other operand), "
                          "where it was not looked for (more than " +
                   std::to_string(kSelfCheckTriangles) + " triangles)";
        default: return args.a + ", " + args.b + ": " + boolean_status_message(s);
    }
}

}  // namespace

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
    auto a = read_or_report(args.a, [&] { return read_mesh_file(args.a); });
    if (!a) return Exit::unreadable;
    auto b = read_or_report(args.b, [&] { return read_mesh_file(args.b); });
    if (!b) return Exit::unreadable;
    // A and B in one unit: B converted where it states another; the figures
    // are then scaled to --to, as volume's are.
    const PairUnits units = pair_units(a->unit, b->unit, args.unit_flags.units, args.unit_flags.to);
    const std::string names[2] = {args.a + " (A)", args.b + " (B)"};
    if (!units.error.empty()) {
        if (units.error_operand >= 0)
            std::cerr << "polyvol: " << names[units.error_operand] << ": " << units.error << ": --units gives it ("
                      << kLengthUnitNames << ")\n";
        else
            std::cerr << "polyvol: " << units.error << "\n";
        return Exit::invalid;
    }
    LoadedMesh* const operand[2] = {&*a, &*b};
    for (int i = 0; i < 2; ++i) {
        if (!units.common.notes[i].empty())
            std::cerr << "polyvol: warning: " << names[i] << ": " << units.common.notes[i] << "\n";
        operand[i]->coordinate_error =
            scale_coordinates(operand[i]->mesh, units.common.factors[i], operand[i]->coordinate_error);
    }
    const auto start = std::chrono::steady_clock::now();
    // Each operand the solid it means, as `volume` takes it.
    SolidOptions policy = args.solid_flags.policy();
    policy.closedness_by_fingerprint = true;  // the booleans need no shells' report: the cheap checks
    policy.shells = false;
    const auto sa = solid_or_report(args.a + " (A)", a->mesh, policy);
    if (!sa) return Exit::invalid;
    const auto sb = solid_or_report(args.b + " (B)", b->mesh, policy);
    if (!sb) return Exit::invalid;
    BooleanVolumes r = solid_booleans(a->mesh.view(), *sa, b->mesh.view(), *sb);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.status != BooleanStatus::ok) {
        std::cerr << "polyvol: " << status_text(r.status, args) << "\n";
        return Exit::invalid;
    }
    // Coordinates a reader computed (3MF transforms, a unit conversion), then the unit asked for.
    widen_for_coordinate_error(r, a->mesh.view(), a->coordinate_error, b->mesh.view(), b->coordinate_error);
    scale_boolean_volumes(r, units.figures);
    const std::string& out_unit = units.unit;
    if (args.json)
        std::cout << overlap_json(args.a, args.b, r, out_unit, seconds).dump(2) << "\n";
    else
        std::cout << overlap_table(args.a, args.b, r, out_unit, seconds);
    return Exit::ok;
}

}  // namespace polyvol::cli
