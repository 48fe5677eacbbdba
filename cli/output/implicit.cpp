// cli/output/implicit.cpp — cli/output/implicit.hpp.
#include "output/implicit.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "output/format.hpp"

namespace polyvol::cli {
namespace {

nlohmann::json pass_json(const ImplicitPass& p) {
    return {{"spacing", p.spacing},
            {"cells", p.cells},
            {"volume", p.volume},
            {"rounding_error_bound", p.rounding_error_bound},
            {"boundary_simplices", p.boundary_simplices},
            {"crossed_simplices", p.crossed_simplices},
            {"face_simplices", p.face_simplices},
            {"function_evaluations", p.function_evaluations},
            {"components", p.components},
            {"box_vertices_inside", p.box_vertices_inside},
            {"seconds", p.seconds}};
}

}  // namespace

std::string short_number(double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

nlohmann::json implicit_json(const ImplicitVolume& r, const ImplicitPrint& p) {
    nlohmann::json j = {{"expression", p.expression},
                        {"dimension", r.dimension},
                        {"h", r.h},
                        {"spacing", r.fine.spacing},
                        {"volume", r.volume},
                        {"volume_pl", r.fine.volume},
                        {"error_estimate", p.estimate ? nlohmann::json(r.error_estimate) : nlohmann::json()},
                        {"boundary_simplices", r.fine.boundary_simplices},
                        {"clipped", r.clipped},
                        {"box_rule", p.box_rule},
                        {"formula", p.formula},
                        {"streamed", p.streamed},
                        {"seconds", r.seconds},
                        {"fine", pass_json(r.fine)}};
    if (r.coarse) {
        j["volume_pl_2h"] = r.coarse->volume;
        j["coarse"] = pass_json(*r.coarse);
        j["extrapolated_error_estimate"] = json_number(r.extrapolated_error_estimate);  // null: not estimated
        j["volume_pl_4h"] = r.coarser ? nlohmann::json(r.coarser->volume) : nlohmann::json(nullptr);
    }
    return j;
}

std::string implicit_report(const ImplicitVolume& r, const ImplicitPrint& p) {
    std::ostringstream out;
    out << "dimension           " << r.dimension << "\n";
    out << "h                   " << shortest(r.h) << "  (lattice";
    for (std::size_t k = 0; k < r.fine.cells.size(); ++k) out << (k ? " x " : " ") << r.fine.cells[k];
    out << " cells)\n";
    if (p.estimate) {
        // Each number beside its estimate, with the digits the estimate leaves.
        // (V(2h) - V(4h)) / (V(h) - V(2h)): 4 in the h^2 regime (implicit.hpp).
        const double ratio = r.coarser ? (r.coarse->volume - r.coarser->volume) / (r.fine.volume - r.coarse->volume)
                                       : std::nan("");
        if (std::isfinite(r.extrapolated_error_estimate))
            out << "volume              " << plus_minus(r.volume, r.extrapolated_error_estimate, 0)
                << "  (Richardson extrapolation R(h) from h and 2h; ± is |R(h) - R(2h)|, R(2h) from 2h and 4h, "
                   "its estimated error: the lattices show V converging as h^2, ratio of differences "
                << short_number(ratio) << ")\n";
        else
            out << "volume              " << plus_minus(r.volume, r.error_estimate, 0)
                << "  (Richardson extrapolation from h and 2h; ± is |V(h) - V(2h)| / 3, the estimated error of "
                   "V(h), which also bounds the extrapolation's while V(h) converges as h^2"
                << (r.coarser && !(ratio >= 3 && ratio <= 5)
                        ? "; but the 4h lattice does not show that regime (ratio of differences " + short_number(ratio) +
                              ", 4 expected): this estimate may not hold"
                        : std::string())
                << ")\n";
        out << "PL volume at h      " << plus_minus(r.fine.volume, r.error_estimate, 0)
            << "  (the piecewise-linear solid's, V(h))\n";
        out << "PL volume at 2h     " << plus_minus(r.coarse->volume, 4 * r.error_estimate, 0)
            << "  (V(2h): 4 times the error at h)\n";
    } else {
        out << "volume              " << shortest(r.volume) << "  (the PL solid at h; no error estimate)\n";
    }
    out << "boundary simplices  " << r.fine.boundary_simplices << "  (" << r.fine.crossed_simplices
        << " crossed " << r.dimension << "-simplices, " << r.fine.face_simplices << " in the box faces)\n";
    out << "seconds             " << short_number(r.seconds) << "\n";
    if (!p.stl.empty()) out << "surface written     " << p.stl << "\n";
    return out.str();
}

}  // namespace polyvol::cli
