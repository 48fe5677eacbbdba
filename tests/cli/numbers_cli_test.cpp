// Readable numbers (issue #21): the table shows the digits each figure's
// guarantee supports (--digits caps them), never "-0"; tensors have labelled
// rows and columns; the footers are short unless --verbose; --density adds a
// mass column; --csv gives every digit to spreadsheets.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"
#include "output/format.hpp"

namespace {

using cli_test::run_polyvol;

const std::string kBox = "'" + std::string(POLYVOL_TEST_DATA) + "/weld/box.obj'";
const std::string kTetra = "'" + std::string(POLYVOL_TEST_DATA) + "/grammar/tetra.obj'";

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

nlohmann::json json_of(const std::string& args) { return nlohmann::json::parse(run_polyvol(args).out)[0]; }

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string x; std::getline(s, x, sep);) f.push_back(x);
    if (!line.empty() && line.back() == sep) f.emplace_back();
    return f;
}

TEST(NumbersCli, MassColumnShowsTheDecimalDensitysMass) {
    // the box's volume is 0.3^3 of the doubles: 0.026999999999999996 (correctly rounded)
    const auto r = run_polyvol("volume --density 7.85 " + kBox);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "mass")) << r.out;
    EXPECT_TRUE(has(r.out, "0.21195 ")) << r.out;  // not 0.21194999999999997
    EXPECT_TRUE(has(r.out, "0.026999999999999996")) << r.out;
    EXPECT_FALSE(has(run_polyvol("volume " + kBox).out, "mass"));
}

TEST(NumbersCli, DigitsFollowTheGuaranteeAndTheOption) {
    const auto fast = run_polyvol("volume --accuracy fast " + kBox);
    ASSERT_EQ(fast.code, 0) << fast.err;
    EXPECT_TRUE(has(fast.out, "±")) << fast.out;
    const auto three = run_polyvol("volume --digits 3 " + kBox);
    EXPECT_TRUE(has(three.out, "0.027 ")) << three.out;
    EXPECT_EQ(run_polyvol("volume --digits 0 " + kBox).code, 1);
}

TEST(NumbersCli, TensorsAreLabelledAndFootersShortUnlessVerbose) {
    const auto m = run_polyvol("measure " + kTetra);
    ASSERT_EQ(m.code, 0) << m.err;
    EXPECT_TRUE(has(m.out, "    x ")) << m.out;
    EXPECT_TRUE(has(m.out, "    z ")) << m.out;
    EXPECT_FALSE(has(m.out, "-0 ")) << m.out;
    const auto brief = run_polyvol("volume " + kTetra);
    const auto full = run_polyvol("volume --verbose " + kTetra);
    EXPECT_TRUE(has(brief.out, "--verbose")) << brief.out;
    EXPECT_FALSE(has(brief.out, "area relative error")) << brief.out;
    EXPECT_TRUE(has(full.out, "area relative error <= ")) << full.out;
    EXPECT_LT(brief.out.size(), full.out.size());
}

TEST(NumbersCli, CsvHasAHeaderAndARowPerFile) {
    const auto r = run_polyvol("measure --csv --density 2 " + kTetra + " " + kBox + " /nonexistent.stl");
    EXPECT_EQ(r.code, 2);
    std::vector<std::string> lines;
    for (const std::string& l : split(r.out, '\n')) if (!l.empty()) lines.push_back(l.substr(0, l.size() - 1));  // \r\n
    ASSERT_EQ(lines.size(), 4u) << r.out;
    const auto header = split(lines[0], ',');
    ASSERT_EQ(header[3], "volume");
    for (std::size_t i = 1; i < lines.size(); ++i) EXPECT_EQ(split(lines[i], ',').size(), header.size()) << lines[i];
    const auto tet = split(lines[1], ',');
    EXPECT_EQ(tet[1], "0");
    EXPECT_EQ(tet[3], "0.16666666666666666");
    EXPECT_EQ(tet[5], "0.3333333333333333");  // mass = 2 × volume
    EXPECT_EQ(split(lines[3], ',')[1], "2");
    EXPECT_EQ(run_polyvol("volume --csv --json " + kTetra).code, 1);
}

// Printed bounds round up, and a subnormal one is printed as it is.
TEST(NumbersCli, BoundsRoundUp) {
    EXPECT_EQ(polyvol::cli::bound_text(3.33e-16), "3.4e-16");
    EXPECT_EQ(polyvol::cli::bound_text(0.0125), "0.013");
    EXPECT_EQ(polyvol::cli::bound_text(5e-324), "5e-324");
    EXPECT_EQ(polyvol::cli::plus_minus(2.0, 0.25, 0), "2 ±0.25");
}

TEST(NumbersCli, AScaleTypedWithMoreDigitsThanItsDoubleIsNotExact) {
    EXPECT_EQ(json_of("volume --json --scale 1.0000000000000001 " + kBox)["accuracy"], "error-bound");
    EXPECT_EQ(json_of("volume --json --scale 2.0 " + kBox)["accuracy"], "correctly-rounded");
}

}  // namespace
