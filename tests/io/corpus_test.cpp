// Every STL, OBJ, OFF and PLY file of the shared corpus against its manifest
// entry: invalid files must fail with a ReadError naming the file; the others
// must give the manifest's counts, format, encoding, notes and exact bbox.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "polyvol/io.hpp"

namespace {

using nlohmann::json;
using polyvol::LoadedMesh;
using polyvol::ReadError;
using polyvol::test::corpus_manifest;
using polyvol::test::manifest_entry;

bool ours(const json& e) {
    const std::string f = e.value("format", "");
    return f == "stl" || f == "obj" || f == "off" || f == "ply";
}

std::string basename(const std::string& p) { return p.substr(p.find_last_of('/') + 1); }

class Corpus : public testing::TestWithParam<std::string> {};

TEST(CorpusManifest, IsThereAndCoversEveryFormat) {
    ASSERT_FALSE(corpus_manifest().empty()) << "no manifest at " << polyvol::test::corpus_dir();
    std::map<std::string, int> n;
    for (const json& e : corpus_manifest()) ++n[e.value("format", "")];
    EXPECT_GE(n["stl"], 40);
    EXPECT_GE(n["obj"], 15);
    EXPECT_GE(n["off"], 30);
    EXPECT_GE(n["ply"], 5);
}

TEST_P(Corpus, MatchesManifest) {
    const json& e = manifest_entry(GetParam());
    const std::string rel = e.at("path");
    const std::string path = polyvol::test::corpus_file(rel);
    if (e.at("category") == "invalid") {
        try {
            (void)polyvol::read_mesh_file(path);
            FAIL() << rel << " read without error; the manifest says: " << e.value("error", "");
        } catch (const ReadError& err) {
            const std::string what = err.what();
            EXPECT_NE(what.find(basename(rel)), std::string::npos) << what;
            EXPECT_FALSE(err.message.empty());
        }
        return;
    }

    LoadedMesh r;
    ASSERT_NO_THROW(r = polyvol::read_mesh_file(path)) << rel;
    EXPECT_EQ(polyvol::format_name(r.format), e.at("format").get<std::string>());
    EXPECT_EQ(r.encoding, e.at("encoding").get<std::string>());

    const json& c = e.at("counts");
    const polyvol::MeshView v = r.mesh.view();
    EXPECT_EQ(r.vertices_in_file, c.at("vertices_in_file").get<std::size_t>());
    // STL facets share no vertex in the file: the reader welds them, and
    // every welded vertex is some facet's corner.
    const bool stl = r.format == polyvol::Format::stl;
    EXPECT_EQ(v.vertex_count(), c.at(stl ? "vertices_welded" : "vertices_in_file").get<std::size_t>());
    EXPECT_EQ(v.face_count(), c.at("faces").get<std::size_t>());
    EXPECT_EQ(v.triangle_count(), c.at("triangles").get<std::size_t>());
    std::size_t lt3 = 0;
    std::map<std::string, std::size_t> hist;
    for (std::size_t f = 0; f < v.face_count(); ++f) {
        if (v.face_size(f) < 3) ++lt3;
        ++hist[std::to_string(v.face_size(f))];
    }
    EXPECT_EQ(lt3, c.at("faces_with_lt3_vertices").get<std::size_t>());
    std::map<std::string, std::size_t> want_hist;
    for (const auto& [k, n] : c.at("face_size_histogram").items()) want_hist[k] = n.get<std::size_t>();
    EXPECT_EQ(hist, want_hist);
    // Every index is in range (mesh.hpp's promise).
    for (uint32_t i : v.indices) ASSERT_LT(i, v.vertex_count());

    // The exact bbox: proves every number parsed to the correctly rounded double.
    const json bbox = e.value("bbox", json());
    if (bbox.is_null()) {
        EXPECT_EQ(v.vertex_count(), 0u);
    } else {
        double lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::numeric_limits<double>::infinity();
            hi[k] = -lo[k];
        }
        for (std::size_t i = 0; i < v.vertex_count(); ++i) {
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], v.positions[3 * i + k]);
                hi[k] = std::max(hi[k], v.positions[3 * i + k]);
            }
        }
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(lo[k], bbox.at("min").at(k).get<double>()) << "axis " << k;
            EXPECT_EQ(hi[k], bbox.at("max").at(k).get<double>()) << "axis " << k;
        }
    }

    // Notes: every quirk of the manifest that is about reading is reported.
    std::vector<std::string> quirks;
    for (const json& q : e.at("quirks")) {
        const std::string s = q;
        if (s.rfind("signed-zero-coordinates-merged", 0) == 0) continue;  // a welding remark
        quirks.push_back(s);
        EXPECT_NE(std::find(r.notes.begin(), r.notes.end(), s), r.notes.end()) << "missing note " << s;
    }
    EXPECT_EQ(r.gzip, std::find(quirks.begin(), quirks.end(), "gzip-compressed") != quirks.end());
    // Every note has words for people (an unknown one comes back as it is).
    for (const std::string& n : r.notes) EXPECT_NE(polyvol::note_words(n), n) << "no words for note " << n;
}

TEST(NoteWords, ArgumentsGoIntoTheWords) {
    EXPECT_EQ(polyvol::note_words("stl-multiple-solids(2)"), "2 solids in one file, measured together");
    EXPECT_EQ(polyvol::note_words("3mf-unit(inch)"), "the file's unit is inch");
    EXPECT_EQ(polyvol::note_words("off-header-COFF"), "an OFF variant header (COFF), read as OFF");
    EXPECT_EQ(polyvol::note_words("off-trailing-data(3 lines)"), "3 lines after the last face ignored");
    EXPECT_EQ(polyvol::note_words("obj-face-with-2-vertices"), "faces of 2 vertices, which bound nothing (ignored)");
    EXPECT_EQ(polyvol::note_words("something-new(3)"), "something-new(3)");
}

INSTANTIATE_TEST_SUITE_P(Manifest, Corpus, testing::ValuesIn(polyvol::test::manifest_paths(ours)),
                         polyvol::test::corpus_param_name);

}  // namespace
