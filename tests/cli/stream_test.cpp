// `polyvol volume` on binary STL through the streaming path: the table, JSON
// with --stream, and the fall-back to the full path for open surfaces.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"
#include "common/manifest.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path& kCorpus = polyvol::test::corpus_dir();

using cli_test::CliRun;

CliRun polyvol(const std::string& args) { return cli_test::run_polyvol(args); }

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

TEST(CliStream, EveryClosedBinaryStlStreamsToTheManifestVolume) {
    const json& manifest = polyvol::test::corpus_manifest();
    ASSERT_FALSE(manifest.empty()) << "corpus missing at " << kCorpus;
    int streamed = 0, open = 0;
    for (const auto& e : manifest) {
        if (e.value("format", "") != "stl" || e.value("encoding", "") != "binary_le") continue;
        const std::string rel = e["path"].get<std::string>();
        SCOPED_TRACE(rel);
        const double volume = polyvol::test::corpus_reference(e["volume"]);
        const CliRun r = polyvol("volume --json --stream " + quoted(kCorpus / rel));
        const json j = json::parse(r.out)[0];
        if (e["topology"]["closed_2_cycle"].get<bool>()) {
            ++streamed;
            ASSERT_EQ(r.code, 0) << r.err;
            EXPECT_TRUE(j.value("streamed", false));
            EXPECT_EQ(j["volume"].get<double>(), volume);
            EXPECT_EQ(j["accuracy"], "correctly-rounded");
            EXPECT_EQ(j["triangles"], e["counts"]["triangles"]);
            for (const char* key : {"area", "area_relative_error", "centroid", "moments_accuracy", "first_moments"})
                EXPECT_TRUE(j.contains(key)) << key;
            EXPECT_EQ(j["moments_accuracy"], "correctly-rounded");  // as loaded
        } else {
            // Open: the fingerprint says so, the full path names the edges.
            ++open;
            EXPECT_EQ(r.code, 3);
            EXPECT_FALSE(j.contains("streamed"));
            EXPECT_EQ(j["unbalanced_edges"], e["topology"]["unbalanced_edges"]);
            EXPECT_NE(r.err.find("unbalanced edge"), std::string::npos) << r.err;
        }
    }
    EXPECT_GE(streamed, 10);
    EXPECT_GE(open, 3);
}

TEST(CliStream, TableStreamsAndStatesTheGuarantees) {
    const fs::path torus = kCorpus / "meshes/prusa-slicer/torus.stl";
    const CliRun r = polyvol("volume --verbose --stream " + quoted(torus));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("streamed: its shells were not checked for overlap"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("correctly rounded"), std::string::npos);
    EXPECT_NE(r.out.find("area relative error <="), std::string::npos);
    EXPECT_NE(r.out.find("centroid within"), std::string::npos);  // the table's: pass 1's bound
    // The same volume as the full path prints.
    const CliRun full = polyvol("volume --json " + quoted(torus));
    ASSERT_EQ(full.code, 0);
    const json j = json::parse(full.out)[0];
    EXPECT_FALSE(j.contains("streamed"));
    EXPECT_TRUE(j.contains("second_moments"));
    char shortest[64];
    std::snprintf(shortest, sizeof shortest, "%.17g", j["volume"].get<double>());
    const CliRun again = polyvol("volume --json --stream " + quoted(torus));
    const json a = json::parse(again.out)[0];
    EXPECT_TRUE(a.value("streamed", false));
    EXPECT_EQ(a["volume"].get<double>(), j["volume"].get<double>()) << shortest;
    // One result type: the streamed centroid and first moments are the loaded ones, bit for bit.
    EXPECT_EQ(a["centroid"], j["centroid"]);
    EXPECT_EQ(a["first_moments"], j["first_moments"]);
    EXPECT_EQ(a["moments_accuracy"], j["moments_accuracy"]);
}

