// One grammar for every command (issue #21): mistyped commands and options
// get the nearest real one, `polyvol help` works, a number that is not one
// says so, the same flag names the same idea everywhere (old spellings kept
// as hidden aliases), ndim and area take several files and print a JSON
// array, and an error names the command that reads the file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using cli_test::run_polyvol;

std::string data(const std::string& name) { return "'" + std::string(POLYVOL_TEST_DATA) + "/grammar/" + name + "'"; }

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(GrammarCli, MistypedCommandGetsTheNearestOne) {
    const auto r = run_polyvol("mesure " + data("tetra.obj"));
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "unknown command 'mesure'; did you mean 'measure'?")) << r.err;
    EXPECT_TRUE(has(run_polyvol("volum x").err, "did you mean 'volume'?"));
    EXPECT_FALSE(has(run_polyvol("frobnicate x").err, "did you mean"));
}

TEST(GrammarCli, MistypedOptionGetsTheNearestOne) {
    const auto r = run_polyvol("volume --densty 2 " + data("tetra.obj"));
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "unknown option '--densty'; did you mean '--density'?")) << r.err;
    EXPECT_TRUE(has(run_polyvol("grid --cell 8 " + data("tetra.obj")).err, "did you mean '--cells'?"));
}

TEST(GrammarCli, HelpWorksAsACommand) {
    const auto all = run_polyvol("help");
    EXPECT_EQ(all.code, 0);
    EXPECT_TRUE(has(all.out, "volume")) << all.out;
    EXPECT_TRUE(has(all.out, "implicit"));
    const auto one = run_polyvol("help measure");
    EXPECT_EQ(one.code, 0);
    EXPECT_TRUE(has(one.out, "--density")) << one.out;
}

TEST(GrammarCli, NotANumberSaysSo) {
    const auto r = run_polyvol("volume --density abc " + data("tetra.obj"));
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "not a number: abc")) << r.err;
    EXPECT_LT(r.err.size(), 200u);  // no 309-digit range
    EXPECT_TRUE(has(run_polyvol("volume --density -2 " + data("tetra.obj")).err, "must be a number > 0"));
    EXPECT_TRUE(has(run_polyvol("grid --cells 2.5 " + data("tetra.obj")).err, "not a whole number: 2.5"));
}

TEST(GrammarCli, SameFlagsForTheSameIdeas) {
    // --method everywhere (--formula kept as a hidden alias), the same --accuracy values
    const json a = json::parse(run_polyvol("ndim --json --method prism --accuracy correctly-rounded " + data("tetra.chain")).out)[0];
    EXPECT_EQ(a["formula"], "prism");
    EXPECT_EQ(a["volume"], 1.0 / 6.0);
    EXPECT_EQ(a["accuracy"], "correctly-rounded");
    const json b = json::parse(run_polyvol("ndim --json --formula prism --accuracy exact " + data("tetra.chain")).out)[0];
    EXPECT_EQ(b["volume"], a["volume"]);
    const json c = json::parse(run_polyvol("volume --json --formula prism --accuracy exact " + data("tetra.obj")).out)[0];
    EXPECT_EQ(c["method"], "prism");
    EXPECT_EQ(c["volume"], 1.0 / 6.0);
    EXPECT_EQ(json::parse(run_polyvol("volume --json --accuracy bounded " + data("tetra.obj")).out)[0]["volume"], 1.0 / 6.0);
    // --bounds (implicit's --box kept as a hidden alias), -o/--output for every file written
    const fs::path stl = fs::temp_directory_path() / ("polyvol_grammar_" + std::to_string(::getpid()) + ".stl");
    const auto i = run_polyvol("implicit 'x^2+y^2+z^2-1' --bounds -1.5:1.5 --h 0.25 --json -o '" + stl.string() + "'");
    ASSERT_EQ(i.code, 0) << i.err;
    EXPECT_GT(fs::file_size(stl), 84u);
    const auto old = run_polyvol("implicit 'x^2+y^2+z^2-1' --box -1.5:1.5 --h 0.25 --json --stl '" + stl.string() + "'");
    EXPECT_EQ(json::parse(old.out)["volume"], json::parse(i.out)["volume"]);
    EXPECT_EQ(run_polyvol("implicit 'x^2+y^2-1'").code, 1);  // no box
    fs::remove(stl);
}

TEST(GrammarCli, NdimAndAreaTakeSeveralFiles) {
    const auto r = run_polyvol("ndim --json " + data("tetra.chain") + " " + data("tetra_misoriented.chain"));
    EXPECT_EQ(r.code, 3);  // the highest of the files'
    const json j = json::parse(r.out);
    ASSERT_EQ(j.size(), 2u);
    EXPECT_EQ(j[0]["exit_code"], 0);
    EXPECT_EQ(j[1]["exit_code"], 3);
    const auto table = run_polyvol("ndim " + data("tetra.chain") + " " + data("tetra.chain"));
    EXPECT_EQ(table.code, 0);
    EXPECT_EQ(table.out.find("file  "), table.out.rfind("file  ") - table.out.find("\n\n") - 2);
}

TEST(GrammarCli, ErrorsNameTheRightCommand) {
    const auto n = run_polyvol("ndim " + data("tetra.obj"));
    EXPECT_EQ(n.code, 2);
    EXPECT_TRUE(has(n.err, "is a 3D mesh (obj): `polyvol volume`")) << n.err;
    const auto v = run_polyvol("volume " + data("tetra.chain"));
    EXPECT_EQ(v.code, 2);
    EXPECT_TRUE(has(v.err, "`polyvol ndim` measures it")) << v.err;
    const auto m = run_polyvol("ndim " + data("tetra_misoriented.chain"));
    EXPECT_EQ(m.code, 3);
    EXPECT_TRUE(has(m.err, "--orient orients them")) << m.err;
    EXPECT_EQ(json::parse(run_polyvol("ndim --json --orient " + data("tetra_misoriented.chain")).out)[0]["volume"],
              1.0 / 6.0);
}

}  // namespace
