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
    return cmd;
}

int run_overlap_command(const OverlapArgs& args) {
    auto a = read_or_report(args.a, [&] { return read_mesh_file(args.a); });
    if (!a) return Exit::unreadable;
    auto b = read_or_report(args.b, [&] { return read_mesh_file(args.b); });
    if (!b) return Exit::unreadable;
    const auto start = std::chrono::steady_clock::now();
    // Each operand the solid it means, as `volume` takes it.
    SolidOptions policy = args.solid_flags.policy();
    policy.closedness_by_fingerprint = true;  // the booleans need no shells' report: the cheap checks
    policy.shells = false;
    const auto sa = solid_or_report(args.a + " (A)", a->mesh, policy);
    if (!sa) return Exit::invalid;
    const auto sb = solid_or_report(args.b + " (B)", b->mesh, policy);
    if (!sb) return Exit::invalid;
    const BooleanVolumes r = solid_booleans(a->mesh.view(), *sa, b->mesh.view(), *sb);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.status != BooleanStatus::ok) {
        std::cerr << "polyvol: " << status_text(r.status, args) << "\n";
        return Exit::invalid;
    }
    // Coordinates a reader computed (3MF transforms): every result is a region
    // bounded by pieces of A and B, so it moves by at most what their
    // triangles sweep (docs/numerics.md), beside its own half-ulp rounding.
    double bound = 0;
    if (a->coordinate_error > 0 || b->coordinate_error > 0) {
        double largest = 0;
        for (double v : {r.volume_a, r.volume_b, r.union_volume}) largest = std::max(largest, std::fabs(v));
        bound = (0x1p-53 * largest + perturbation_bounds(a->mesh.view(), a->coordinate_error, true).swept_volume +
                 perturbation_bounds(b->mesh.view(), b->coordinate_error, true).swept_volume) *
                (1 + 0x1p-40);
    }
    if (args.json)
        std::cout << overlap_json(args.a, args.b, r, bound, seconds).dump(2) << "\n";
    else
        std::cout << overlap_table(args.a, args.b, r, bound, seconds);
    return Exit::ok;
}

}  // namespace polyvol::cli
