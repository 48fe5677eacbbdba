// glTF 2.0 through the command (tests/data/gltf/make.py): .gltf with its
// .bin, .glb, data: URIs, fans and strips, quantized and sparse positions,
// node transforms with a bound that holds; Draco and buffers outside the
// file's directory refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

using cli_test::run_polyvol;
using nlohmann::json;

std::string gltf(const std::string& name) { return "'" + std::string(POLYVOL_TEST_DATA) + "/gltf/" + name + "'"; }

json measure(const std::string& name) {
    const auto r = run_polyvol("measure --json " + gltf(name));
    EXPECT_EQ(r.code, 0) << name << ": " << r.err;
    return json::parse(r.out)[0];
}

// |value - exact| within the stated bound (exactly equal when correctly rounded).
void within(const json& j, double exact) {
    const double v = j["volume"].get<double>();
    if (j["accuracy"] == "correctly-rounded") EXPECT_EQ(v, exact);
    else EXPECT_LE(std::fabs(v - exact), j["volume_error_bound"].get<double>());
    EXPECT_LT(j["volume_error_bound"].get<double>(), 1e-12 * exact);
}

TEST(GltfCli, TheCubeInEveryEncoding) {
    const json text = measure("cube.gltf");  // translated by (10, 0, 0)
    EXPECT_EQ(text["format"], "gltf");
    EXPECT_EQ(text["encoding"], "json");
    EXPECT_EQ(text["unit"], "m");
    within(text, 8);
    EXPECT_NEAR(text["centroid"][0].get<double>(), 11, 1e-12);
    const json glb = measure("cube.glb");  // rotated 90 degrees about z, scaled by 2
    EXPECT_EQ(glb["encoding"], "glb");
    within(glb, 64);
    EXPECT_NEAR(glb["centroid"][0].get<double>(), -2, 1e-12);
    EXPECT_NEAR(glb["centroid"][1].get<double>(), 2, 1e-12);
    EXPECT_EQ(glb["notes"][0], "gltf-transform");
    const json fans = measure("fan_strip.gltf");  // no transform: exact
    EXPECT_EQ(fans["accuracy"], "correctly-rounded");
    EXPECT_EQ(fans["volume"], 8.0);
    EXPECT_EQ(fans["closed_2_cycle"], true);
    EXPECT_EQ(fans["notes"][0], "gltf-non-triangle-primitives-skipped(1)");
    const json quantized = measure("quantized.gltf");  // normalized shorts, sparse, scale 2
    within(quantized, 8);
}

TEST(GltfCli, CompressedOrEscapingFilesAreRefusedByName) {
    const auto draco = run_polyvol("volume " + gltf("draco.gltf"));
    EXPECT_EQ(draco.code, 2);
    EXPECT_NE(draco.err.find("KHR_draco_mesh_compression"), std::string::npos) << draco.err;
    const auto escape = run_polyvol("volume " + gltf("escape.gltf"));
    EXPECT_EQ(escape.code, 2);
    EXPECT_NE(escape.err.find("outside the glTF file's directory"), std::string::npos) << escape.err;
}

}  // namespace
