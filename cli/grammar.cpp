#include "grammar.hpp"
#include "output/format.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string_view>

namespace polyvol::cli {

CLI::Validator positive_number() {
    return CLI::Validator(
        [](std::string& s) -> std::string {
            double v = 0;
            const char* first = s.data() + (!s.empty() && s[0] == '+');
            const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
            if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return "not a number: " + s;
            if (!(v > 0)) return "must be a number > 0, got " + s;
            return "";
        },
        "NUMBER > 0");
}

CLI::Validator whole_number(long long lo, long long hi) {
    return CLI::Validator(
        [lo, hi](std::string& s) -> std::string {
            long long v = 0;
            const char* first = s.data() + (!s.empty() && s[0] == '+');
            const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
            if (ec != std::errc() || end != s.data() + s.size()) return "not a whole number: " + s;
            if (v < lo || v > hi) return "must be from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + s;
            return "";
        },
        "INTEGER in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

namespace {

// Levenshtein distance (insert, delete, substitute), plus one for a swap of
// neighbours counted as a single slip (Damerau's restricted form).
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
    for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
        for (std::size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

std::vector<std::string> long_names(const CLI::App& cmd) {
    std::vector<std::string> names{"--help"};
    for (const CLI::Option* o : cmd.get_options())
        for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    return names;
}

}  // namespace

std::string lower_extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

int usage_error(const std::string& command, const std::string& message) {
    std::cerr << "polyvol " << command << ": " << message << "\n";
    return Exit::usage;
}

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const std::string& c : candidates) {
        // A prefix of one name only is meant as that name.
        const std::size_t d = c.rfind(word, 0) == 0 ? 1 : edit_distance(word, c);
        if (d < best_d) {
            best_d = d;
            best = c;
        }
    }
    return best;
}

int answer_before_parse(CLI::App& app, int argc, char** argv) {
    if (argc < 2) return -1;
    const std::string first = argv[1];
    std::vector<std::string> commands;
    CLI::App* sub = nullptr;
    for (CLI::App* s : app.get_subcommands({})) {
        commands.push_back(s->get_name());
        if (s->get_name() == first) sub = s;
    }
    if (first == "help") {
        CLI::App* topic = nullptr;
        for (CLI::App* s : app.get_subcommands({}))
            if (argc > 2 && s->get_name() == argv[2]) topic = s;
        std::cout << (topic ? topic->help() : app.help());
        return 0;
    }
    if (first.empty() || first[0] == '-') return -1;
    if (!sub) {
        const std::string guess = nearest(first, commands);
        std::cerr << "polyvol: unknown command '" << first << "'";
        if (!guess.empty()) std::cerr << "; did you mean '" << guess << "'?";
        std::cerr << " (polyvol help lists the commands)\n";
        return 1;
    }
    const std::vector<std::string> names = long_names(*sub);
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--") break;
        if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
        const std::string name = arg.substr(0, arg.find('='));
        if (std::find(names.begin(), names.end(), name) != names.end()) continue;
        const std::string guess = nearest(name, names);
        std::cerr << "polyvol " << first << ": unknown option '" << name << "'";
        if (!guess.empty()) std::cerr << "; did you mean '" << guess << "'?";
        std::cerr << " (polyvol help " << first << " lists its options)\n";
        return 1;
    }
    return -1;
}

void add_solid_flags(CLI::App* cmd, SolidFlags& flags, bool keep_signed) {
    cmd->add_flag("--orient", flags.orient,
                  "Orient the faces first: consistently within each shell (a walk over the faces), and outward, "
                  "cavities inward by nesting; reports the faces flipped, then measures the oriented mesh");
    cmd->add_option("--weld-tolerance", flags.weld_tolerance,
                    "Merge points within this distance of one another (transitively) before anything else, for "
                    "exports whose coordinates differ in the last digits; the report says so, and the figures are "
                    "the welded mesh's")
        ->check(positive_number());
    if (keep_signed)
        cmd->add_flag("--signed", flags.keep_signed,
                  "Keep the signed sums of a surface that is inside out (negative volume, mass and inertia); by "
                  "default its shells are turned outward, and the report says so");
}

void add_unit_flags(CLI::App* cmd, UnitFlags& flags, const std::string& to_help) {
    const std::vector<std::string> units{"micron", "um", "mm", "cm", "m", "in", "ft"};
    cmd->add_option("--units", flags.units,
                    "The coordinates' length unit (mm, cm, m, in, ft, micron); a 3MF or AMF file states its own, "
                    "which this overrides (with a warning)")
        ->check(CLI::IsMember(units));
    cmd->add_option("--to", flags.to, to_help)->check(CLI::IsMember(units));
}

}  // namespace polyvol::cli
