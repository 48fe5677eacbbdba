// polyvol/units.hpp: the plan of one mesh's units, several meshes put in
// one unit, and coordinates converted with a bound that holds (checked
// against the exact product in long double, whose 64-bit significand holds
// x × 254 / 10000 to well within the bound).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "polyvol/units.hpp"

namespace polyvol {
namespace {

UnitsRequest request(std::string units, std::string to, bool density_si = false) {
    UnitsRequest q;
    q.units = std::move(units);
    q.to = std::move(to);
    q.density_si = density_si;
    return q;
}

TEST(Units, PlanOfOneMesh) {
    const UnitsPlan declared = plan_units("in", request("", "mm"));
    EXPECT_EQ(declared.error, "");
    EXPECT_EQ(declared.from, "in");
    EXPECT_EQ(declared.source, "declared by the file");
    EXPECT_EQ(declared.length_unit, "mm");
    EXPECT_EQ(declared.length.factor, 25.4);
    EXPECT_GT(declared.length.relative_error, 0.0);  // 25.4 is not a double
    const UnitsPlan over = plan_units("in", request("mm", ""));
    EXPECT_NE(over.warning.find("declares its unit as in; mm is used instead"), std::string::npos);
    EXPECT_EQ(over.length.factor, 1.0);
    EXPECT_NE(plan_units("", request("", "m")).error.find("not known"), std::string::npos);
    EXPECT_EQ(plan_units("", request("", "", true)).error.find("not known") != std::string::npos, true);
    EXPECT_EQ(plan_units("", request("", "")).length_unit, "");  // nothing asked, nothing known: no unit
    EXPECT_NE(plan_units("", request("furlong", "")).error.find("unknown unit furlong"), std::string::npos);
    EXPECT_EQ(plan_units("mm", request("", "", true)).length_unit, "m");
}

TEST(Units, DensityInUnits) {
    const Density pla = *parse_density("1.24g/cm3");
    EXPECT_TRUE(pla.si);
    EXPECT_EQ(pla.kg_per_m3, 1240.0);
    const DensityIn g_per_mm3 = density_in(pla, *length_unit("mm"), "g");
    EXPECT_NEAR(g_per_mm3.value, 1.24e-3, 1.24e-3 * g_per_mm3.relative_error);
    EXPECT_EQ(density_in(*parse_density("2"), *length_unit("mm"), "kg").value, 2.0);  // no unit: as typed
    EXPECT_FALSE(parse_density("7850kg/l"));
    EXPECT_FALSE(mass_units_per_kg("ton"));
}

TEST(Units, CommonUnitConvertsAssumesOrRefuses) {
    const std::vector<std::string> m_in{"m", "in"};
    const CommonUnit c = common_unit(m_in, "", "");
    EXPECT_EQ(c.error, "");
    EXPECT_EQ(c.unit, "m");
    EXPECT_EQ(c.factors[0].factor, 1.0);
    EXPECT_EQ(c.factors[1].factor, 0.0254);
    EXPECT_GT(c.factors[1].relative_error, 0.0);  // 0.0254 is not a double
    EXPECT_NE(c.notes[1].find("converted from in to m"), std::string::npos);
    const std::vector<std::string> none_mm{"", "mm"};
    const CommonUnit assumed = common_unit(none_mm, "", "");
    EXPECT_EQ(assumed.unit, "mm");
    EXPECT_NE(assumed.notes[0].find("states no unit: taken to be in mm"), std::string::npos);
    EXPECT_EQ(assumed.factors[0].factor, 1.0);
    const CommonUnit refused = common_unit(none_mm, "", "cm");
    EXPECT_NE(refused.error.find("not known"), std::string::npos);
    EXPECT_EQ(refused.notes[0], refused.error);  // says which mesh
    const std::vector<std::string> none{"", ""};
    EXPECT_EQ(common_unit(none, "", "").unit, "");  // nothing known: the coordinates as they are
    EXPECT_EQ(common_unit(none, "cm", "mm").factors[1].factor, 10.0);
}

TEST(Units, ScaledCoordinatesWithinTheirBound) {
    Mesh mesh;
    for (int i = 0; i < 300; ++i) mesh.positions.push_back(std::ldexp(1.0 + i / 7.0, i % 40 - 20) * (i % 3 ? 1 : -1));
    const std::vector<double> before = mesh.positions;
    const LengthFactor in_to_mm = length_factor(*length_unit("in"), *length_unit("mm"));
    const double old_error = 1e-9;  // as if a reader had computed them
    const double bound = scale_coordinates(mesh, in_to_mm, old_error);
    for (std::size_t i = 0; i < before.size(); ++i) {
        // the coordinate meant lies within old_error of the one read: the worst of both ends
        for (const long double meant : {before[i] - old_error, before[i] + old_error}) {
            const long double exact = static_cast<long double>(meant) * 254.0L / 10.0L;
            EXPECT_LE(std::fabs(static_cast<long double>(mesh.positions[i]) - exact), bound) << i;
        }
    }
    Mesh twice;
    twice.positions = before;
    EXPECT_EQ(scale_coordinates(twice, scale_only(2.0), 0.0), 0.0);  // a power of two moves nothing
    EXPECT_EQ(twice.positions[5], 2 * before[5]);
}

TEST(PairUnits, BGoesIntoAsUnitAndTheFiguresIntoTo) {
    PairUnits p = pair_units("mm", "in", "", "");
    EXPECT_EQ(p.error, "");
    EXPECT_EQ(p.unit, "mm");
    EXPECT_EQ(p.common.factors[0].factor, 1.0);
    EXPECT_EQ(p.common.factors[1].factor, 25.4);
    EXPECT_NE(p.common.notes[1].find("converted from in to mm"), std::string::npos) << p.common.notes[1];
    EXPECT_EQ(p.figures.factor, 1.0);
    p = pair_units("mm", "in", "", "m");  // the figures in m, the operands still in mm
    EXPECT_EQ(p.unit, "m");
    EXPECT_EQ(p.common.factors[1].factor, 25.4);
    EXPECT_EQ(p.figures.factor, 0.001);
    p = pair_units("", "mm", "", "m");  // A's unit unknown: named
    EXPECT_NE(p.error.find("not known"), std::string::npos) << p.error;
    EXPECT_EQ(p.error_operand, 0);
    p = pair_units("", "", "", "");  // nothing known: as they are
    EXPECT_EQ(p.error, "");
    EXPECT_EQ(p.unit, "");
    EXPECT_EQ(pair_units("mm", "", "furlong", "").error_operand, -1);
}

TEST(IntoUnit, ABodyIsPutIntoTheMeshsUnitOrSaysWhatWasAssumed) {
    // --units first, then the file's own; the factor common_unit gives.
    UnitChange u = into_unit("in", "", "m");
    EXPECT_EQ(u.error, "");
    EXPECT_EQ(u.factor.factor, 0.0254);
    EXPECT_NE(u.note.find("converted from in to m"), std::string::npos) << u.note;
    u = into_unit("in", "mm", "mm");
    EXPECT_EQ(u.factor.factor, 1.0);
    EXPECT_NE(u.note.find("declares its unit as in; mm is used instead"), std::string::npos) << u.note;
    u = into_unit("", "", "m");  // none known: taken in the mesh's
    EXPECT_EQ(u.factor.factor, 1.0);
    EXPECT_EQ(u.note, "it states no unit: taken to be in m, the mesh's");
    u = into_unit("mm", "", "");  // the mesh's not known: as they are
    EXPECT_EQ(u.factor.factor, 1.0);
    EXPECT_EQ(u.note, "the mesh states no unit: its coordinates are taken as they are");
    EXPECT_EQ(into_unit("m", "", "m").note, "");
    EXPECT_NE(into_unit("", "furlong", "m").error.find("unknown unit furlong"), std::string::npos);
}

}  // namespace
}  // namespace polyvol
