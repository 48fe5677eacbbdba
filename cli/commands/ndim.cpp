// `polyvol ndim FILE...` and `polyvol area FILE...`: read, validate, measure,
// print (a report for people, or a JSON array of one object per file). Exit codes as the rest of the
// command: 0 ok, 1 usage, 2 unreadable input, 3 a chain with unmatched faces
// (its volume would depend on the origin) unless --allow-open.
#include "commands/ndim.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "polyvol/chain_io.hpp"
#include "polyvol/simplicial.hpp"
#include "read_input.hpp"
#include "output/format.hpp"
#include "output/ndim.hpp"

namespace polyvol::cli {

namespace {

ChainOptions chain_options(const NdimOptions& o) {
    ChainOptions c;
    c.formula = o.formula == "prism" ? SimplexFormula::prism : SimplexFormula::cone;
    // The values of volume's --accuracy mean the same here.
    c.accuracy = o.accuracy == "exact" || o.accuracy == "correctly-rounded" ? ChainAccuracy::exact
                 : o.accuracy == "bounded" || o.accuracy == "fast"          ? ChainAccuracy::bounded
                                                                             : ChainAccuracy::automatic;
    c.traversal = o.traversal == "refactor" ? Traversal::refactor : Traversal::rank_one;
    return c;
}

void add_common(CLI::App* cmd, NdimOptions& o) {
    cmd->add_option("--method", o.formula,
                    "cone: Allgower-Schmidt (2.1), det/n! per simplex; prism: (2.2), mean last coordinate "
                    "times the projected simplex")
        ->check(CLI::IsMember({"cone", "prism"}))
        ->capture_default_str();
    cmd->add_option("--formula", o.formula, "")->check(CLI::IsMember({"cone", "prism"}))->group("");  // old spelling
    cmd->add_option("--accuracy", o.accuracy,
                    "auto (correctly rounded for n <= 3, rigorous error bound for n >= 4), fast (a rigorous error "
                    "bound; also spelled bounded), or correctly-rounded (for any n, GMP: slow; also spelled exact)")
        ->check(CLI::IsMember({"auto", "bounded", "exact", "fast", "correctly-rounded"}))
        ->capture_default_str();
    cmd->add_flag("--json", o.json, "Print JSON (an array with one object per file)");
    cmd->add_flag("--orient", o.orient,
                  "Orient first: consistent within each component, outer boundaries outward, cavities and "
                  "holes inward (by nesting)");
}

// The shared tail: orient, measure, judge, print (with --json: into `array`).
int measure_and_print(const std::string& file, const std::string& what, Chain& chain, bool force_orient,
                      const NdimOptions& o, std::vector<std::string> extra, nlohmann::json& array) {
    ChainOutcome out;
    if (o.orient || force_orient) {
        const OrientResult orr = orient_chain(chain);
        std::ostringstream s;
        s << "oriented    ";
        if (!orr.orientable) {
            s << "not orientable: left as read";
        } else {
            s << orr.flipped << " simplices flipped in " << orr.components << " component"
              << (orr.components == 1 ? "" : "s");
            if (orr.undecided) s << " (" << orr.undecided << " undecided)";
        }
        extra.push_back(s.str());
    }
    const ChainVolume v = chain_volume(chain.view(), chain_options(o));
    const ChainReport& r = v.topology;
    const bool show = r.closed() || o.allow_open;
    if (!r.closed()) {
        if (o.allow_open) {
            out.warning = file + ": " + unmatched_text(r) +
                          ": the chain is not closed, so the figures depend on the origin (they are the sums about 0)";
        } else {
            out.code = Exit::invalid;
            out.error = file + ": " + unmatched_text(r) + ": the volume would depend on the origin";
            if (r.misoriented_faces > 0 && r.boundary_faces == 0 && r.nonmanifold_faces == 0)
                out.error += "; the simplices are oriented inconsistently: --orient orients them";
        }
    }
    if (!out.error.empty()) std::cerr << "polyvol: " << out.error << "\n";
    if (!out.warning.empty()) std::cerr << "polyvol: warning: " << out.warning << "\n";
    if (o.json) {
        nlohmann::json j = chain_json(file, show ? &v : nullptr, r, o.formula, out);
        j["format"] = what;
        if (r.dimension == 2 && show) j["area"] = json_number(v.volume);
        array.push_back(std::move(j));
    } else {
        std::cout << chain_report(file, what, show ? &v : nullptr, r, o.formula, extra);
    }
    return out.code;
}

// A file the chain or polygon reader refused, in `array` (--json) and, when
// it reads as a 3D mesh, with the command that measures it.
int unreadable(const std::string& file, nlohmann::json& array, const NdimOptions& o) {
    std::string hint;
    if (file != "-") {
        try {
            const LoadedMesh m = read_mesh_file(file);
            if (m.mesh.face_count() > 0)
                hint = file + " is a 3D mesh (" + std::string(format_name(m.format)) +
                       "): `polyvol volume`, `measure` and `check` measure it";
        } catch (const std::exception&) {
        }
    }
    if (!hint.empty()) std::cerr << "polyvol: " << hint << "\n";
    if (o.json) array.push_back({{"file", file}, {"error", hint.empty() ? "unreadable" : hint}, {"exit_code", Exit::unreadable}});
    return Exit::unreadable;
}

int run_one_ndim(const std::string& file, const NdimOptions& o, nlohmann::json& array) {
    std::optional<LoadedChain> loaded = read_or_report(file, [&] { return read_chain_file(file); });
    if (!loaded) return unreadable(file, array, o);
    std::vector<std::string> extra;
    if (loaded->format == ChainFormat::qhull) {
        std::ostringstream s;
        s << "qhull       " << loaded->qhull_facets << " facets, " << loaded->facets_reoriented
          << " turned outward, " << loaded->facets_undecided << " flat ones oriented by their neighbours";
        extra.push_back(s.str());
    }
    return measure_and_print(file, std::string(chain_format_name(loaded->format)), loaded->chain,
                             loaded->facets_undecided > 0, o, std::move(extra), array);
}

int run_one_area(const std::string& file, const NdimOptions& o, nlohmann::json& array) {
    const std::optional<Polygons> p = read_or_report(file, [&] { return read_polygons_file(file); });
    if (!p) return unreadable(file, array, o);
    Chain c = polygon_chain(p->view());
    std::vector<std::string> extra{"loops       " + std::to_string(p->loop_count())};
    // A hole wound like its outer loop counts as land: said, unless --orient winds them by nesting.
    const std::size_t against = o.orient ? 0 : loops_wound_like_their_container(p->view()).size();
    if (against > 0)
        std::cerr << "polyvol: warning: " << file << ": " << against << " loop" << (against == 1 ? " is" : "s are")
                  << " wound like the loop around " << (against == 1 ? "it" : "them")
                  << " (a hole counter-clockwise inside a counter-clockwise outer loop, say): "
                  << (against == 1 ? "its" : "their") << " area is added, not taken away; --orient winds loops by "
                  << "nesting\n";
    const int code = measure_and_print(file, "polygons", c, false, o, std::move(extra), array);
    if (o.json && !array.empty()) array.back()["loops_wound_like_container"] = against;
    return code;
}

// Every file in turn (a blank line between reports); with --json one array
// of per-file objects, as `volume` prints. The exit code is the highest.
template <class RunOne>
int run_files(const NdimOptions& o, RunOne run_one) {
    nlohmann::json array = nlohmann::json::array();
    int code = Exit::ok;
    for (std::size_t i = 0; i < o.files.size(); ++i) {
        if (i > 0 && !o.json) std::cout << "\n";
        code = std::max(code, run_one(o.files[i], o, array));
    }
    if (o.json) std::cout << array.dump(2) << "\n";
    return code;
}

}  // namespace

void add_ndim_commands(CLI::App& app, NdimCommands& c) {
    c.ndim = app.add_subcommand("ndim", "Volume and centroid of a polyhedron in R^n from its oriented simplicial "
                                        "boundary (.chain, or the output of `qconvex o Qt`), with its guarantee");
    c.ndim->add_option("files", c.ndim_options.files, ".chain files or qhull's OFF output; - reads stdin")->required();
    add_common(c.ndim, c.ndim_options);
    c.ndim->add_option("--traversal", c.ndim_options.traversal,
                       "rank-one (LU column-replacement updates along a walk of adjacent simplices) or refactor "
                       "(a fresh LU per simplex)")
        ->check(CLI::IsMember({"rank-one", "refactor"}))
        ->capture_default_str();
    c.ndim->add_flag("--allow-open", c.ndim_options.allow_open,
                     "Measure chains with unmatched faces anyway (the result then depends on the origin)");
    c.area = app.add_subcommand("area", "Area and centroid of plane polygons with holes and islands (one vertex "
                                        "loop per line: x0 y0 x1 y1 ...), correctly rounded");
    c.area->add_option("files", c.area_options.files, "Polygon files; - reads stdin")->required();
    add_common(c.area, c.area_options);
}

int run_ndim_commands(const NdimCommands& c) {
    if (c.ndim && *c.ndim) return run_files(c.ndim_options, run_one_ndim);
    if (c.area && *c.area) return run_files(c.area_options, run_one_area);
    return -1;
}

}  // namespace polyvol::cli