// Two cubes of side 2 overlapping in a unit cube, as one binary STL: the
// solid is 15, the shells' sum 16.
fs::path two_overlapping_cubes_stl() {
    const fs::path p = fs::temp_directory_path() / ("polyvol_stream_two_cubes_" + std::to_string(::getpid()) + ".stl");
    std::ofstream out(p, std::ios::binary);
    const char header[80] = {};
    out.write(header, 80);
    const uint32_t n = 24;
    out.write(reinterpret_cast<const char*>(&n), 4);
    const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                              {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    for (const float o : {0.0f, 1.0f}) {
        const float v[8][3] = {{o, o, o},         {o + 2, o, o},     {o + 2, o + 2, o},     {o, o + 2, o},
                               {o, o, o + 2},     {o + 2, o, o + 2}, {o + 2, o + 2, o + 2}, {o, o + 2, o + 2}};
        for (const auto& f : faces) {
            float record[12] = {};
            for (int i = 0; i < 3; ++i)
                for (int k = 0; k < 3; ++k) record[3 + 3 * i + k] = v[f[i]][k];
            out.write(reinterpret_cast<const char*>(record), sizeof record);
            const uint16_t attribute = 0;
            out.write(reinterpret_cast<const char*>(&attribute), 2);
        }
    }
    return p;
}

TEST(CliStream, ABinaryStlOfOverlappingShellsGivesItsSolidInTheTable) {
    // Up to 250000 triangles a binary STL is checked in full, as every other
    // file: the table gives the solid, as the JSON does.
    const fs::path two = two_overlapping_cubes_stl();
    const CliRun table = polyvol("volume " + quoted(two));
    ASSERT_EQ(table.code, 0) << table.err;
    EXPECT_NE(table.out.find(" 15 "), std::string::npos) << table.out;
    EXPECT_EQ(table.out.find(" 16 "), std::string::npos) << table.out;
    EXPECT_EQ(table.out.find("streamed"), std::string::npos) << table.out;
    const CliRun only = polyvol("volume --volume-only " + quoted(two));
    EXPECT_NE(only.out.find(" 15"), std::string::npos) << only.out;
    const json j = json::parse(polyvol("volume --json " + quoted(two)).out)[0];
    EXPECT_EQ(j["volume"].get<double>(), 15.0);
    // --stream asks for the stream at any size: the shells' sum, and the
    // table says the shells were not checked.
    const CliRun streamed = polyvol("volume --stream " + quoted(two));
    ASSERT_EQ(streamed.code, 0) << streamed.err;
    EXPECT_NE(streamed.out.find(" 16 "), std::string::npos) << streamed.out;
    EXPECT_NE(streamed.out.find("streamed: its shells were not checked for overlap, so the figures are the shells' sums"),
              std::string::npos)
        << streamed.out;
    const json s = json::parse(polyvol("volume --json --stream " + quoted(two)).out)[0];
    EXPECT_TRUE(s.value("streamed", false));
    EXPECT_EQ(s["overlap_checked"], false);
    EXPECT_EQ(s["volume"].get<double>(), 16.0);
    fs::remove(two);
}

TEST(CliStream, OpenSurfaceInTheTableIsCheckedInFull) {
    const CliRun r = polyvol("volume " + quoted(kCorpus / "meshes/stl-models/bunny.bin.stl"));
    EXPECT_EQ(r.code, 3);
    EXPECT_NE(r.err.find("unbalanced edge"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("open surface"), std::string::npos) << r.out;
    // --allow-open measures it anyway, through the full path.
    const CliRun allowed = polyvol("volume --verbose --allow-open " + quoted(kCorpus / "meshes/stl-models/bunny.bin.stl"));
    EXPECT_EQ(allowed.code, 0) << allowed.err;
    EXPECT_EQ(allowed.out.find("streamed: its shells"), std::string::npos);
}

TEST(CliStream, OtherMethodsAndFormatsUseTheFullPath) {
    const CliRun prism = polyvol("volume --verbose --method prism " + quoted(kCorpus / "meshes/prusa-slicer/torus.stl"));
    EXPECT_EQ(prism.code, 0);
    EXPECT_EQ(prism.out.find("streamed: its shells"), std::string::npos);
    const CliRun ascii = polyvol("volume --verbose " + quoted(kCorpus / "meshes/stl-models/unitCube.ascii.stl"));
    EXPECT_EQ(ascii.code, 0);
    EXPECT_EQ(ascii.out.find("streamed: its shells"), std::string::npos);
}

TEST(CliStream, VolumeOnlyGivesTheManifestVolumeOnEveryPath) {
    // Every closed corpus mesh the CLI reads: --volume-only gives the
    // manifest's correctly rounded volume, streamed (binary STL) or through
    // signed_volume (the rest), and no other figure.
    const json& manifest = polyvol::test::corpus_manifest();
    ASSERT_FALSE(manifest.empty()) << "corpus missing at " << kCorpus;
    int checked = 0, streamed = 0;
    for (const auto& e : manifest) {
        if (!e.contains("topology") || !e["topology"].is_object() || !e["topology"]["closed_2_cycle"].get<bool>() ||
            !e["volume"].is_object())
            continue;
        const std::string rel = e["path"].get<std::string>();
        SCOPED_TRACE(rel);
        const double volume = polyvol::test::corpus_reference(e["volume"]);
        // --signed: an inside-out file's signed sums, the manifest's (by
        // default its shells are turned outward: below).
        const CliRun r = polyvol("volume --volume-only --json --stream --signed " + quoted(kCorpus / rel));
        ASSERT_EQ(r.code, 0) << r.err;
        const json j = json::parse(r.out)[0];
        // 3MF transforms: the manifest transforms in rationals, polyvol rounds
        // each transformed coordinate to a double (tests/corpus/corpus_test.cpp)
        // and says so with a bound; the full path's volume of those doubles
        // is the reference then.
        const auto& quirks = e["quirks"];
        // Where shells overlap the volume is the solid's; the manifest's figure
        // is the shells' sum, `winding_volume` (unless streamed: not checked).
        auto winding = [](const json& x) { return (x.contains("winding_volume") ? x["winding_volume"] : x["volume"]).get<double>(); };
        if (std::find(quirks.begin(), quirks.end(), "3mf-transform") == quirks.end() && e.value("exact", false)) {
            EXPECT_EQ(winding(j), volume);
        }
        const CliRun full = polyvol("volume --json --signed " + quoted(kCorpus / rel));
        ASSERT_EQ(full.code, 0) << full.err;
        const json f = json::parse(full.out)[0];
        EXPECT_EQ(winding(j), winding(f));
        if (j.contains("winding_volume")) {
            EXPECT_EQ(j["volume"].get<double>(), f["volume"].get<double>());
        }
        if (std::find(quirks.begin(), quirks.end(), "3mf-transform") == quirks.end()) {
            EXPECT_EQ(j["accuracy"], "correctly-rounded");
            EXPECT_EQ(j["volume_error_bound"].get<double>(), 0.0);
        } else {  // the volume of the rounded coordinates, with a bound on the exact transform's
            EXPECT_EQ(j["accuracy"], "error-bound");
            if (!j.contains("winding_volume")) {
                EXPECT_LE(std::fabs(j["volume"].get<double>() - volume), j["volume_error_bound"].get<double>());
            }
        }
        EXPECT_EQ(j["closed_2_cycle"], true);
        for (const char* key : {"area", "centroid", "first_moments", "second_moments", "edge_length", "mass",
                                "shells", "cavities", "density"})
            EXPECT_FALSE(j.contains(key)) << key;
        ++checked;
        streamed += j.value("streamed", false);
    }
    EXPECT_GE(checked, 60);
    EXPECT_GE(streamed, 10);
}

TEST(CliStream, VolumeOnlyTable) {
    const fs::path torus = kCorpus / "meshes/prusa-slicer/torus.stl";
    const fs::path cube = kCorpus / "meshes/stl-models/unitCube.ascii.stl";
    const CliRun r = polyvol("volume --verbose --volume-only --stream " + quoted(torus) + " " + quoted(cube));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("volume"), std::string::npos);
    EXPECT_EQ(r.out.find("area"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("centroid"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("correctly rounded"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("streamed: its shells were not checked for overlap"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("1791.8163324528632"), std::string::npos) << r.out;  // the torus, as the full path prints it
    // The JSON without --stream keeps the loaded mesh's edge counts: a binary STL is loaded for it.
    const json loaded = json::parse(polyvol("volume --volume-only --json " + quoted(torus)).out)[0];
    EXPECT_FALSE(loaded.contains("streamed"));
    EXPECT_TRUE(loaded.contains("edges"));
    EXPECT_EQ(loaded["volume"].get<double>(), 1791.8163324528632);
    // Open surfaces are refused as without the flag; other methods keep their bound.
    const CliRun open = polyvol("volume --volume-only " + quoted(kCorpus / "meshes/stl-models/bunny.bin.stl"));
    EXPECT_EQ(open.code, 3);
    EXPECT_NE(open.err.find("unbalanced edge"), std::string::npos) << open.err;
    const CliRun vtnb = polyvol("volume --volume-only --json --method vtnb " + quoted(cube));
    ASSERT_EQ(vtnb.code, 0) << vtnb.err;
    const json p = json::parse(vtnb.out)[0];
    EXPECT_EQ(p["accuracy"], "error-bound");
    EXPECT_LE(std::fabs(p["volume"].get<double>() - 1.0), p["volume_error_bound"].get<double>());
    EXPECT_FALSE(p.contains("area"));
    const CliRun prism = polyvol("volume --volume-only --json --method prism " + quoted(torus));
    ASSERT_EQ(prism.code, 0) << prism.err;
    EXPECT_EQ(json::parse(prism.out)[0]["accuracy"], "correctly-rounded");
    EXPECT_EQ(json::parse(prism.out)[0]["volume"].get<double>(), 1791.8163324528632);
}

// One file, one set of numbers (issue #21): a box centred at 1e6 was shown
// by the streamed table as 1000000.0000016685 ±0.043 and by the loaded JSON
// as 1e+06. The table now shows each figure to within half its bound, so
// both routes read the same.
TEST(CliStream, TheTableAndTheJsonShowTheSameNumbers) {
    const fs::path p = fs::temp_directory_path() / ("polyvol_stream_1e6_" + std::to_string(::getpid()) + ".stl");
    {
        std::ofstream out(p, std::ios::binary);
        out << std::string(80, ' ');
        const float lo[3] = {1e6f - 1, 1e6f - 2, 1e6f - 3}, hi[3] = {1e6f + 1, 1e6f + 2, 1e6f + 3};
        const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        const uint32_t n = 12;
        out.write(reinterpret_cast<const char*>(&n), 4);
        for (const auto& q : quads)
            for (const auto& t : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
                float rec[12] = {0, 0, 0};
                for (int c = 0; c < 3; ++c)
                    for (int k = 0; k < 3; ++k) rec[3 + 3 * c + k] = (t[static_cast<std::size_t>(c)] >> k & 1) ? hi[k] : lo[k];
                out.write(reinterpret_cast<const char*>(rec), 48);
                out.write("\0\0", 2);
            }
    }
    const CliRun table = polyvol("volume " + quoted(p));
    ASSERT_EQ(table.code, 0) << table.err;
    const json loaded = json::parse(polyvol("volume --json " + quoted(p)).out)[0];
    EXPECT_EQ(loaded["centroid"], json::array({1e6, 1e6, 1e6}));
    EXPECT_EQ(loaded["volume"], 48.0);
    EXPECT_NE(table.out.find("48                        "), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("(1000000, 1000000, 1000000)"), std::string::npos) << table.out;  // streamed, as loaded
    fs::remove(p);
}

}  // namespace
