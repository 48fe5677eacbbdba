// Readable numbers (issue #21): the table shows the digits each figure's
// guarantee supports (--digits caps them), never "-0"; tensors have labelled
// rows and columns; the footers are short unless --verbose; --density adds a
// mass column; --csv gives every digit to spreadsheets.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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

namespace {
// Positional decimals between 1e-4 and 1e15, an exponent outside (#33):
// 400, not 4e+02, with the shortest-within-half-the-bound digits kept.
TEST(NumbersCli, PositionalDecimalsBetweenTenToTheMinusFourAndTenToTheFifteen) {
    using polyvol::cli::number_text;
    EXPECT_EQ(number_text(400, 1e-12, 0), "400");
    EXPECT_EQ(number_text(10, 1e-13, 0), "10");
    EXPECT_EQ(number_text(2800, 1e-11, 0), "2800");
    EXPECT_EQ(number_text(15000, 1e-10, 0), "15000");
    EXPECT_EQ(number_text(40.000000000000007, 4e-14, 0), "40");
    EXPECT_EQ(number_text(1e6 + 1e-9, 1e-6, 0), "1000000");
    EXPECT_EQ(number_text(0.00012345, 1e-12, 0), "0.00012345");
    EXPECT_EQ(number_text(2.5e-5, 1e-12, 0), "2.5e-05");  // below 1e-4: an exponent
    EXPECT_EQ(number_text(1.5e20, 1e5, 0), "1.5e+20");    // 1e15 and above: an exponent
    EXPECT_EQ(number_text(9.96, 0.1, 0), "10");            // rounding carries into a new power of ten
    EXPECT_EQ(number_text(12345.678, 0, 2), "12000");      // --digits 2
}

// A value within its bound of 0 is 0: the shortest decimal within the bound (#33).
TEST(NumbersCli, NoiseWithinTheBoundIsZero) {
    using polyvol::cli::shortest_within;
    EXPECT_EQ(shortest_within(-1e-22, 2.2e-15), "0");
    EXPECT_EQ(shortest_within(1e-22, 2.2e-15), "0");
    EXPECT_EQ(shortest_within(-4e-28, 1e-20), "0");
    EXPECT_EQ(shortest_within(2.5, 2.2e-15), "2.5");
    EXPECT_EQ(shortest_within(-1e-22, 0), "-1e-22");  // correctly rounded: the value itself
}
}  // namespace

namespace {
// The positional form is the rounded value's, never more digits than asked.
TEST(NumbersCli, PositionalDigitsAreTheRoundedOnes) {
    EXPECT_EQ(polyvol::cli::number_text(1234567.8, 0, 1), "1000000");
    EXPECT_EQ(polyvol::cli::number_text(-0.0012345678, 0, 3), "-0.00123");
}
}  // namespace

namespace {
// CSV names its units (in the header when every file shares them, and in
// each row), gives each figure the digits its guarantee supports — 8 cm³
// converted from mm³, not 8.000000000000002 — and measure's CSV has the box (#33).
TEST(NumbersCli, CsvNamesItsUnitsAndKeepsTheDigitsItsBoundsSupport) {
    const std::filesystem::path cube =
        std::filesystem::temp_directory_path() / ("polyvol_csv_cube_" + std::to_string(::getpid()) + ".obj");
    cli_test::write_boxes_obj(cube, {{0.1, 0.2, 0.3, 20.1, 20.2, 20.3}});
    const auto v = run_polyvol("volume --csv --units mm --to cm '" + cube.string() + "'");
    ASSERT_EQ(v.code, 0) << v.err;
    std::vector<std::string> lines;
    for (const std::string& l : split(v.out, '\n')) if (!l.empty()) lines.push_back(l.substr(0, l.size() - 1));
    ASSERT_EQ(lines.size(), 2u) << v.out;
    const auto header = split(lines[0], ','), row = split(lines[1], ',');
    ASSERT_EQ(header.size(), row.size());
    EXPECT_EQ(header[3], "volume_cm3");
    EXPECT_EQ(row[3], "8");
    EXPECT_EQ(header[6], "area_cm2");
    EXPECT_EQ(row[6], "24");
    EXPECT_EQ(header[8], "centroid_x_cm");
    EXPECT_EQ(row[8], "1.01");
    EXPECT_EQ(header.end()[-2], "length_unit");
    EXPECT_EQ(row.end()[-2], "cm");
    const auto m = run_polyvol("measure --csv --units mm --to cm --density 1.24g/cm3 '" + cube.string() + "'");
    ASSERT_EQ(m.code, 0) << m.err;
    const std::string mhead = split(m.out, '\n')[0];
    EXPECT_TRUE(has(mhead, ",mass_kg,")) << mhead;
    EXPECT_TRUE(has(mhead, ",ixx_kg_cm2,")) << mhead;
    EXPECT_TRUE(has(mhead, ",xmin_cm,ymin_cm,zmin_cm,xmax_cm,ymax_cm,zmax_cm,")) << mhead;
    EXPECT_TRUE(has(split(m.out, '\n')[1], ",0.00992,")) << m.out;  // 8 cm³ × 1.24 g/cm³ in kg
    std::filesystem::remove(cube);
}
}  // namespace
