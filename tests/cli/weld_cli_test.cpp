// --weld-tolerance (tests/data/weld/): a box exported with its last digits
// off is refused as open, with the tolerance that would close it; welded, it
// is the exact box, and the report says that it was welded.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

using nlohmann::json;

const std::string kNear = "'" + std::string(POLYVOL_TEST_DATA) + "/weld/near_box.obj'";
const std::string kBox = "'" + std::string(POLYVOL_TEST_DATA) + "/weld/box.obj'";

TEST(WeldCli, RefusedMeshNamesTheToleranceThatClosesIt) {
    const auto r = cli_test::run_polyvol("volume " + kNear);
    EXPECT_EQ(r.code, 3);
    EXPECT_NE(r.err.find("16 unbalanced edges"), std::string::npos) << r.err;
    // its size (the box's diagonal) is 0.52: 1e-9 of it rounds down to 1e-10
    EXPECT_NE(r.err.find("--weld-tolerance 1e-10"), std::string::npos) << r.err;
}

TEST(WeldCli, WeldedMeshIsTheExactBox) {
    const auto r = cli_test::run_polyvol("measure --json --weld-tolerance 1e-12 " + kNear + " " + kBox);
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    const json& near = j[0];
    const json& box = j[1];
    EXPECT_EQ(near["volume"], box["volume"]);
    EXPECT_EQ(near["accuracy"], "correctly-rounded");
    EXPECT_EQ(near["inertia"], box["inertia"]);
    EXPECT_EQ(near["weld_tolerance"], 1e-12);
    EXPECT_EQ(near["welded_points_moved"], 16);  // 4 faces x 4 perturbed corners
    EXPECT_LT(near["weld_largest_move"].get<double>(), 1e-16);
    EXPECT_GT(near["weld_largest_move"].get<double>(), 0.0);
    EXPECT_EQ(box["welded_points_moved"], 0);
    const auto table = cli_test::run_polyvol("measure --weld-tolerance 1e-12 " + kNear);
    EXPECT_NE(table.out.find("welded at 1e-12: 16 points moved"), std::string::npos) << table.out;
}

TEST(WeldCli, ToleranceTooSmallToCloseLeavesItOpen) {
    EXPECT_EQ(cli_test::run_polyvol("volume --weld-tolerance 1e-20 " + kNear).code, 3);
    EXPECT_EQ(cli_test::run_polyvol("volume --weld-tolerance -1 " + kNear).code, 1);
    EXPECT_EQ(cli_test::run_polyvol("check --weld-tolerance 1e-12 " + kNear).code, 0);
}

}  // namespace
