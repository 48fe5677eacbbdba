// Convex hulls of random points in R^3 .. R^7: `qconvex o Qt` read as a chain
// gives the volume `qconvex FA` prints (8 significant digits). The test needs
// qconvex (Debian qhull-bin) and fails without it.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "polyvol/chain_io.hpp"
#include "polyvol/simplicial.hpp"

using namespace polyvol;
namespace fs = std::filesystem;

namespace {

std::string run(const std::string& cmd, int& status) {
    std::string out;
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) {
        status = -1;
        return out;
    }
    std::array<char, 4096> buf;
    std::size_t got;
    while ((got = std::fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), got);
    status = ::pclose(p);
    return out;
}

}  // namespace

TEST(Qhull, ConvexHullVolumesMatchQconvex) {
    int status = 0;
    run("command -v qconvex >/dev/null 2>&1", status);
    ASSERT_EQ(status, 0) << "qconvex not found: install qhull-bin";
    const fs::path dir = fs::temp_directory_path() / ("polyvol_qhull_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::mt19937_64 rng(2024);
    std::normal_distribution<double> g;
    for (int n = 3; n <= 7; ++n) {
        for (int trial = 0; trial < 2; ++trial) {
            const int count = n <= 5 ? 60 : 24;
            const fs::path in = dir / ("pts" + std::to_string(n) + "_" + std::to_string(trial) + ".txt");
            {
                std::ofstream f(in);
                f.precision(17);
                f << n << "\n" << count << "\n";
                for (int i = 0; i < count; ++i) {
                    for (int k = 0; k < n; ++k) f << (trial == 1 ? 100 + 3 * k : 0) + g(rng) << " ";
                    f << "\n";
                }
            }
            const fs::path off = dir / ("hull" + std::to_string(n) + ".off");
            run("qconvex o Qt < '" + in.string() + "' > '" + off.string() + "'", status);
            ASSERT_EQ(status, 0);
            const std::string fa = run("qconvex FA Qt < '" + in.string() + "' 2>&1", status);
            ASSERT_EQ(status, 0);
            // "Total volume: X" or "Approximate volume: X" (8 significant digits).
            const std::size_t at = fa.find(" volume:");
            ASSERT_NE(at, std::string::npos) << fa;
            const double want = std::strtod(fa.c_str() + at + 8, nullptr);
            ASSERT_GT(want, 0) << fa;

            const LoadedChain l = read_chain_file(off.string());
            EXPECT_EQ(l.format, ChainFormat::qhull);
            EXPECT_EQ(l.chain.dimension, n);
            for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
                ChainOptions o;
                o.formula = f;
                const ChainVolume v = chain_volume(l.chain.view(), o);
                EXPECT_EQ(v.topology.unmatched_faces, 0u) << n;
                EXPECT_NEAR(v.volume, want, 1e-7 * want + 1e-12) << "n=" << n << " trial " << trial;
                EXPECT_LT(v.volume_error_bound, 1e-8 * want);
            }
        }
    }
    fs::remove_all(dir);
}
