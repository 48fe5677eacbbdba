#include "commands/overlap.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <span>

#include <nlohmann/json.hpp>

#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"
#include "read_input.hpp"
#include "output/format.hpp"
#include "output/overlap.hpp"

namespace polyvol::cli {
namespace {

// Which operand a status is about, and the sentence for it.
std::string status_text(BooleanStatus s, const OverlapArgs& args, const Mesh& a, const Mesh& b) {
    const bool about_b = s == BooleanStatus::b_not_closed || s == BooleanStatus::b_inside_out ||
                         s == BooleanStatus::b_overlaps_itself;
    std::string text = (about_b ? args.b + " (B): " : args.a + " (A): ");
    if (s == BooleanStatus::a_not_closed || s == BooleanStatus::b_not_closed) {
        TopologyOptions edges_only;
        edges_only.shells = false;
        const TopologyReport t = analyze_topology((about_b ? b : a).view(), edges_only);
        text += "not a closed surface: " + std::to_string(t.unbalanced_edges) + " unbalanced edge" +
                (t.unbalanced_edges == 1 ? "" : "s") + " (used a different number of times in its two directions)";
        if (t.unbalanced_example) {
            const auto& e = *t.unbalanced_example;
            text += ", e.g. " + point_text(std::span(e).first<3>()) + " - " + point_text(std::span(e).last<3>());
        }
        return text;
    }
    switch (s) {
        case BooleanStatus::a_inside_out:
        case BooleanStatus::b_inside_out: return text + "inside out: its volume is negative (faces clockwise seen from outside)";
        case BooleanStatus::a_overlaps_itself:
        case BooleanStatus::b_overlaps_itself:
            return text + "its shells overlap or its surface crosses itself (winding number above 1 at a vertex of the other operand)";
        default: return args.a + ", " + args.b + ": " + boolean_status_message(s);
    }
}

}  // namespace

CLI::App* add_overlap_command(CLI::App& app, OverlapArgs& args) {
    auto* cmd = app.add_subcommand("overlap",
                                   "Volumes of A, B, A∩B, A∪B, A−B and B−A of two closed meshes, correctly "
                                   "rounded, without building the result; boundary areas with a bound");
    cmd->add_option("a", args.a, "Mesh A (any format polyvol reads; - reads stdin)")->required();
    cmd->add_option("b", args.b, "Mesh B")->required();
    cmd->add_flag("--json", args.json, "Print one JSON object");
    return cmd;
}

int run_overlap_command(const OverlapArgs& args) {
    const auto a = read_or_report(args.a, [&] { return read_mesh_file(args.a); });
    if (!a) return Exit::unreadable;
    const auto b = read_or_report(args.b, [&] { return read_mesh_file(args.b); });
    if (!b) return Exit::unreadable;
    const auto start = std::chrono::steady_clock::now();
    const BooleanVolumes r = boolean_volumes(a->mesh.view(), b->mesh.view());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.status != BooleanStatus::ok) {
        std::cerr << "polyvol: " << status_text(r.status, args, a->mesh, b->mesh) << "\n";
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
