// polyvol/report.hpp: the library measures a file. The route is the
// library's (a binary STL streamed for the table's figures, loaded when
// anything needs the mesh or the stream finds it open or inside out), the
// same figures either way; refusals are fields with their exit codes; the
// JSON keys are report_json's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "polyvol/report.hpp"

namespace polyvol {
namespace {

namespace fs = std::filesystem;

// The mesh's fan triangles as a binary STL file (zero normals).
std::string write_stl(const Mesh& m, const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("polyvol_report_" + std::to_string(::getpid()) + "_" + name);
    const MeshView v = m.view();
    std::vector<uint32_t> tri;
    for (std::size_t f = 0; f < v.face_count(); ++f)
        for (std::size_t k = 1; k + 1 < v.face_size(f); ++k)
            tri.insert(tri.end(), {v.indices[v.face_begin(f)], v.indices[v.face_begin(f) + k],
                                   v.indices[v.face_begin(f) + k + 1]});
    std::ofstream out(p, std::ios::binary);
    const std::string header(80, ' ');
    out.write(header.data(), 80);
    const auto n = static_cast<uint32_t>(tri.size() / 3);
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (uint32_t t = 0; t < n; ++t) {
        float record[12] = {};
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) record[3 + 3 * c + k] = static_cast<float>(v.positions[3 * tri[3 * t + c] + k]);
        out.write(reinterpret_cast<const char*>(record), sizeof record);
        const uint16_t attribute = 0;
        out.write(reinterpret_cast<const char*>(&attribute), 2);
    }
    return p.string();
}

FileOptions table() {  // `polyvol volume`'s table
    FileOptions o;
    o.table_only = true;
    o.edge_counts = false;
    o.moments_bounded = true;
    o.measure.second_moments = false;
    o.measure.edge_length = false;
    return o;
}

TEST(MeasureFile, TheRouteIsTheLibrarysAndTheFiguresAgree) {
    const std::string stl = write_stl(test::box({0, 0, 0}, {2, 2, 2}), "box.stl");
    // Up to kStreamAboveTriangles a binary STL is loaded and checked in full.
    const FileReport small = measure_file(stl, table());
    EXPECT_FALSE(small.streamed);
    EXPECT_TRUE(small.policy.overlap_checked);
    FileOptions stream = table();
    stream.stream_any_size = true;  // `volume --stream`
    const FileReport streamed = measure_file(stl, stream);
    EXPECT_TRUE(streamed.streamed);
    EXPECT_FALSE(streamed.policy.overlap_checked);
    EXPECT_FALSE(streamed.loaded.has_value());
    ASSERT_TRUE(streamed.mass.has_value());
    EXPECT_EQ(streamed.mass->volume, 8.0);
    EXPECT_EQ(streamed.triangles, 12u);
    FileOptions counts = table();
    counts.mesh_counts = true;  // the loaded mesh's counts: loaded
    const FileReport loaded = measure_file(stl, counts);
    EXPECT_FALSE(loaded.streamed);
    ASSERT_TRUE(loaded.loaded.has_value() && loaded.mass.has_value());
    EXPECT_EQ(loaded.mass->volume, streamed.mass->volume);
    EXPECT_EQ(loaded.mass->area, 24.0);
    const FileReport full = measure_file(stl, FileOptions{});  // `measure`
    EXPECT_FALSE(full.streamed);
    ASSERT_TRUE(full.policy.topology.has_value());
    EXPECT_TRUE(full.policy.topology->closed_2_cycle);
    EXPECT_EQ(full.mass->centroid[0], 1.0);
    fs::remove(stl);
}

// FileOptions::progress: the stages in order; a streamed file's records by
// whole percents, never backwards within a stage, up to 1; (measuring, 1) last.
TEST(MeasureFile, ProgressGoesThroughTheStagesAndNeverBack) {
    const std::string stl = write_stl(generate::sphere_with_triangles(100000, 5.0), "sphere.stl");
    std::vector<std::pair<FileStage, double>> seen;
    FileOptions stream = table();
    stream.stream_any_size = true;
    stream.progress = [&](FileStage s, double f) { seen.emplace_back(s, f); };
    const FileReport streamed = measure_file(stl, stream);
    ASSERT_TRUE(streamed.streamed);
    ASSERT_GE(seen.size(), 20u);  // 100,000 records in windows of about 4,000: a call per window at least
    EXPECT_EQ(seen.front(), std::make_pair(FileStage::reading, 0.0));
    EXPECT_EQ(seen.back(), std::make_pair(FileStage::measuring, 1.0));
    for (std::size_t i = 1; i < seen.size(); ++i) {
        EXPECT_GE(seen[i].first, seen[i - 1].first);  // reading, then measuring
        if (seen[i].first == seen[i - 1].first) {
            EXPECT_GE(seen[i].second, seen[i - 1].second) << i;
        }
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), std::make_pair(FileStage::reading, 1.0)), 1);  // pass 1, whole

    // Centred on the origin, the first moments cancel: `--stream --json`
    // (the centroid correctly rounded) takes passes 2 and 3, measuring.
    const std::string centred = write_stl(generate::sphere_with_triangles(100000), "centred.stl");
    seen.clear();
    stream.moments_bounded = false;
    const FileReport exact = measure_file(centred, stream);
    ASSERT_TRUE(exact.streamed);
    ASSERT_GT(std::count_if(seen.begin(), seen.end(), [](const auto& p) { return p.first == FileStage::measuring; }), 10);
    EXPECT_EQ(seen.back(), std::make_pair(FileStage::measuring, 1.0));
    for (std::size_t i = 1; i < seen.size(); ++i) {
        EXPECT_GE(seen[i].first, seen[i - 1].first);
        if (seen[i].first == seen[i - 1].first) {
            EXPECT_GE(seen[i].second, seen[i - 1].second) << i;
        }
    }
    fs::remove(centred);

    seen.clear();
    FileOptions loaded;  // `measure`: the file loaded and checked
    loaded.progress = stream.progress;
    const FileReport full = measure_file(stl, loaded);
    EXPECT_EQ(full.exit_code, Exit::ok);
    const std::vector<std::pair<FileStage, double>> stages = {
        {FileStage::reading, 0}, {FileStage::checking, 0}, {FileStage::measuring, 0}, {FileStage::measuring, 1}};
    EXPECT_EQ(seen, stages);
    fs::remove(stl);
}

