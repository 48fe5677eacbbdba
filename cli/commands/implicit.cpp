// `polyvol implicit EXPR --bounds LO:HI [--dim N] [--h H] [--json] [-o OUT.stl]`.
//
// Prints the volume of {F <= 0} within the box (the Richardson extrapolation
// from the lattices of spacing h and 2h), its error estimate, the number of
// boundary simplices of the PL surface at h and the time. The volume is
// streamed (no chain is built) unless -o or --method prism needs the
// chain. Exit codes: 0 ok, 1 usage, 2 an expression that does not parse, 3 F
// is NaN at a lattice vertex / the solid reaches the box with --box-rule
// error / the lattice is too large.
#include "commands/implicit.hpp"

#include "grammar.hpp"
#include "memory.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "polyvol/implicit.hpp"
#include "output/format.hpp"
#include "output/implicit.hpp"

namespace polyvol::cli {

namespace {

// "LO:HI" or "LO:HI,LO:HI,..."; false when malformed.
bool parse_box(const std::string& text, std::vector<double>& lo, std::vector<double>& hi) {
    std::stringstream all(text);
    std::string item;
    while (std::getline(all, item, ',')) {
        const auto colon = item.find(':');
        if (colon == std::string::npos) return false;
        try {
            std::size_t used = 0;
            const std::string a = item.substr(0, colon), b = item.substr(colon + 1);
            lo.push_back(std::stod(a, &used));
            if (used != a.size()) return false;
            hi.push_back(std::stod(b, &used));
            if (used != b.size()) return false;
        } catch (const std::exception&) {
            return false;
        }
    }
    return !lo.empty();
}

bool parse_point(const std::string& text, std::vector<double>& out) {
    std::stringstream all(text);
    std::string item;
    while (std::getline(all, item, ',')) {
        try {
            std::size_t used = 0;
            out.push_back(std::stod(item, &used));
            if (used != item.size()) return false;
        } catch (const std::exception&) {
            return false;
        }
    }
    return true;
}

// Binary STL of a 3D chain (triangles counter-clockwise seen from outside),
// in float32 as STL holds it. A triangle two of whose corners are the same
// point in the file (a crossing at a lattice vertex where F is 0, met from
// several edges; or two points float32 cannot tell apart) is left out: it
// has no area and, using its third edge once each way, adds nothing to the
// 2-cycle, so the file stays closed (docs/implicit.md, "The written surface").
bool write_stl(const std::string& path, const Chain& chain) {
    std::ofstream out(path, std::ios::binary);
    if (!out) return false;
    std::vector<std::array<float, 12>> records;
    records.reserve(chain.simplex_count());
    for (std::size_t s = 0; s < chain.simplex_count(); ++s) {
        std::array<float, 12> r{};
        float* v = r.data() + 3;
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                v[3 * i + k] = static_cast<float>(chain.coordinates[3 * chain.simplices[3 * s + i] + k]);
        const auto same = [&](int i, int j) {
            return v[3 * i] == v[3 * j] && v[3 * i + 1] == v[3 * j + 1] && v[3 * i + 2] == v[3 * j + 2];
        };
        if (same(0, 1) || same(1, 2) || same(0, 2)) continue;
        const double a[3] = {double(v[3]) - v[0], double(v[4]) - v[1], double(v[5]) - v[2]};
        const double b[3] = {double(v[6]) - v[0], double(v[7]) - v[1], double(v[8]) - v[2]};
        const double nrm[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        for (int k = 0; k < 3; ++k) r[static_cast<std::size_t>(k)] = len > 0 ? static_cast<float>(nrm[k] / len) : 0.0f;
        records.push_back(r);
    }
    char header[80] = "polyvol implicit: PL surface";
    out.write(header, sizeof header);
    const auto count = static_cast<uint32_t>(records.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    const uint16_t attribute = 0;
    for (const auto& r : records) {
        out.write(reinterpret_cast<const char*>(r.data()), 48);
        out.write(reinterpret_cast<const char*>(&attribute), 2);
    }
    return static_cast<bool>(out);
}

// Progress on stderr for a lattice that takes more than a second or two:
// the estimate up front (from the 2h lattice), then a bar on a terminal.
class ProgressBar {
public:
    void operator()(const ImplicitProgress& p) {
        if (p.pass != 1) return;
        if (p.evaluations == 0) {
            if (p.expected_seconds > 2)
                std::cerr << "polyvol implicit: the lattice at h: about " << short_number(p.expected_evaluations)
                          << " vertices to evaluate, about " << short_number(p.expected_seconds)
                          << " s (estimated from the 2h lattice)\n";
            bar_ = p.expected_seconds > 1 && ::isatty(2);
            return;
        }
        if (!bar_ || !(p.expected_evaluations > 0)) return;
        const double f = std::min(0.99, static_cast<double>(p.evaluations) / p.expected_evaluations);
        const int filled = static_cast<int>(40 * f);
        std::cerr << "\r[" << std::string(static_cast<std::size_t>(filled), '#')
                  << std::string(static_cast<std::size_t>(40 - filled), ' ') << "] " << static_cast<int>(100 * f) << "%"
                  << std::flush;
        drawn_ = true;
    }
    ~ProgressBar() {
        if (drawn_) std::cerr << "\r" << std::string(48, ' ') << "\r" << std::flush;
    }

private:
    bool bar_ = false, drawn_ = false;
};

}  // namespace

CLI::App* add_implicit_command(CLI::App& app, ImplicitArgs& a) {
    auto* cmd = app.add_subcommand(
        "implicit",
        "Volume of {x : F(x) <= 0} in R^n from a piecewise-linear approximation of F = 0 on a Kuhn "
        "triangulation (Richardson estimate from spacings h and 2h). In EXPR, x, y, z are the first "
        "three coordinates and x1 .. xn all of them; pi and muparser's functions (sqrt, sin, exp, abs, "
        "min, max, ...) are known.");
    cmd->add_option("expression", a.expression, "F as an expression, e.g. 'x^2 + y^2 + z^2 - 1'")->required();
    cmd->add_option("--dim", a.dimension,
                    "Dimension n, 2 .. 8 (default: the highest coordinate EXPR names, at least 2)")
        ->check(whole_number(2, kImplicitMaxDimension));
    cmd->add_option("--bounds", a.box, "The box: LO:HI for every axis, or LO:HI,LO:HI,... one per axis (required)");
    cmd->add_option("--box", a.box, "")->group("");  // the old spelling, hidden
    cmd->add_option("--h", a.h,
                    "Lattice spacing (default: the widest side / 512, 96, 32, 16, 12 cells for n = 2 .. 6; "
                    "the spacing used is <= h, an even number of cells per side)")
        ->check(positive_number());
    cmd->add_option("--coarse-cells", a.coarse_cells,
                    "Cells per axis of the coarse seeding scan (default: 256, 48, 16, 10, 6 for n = 2 .. 6; "
                    "-1: none, seeds only)")
        ->check(whole_number(-1, 1 << 20));
    cmd->add_option("--seed", a.seeds, "A seed point x1,x2,...: the surface first met along +x1 from it is "
                                        "walked too (repeatable)");
    cmd->add_option("--box-rule", a.box_rule,
                    "clip: F counts as +inf outside the box, the solid is clipped by it (default); error: "
                    "exit 3 when the solid reaches the box boundary")
        ->check(CLI::IsMember({"clip", "error"}))
        ->capture_default_str();
    cmd->add_option("--method", a.formula,
                    "Volume formula: cone (2.1; streamed, no chain built) or prism (2.2; the chain is built and "
                    "measured by chain_volume)")
        ->check(CLI::IsMember({"cone", "prism"}))
        ->capture_default_str();
    cmd->add_option("--formula", a.formula, "")->check(CLI::IsMember({"cone", "prism"}))->group("");  // old spelling
    cmd->add_flag("--no-estimate", a.no_estimate, "Skip the 2h lattice: volume of the PL solid at h only");
    cmd->add_flag("--json", a.json, "Print one JSON object");
    cmd->add_option("-o,--output", a.stl, "3D only: write the PL surface at h (marching tetrahedra) as binary STL");
    cmd->add_option("--stl", a.stl, "")->group("");  // the old spelling
    cmd->add_option("--max-memory", a.max_memory,
                    "Refuse a lattice that would need more memory than this, e.g. 8G or 512M (estimated from the 2h "
                    "lattice before the fine one starts; default: three quarters of physical memory)");
    return cmd;
}

namespace {

// The options the arguments give, or the usage error's exit code after
// printing it; limit: the memory limit in bytes.
std::variant<ImplicitOptions, int> implicit_options(const ImplicitArgs& a, uint64_t& limit) {
    int dimension = a.dimension;
    try {
        if (dimension == 0) dimension = std::max(2, expression_coordinates(a.expression));
    } catch (const ExpressionError& e) {
        std::cerr << "polyvol: " << e.what() << "\n";
        return Exit::usage;  // the expression is an argument, not input read
    }
    if (dimension > kImplicitMaxDimension) {
        std::cerr << "polyvol: the expression names coordinate x" << dimension << "; at most "
                  << kImplicitMaxDimension << " dimensions are supported\n";
        return Exit::usage;
    }
    ImplicitOptions o;
    o.dimension = dimension;
    o.lo.clear();
    o.hi.clear();
    if (a.box.empty()) {
        std::cerr << "polyvol implicit: --bounds LO:HI is required (the box the solid is measured in)\n";
        return Exit::usage;
    }
    if (!parse_box(a.box, o.lo, o.hi) || (o.lo.size() != 1 && o.lo.size() != static_cast<std::size_t>(dimension))) {
        std::cerr << "polyvol: --bounds wants LO:HI or " << dimension << " comma-separated LO:HI ranges, got '" << a.box
                  << "'\n";
        return Exit::usage;
    }
    o.h = a.h;
    o.coarse_cells = a.coarse_cells;
    for (const std::string& s : a.seeds) {
        std::vector<double> p;
        if (!parse_point(s, p) || p.size() != static_cast<std::size_t>(dimension)) {
            std::cerr << "polyvol: --seed wants " << dimension << " comma-separated coordinates, got '" << s << "'\n";
            return Exit::usage;
        }
        o.seeds.insert(o.seeds.end(), p.begin(), p.end());
    }
    o.box_rule = a.box_rule == "error" ? BoxRule::error : BoxRule::clip;
    o.formula = a.formula == "prism" ? SimplexFormula::prism : SimplexFormula::cone;
    o.error_estimate = !a.no_estimate;
    if (!a.stl.empty() && dimension != 3) {
        std::cerr << "polyvol: -o (the STL surface) needs --dim 3 (this is " << dimension << "-dimensional)\n";
        return Exit::usage;
    }
    o.keep_chain = !a.stl.empty();
    const std::optional<uint64_t> limit_given =
        a.max_memory.empty() ? std::optional<uint64_t>(default_memory_limit()) : parse_bytes(a.max_memory);
    if (!limit_given) {
        std::cerr << "polyvol: --max-memory takes a size such as 8G or 512M, not '" << a.max_memory << "'\n";
        return Exit::usage;
    }
    o.max_memory_bytes = static_cast<std::size_t>(*limit_given);
    limit = *limit_given;
    return o;
}

}  // namespace

int run_implicit_command(const ImplicitArgs& a) {
    uint64_t limit = 0;
    auto parsed = implicit_options(a, limit);
    if (const int* code = std::get_if<int>(&parsed)) return *code;
    ImplicitOptions& o = std::get<ImplicitOptions>(parsed);
    ImplicitVolume r;
    try {
        const ImplicitFunction f = parse_implicit_expression(a.expression, o.dimension);
        ProgressBar bar;
        o.progress = [&bar](const ImplicitProgress& p) { bar(p); };
        r = implicit_volume(f, o);
    } catch (const ExpressionError& e) {
        std::cerr << "polyvol: " << e.what();
        if (e.position() >= 0) std::cerr << " (at character " << e.position() + 1 << ")";
        std::cerr << "\n";
        return Exit::usage;
    } catch (const ImplicitError& e) {
        std::cerr << "polyvol: " << e.what();
        if (e.code() == ImplicitError::Code::too_large && std::string(e.what()).find("memory") != std::string::npos)
            std::cerr << " (the limit: " << (a.max_memory.empty() ? "three quarters of this machine's memory, " : "--max-memory ")
                      << bytes_text(static_cast<double>(limit)) << ")";
        std::cerr << "\n";
        return Exit::invalid;
    } catch (const std::invalid_argument& e) {
        std::cerr << "polyvol: " << e.what() << "\n";
        return Exit::usage;
    }
    if (!a.stl.empty() && (!r.chain || !write_stl(a.stl, *r.chain))) {
        std::cerr << "polyvol: cannot write " << a.stl << "\n";
        return Exit::unreadable;
    }
    if (r.clipped)
        std::cerr << "polyvol: warning: the solid reaches the box boundary (" << r.fine.box_vertices_inside
                  << " boundary lattice vertices with F <= 0): it is clipped by the box\n";

    const ImplicitPrint print{.expression = a.expression,
                              .box_rule = a.box_rule,
                              .formula = a.formula,
                              .stl = a.stl,
                              .streamed = !o.keep_chain && o.formula == SimplexFormula::cone,
                              .estimate = o.error_estimate};
    if (a.json)
        std::cout << implicit_json(r, print).dump(2) << "\n";
    else
        std::cout << implicit_report(r, print);
    return Exit::ok;
}

}  // namespace polyvol::cli
