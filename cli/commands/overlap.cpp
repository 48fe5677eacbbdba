#include "commands/overlap.hpp"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"
#include "read_input.hpp"
#include "output/format.hpp"

namespace polyvol::cli {
namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

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
            text += ", e.g. (" + shortest(e[0]) + ", " + shortest(e[1]) + ", " + shortest(e[2]) + ") - (" +
                    shortest(e[3]) + ", " + shortest(e[4]) + ", " + shortest(e[5]) + ")";
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
    if (args.json) {
        nlohmann::json j = {{"a", args.a},
                            {"b", args.b},
                            {"volume_a", number(r.volume_a)},
                            {"volume_b", number(r.volume_b)},
                            {"intersection", number(r.intersection)},
                            {"union", number(r.union_volume)},
                            {"a_minus_b", number(r.a_minus_b)},
                            {"b_minus_a", number(r.b_minus_a)},
                            {"accuracy", bound > 0 ? "error-bound" : "correctly-rounded"},
                            {"volume_error_bound", bound},
                            {"area_a", number(r.area_a)},
                            {"area_b", number(r.area_b)},
                            {"area_intersection", number(r.area_intersection)},
                            {"area_union", number(r.area_union)},
                            {"area_a_minus_b", number(r.area_a_minus_b)},
                            {"area_b_minus_a", number(r.area_b_minus_a)},
                            {"area_error_bound", number(r.area_error_bound)},
                            {"triangles_a", r.triangles_a},
                            {"triangles_b", r.triangles_b},
                            {"candidate_pairs", r.candidate_pairs},
                            {"crossing_pairs", r.crossing_pairs},
                            {"rational_terms", r.rational_terms},
                            {"seconds", seconds}};
        std::cout << j.dump(2) << "\n";
        return Exit::ok;
    }
    std::ostringstream out;
    out << "A = " << args.a << " (" << r.triangles_a << " triangles), B = " << args.b << " (" << r.triangles_b
        << " triangles)\n\n";
    out << std::left << std::setw(8) << "" << std::setw(26) << "volume" << "area\n";
    const std::pair<const char*, std::pair<double, double>> rows[] = {
        {"A", {r.volume_a, r.area_a}},
        {"B", {r.volume_b, r.area_b}},
        {"A ∩ B", {r.intersection, r.area_intersection}},
        {"A ∪ B", {r.union_volume, r.area_union}},
        {"A − B", {r.a_minus_b, r.area_a_minus_b}},
        {"B − A", {r.b_minus_a, r.area_b_minus_a}},
    };
    for (const auto& [name, v] : rows) {
        // setw counts bytes: ∩ ∪ − are three bytes each, shown as one column.
        const std::string label = name;
        const int pad = label.size() > 1 ? 8 + 2 : 8;
        out << std::setw(pad) << label << std::setw(26) << shortest(v.first) << shortest(v.second) << "\n";
    }
    out << "\nvolumes: "
        << (bound > 0 ? "within ±" + shortest(bound) + " each (3MF transforms, applied in floating point)"
                      : std::string("correctly rounded (the exact volume of the coordinates as read, rounded once)"))
        << "\n"
        << "areas: within ±" << std::setprecision(2) << r.area_error_bound << " each\n"
        << r.crossing_pairs << " crossing triangle pair" << (r.crossing_pairs == 1 ? "" : "s") << " (of "
        << r.candidate_pairs << " whose boxes meet), " << std::setprecision(3) << seconds << " s\n";
    std::cout << out.str();
    return Exit::ok;
}

}  // namespace polyvol::cli