TEST(MeasureFile, InsideOutIsTurnedOpenIsRefusedUnreadableIsTwo) {
    const std::string inverted = write_stl(test::box({0, 0, 0}, {1, 1, 1}, {.inverted = true}), "inverted.stl");
    FileOptions stream = table();
    stream.stream_any_size = true;
    const FileReport turned = measure_file(inverted, stream);
    EXPECT_FALSE(turned.streamed);  // the stream found it inside out: loaded to be turned
    EXPECT_TRUE(turned.policy.turned_outward.has_value());
    EXPECT_EQ(turned.mass->volume, 1.0);
    EXPECT_NE(turned.warning.find("inside out"), std::string::npos) << turned.warning;
    FileOptions check;
    check.need_mass = false;  // `check`: the file as it is needs a repair
    const FileReport judged = measure_file(inverted, check);
    EXPECT_EQ(judged.exit_code, Exit::invalid);
    EXPECT_FALSE(judged.repairs.empty());

    Mesh open = test::box({0, 0, 0}, {1, 1, 1});
    open.indices.resize(open.indices.size() - 6);  // two triangles gone
    const std::string hole = write_stl(open, "open.stl");
    const FileReport refused = measure_file(hole, table());
    EXPECT_EQ(refused.exit_code, Exit::invalid);
    EXPECT_FALSE(refused.mass.has_value());
    EXPECT_NE(refused.error.find("unbalanced edge"), std::string::npos) << refused.error;

    const FileReport missing = measure_file("/nonexistent/polyvol.stl", table());
    EXPECT_EQ(missing.exit_code, Exit::unreadable);
    EXPECT_FALSE(missing.error.empty());
    for (const std::string& f : {inverted, hole}) fs::remove(f);
}

TEST(MeasureFile, UnitsAndTheJsonKeys) {
    const std::string stl = write_stl(test::box({0, 0, 0}, {10, 10, 10}), "mm.stl");
    FileOptions o;
    o.units = "mm";
    o.to = "cm";
    const FileReport r = measure_file(stl, o);
    ASSERT_EQ(r.exit_code, Exit::ok) << r.error;
    EXPECT_EQ(r.length_unit, "cm");
    EXPECT_EQ(r.length_factor, 0.1);
    EXPECT_LE(std::fabs(r.mass->volume - 1.0), r.mass->volume_error_bound);
    const nlohmann::json j = report_json(r, o);
    EXPECT_EQ(j["unit"], "cm");
    EXPECT_EQ(j["exit_code"], 0);
    EXPECT_EQ(j["volume"].get<double>(), r.mass->volume);
    for (const char* key : {"file", "format", "vertices", "faces", "edges", "closed_2_cycle", "shells", "area",
                            "centroid", "bounds", "inertia", "principal_moments", "principal_axes", "edge_length"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["bounds"][3].get<double>(), 1.0);
    o.to = "furlong";
    EXPECT_EQ(measure_file(stl, o).exit_code, Exit::invalid);
    fs::remove(stl);
}

TEST(MeasureFile, InputsOfAPlainPath) {
    const auto inputs = file_inputs({"/nonexistent/a.stl", "-"});
    ASSERT_EQ(inputs.size(), 2u);
    EXPECT_EQ(inputs[0].first, "/nonexistent/a.stl");
    EXPECT_EQ(inputs[0].second, "");
    EXPECT_EQ(inputs[1].first, "-");
}

}  // namespace
}  // namespace polyvol
