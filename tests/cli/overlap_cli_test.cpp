// `polyvol overlap A B` as users run it: the table, the JSON keys and values
// for two overlapping cubes (closed forms), and the exit codes for an open
// operand (3, naming it), an operand whose shells overlap (3) and a missing
// file (2).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("polyvol_overlap_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

fs::path write_boxes(const std::string& name, std::initializer_list<std::array<double, 6>> boxes,
                     bool drop_last = false) {
    const fs::path p = scratch(name);
    cli_test::write_boxes_obj(p, boxes, drop_last);
    return p;
}

TEST(OverlapCli, TwoCubesTableAndJson) {
    const fs::path a = write_boxes("a.obj", {{0, 0, 0, 2, 2, 2}});
    const fs::path b = write_boxes("b.obj", {{1, 1, 1, 3, 3, 3}});
    const auto table = cli_test::run_polyvol("overlap '" + a.string() + "' '" + b.string() + "'");
    ASSERT_EQ(table.code, 0) << table.err;
    EXPECT_NE(table.out.find("A ∩ B   1 "), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("A ∪ B   15 "), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("correctly rounded"), std::string::npos) << table.out;

    const auto run = cli_test::run_polyvol("overlap --json '" + a.string() + "' '" + b.string() + "'");
    ASSERT_EQ(run.code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["volume_a"], 8.0);
    EXPECT_EQ(j["volume_b"], 8.0);
    EXPECT_EQ(j["intersection"], 1.0);
    EXPECT_EQ(j["union"], 15.0);
    EXPECT_EQ(j["a_minus_b"], 7.0);
    EXPECT_EQ(j["b_minus_a"], 7.0);
    EXPECT_EQ(j["accuracy"], "correctly-rounded");
    EXPECT_NEAR(j["area_intersection"].get<double>(), 6.0, j["area_error_bound"].get<double>());
    EXPECT_NEAR(j["area_union"].get<double>(), 42.0, j["area_error_bound"].get<double>());
    EXPECT_GT(j["crossing_pairs"].get<int>(), 0);
    EXPECT_TRUE(j.contains("seconds"));
}

TEST(OverlapCli, InvalidOperandsExitWithTheirReason) {
    const fs::path good = write_boxes("good.obj", {{0, 0, 0, 1, 1, 1}});
    const fs::path open = write_boxes("open.obj", {{0, 0, 0, 1, 1, 1}}, true);
    const auto r = cli_test::run_polyvol("overlap '" + good.string() + "' '" + open.string() + "'");
    EXPECT_EQ(r.code, 3);
    EXPECT_NE(r.err.find("open.obj (B): not a closed surface: 4 unbalanced edges"), std::string::npos) << r.err;

    const fs::path twice = write_boxes("twice.obj", {{0, 0, 0, 2, 2, 2}, {1, 1, 1, 3, 3, 3}});
    const fs::path probe = write_boxes("probe.obj", {{1.25, 1.25, 1.25, 1.5, 1.5, 1.5}});
    // An operand whose shells overlap is its solid (15, not the shells' 16),
    // as `volume` takes it: the probe lies inside both cubes.
    const auto o = cli_test::run_polyvol("overlap --json '" + twice.string() + "' '" + probe.string() + "'");
    ASSERT_EQ(o.code, 0) << o.err;
    const auto j = nlohmann::json::parse(o.out);
    EXPECT_EQ(j["volume_a"], 15.0);
    EXPECT_EQ(j["volume_b"], 0.015625);
    EXPECT_EQ(j["intersection"], 0.015625);
    EXPECT_EQ(j["union"], 15.0);
    EXPECT_EQ(j["a_minus_b"], 14.984375);
    EXPECT_EQ(j["b_minus_a"], 0.0);
    // Areas: the solid's boundary (2 x 24 less the 6 unit faces inside the
    // other cube), the probe's, and A ∩ B = |∂A| + |∂B| - |∂(A ∪ B)|.
    const double bound = j["area_error_bound"].get<double>();
    EXPECT_GT(bound, 0);
    EXPECT_LT(bound, 1e-12);
    EXPECT_NEAR(j["area_a"].get<double>(), 42.0, bound);
    EXPECT_NEAR(j["area_b"].get<double>(), 0.375, bound);
    EXPECT_NEAR(j["area_union"].get<double>(), 42.0, bound);
    EXPECT_NEAR(j["area_intersection"].get<double>(), 0.375, bound);
    EXPECT_TRUE(j["area_a_minus_b"].is_null());  // the parts of ∂A inside B are not formed

    const auto missing = cli_test::run_polyvol("overlap '" + good.string() + "' '" + scratch("none.obj").string() + "'");
    EXPECT_EQ(missing.code, 2);
    EXPECT_NE(missing.err.find("none.obj"), std::string::npos) << missing.err;
}

