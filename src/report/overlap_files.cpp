// report/overlap_files.cpp — two files' A ∩ B, A ∪ B, A − B (polyvol/report.hpp).
#include <chrono>
#include <new>

#include "polyvol/boolean.hpp"
#include "polyvol/report.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/units.hpp"

namespace polyvol {
namespace {

// The sentence for what the solid policy leaves to boolean_volumes, with the
// operand it is about: an inside-out operand kept by --signed, a shell
// crossing itself that was not looked for, coordinates out of range.
std::string status_text(BooleanStatus s, const std::string& a, const std::string& b) {
    const bool about_b = s == BooleanStatus::b_not_closed || s == BooleanStatus::b_inside_out ||
                         s == BooleanStatus::b_overlaps_itself;
    const std::string text = (about_b ? b + " (B): " : a + " (A): ");
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
        default: return a + ", " + b + ": " + boolean_status_message(s);
    }
}

}  // namespace

OverlapReport overlap_files(const std::string& a_file, const std::string& b_file, const OverlapWords& w) {
    OverlapReport r;
    const auto fail = [&](int code, std::string message) {
        r.exit_code = code;
        r.messages.push_back(std::move(message));
        return r;
    };
    std::optional<LoadedMesh> operand[2];
    const std::string files[2] = {a_file, b_file};
    for (int i = 0; i < 2; ++i) {
        try {
            operand[i] = read_mesh_file(files[i]);
        } catch (const ReadError& e) {
            return fail(Exit::unreadable, e.what());
        } catch (const std::bad_alloc&) {
            return fail(Exit::unreadable, files[i] + ": out of memory while reading");
        }
    }
    // A and B in one unit: B converted where it states another; the figures
    // are then scaled to `to`, as volume's are.
    // units_where_unstated: `units` is the unit of an operand that states none.
    const auto declared = [&](int i) { return operand[i]->unit.empty() ? w.units : operand[i]->unit; };
    const PairUnits units = w.units_where_unstated ? pair_units(declared(0), declared(1), "", w.to)
                                                   : pair_units(operand[0]->unit, operand[1]->unit, w.units, w.to);
    const std::string names[2] = {a_file + " (A)", b_file + " (B)"};
    if (!units.error.empty()) {
        if (units.error_operand >= 0)
            return fail(Exit::invalid, names[units.error_operand] + ": " + units.error + ": --units gives it (" +
                                           kLengthUnitNames + ")");
        return fail(Exit::invalid, units.error);
    }
    for (int i = 0; i < 2; ++i) {
        if (!units.common.notes[i].empty()) r.messages.push_back("warning: " + names[i] + ": " + units.common.notes[i]);
        operand[i]->coordinate_error =
            scale_coordinates(operand[i]->mesh, units.common.factors[i], operand[i]->coordinate_error);
    }
    const auto start = std::chrono::steady_clock::now();
    // Each operand the solid it means, as `volume` takes it (the booleans need
    // no shells' report: the cheap closedness checks).
    SolidOptions policy{.weld_tolerance = w.weld_tolerance, .orient = w.orient, .keep_signed = w.keep_signed};
    policy.closedness_by_fingerprint = true;
    policy.shells = false;
    std::optional<MeshSolid> solid[2];
    for (int i = 0; i < 2; ++i) {
        MeshSolid s = make_solid(operand[i]->mesh, policy);
        for (const SolidNote& n : s.notes) r.messages.push_back("warning: " + names[i] + ": " + n.text);
        if (s.status != SolidStatus::ok) return fail(Exit::invalid, names[i] + ": " + s.message);
        solid[i] = std::move(s);
    }
    BooleanVolumes v = solid_booleans(operand[0]->mesh.view(), *solid[0], operand[1]->mesh.view(), *solid[1]);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (v.status != BooleanStatus::ok) return fail(Exit::invalid, status_text(v.status, a_file, b_file));
    // Coordinates a reader computed (3MF transforms, a unit conversion), then the unit asked for.
    widen_for_coordinate_error(v, operand[0]->mesh.view(), operand[0]->coordinate_error, operand[1]->mesh.view(),
                               operand[1]->coordinate_error);
    scale_boolean_volumes(v, units.figures);
    r.volumes = v;
    r.unit = units.unit;
    return r;
}

nlohmann::json overlap_json(const std::string& a, const std::string& b, const OverlapReport& report) {
    const BooleanVolumes& r = *report.volumes;
    const double bound = r.volume_error_bound;
    return {{"a", a},
            {"b", b},
            {"unit", report.unit.empty() ? nlohmann::json(nullptr) : nlohmann::json(report.unit)},
            {"volume_a", json_number(r.volume_a)},
            {"volume_b", json_number(r.volume_b)},
            {"intersection", json_number(r.intersection)},
            {"union", json_number(r.union_volume)},
            {"a_minus_b", json_number(r.a_minus_b)},
            {"b_minus_a", json_number(r.b_minus_a)},
            {"accuracy", bound > 0 ? "error-bound" : "correctly-rounded"},
            {"volume_error_bound", bound},
            {"area_a", json_number(r.area_a)},
            {"area_b", json_number(r.area_b)},
            {"area_intersection", json_number(r.area_intersection)},
            {"area_union", json_number(r.area_union)},
            {"area_a_minus_b", json_number(r.area_a_minus_b)},
            {"area_b_minus_a", json_number(r.area_b_minus_a)},
            {"area_error_bound", json_number(r.area_error_bound)},
            {"triangles_a", r.triangles_a},
            {"triangles_b", r.triangles_b},
            {"candidate_pairs", r.candidate_pairs},
            {"crossing_pairs", r.crossing_pairs},
            {"rational_terms", r.rational_terms},
            {"seconds", report.seconds}};
}

}  // namespace polyvol
