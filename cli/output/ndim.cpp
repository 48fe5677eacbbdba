// cli/output/ndim.cpp — cli/output/ndim.hpp.
#include "output/ndim.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "output/format.hpp"

namespace polyvol::cli {

std::string unmatched_text(const ChainReport& r) {
    std::ostringstream s;
    s << r.unmatched_faces << " unmatched (n-2)-face" << (r.unmatched_faces == 1 ? "" : "s") << " ("
      << r.boundary_faces << " boundary, " << r.misoriented_faces << " misoriented, " << r.nonmanifold_faces
      << " non-manifold)";
    if (r.unmatched_example) {
        const UnmatchedFace& e = *r.unmatched_example;
        s << ", e.g. the face (";
        for (std::size_t i = 0; i < e.vertices.size(); ++i) s << (i ? " " : "") << e.vertices[i];
        s << ") of simplex " << e.simplex << ", used " << e.same << " time" << (e.same == 1 ? "" : "s")
          << " with that orientation and " << e.opposite << " the other way";
    }
    return s.str();
}

nlohmann::json chain_json(const std::string& file, const ChainVolume* v, const ChainReport& r,
                          const std::string& formula, const ChainOutcome& out) {
    nlohmann::json j;
    j["file"] = file;
    j["dimension"] = r.dimension;
    j["vertices"] = r.vertices;
    j["vertices_welded"] = r.vertices_welded;
    j["simplices"] = r.simplices;
    j["degenerate_simplices"] = r.degenerate_simplices;
    j["faces"] = r.faces;
    j["unmatched_faces"] = r.unmatched_faces;
    j["boundary_faces"] = r.boundary_faces;
    j["misoriented_faces"] = r.misoriented_faces;
    j["nonmanifold_faces"] = r.nonmanifold_faces;
    j["components"] = r.components;
    if (r.unmatched_example) {
        const UnmatchedFace& e = *r.unmatched_example;
        j["unmatched_example"] = {{"vertices", e.vertices}, {"simplex", e.simplex}, {"same", e.same},
                                  {"opposite", e.opposite}};
    }
    j["formula"] = formula;
    if (v) {
        j["accuracy"] = v->volume_correctly_rounded ? "correctly-rounded" : "error-bound";
        j["volume"] = json_number(v->volume);
        j["error_bound"] = std::isfinite(v->volume_error_bound) ? nlohmann::json(v->volume_error_bound)
                                                                : nlohmann::json(nullptr);
        j["correctly_rounded"] = v->volume_correctly_rounded;
        nlohmann::json c = nlohmann::json::array();
        for (double x : v->centroid) c.push_back(json_number(x));
        j["centroid"] = c;
        j["centroid_error_bound"] = json_number(v->centroid_error_bound);
        j["centroid_correctly_rounded"] = v->centroid_correctly_rounded;
        if (v->accuracy == ChainAccuracy::bounded) {
            j["traversal"] = std::string(traversal_name(v->traversal));
            const ChainStats& s = v->stats;
            j["stats"] = {{"factorizations", s.factorizations},
                          {"updates", s.updates},
                          {"jumps", s.jumps},
                          {"stability_refactors", s.stability_refactors},
                          {"pass_throughs", s.pass_throughs},
                          {"elimination_steps", s.elimination_steps},
                          {"max_backward_error", s.max_backward_error},
                          {"seconds_topology", s.seconds_topology},
                          {"seconds_sweep", s.seconds_sweep}};
        }
    } else {
        j["volume"] = nullptr;
        j["error_bound"] = nullptr;
        j["centroid"] = nullptr;
    }
    if (!out.warning.empty()) j["warning"] = out.warning;
    if (!out.error.empty()) j["error"] = out.error;
    j["exit_code"] = out.code;
    return j;
}

std::string chain_report(const std::string& file, const std::string& what, const ChainVolume* v,
                         const ChainReport& r, const std::string& formula, const std::vector<std::string>& extra) {
    std::ostringstream s;
    s << "file        " << file << " (" << what << ")\n";
    s << "dimension   " << r.dimension << "\n";
    s << "simplices   " << r.simplices << " (" << r.degenerate_simplices << " degenerate), vertices " << r.vertices
      << " (" << r.vertices_welded << " distinct)\n";
    s << "faces       " << r.faces << " (n-2)-faces: unmatched " << r.unmatched_faces << ", boundary "
      << r.boundary_faces << ", misoriented " << r.misoriented_faces << ", non-manifold " << r.nonmanifold_faces
      << "; " << r.components << " component" << (r.components == 1 ? "" : "s") << "\n";
    for (const auto& line : extra) s << line << "\n";
    s << "formula     " << formula << (formula == "prism" ? " (Allgower-Schmidt 2.2)" : " (Allgower-Schmidt 2.1)")
      << "\n";
    if (!v) return s.str();
    const std::string name = r.dimension == 2 ? "area" : "volume";
    s << (name == "area" ? "area        " : "volume      ");
    if (v->volume_correctly_rounded) {
        s << shortest(v->volume) << "  (correctly rounded: the exact " << name << " of the coordinates as read, rounded once)\n";
    } else {  // the digits the bound supports, ± covering the display's rounding too (the JSON has every digit)
        s << plus_minus(v->volume, v->volume_error_bound, 0) << "  (rigorous absolute error bound)\n";
    }
    s << "centroid    ";
    if (v->centroid_correctly_rounded) {
        s << point_text(v->centroid) << "  (each coordinate correctly rounded)\n";
    } else {
        const double e = v->centroid_error_bound;
        double worst = e;
        std::string text = "(";
        for (std::size_t i = 0; i < v->centroid.size(); ++i) {
            const std::string c = number_text(v->centroid[i], e, 0);
            worst = std::max(worst, e + std::fabs(std::strtod(c.c_str(), nullptr) - v->centroid[i]));
            text += (i ? ", " : "") + c;
        }
        s << text << ") ±" << bound_text(worst) << " each\n";
    }
    if (v->accuracy == ChainAccuracy::bounded) {
        const ChainStats& st = v->stats;
        s << "traversal   " << traversal_name(v->traversal) << ": " << st.updates << " column replacements, "
          << st.factorizations << " fresh LU factorisation" << (st.factorizations == 1 ? "" : "s") << " ("
          << st.jumps << " after jumps, " << st.stability_refactors << " for stability), " << st.pass_throughs
          << " pass-throughs\n";
    }
    return s.str();
}

}  // namespace polyvol::cli
