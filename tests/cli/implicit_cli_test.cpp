// `polyvol implicit` as users run it: JSON keys, exit codes (0 ok, 1 usage,
// 2 an expression that does not parse, 3 NaN / the solid reaching the box with
// --box-rule error), the clipping warning, and --stl.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"
#include "output/format.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using CliResult = cli_test::CliRun;

CliResult polyvol(const std::string& args) { return cli_test::run_polyvol(args); }

TEST(ImplicitCli, JsonHasTheKeysAndTheBallVolume) {
    const CliResult r = polyvol("implicit 'x^2 + y^2 + z^2 - 1' --dim 3 --box -1.25:1.25 --h 0.0625 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    for (const char* key : {"dimension", "h", "volume", "error_estimate", "boundary_simplices", "seconds",
                            "volume_pl", "volume_pl_2h", "spacing", "clipped"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["dimension"], 3);
    EXPECT_EQ(j["h"].get<double>(), 0.0625);
    const double exact = 4.0 / 3.0 * std::numbers::pi;
    EXPECT_NEAR(j["volume"].get<double>(), exact, 1e-3 * exact);
    EXPECT_LE(std::fabs(j["volume"].get<double>() - exact), j["error_estimate"].get<double>());
    EXPECT_GT(j["boundary_simplices"].get<int>(), 1000);
    EXPECT_FALSE(j["clipped"].get<bool>());
}

// The default streams the volume; --formula prism builds the chain. Both
// measure the same PL solid: they agree within their rounding bounds.
TEST(ImplicitCli, StreamedAndPrismAgree) {
    const std::string ball = "implicit 'x1^2 + x2^2 + x3^2 + x4^2 - 1' --box 0:1.2 --h 0.2 --no-estimate --json";
    const CliResult streamed = polyvol(ball), prism = polyvol(ball + " --formula prism");
    ASSERT_EQ(streamed.code, 0) << streamed.err;
    ASSERT_EQ(prism.code, 0) << prism.err;
    const json a = json::parse(streamed.out), b = json::parse(prism.out);
    EXPECT_TRUE(a["streamed"].get<bool>());
    EXPECT_FALSE(b["streamed"].get<bool>());
    EXPECT_EQ(a["boundary_simplices"], b["boundary_simplices"]);
    EXPECT_LE(std::fabs(a["volume"].get<double>() - b["volume"].get<double>()),
              a["fine"]["rounding_error_bound"].get<double>() + b["fine"]["rounding_error_bound"].get<double>());
    const double exact = std::numbers::pi * std::numbers::pi / 2;  // the PL solid at h = 0.2: 5.3% less
    EXPECT_NEAR(16 * a["volume"].get<double>(), 0.947 * exact, 0.005 * exact);
}

TEST(ImplicitCli, TableAndDimensionFromTheExpression) {
    const CliResult r = polyvol("implicit 'x1^2 + x2^2 + x3^2 + x4^2 - 1' --box 0:1.2 --h 0.2");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("dimension           4"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("boundary simplices"), std::string::npos) << r.out;
    // Each volume beside its own estimate, with the digits the estimate leaves
    // (the JSON holds every digit).
    const json j = json::parse(polyvol("implicit 'x1^2 + x2^2 + x3^2 + x4^2 - 1' --bounds 0:1.2 --h 0.2 --json").out);
    const double e = j["error_estimate"].get<double>();
    ASSERT_GT(e, 1e-3);
    EXPECT_NE(r.out.find("volume              " + polyvol::cli::plus_minus(j["volume"].get<double>(), e, 0)),
              std::string::npos) << r.out;
    EXPECT_NE(r.out.find("PL volume at h      " + polyvol::cli::plus_minus(j["volume_pl"].get<double>(), e, 0)),
              std::string::npos) << r.out;
    EXPECT_NE(r.out.find("PL volume at 2h     "), std::string::npos) << r.out;
    EXPECT_LT(polyvol::cli::number_text(j["volume"].get<double>(), e, 0).size(), 8u);  // not 17 digits
    EXPECT_NE(r.err.find("clipped"), std::string::npos) << r.err;  // the orthant: clipped, with a warning
}

// The Richardson value with its own estimate (from the 4h lattice): the
// ball's volume to five or six digits, not V(h)'s three (#33 item 14).
TEST(ImplicitCli, ExtrapolatedVolumeWithItsOwnEstimate) {
    const std::string ball = "implicit 'x^2 + y^2 + z^2 - 1' --dim 3 --bounds -1.5:1.5";
    const CliResult r = polyvol(ball);
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(polyvol(ball + " --json").out);
    const double e = j["extrapolated_error_estimate"].get<double>();
    const double exact = 4.0 / 3.0 * std::numbers::pi;
    EXPECT_LE(std::fabs(j["volume"].get<double>() - exact), e);
    EXPECT_LT(e, j["error_estimate"].get<double>() / 10);
    EXPECT_TRUE(j.contains("volume_pl_4h"));
    EXPECT_NE(r.out.find("volume              " + polyvol::cli::plus_minus(j["volume"].get<double>(), e, 0)),
              std::string::npos) << r.out;
    EXPECT_NE(r.out.find("4.18879"), std::string::npos) << r.out;
    // a square whose sides fall between lattice planes: no h^2 regime, and the table says so
    const CliResult square = polyvol("implicit 'max(abs(x),abs(y)) - 1' --dim 2 --bounds -1.5:1.5");
    EXPECT_NE(square.out.find("this estimate may not hold"), std::string::npos) << square.out;
}

