// `polyvol check` on hand-written files (tests/data/check/): holes (boundary
// loops), STL facet normals against the winding, and the exit code scripts
// rely on (3: not a closed 2-cycle).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kData = std::string(POLYVOL_TEST_DATA) + "/check/";

TEST(CheckCli, CountsFacetNormalsAgainstTheWinding) {
    const auto r = cli_test::run_polyvol("check --json '" + kData + "tetra_one_normal_flipped.stl'");
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out)[0];
    EXPECT_EQ(j["facet_normals_against_winding"], 1);
    EXPECT_EQ(j["holes"], 0);
    const auto table = cli_test::run_polyvol("check '" + kData + "tetra_one_normal_flipped.stl'");
    EXPECT_NE(table.out.find("facet normals   1 of 4 point against"), std::string::npos) << table.out;
    // The winding decides: the volume is the outward tetrahedron's.
    const json v = json::parse(cli_test::run_polyvol("volume --json '" + kData + "tetra_one_normal_flipped.stl'").out)[0];
    EXPECT_EQ(v["volume"], 1.0 / 6.0);
}

// A binary STL of the same tetrahedron, every normal reversed but one.
TEST(CheckCli, CountsBinaryFacetNormalsAgainstTheWinding) {
    const float tri[4][9] = {{0, 0, 0, 0, 1, 0, 1, 0, 0},
                             {0, 0, 0, 1, 0, 0, 0, 0, 1},
                             {0, 0, 0, 0, 0, 1, 0, 1, 0},
                             {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    const float normal[4][3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {1, 1, 1}};  // the last one agrees
    const fs::path p = fs::temp_directory_path() / ("polyvol_check_cli_" + std::to_string(::getpid()) + ".stl");
    {
        std::ofstream out(p, std::ios::binary);
        out << std::string(80, ' ');
        const uint32_t n = 4;
        out.write(reinterpret_cast<const char*>(&n), 4);
        for (int t = 0; t < 4; ++t) {
            out.write(reinterpret_cast<const char*>(normal[t]), 12);
            out.write(reinterpret_cast<const char*>(tri[t]), 36);
            out.write("\0\0", 2);
        }
    }
    const auto r = cli_test::run_polyvol("check --json '" + p.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out)[0]["facet_normals_against_winding"], 3);
    fs::remove(p);
}

TEST(CheckCli, CountsHolesAndExitsThreeWhenOpen) {
    const auto r = cli_test::run_polyvol("check --json '" + kData + "open_tube.obj'");
    EXPECT_EQ(r.code, 3);
    const json j = json::parse(r.out)[0];
    EXPECT_EQ(j["boundary_edges"], 8);
    EXPECT_EQ(j["holes"], 2);
    EXPECT_FALSE(j.contains("facet_normals_against_winding"));  // an STL key
    const auto table = cli_test::run_polyvol("check '" + kData + "open_tube.obj'");
    EXPECT_EQ(table.code, 3);
    EXPECT_NE(table.out.find("8 edges in 2 holes"), std::string::npos) << table.out;
}

}  // namespace
