// `polyvol ndim` and `polyvol area` as users run them: JSON keys and values,
// exit codes (0 ok, 1 usage, 2 unreadable, 3 unmatched faces), messages.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using cli_test::CliRun;

CliRun polyvol(const std::string& args) { return cli_test::run_polyvol(args); }

// The boundary of the cross-polytope in R^n as .chain text; `drop` removes
// that simplex, `flip` reverses that one.
std::string cross_polytope(int n, int drop = -1, int flip = -1) {
    std::ostringstream s;
    const int k = 1 << n;
    s << "# cross-polytope in R^" << n << ", volume 2^n/n!\n" << n << " " << 2 * n << " " << (k - (drop >= 0)) << "\n";
    for (int v = 0; v < 2 * n; ++v) {
        for (int i = 0; i < n; ++i) s << (i == v / 2 ? (v % 2 ? -1 : 1) : 0) << (i + 1 < n ? " " : "\n");
    }
    for (int mask = 0; mask < k; ++mask) {
        if (mask == drop) continue;
        std::vector<int> f;
        int neg = 0;
        for (int i = 0; i < n; ++i) {
            f.push_back(2 * i + ((mask >> i) & 1));
            neg += (mask >> i) & 1;
        }
        if ((neg % 2 == 1) != (mask == flip)) std::swap(f[0], f[1]);
        for (int i = 0; i < n; ++i) s << f[i] << (i + 1 < n ? " " : "\n");
    }
    return s.str();
}

class NdimCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("polyvol_ndim_cli_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string file(const std::string& name, const std::string& text) {
        const fs::path p = dir_ / name;
        std::ofstream(p) << text;
        return "'" + p.string() + "'";
    }
    fs::path dir_;
};

}  // namespace

TEST_F(NdimCli, JsonHasTheDocumentedKeys) {
    const CliRun r = polyvol("ndim --json " + file("x5.chain", cross_polytope(5)));
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out)[0];
    for (const char* key : {"dimension", "simplices", "formula", "volume", "error_bound", "centroid", "unmatched_faces"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["dimension"], 5);
    EXPECT_EQ(j["simplices"], 32);
    EXPECT_EQ(j["formula"], "cone");
    EXPECT_EQ(j["unmatched_faces"], 0);
    const double want = 32.0 / 120;
    EXPECT_LE(std::abs(j["volume"].get<double>() - want), j["error_bound"].get<double>());
    EXPECT_LT(j["error_bound"].get<double>(), 1e-13);
    EXPECT_EQ(j["centroid"].size(), 5u);
    EXPECT_EQ(j["correctly_rounded"], false);
}

TEST_F(NdimCli, PrismFormulaAndRefactorTraversal) {
    const CliRun r = polyvol("ndim --json --formula prism --traversal refactor " + file("x4.chain", cross_polytope(4)));
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out)[0];
    EXPECT_EQ(j["formula"], "prism");
    EXPECT_EQ(j["traversal"], "refactor");
    EXPECT_LE(std::abs(j["volume"].get<double>() - 16.0 / 24), j["error_bound"].get<double>());
}

TEST_F(NdimCli, ThreeDimensionsIsCorrectlyRounded) {
    const CliRun r = polyvol("ndim --json " + file("x3.chain", cross_polytope(3)));
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out)[0];
    EXPECT_EQ(j["volume"].get<double>(), 8.0 / 6);
    EXPECT_EQ(j["error_bound"].get<double>(), 0.0);
    EXPECT_EQ(j["correctly_rounded"], true);
    // The text report says so.
    const CliRun t = polyvol("ndim " + file("x3b.chain", cross_polytope(3)));
    EXPECT_EQ(t.code, 0);
    EXPECT_NE(t.out.find("correctly rounded"), std::string::npos) << t.out;
}

TEST_F(NdimCli, MissingSimplexExitsThree) {
    const CliRun r = polyvol("ndim --json " + file("open.chain", cross_polytope(4, 3)));
    EXPECT_EQ(r.code, 3);
    EXPECT_NE(r.err.find("unmatched"), std::string::npos) << r.err;
    const json j = json::parse(r.out)[0];
    EXPECT_EQ(j["unmatched_faces"], 4);
    EXPECT_EQ(j["boundary_faces"], 4);
    EXPECT_TRUE(j["volume"].is_null());
    EXPECT_TRUE(j.contains("unmatched_example"));
    const CliRun a = polyvol("ndim --allow-open --json " + file("open2.chain", cross_polytope(4, 3)));
    EXPECT_EQ(a.code, 0);
    EXPECT_TRUE(json::parse(a.out)[0]["volume"].is_number());
}

