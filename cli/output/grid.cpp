// cli/output/grid.cpp — cli/output/grid.hpp.
#include "output/grid.hpp"

#include <cmath>
#include <sstream>

#include "output/format.hpp"

namespace polyvol::cli {

nlohmann::json grid_summary_json(const std::vector<std::string>& files, const std::vector<double>& mesh_volumes,
                            const GridAxes& g, const GridSummary& s, double seconds, const std::string& union_problem,
                                 const std::string& unit) {
    nlohmann::json j;
    nlohmann::json grid{{"dims", {g.nx(), g.ny(), g.nz()}}, {"bounds", g.bounds()}, {"cells", g.cell_count()},
                        {"uniform", g.uniform()}};
    if (g.uniform())
        grid["spacing"] = {(g.x.back() - g.x.front()) / static_cast<double>(g.nx()),
                           (g.y.back() - g.y.front()) / static_cast<double>(g.ny()),
                           (g.z.back() - g.z.front()) / static_cast<double>(g.nz())};
    j["grid"] = grid;
    j["unit"] = unit.empty() ? nlohmann::json(nullptr) : nlohmann::json(unit);  // of every length; volumes in unit³
    nlohmann::json bodies = nlohmann::json::array(), volumes = nlohmann::json::array();
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        const GridBodySummary& body = s.bodies[b];
        bodies.push_back({{"file", files[b]},
                          {"triangles", body.triangles},
                          {"volume", body.volume},
                          {"mesh_volume", mesh_volumes[b]},
                          {"pieces", body.pieces},
                          {"full_cells", body.full_cells},
                          {"empty_cells", body.empty_cells},
                          {"cut_cells", body.cut_cells}});
        volumes.push_back(body.volume);
    }
    j["bodies"] = bodies;
    j["body_volumes"] = volumes;
    j["union_volume"] = std::isnan(s.union_volume) ? nlohmann::json(nullptr) : nlohmann::json(s.union_volume);
    if (!union_problem.empty()) j["union_error"] = union_problem;
    if (!std::isnan(s.intersection_volume)) j["intersection_volume"] = s.intersection_volume;
    j["crossing_pairs"] = s.crossing_pairs;
    j["full_cells"] = s.full_cells;
    j["empty_cells"] = s.empty_cells;
    j["cut_cells"] = s.cut_cells;
    j["contact_cells"] = s.contact_cells;
    j["device"] = s.device;
    if (s.device.starts_with("opencl"))
        j["device_seconds"] = {{"kernels", s.device_kernel_seconds},
                               {"transfers", s.device_transfer_seconds},
                               {"build", s.device_build_seconds}};
    j["seconds"] = seconds;
    return j;
}

std::string grid_summary_text(const std::vector<std::string>& files, const std::vector<double>& mesh_volumes,
                         const GridAxes& g, const GridSummary& s, const std::string& union_problem,
                              const std::string& unit) {
    std::ostringstream out;
    const auto bb = g.bounds();
    out << "grid " << g.nx() << " x " << g.ny() << " x " << g.nz() << " cells over [" << shortest(bb[0]) << ", "
        << shortest(bb[3]) << "] x [" << shortest(bb[1]) << ", " << shortest(bb[4]) << "] x [" << shortest(bb[2])
        << ", " << shortest(bb[5]) << "]";
    if (g.uniform())
        out << ", spacing " << shortest((g.x.back() - g.x.front()) / static_cast<double>(g.nx())) << " x "
            << shortest((g.y.back() - g.y.front()) / static_cast<double>(g.ny())) << " x "
            << shortest((g.z.back() - g.z.front()) / static_cast<double>(g.nz()));
    if (!unit.empty()) out << " (lengths in " << unit << ", volumes in " << unit << "³)";
    out << "\n";
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        const GridBodySummary& body = s.bodies[b];
        out << files[b] << ": " << body.triangles << " triangles, " << body.pieces << " pieces; volume in the grid "
            << shortest(body.volume) << " (mesh " << shortest(mesh_volumes[b]) << "); cells: " << body.full_cells
            << " full, " << body.cut_cells << " cut, " << body.empty_cells << " empty\n";
    }
    if (s.bodies.size() > 1 && !union_problem.empty()) {
        out << "union: not computed (" << union_problem << ")\n";
    } else if (s.bodies.size() > 1) {
        out << "union: " << shortest(s.union_volume);
        if (!std::isnan(s.intersection_volume)) out << "; intersection: " << shortest(s.intersection_volume);
        out << " (exact in every cell; " << s.crossing_pairs << " crossing triangle pairs, " << s.contact_cells
            << " contact cells, where surfaces of two or more bodies meet)\n";
    }
    out << "cells: " << s.full_cells << " full, " << s.cut_cells << " cut, " << s.contact_cells << " contact, "
        << s.empty_cells << " empty\n";
    if (s.device != "cpu") out << "computed on: " << s.device << "\n";
    return out.str();
}

}  // namespace polyvol::cli