// One file with two overlapping cubes: `volume` and `measure` give the
// solid's 15 (not the shells' 16), `check` names the crossing shells.
TEST(OverlapCli, OverlappingShellsOfOneFile) {
    const fs::path two = write_boxes("two.obj", {{0, 0, 0, 2, 2, 2}, {1, 1, 1, 3, 3, 3}});
    const auto json_run = cli_test::run_polyvol("volume --json '" + two.string() + "'");
    ASSERT_EQ(json_run.code, 0) << json_run.err;
    const auto j = nlohmann::json::parse(json_run.out)[0];
    EXPECT_EQ(j["volume"], 15.0);
    EXPECT_EQ(j["winding_volume"], 16.0);
    EXPECT_EQ(j["overlapping_shells"], 2);
    EXPECT_EQ(j["overlap_checked"], true);
    EXPECT_GT(j["crossing_pairs"].get<int>(), 0);
    EXPECT_EQ(j["shells"][0]["role"], "crossing");
    // The solid's centroid and inertia (the union of two cubes is symmetric about (1.5, 1.5, 1.5)).
    EXPECT_EQ(j["centroid"][0], 1.5);
    EXPECT_EQ(j["mass"], 15.0);
    // The solid's area: 2 x 24 less the 6 unit faces each cube has inside the other.
    EXPECT_NEAR(j["area"].get<double>(), 42.0, 42.0 * j["area_relative_error"].get<double>());
    const double ixx = j["inertia"][0][0].get<double>(), ixy = j["inertia"][0][1].get<double>();
    // About c = (1.5, 1.5, 1.5), by inclusion-exclusion over A, B and A ∩ B = [1, 2]^3:
    // ∫(x - 1.5)^2 = 2 (8 * 4/12 + 8 * 0.25) - 1/12 = 111/12, so Ixx = 2 * 111/12 = 18.5;
    // ∫(x - 1.5)(y - 1.5) = 2 (8 * 0.25) - 0 = 4, so Ixy = -4.
    EXPECT_NEAR(ixx, 18.5, 1e-12);
    EXPECT_NEAR(ixy, -4.0, 1e-12);

    const auto table = cli_test::run_polyvol("volume '" + two.string() + "'");
    ASSERT_EQ(table.code, 0) << table.err;
    EXPECT_NE(table.out.find("  15 "), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("2 of 2 shells overlap"), std::string::npos) << table.out;

    const auto measure = cli_test::run_polyvol("measure '" + two.string() + "'");
    ASSERT_EQ(measure.code, 0) << measure.err;
    EXPECT_NE(measure.out.find("volume          15 "), std::string::npos) << measure.out;

    const auto check = cli_test::run_polyvol("check '" + two.string() + "'");
    ASSERT_EQ(check.code, 0) << check.err;
    EXPECT_NE(check.out.find("crossing another shell"), std::string::npos) << check.out;
    EXPECT_NE(check.out.find("2 overlapping shells"), std::string::npos) << check.out;
    EXPECT_EQ(check.out.find("nested"), std::string::npos) << check.out;

    // Apart, nothing changes: the volume is the shells' sum.
    const fs::path apart = write_boxes("apart.obj", {{0, 0, 0, 1, 1, 1}, {2, 2, 2, 3, 3, 3}});
    const auto a = nlohmann::json::parse(cli_test::run_polyvol("volume --json '" + apart.string() + "'").out)[0];
    EXPECT_EQ(a["volume"], 2.0);
    EXPECT_EQ(a["overlapping_shells"], 0);
}