TEST_F(NdimCli, FlippedSimplexExitsThreeUnlessOriented) {
    const std::string f = file("flip.chain", cross_polytope(4, -1, 6));
    const CliRun r = polyvol("ndim --json " + f);
    EXPECT_EQ(r.code, 3);
    EXPECT_EQ(json::parse(r.out)[0]["misoriented_faces"], 4);
    const CliRun o = polyvol("ndim --orient --json " + f);
    ASSERT_EQ(o.code, 0) << o.err;
    const json j = json::parse(o.out)[0];
    EXPECT_LE(std::abs(j["volume"].get<double>() - 16.0 / 24), j["error_bound"].get<double>());
}

TEST_F(NdimCli, QhullOutputFromStdin) {
    const CliRun r = polyvol("ndim --json - < /dev/null");
    EXPECT_EQ(r.code, 2);
    int status = std::system("command -v qconvex >/dev/null 2>&1");
    ASSERT_EQ(status, 0) << "qconvex not found: install qhull-bin";
    const fs::path off = dir_ / "cube4.off";
    status = std::system(("rbox c D4 | qconvex o Qt > '" + off.string() + "'").c_str());
    ASSERT_EQ(status, 0);
    const CliRun c = polyvol("ndim --json - < '" + off.string() + "'");
    ASSERT_EQ(c.code, 0) << c.err;
    const json j = json::parse(c.out)[0];
    EXPECT_EQ(j["format"], "qhull");
    EXPECT_EQ(j["unmatched_faces"], 0);
    EXPECT_LE(std::abs(j["volume"].get<double>() - 1.0), j["error_bound"].get<double>() + 1e-15);
}

TEST_F(NdimCli, UnreadableAndUsage) {
    const CliRun r = polyvol("ndim " + file("bad.chain", "2 3 1\n0 0\n1 zero\n0 1\n0 1\n"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("bad.chain:3:"), std::string::npos) << r.err;
    EXPECT_EQ(polyvol("ndim /nonexistent/x.chain").code, 2);
    EXPECT_EQ(polyvol("ndim --formula pyramid " + file("x2.chain", cross_polytope(2))).code, 1);
    EXPECT_EQ(polyvol("ndim").code, 1);
}

TEST_F(NdimCli, AreaOfPolygonsWithHoles) {
    const std::string f = file("holes.txt",
                               "# outer counter-clockwise, hole clockwise\n"
                               "0 0 10 0 10 10 0 10\n"
                               "2 2 2 8 8 8 8 2\n");
    for (const char* formula : {"cone", "prism"}) {
        const CliRun r = polyvol(std::string("area --json --formula ") + formula + " " + f);
        ASSERT_EQ(r.code, 0) << r.err;
        const json j = json::parse(r.out)[0];
        EXPECT_EQ(j["area"].get<double>(), 64.0);
        EXPECT_EQ(j["volume"].get<double>(), 64.0);
        EXPECT_EQ(j["correctly_rounded"], true);
        EXPECT_EQ(j["centroid"], json::array({5.0, 5.0}));
        EXPECT_EQ(j["unmatched_faces"], 0);
    }
    // All loops listed clockwise: --orient makes the outer one positive, the hole negative.
    const std::string g = file("cw.txt", "0 0 0 10 10 10 10 0\n2 2 2 8 8 8 8 2\n");
    EXPECT_EQ(json::parse(polyvol("area --json " + g).out)[0]["area"].get<double>(), -64.0 - 72.0);
    EXPECT_EQ(json::parse(polyvol("area --orient --json " + g).out)[0]["area"].get<double>(), 64.0);
    const CliRun t = polyvol("area " + f);
    EXPECT_NE(t.out.find("area        64"), std::string::npos) << t.out;
    EXPECT_EQ(t.err.find("wound like"), std::string::npos) << t.err;
    // A hole wound like its outer loop counts as land: said, and --orient fixes it.
    const std::string h = file("ccw_hole.txt", "0 0 10 0 10 10 0 10\n2 2 8 2 8 8 2 8\n");
    const CliRun w = polyvol("area --json " + h);
    ASSERT_EQ(w.code, 0) << w.err;
    EXPECT_NE(w.err.find("1 loop is wound like the loop around it"), std::string::npos) << w.err;
    EXPECT_NE(w.err.find("--orient"), std::string::npos) << w.err;
    EXPECT_EQ(json::parse(w.out)[0]["area"].get<double>(), 136.0);
    EXPECT_EQ(json::parse(w.out)[0]["loops_wound_like_container"], 1);
    const CliRun fixed = polyvol("area --orient --json " + h);
    EXPECT_EQ(json::parse(fixed.out)[0]["area"].get<double>(), 64.0);
    EXPECT_EQ(fixed.err.find("wound like"), std::string::npos) << fixed.err;
}