TEST(ImplicitCli, PerAxisBoxAndNoEstimate) {
    const CliResult r = polyvol("implicit 'x^2/4 + y^2 - 1' --box -2.5:2.5,-1.5:1.5 --h 0.01 --no-estimate --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["dimension"], 2);
    EXPECT_TRUE(j["error_estimate"].is_null());
    EXPECT_NEAR(j["volume"].get<double>(), 2 * std::numbers::pi, 1e-3);
}

TEST(ImplicitCli, ExitCodes) {
    EXPECT_EQ(polyvol("implicit 'x^2 + ' --dim 2 --box -1:1").code, 1);            // does not parse
    EXPECT_EQ(polyvol("implicit 'x + foo' --dim 2 --box -1:1").code, 1);           // unknown name
    EXPECT_EQ(polyvol("implicit 'x + z' --dim 2 --box -1:1").code, 1);             // z beyond n = 2
    EXPECT_EQ(polyvol("implicit 'x^2 + y^2 - 1' --dim 2 --box 1").code, 1);        // bad box
    EXPECT_EQ(polyvol("implicit 'x^2 + y^2 - 1' --dim 2 --box 1:-1").code, 1);     // empty box
    EXPECT_EQ(polyvol("implicit 'x^2 + y^2 - 1' --dim 2 --box -2:2 --stl /dev/null").code, 1);  // --stl is 3D
    const CliResult nan = polyvol("implicit 'sqrt(x) - 0.5' --dim 2 --box -1:1 --h 0.1");
    EXPECT_EQ(nan.code, 3);
    EXPECT_NE(nan.err.find("NaN"), std::string::npos) << nan.err;
    const CliResult touch = polyvol("implicit 'x^2 + y^2 - 1' --dim 2 --box -1:1 --h 0.1 --box-rule error");
    EXPECT_EQ(touch.code, 3);
    EXPECT_NE(touch.err.find("box"), std::string::npos) << touch.err;
    const CliResult clip = polyvol("implicit 'x^2 + y^2 - 1' --dim 2 --box 0:1 --h 0.01 --json");
    EXPECT_EQ(clip.code, 0);
    EXPECT_NEAR(json::parse(clip.out)["volume"].get<double>(), std::numbers::pi / 4, 1e-4);
    // a lattice beyond --max-memory: refused before the fine pass, exit 3, the limit named
    const CliResult big = polyvol("implicit 'x^2 + y^2 + z^2 - 1' --box -1.5:1.5 --h 0.004 --max-memory 200M");
    EXPECT_EQ(big.code, 3);
    EXPECT_NE(big.err.find("--max-memory 200 MiB"), std::string::npos) << big.err;
    EXPECT_NE(big.err.find("estimated from the 2h lattice"), std::string::npos) << big.err;
    EXPECT_EQ(polyvol("implicit 'x^2 + y^2 - 1' --box -2:2 --max-memory lots").code, 1);
}

TEST(ImplicitCli, EmptySet) {
    const CliResult r = polyvol("implicit 'x^2 + y^2 + z^2 + 1' --box -1:1 --h 0.1 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["volume"].get<double>(), 0.0);
    EXPECT_EQ(j["boundary_simplices"], 0);
}

TEST(ImplicitCli, StlIsTheSurface) {
    const fs::path stl = fs::temp_directory_path() / ("polyvol_implicit_" + std::to_string(::getpid()) + ".stl");
    const CliResult r = polyvol("implicit 'x^2 + y^2 + z^2 - 1' --box -1.5:1.5 --h 0.1 --json --stl '" + stl.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    // Every boundary simplex but those with two corners at one point (left out).
    const auto triangles = json::parse(r.out)["boundary_simplices"].get<std::uintmax_t>();
    const json check = json::parse(polyvol("check --json '" + stl.string() + "'").out)[0];
    EXPECT_EQ(fs::file_size(stl), 84 + 50 * check["triangles"].get<std::uintmax_t>());
    EXPECT_LE(check["triangles"].get<std::uintmax_t>(), triangles);
    EXPECT_GT(check["triangles"].get<std::uintmax_t>(), triangles * 95 / 100);  // 264 of 11280 dropped at h = 0.1
    // A closed 2-cycle, edge-manifold; what zero-area triangles remain have three distinct collinear corners.
    EXPECT_EQ(check["closed_2_cycle"], true);
    EXPECT_EQ(check["nonmanifold_edges"], 0);
    EXPECT_LT(check["degenerate_triangles"].get<int>(), 100);
    // The STL measures like the PL solid it came from.
    const CliResult m = polyvol("volume --json '" + stl.string() + "'");
    EXPECT_EQ(m.code, 0) << m.err;
    EXPECT_NEAR(json::parse(m.out)[0]["volume"].get<double>(), json::parse(r.out)["volume_pl"].get<double>(), 1e-5);
    // The torus of the issue (88 non-manifold edges and 128 zero-area triangles before): clean, genus 1.
    const CliResult t = polyvol("implicit '(sqrt(x^2+y^2) - 1)^2 + z^2 - 0.16' --bounds -1.5:1.5,-1.5:1.5,-0.5:0.5 "
                                "--h 0.05 -o '" + stl.string() + "'");
    ASSERT_EQ(t.code, 0) << t.err;
    const json torus = json::parse(polyvol("check --json '" + stl.string() + "'").out)[0];
    EXPECT_EQ(torus["nonmanifold_edges"], 0);
    EXPECT_EQ(torus["degenerate_triangles"], 0);
    EXPECT_EQ(torus["components"], 1);
    EXPECT_EQ(torus["shells"][0]["genus"], 1);
    fs::remove(stl);
}

}  // namespace
