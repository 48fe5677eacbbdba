// One grammar for every command: numbers that say "not a number", and
// mistyped commands and options answered with the nearest real one.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "polyvol/solid.hpp"

namespace polyvol::cli {

// A finite number > 0 ("not a number: abc", "must be > 0: -1").
CLI::Validator positive_number();
// A whole number in [lo, hi] ("not a whole number: 2.5", "must be from 3 to 1048576: 2").
CLI::Validator whole_number(long long lo, long long hi);

// What makes a file's mesh a solid, the same options on every command that
// takes one (polyvol/solid.hpp): --orient, --weld-tolerance, --signed.
struct SolidFlags {
    bool orient = false;
    double weld_tolerance = 0;
    bool keep_signed = false;

    SolidOptions policy() const {
        return SolidOptions{.weld_tolerance = weld_tolerance, .orient = orient, .keep_signed = keep_signed};
    }
};
// keep_signed: whether the command offers --signed (`check` judges the file as it is).
void add_solid_flags(CLI::App* cmd, SolidFlags& flags, bool keep_signed = true);

// --units and --to of a command that puts several meshes in one coordinate
// system (overlap, grid): polyvol::common_unit.
struct UnitFlags {
    std::string units, to;
};
// to_help: what --to sets for this command.
void add_unit_flags(CLI::App* cmd, UnitFlags& flags, const std::string& to_help);

// A path's extension in lower case, with its dot (".npy"; "" for none).
std::string lower_extension(const std::string& path);

// "polyvol COMMAND: message" on stderr; returns Exit::usage (1).
int usage_error(const std::string& command, const std::string& message);

// The candidate nearest to `word` by edit distance, if it is near enough to
// be a typing slip (at most a third of the word's letters, and 2 at least);
// else "".
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

// Before CLI11 parses: `polyvol help [COMMAND]` prints the help, and an
// unknown command or an unknown long option of the chosen command gets a
// "did you mean". Returns the exit code when it answered (0 for help, 1 for
// a mistake), or -1 to let the parse go on.
int answer_before_parse(CLI::App& app, int argc, char** argv);

}  // namespace polyvol::cli
