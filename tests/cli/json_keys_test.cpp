// Keys of `--json` that claimed what was not so (issue #21): --volume-only
// gives no shell counts it did not compute, a triangle with a repeated vertex
// is one degenerate triangle (not two), and vtnb's edge length and area on an
// open surface are the surface's (the direct sums), as the cone method's.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path scratch(const std::string& name, const std::string& text) {
    const fs::path p = fs::temp_directory_path() / ("polyvol_json_keys_" + std::to_string(::getpid()) + "_" + name);
    std::ofstream(p) << text;
    return p;
}

json run(const std::string& args) { return json::parse(cli_test::run_polyvol(args).out)[0]; }

struct CliRunJson {
    int code;
    json j;
};
CliRunJson run_both(const std::string& args) {
    const auto r = cli_test::run_polyvol(args);
    return {r.code, json::parse(r.out)[0]};
}

TEST(JsonKeys, VolumeOnlyHasNoShellCountsItDidNotCompute) {
    const fs::path p = scratch("cube.obj", "");
    cli_test::write_boxes_obj(p, {{0, 0, 0, 1, 2, 3}});
    const json j = run("volume --volume-only --json '" + p.string() + "'");
    EXPECT_EQ(j["volume"], 6.0);
    for (const char* key : {"components", "degenerate_triangles", "shells", "cavities"})
        EXPECT_FALSE(j.contains(key)) << key;
    const json full = run("volume --json '" + p.string() + "'");
    EXPECT_EQ(full["components"], 1);
    EXPECT_EQ(full["degenerate_triangles"], 0);
    fs::remove(p);
}

TEST(JsonKeys, ATriangleWithARepeatedVertexIsOneDegenerateTriangle) {
    // a tetrahedron plus two triangles with a repeated vertex and one flat (collinear) triangle
    const fs::path p = scratch("degenerate.obj",
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 2 0 0\n"
                               "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 1 2\nf 3 4 4\nf 1 2 5\n");
    const json j = run("check --json '" + p.string() + "'");
    EXPECT_EQ(j["triangles"], 7);
    EXPECT_EQ(j["degenerate_triangles"], 3);
    fs::remove(p);
}

TEST(JsonKeys, VtnbOnAnOpenSurfaceGivesTheSurfacesAreaAndEdgeLength) {
    const fs::path p = scratch("open.obj", "");
    cli_test::write_boxes_obj(p, {{0, 0, 0, 1, 2, 3}}, /*drop_last=*/true);
    const json cone = run("measure --allow-open --json '" + p.string() + "'");
    const json vtnb = run("measure --allow-open --method vtnb --json '" + p.string() + "'");
    EXPECT_EQ(cone["edge_length"], 2 * (1 + 2 + 3) * 2.0);  // 12 edges, all kept by the open box
    EXPECT_EQ(vtnb["edge_length"], cone["edge_length"]);
    EXPECT_EQ(vtnb["area"], cone["area"]);
    // closed: Franklin's sums, within their bounds of the same values
    const fs::path q = scratch("closed.obj", "");
    cli_test::write_boxes_obj(q, {{0, 0, 0, 1, 2, 3}});
    const json closed = run("measure --method vtnb --json '" + q.string() + "'");
    EXPECT_NEAR(closed["edge_length"].get<double>(), 24.0, 1e-12);
    EXPECT_NEAR(closed["area"].get<double>(), 22.0, 1e-12);
    fs::remove(p);
    fs::remove(q);
}

TEST(JsonKeys, AFileWithoutFacesSaysSo) {
    const fs::path p = scratch("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const CliRunJson r = run_both("volume --json '" + p.string() + "'");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.j.value("warning", "").find("no faces"), std::string::npos) << r.j.dump();
    EXPECT_NE(cli_test::run_polyvol("volume '" + p.string() + "'").err.find("no faces"), std::string::npos);
    fs::remove(p);
}

// --accuracy fast on a part far from the origin: its bound would mean wrong
// leading digits, so the moments are computed correctly rounded and say so.
TEST(JsonKeys, FastFallsBackWhereItsBoundMeansNothing) {
    const fs::path p = scratch("far.obj", "");
    cli_test::write_boxes_obj(p, {{1e5, 1e5, 1e5, 1e5 + 1, 1e5 + 2, 1e5 + 3}});  // 6 digits: written exactly
    const json j = run("measure --accuracy fast --json '" + p.string() + "'");
    EXPECT_EQ(j["volume"], 6.0);
    EXPECT_EQ(j["accuracy"], "correctly-rounded");
    EXPECT_EQ(j["moments_accuracy"], "correctly-rounded");
    EXPECT_EQ(j["inertia"][2][2], 6.0 * (1 + 4) / 12);
    const fs::path q = scratch("near.obj", "");
    cli_test::write_boxes_obj(q, {{0, 0, 0, 1, 2, 3}});
    EXPECT_EQ(run("measure --accuracy fast --json '" + q.string() + "'")["moments_accuracy"], "error-bound");
    fs::remove(p);
    fs::remove(q);
}

}  // namespace
