// Per part and per shell (issue #21): measure --json gives each 3MF object's
// (build item's) and each shell's own volume, area and centroid with their
// bounds; the report lists them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

using cli_test::run_polyvol;
using nlohmann::json;

TEST(PartsCli, EachObjectOfA3mfHasItsFigures) {
    const std::string file = "'" + std::string(POLYVOL_TEST_DATA) + "/parts/two_parts.3mf'";
    const auto r = run_polyvol("measure --json " + file);
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out)[0];
    ASSERT_EQ(j["parts"].size(), 2u);
    const json& block = j["parts"][0];
    EXPECT_EQ(block["name"], "block");
    EXPECT_EQ(block["faces"], 12);
    EXPECT_EQ(block["volume"], 24.0);
    EXPECT_EQ(block["volume_error_bound"], 0.0);  // no transform: exact
    EXPECT_EQ(block["area"], 52.0);
    EXPECT_EQ(block["centroid"], json::array({1.0, 1.5, 2.0}));
    const json& pin = j["parts"][1];
    EXPECT_EQ(pin["name"], "pin");
    EXPECT_LE(std::fabs(pin["volume"].get<double>() - 1.0 / 6.0), pin["volume_error_bound"].get<double>() + 0x1p-53);
    EXPECT_NEAR(pin["centroid"][0].get<double>(), 10.25, pin["centroid_error_bound"].get<double>() + 1e-15);
    // the shells are the same two pieces here, largest first
    ASSERT_EQ(j["shells"].size(), 2u);
    EXPECT_EQ(j["shells"][0]["volume"], 24.0);
    EXPECT_EQ(j["shells"][0]["centroid"], json::array({1.0, 1.5, 2.0}));
    const auto table = run_polyvol("measure " + file);
    EXPECT_NE(table.out.find("part block: volume 24 mm³, area 52 mm², centroid (1, 1.5, 2) mm, 12 faces"),
              std::string::npos)
        << table.out;
    EXPECT_NE(table.out.find("shell 2: volume"), std::string::npos) << table.out;
}

}  // namespace