// One shell crossing itself (the box [0, 2]^3 and a tetrahedron on its
// edge from (0,0,0) to (2,0,0) poking out through its top; joined through
// that edge): found, said and resolved, in every command.
TEST(OverlapCli, ASurfaceCrossingItselfIsReported) {
    const fs::path p = scratch("self.obj");
    cli_test::write_boxes_obj(p, {{0, 0, 0, 2, 2, 2}});
    {
        std::ofstream out(p, std::ios::app);
        // vertices 9, 10; the box's vertex 1 is (0,0,0), 2 is (2,0,0)
        out << "v 0.8 0.6 3\nv 1.2 1.4 3\nf 2 10 9\nf 1 9 10\nf 1 2 9\nf 1 10 2\n";
    }
    const auto v = cli_test::run_polyvol("volume '" + p.string() + "'");
    ASSERT_EQ(v.code, 0) << v.err;
    EXPECT_NE(v.out.find("1 shell crosses itself (6 triangle pairs): the volume is the solid's"), std::string::npos)
        << v.out;
    const auto j = nlohmann::json::parse(cli_test::run_polyvol("volume --json '" + p.string() + "'").out)[0];
    EXPECT_EQ(j["self_crossing_checked"], true);
    EXPECT_EQ(j["self_crossing_pairs"], 6);
    EXPECT_EQ(j["self_crossing_example"].size(), 2u);
    // Resolved (tests/boolean/self_solid_test.cpp: the box and the part of
    // the tetrahedron above it, 1108/135), the shells' sum beside it.
    EXPECT_EQ(j["self_crossing_resolved"], true);
    EXPECT_EQ(j["volume"], 1108.0 / 135);
    EXPECT_EQ(j["winding_volume"], 8.8);
    const auto check = cli_test::run_polyvol("check '" + p.string() + "'");
    ASSERT_EQ(check.code, 0) << check.err;
    EXPECT_NE(check.out.find("self-crossing   its surface crosses itself within a shell (6"), std::string::npos)
        << check.out;
    const auto measure = cli_test::run_polyvol("measure --solid '" + p.string() + "'");
    ASSERT_EQ(measure.code, 0) << measure.err;
    EXPECT_NE(measure.out.find("self-crossing   its surface"), std::string::npos) << measure.out;
    // A surface that does not cross itself says so.
    const fs::path box = write_boxes("plain.obj", {{0, 0, 0, 1, 1, 1}});
    EXPECT_NE(cli_test::run_polyvol("check '" + box.string() + "'").out.find("self-crossing   none within a shell"),
              std::string::npos);
}

// One shell crossing itself where nothing touches (tests/data/self_crossing:
// two spheres joined by a tube through both): resolved, the volume and the
// moments are the solid's, equal to those of the same chain as three shells.
TEST(OverlapCli, ASurfaceCrossingItselfIsResolved) {
    const fs::path dir = fs::path(POLYVOL_TEST_DATA) / "self_crossing";
    auto measure = [](const fs::path& p) {
        const auto r = cli_test::run_polyvol("measure --json '" + p.string() + "'");
        EXPECT_EQ(r.code, 0) << r.err;
        return nlohmann::json::parse(r.out)[0];
    };
    const auto one = measure(dir / "one.obj"), three = measure(dir / "three.obj");
    EXPECT_EQ(one["self_crossing_checked"], true);
    EXPECT_EQ(one["self_crossing_pairs"], 88);
    EXPECT_EQ(one["self_crossing_resolved"], true);
    EXPECT_EQ(one["overlapping_shells"], 0);
    EXPECT_EQ(three["overlapping_shells"], 3);
    EXPECT_EQ(one["volume"], three["volume"]);
    EXPECT_EQ(one["winding_volume"], three["winding_volume"]);
    EXPECT_LT(one["volume"].get<double>(), one["winding_volume"].get<double>());
    EXPECT_EQ(one["second_moments"], three["second_moments"]);
    const auto table = cli_test::run_polyvol("measure '" + (dir / "one.obj").string() + "'");
    EXPECT_NE(table.out.find("1 shell crosses itself (88 triangle pairs): the volume is the solid's"), std::string::npos)
        << table.out;
    EXPECT_NE(table.out.find("; resolved: the volume is the solid's"), std::string::npos) << table.out;
}

}  // namespace
