// Units (issue #21): a 3MF or AMF file's declared unit is read and shown;
// --units gives a mesh's, --to converts the figures, --scale scales the
// coordinates, and a density in kg/m3 or g/cm3 gives the mass in kg. Every
// converted figure carries a bound that holds (exact for a power-of-two
// scale).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

using cli_test::run_polyvol;
using nlohmann::json;

std::string data(const std::string& dir, const std::string& name) {
    return "'" + std::string(POLYVOL_TEST_DATA) + "/" + dir + "/" + name + "'";
}
const std::string kInch3mf = data("units", "tetra_inch.3mf");  // volume 4/3 in³
const std::string kMeterAmf = data("units", "tetra_meter.amf");  // volume 4/3 m³
const std::string kBox = data("weld", "box.obj");  // [0, 0.3]^3, no unit

json first(const std::string& args) {
    const auto r = run_polyvol(args);
    EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
    return json::parse(r.out)[0];
}

TEST(UnitsCli, DeclaredUnitsAreReadAndShown) {
    const json inch = first("measure --json " + kInch3mf);
    EXPECT_EQ(inch["unit"], "in");
    EXPECT_EQ(inch["volume"], 4.0 / 3.0);
    EXPECT_EQ(inch["accuracy"], "correctly-rounded");  // no conversion asked
    EXPECT_EQ(first("measure --json " + kMeterAmf)["unit"], "m");
    const auto table = run_polyvol("measure " + kInch3mf);
    EXPECT_NE(table.out.find("the file declares in"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find(" in³"), std::string::npos) << table.out;
}

TEST(UnitsCli, ConvertedFiguresCarryATrueBound) {
    const json mm = first("measure --json --to mm " + kInch3mf);
    EXPECT_EQ(mm["unit"], "mm");
    EXPECT_EQ(mm["length_factor"], 25.4);
    EXPECT_EQ(mm["accuracy"], "error-bound");
    const long double exact = 4.0L / 3.0L * 16387.064L;  // 1 in³ = 16387.064 mm³
    const double v = mm["volume"].get<double>(), bound = mm["volume_error_bound"].get<double>();
    EXPECT_LE(std::fabs(static_cast<long double>(v) - exact), bound);
    EXPECT_LT(bound, 1e-14 * v);
    EXPECT_DOUBLE_EQ(mm["centroid"][0].get<double>(), 12.7);
    const auto table = run_polyvol("volume --to mm " + kInch3mf + " " + kMeterAmf);
    EXPECT_NE(table.out.find("volume (mm³)"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("1333333333.33333"), std::string::npos) << table.out;
}

TEST(UnitsCli, ScaleOfAPowerOfTwoStaysCorrectlyRounded) {
    const json two = first("volume --json --scale 2 " + kBox);
    const json one = first("volume --json " + kBox);
    EXPECT_EQ(two["volume"].get<double>(), 8 * one["volume"].get<double>());
    EXPECT_EQ(two["accuracy"], "correctly-rounded");
    const json tenth = first("volume --json --scale 0.1 " + kBox);
    EXPECT_EQ(tenth["accuracy"], "error-bound");
    EXPECT_GT(tenth["volume_error_bound"].get<double>(), 0.0);
}

TEST(UnitsCli, UnknownUnitIsNotGuessed) {
    const auto r = run_polyvol("volume --to m " + kBox);
    EXPECT_EQ(r.code, 3);
    EXPECT_NE(r.err.find("its length unit is not known"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--units"), std::string::npos) << r.err;
    EXPECT_EQ(run_polyvol("volume --units furlong " + kBox).code, 1);
    EXPECT_EQ(run_polyvol("volume --density 7850kg/l " + kBox).code, 1);
}

TEST(UnitsCli, DensityWithAUnitGivesKilograms) {
    // 0.3 mm box of steel: 0.027 mm³ = 2.7e-11 m³, 7850 kg/m³
    const json steel = first("measure --json --units mm --density 7850kg/m3 " + kBox);
    EXPECT_EQ(steel["unit"], "m");
    EXPECT_EQ(steel["mass_unit"], "kg");
    EXPECT_NEAR(steel["mass"].get<double>(), 2.1195e-7, 1e-21);
    EXPECT_NEAR(steel["inertia"][0][0].get<double>(), 2.1195e-7 * 2 * 0.0003 * 0.0003 / 12, 1e-27);  // m (b² + c²)/12
    const json grams = first("measure --json --units mm --density 7.85g/cm3 " + kBox);
    EXPECT_EQ(grams["mass"], steel["mass"]);
    // the URDF inertial element is in metres and kilograms when the unit is known
    const auto urdf = run_polyvol("measure --format urdf --density 1000kg/m3 " + kInch3mf);
    EXPECT_NE(urdf.out.find("lengths in m, mass in kg"), std::string::npos) << urdf.out;
    EXPECT_NE(urdf.out.find("xyz=\"0.0127 0.0127 0.0127\""), std::string::npos) << urdf.out;
}

}  // namespace

namespace {
// --mass-unit (#33): grams for a print, pounds; only with a density that has
// a unit, and not for URDF/SDF (SI). The box [0, 0.3]^3 mm is 0.027 mm³.
TEST(UnitsCli, MassInGramsOrPounds) {
    const json kg = first("volume --json --units mm --density 1000kg/m3 " + kBox);
    const json g = first("volume --json --units mm --density 1000kg/m3 --mass-unit g " + kBox);
    const json lb = first("volume --json --units mm --density 1000kg/m3 --mass-unit lb " + kBox);
    EXPECT_EQ(g["mass_unit"], "g");
    EXPECT_EQ(lb["mass_unit"], "lb");
    EXPECT_NEAR(kg["mass"].get<double>(), 2.7e-8, 1e-20);  // 0.027e-9 m³ × 1000 kg/m³
    EXPECT_NEAR(g["mass"].get<double>(), 2.7e-5, 1e-17);
    EXPECT_NEAR(lb["mass"].get<double>(), 2.7e-8 / 0.45359237, 1e-20);
    const auto table = run_polyvol("volume --units mm --density 1000kg/m3 --mass-unit g " + kBox);
    EXPECT_NE(table.out.find("mass (g)"), std::string::npos) << table.out;
    EXPECT_EQ(run_polyvol("volume --mass-unit g " + kBox).code, 1);  // no density with a unit
    EXPECT_EQ(run_polyvol("measure --format urdf --units mm --density 1000kg/m3 --mass-unit g " + kBox).code, 1);
}
}  // namespace

namespace {
// #33 item 10: overlap and grid take --units and --to. The operands (the
// bodies) are put in one unit: one that states another is converted into
// it (each coordinate rounded once, said on stderr), one that states none
// is taken to be in it; the figures are then in --to, each within a bound
// that holds.
json parsed(const cli_test::CliRun& r) { return json::parse(r.out); }

TEST(UnitsCli, OverlapInTheUnitAsked) {
    const long double in3_mm3 = 16387.064L;  // 1 in³ in mm³, exactly
    const auto mm = run_polyvol("overlap --json --to mm " + kInch3mf + " " + kInch3mf);
    ASSERT_EQ(mm.code, 0) << mm.err;
    const json j = parsed(mm);
    EXPECT_EQ(j["unit"], "mm");
    EXPECT_EQ(j["accuracy"], "error-bound");
    const double bound = j["volume_error_bound"].get<double>();
    EXPECT_GT(bound, 0.0);
    EXPECT_LT(bound, 1e-13 * 4 / 3 * 16387.064);
    for (const char* key : {"volume_a", "intersection", "union"})
        EXPECT_LE(std::fabs(static_cast<long double>(j[key].get<double>()) - 4.0L / 3.0L * in3_mm3), bound) << key;
    EXPECT_LE(std::fabs(j["a_minus_b"].get<double>()), bound);
    const auto table = run_polyvol("overlap --to mm " + kInch3mf + " " + kInch3mf);
    EXPECT_NE(table.out.find("volume (mm³)"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("21849.41866666"), std::string::npos) << table.out;  // 4/3 × 16387.064 = 21849.4186…

    // no conversion: the file's own unit, correctly rounded
    const json in = parsed(run_polyvol("overlap --json " + kInch3mf + " " + kInch3mf));
    EXPECT_EQ(in["unit"], "in");
    EXPECT_EQ(in["accuracy"], "correctly-rounded");
    EXPECT_EQ(in["volume_a"], 4.0 / 3.0);
}

TEST(UnitsCli, OverlapConvertsAnOperandInAnotherUnit) {
    // A in metres, B in inches: B's coordinates × 0.0254 into metres.
    const auto r = run_polyvol("overlap --json " + kMeterAmf + " " + kInch3mf);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("converted from in to m"), std::string::npos) << r.err;
    const json j = parsed(r);
    EXPECT_EQ(j["unit"], "m");
    const long double b = 4.0L / 3.0L * 0.0254L * 0.0254L * 0.0254L;
    const double bound = j["volume_error_bound"].get<double>();
    EXPECT_LE(std::fabs(static_cast<long double>(j["volume_b"].get<double>()) - b), bound);
    EXPECT_LE(std::fabs(static_cast<long double>(j["intersection"].get<double>()) - b), bound);  // B inside A
    EXPECT_EQ(j["volume_a"], 4.0 / 3.0);                                                            // A unmoved
    // a file that states no unit beside one that does: taken to be in it, and said
    const auto box = run_polyvol("overlap --json " + kInch3mf + " " + kBox);
    ASSERT_EQ(box.code, 0) << box.err;
    EXPECT_NE(box.err.find("states no unit: taken to be in in"), std::string::npos) << box.err;
    // --to with an operand whose unit is not known: refused, with the flag that gives it
    const auto unknown = run_polyvol("overlap --to cm " + kBox + " " + kBox);
    EXPECT_EQ(unknown.code, 3);
    EXPECT_NE(unknown.err.find("its length unit is not known"), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("--units gives it"), std::string::npos) << unknown.err;
    // --units for both: 0.027 cm³ = 27 mm³
    const json cm = parsed(run_polyvol("overlap --json --units cm --to mm " + kBox + " " + kBox));
    EXPECT_NEAR(cm["volume_a"].get<double>(), 27.0, 1e-12);
    EXPECT_LE(std::fabs(cm["volume_a"].get<double>() - 27.0), cm["volume_error_bound"].get<double>() + 4e-15);
}

TEST(UnitsCli, GridInTheUnitAsked) {
    // The tetrahedron of 2 in converted to mm: its grid volume is of the
    // coordinates so converted, within a few ulps of 4/3 × 16387.064.
    const auto r = run_polyvol("grid --json --cells 4 --to mm " + kInch3mf);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("converted from in to mm"), std::string::npos) << r.err;
    const json j = parsed(r);
    EXPECT_EQ(j["unit"], "mm");
    EXPECT_NEAR(j["bodies"][0]["volume"].get<double>(), 4.0 / 3.0 * 16387.064, 1e-9);
    EXPECT_GT(j["grid"]["bounds"][3].get<double>(), 50.8);  // the 2 in edge, in mm, padded
    EXPECT_LE(j["grid"]["bounds"][3].get<double>(), 50.8 * 1.5 + 1e-9);
    // the file's own unit: nothing converted, the volume exact
    const json in = parsed(run_polyvol("grid --json --cells 4 " + kInch3mf));
    EXPECT_EQ(in["unit"], "in");
    EXPECT_EQ(in["bodies"][0]["volume"], 4.0 / 3.0);
    // the typed lengths are in the grid's unit: one 1 mm cell per 1 mm
    const json typed = parsed(run_polyvol("grid --json --units mm --cell-size 0.1 " + kBox));
    EXPECT_EQ(typed["unit"], "mm");
    EXPECT_EQ(typed["grid"]["dims"][0], 5);  // 0.3 mm padded by a cell each side
    const auto text = run_polyvol("grid --cells 4 --units mm " + kBox);
    EXPECT_NE(text.out.find("lengths in mm, volumes in mm³"), std::string::npos) << text.out;
    const auto unknown = run_polyvol("grid --cells 4 --to mm " + kBox);
    EXPECT_EQ(unknown.code, 3);
    EXPECT_NE(unknown.err.find("its length unit is not known"), std::string::npos) << unknown.err;
}
}  // namespace
