// Every mesh of ../shared/corpus against its exact reference figures
// (manifest.json; see the corpus README for the conventions). One test per
// file and property. The suite fails when the corpus is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "common/topology_compare.hpp"
#include "polyvol/parse_options.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

using polyvol::test::corpus_file;
using polyvol::test::corpus_manifest;
using polyvol::test::manifest_entry;
constexpr auto ref = polyvol::test::corpus_reference;

struct Loaded {
    polyvol::LoadedMesh mesh;
    polyvol::TopologyReport topology;
};

// Reads each file once for all the tests that need it.
const Loaded& load(const std::string& path) {
    static std::map<std::string, Loaded> cache;
    auto it = cache.find(path);
    if (it == cache.end()) {
        Loaded l{polyvol::read_mesh_file(corpus_file(path)), {}};
        l.topology = polyvol::analyze_topology(l.mesh.mesh.view());
        it = cache.emplace(path, std::move(l)).first;
    }
    return it->second;
}

// Largest |coordinate| and the bounding-box diagonal of the reference.
struct Scale {
    double reach = 0, diagonal = 0;
};
Scale scale_of(const json& e) {
    Scale s;
    if (!e.contains("bbox") || e["bbox"].is_null()) return s;  // no vertices
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
        const double lo = e["bbox"]["min"][k].get<double>(), hi = e["bbox"]["max"][k].get<double>();
        s.reach = std::max({s.reach, std::abs(lo), std::abs(hi)});
        d2 += (hi - lo) * (hi - lo);
    }
    s.diagonal = std::sqrt(d2);
    return s;
}

constexpr double kRel = 1e-12;
const char* const kSym[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};

class Corpus : public ::testing::TestWithParam<std::string> {
protected:
    const json& entry() const { return manifest_entry(GetParam()); }
    bool invalid() const { return entry()["category"] == "invalid"; }
    bool measurable() const {
        return !invalid() && entry().value("exact", false) && entry()["topology"]["closed_2_cycle"].get<bool>();
    }
    // Closed, edge-manifold, consistently oriented and without degenerate
    // triangles: where Franklin's length formula counts every edge once.
    bool e_manifold() const {
        const json& t = entry()["topology"];
        return t["closed"].get<bool>() && t["edge_manifold"].get<bool>() && t["consistently_oriented"].get<bool>() &&
               t["zero_area_triangles"].get<int>() == 0 && t["triangles_with_repeated_vertex"].get<int>() == 0 &&
               t["degenerate_edge_uses"].get<int>() == 0;
    }
};

TEST(CorpusPresence, ManifestIsThere) {
    ASSERT_TRUE(fs::exists(polyvol::test::corpus_dir() / "manifest.json"))
        << "corpus missing at " << polyvol::test::corpus_dir();
    EXPECT_GE(corpus_manifest().size(), 100u);
}

TEST_P(Corpus, InvalidFilesAreRefusedWithTheirName) {
    if (!invalid()) GTEST_SKIP() << "valid file";
    const std::string path = corpus_file(GetParam());
    try {
        polyvol::read_mesh_file(path);
        FAIL() << "read without error; manifest says: " << entry()["error"];
    } catch (const polyvol::ReadError& e) {
        EXPECT_NE(std::string(e.what()).find(fs::path(path).filename().string()), std::string::npos) << e.what();
        EXPECT_FALSE(e.message.empty());
    }
}

TEST_P(Corpus, CountsMatch) {
    if (invalid()) GTEST_SKIP() << "invalid file";
    const auto& l = load(GetParam());
    const json& c = entry()["counts"];
    EXPECT_EQ(l.mesh.vertices_in_file, c["vertices_in_file"].get<std::size_t>());
    const bool stl = l.mesh.format == polyvol::Format::stl;  // welded as read
    EXPECT_EQ(l.mesh.mesh.vertex_count(), c[stl ? "vertices_welded" : "vertices_in_file"].get<std::size_t>());
    EXPECT_EQ(l.mesh.mesh.face_count(), c["faces"].get<std::size_t>());
    EXPECT_EQ(l.mesh.mesh.view().triangle_count(), c["triangles"].get<std::size_t>());
    EXPECT_EQ(polyvol::format_name(l.mesh.format), entry()["format"].get<std::string>());
}

TEST_P(Corpus, TopologyMatches) {
    if (invalid()) GTEST_SKIP() << "invalid file";
    const auto& t = load(GetParam()).topology;
    const json& m = entry()["topology"];
    EXPECT_EQ(t.edges, m["edges"].get<std::size_t>());
    EXPECT_EQ(t.boundary_edges, m["boundary_edges"].get<std::size_t>());
    EXPECT_EQ(t.nonmanifold_edges, m["nonmanifold_edges"].get<std::size_t>());
    EXPECT_EQ(t.misoriented_edges, m["misoriented_edges"].get<std::size_t>());
    EXPECT_EQ(t.unbalanced_edges, m["unbalanced_edges"].get<std::size_t>());
    EXPECT_EQ(t.closed_2_cycle, m["closed_2_cycle"].get<bool>());
    EXPECT_EQ(t.euler_characteristic, m["euler_characteristic"].get<int64_t>());
    EXPECT_EQ(t.components_edge_connected, m["components_edge_connected"].get<std::size_t>());
    EXPECT_EQ(t.components_vertex_connected, m["components_vertex_connected"].get<std::size_t>());
    EXPECT_EQ(t.vertices_welded, entry()["counts"]["vertices_welded"].get<std::size_t>());
}

// An STL as the file lists it (every corner its own vertex: the reader's
// soup before it welds) gives the topology and the correctly rounded volume,
// bits and all, of the welded mesh the reader returns, so the soup paths
// (its numbering in topology, its range check in the volume) meet real files.
TEST_P(Corpus, StlSoupMeasuresAsTheWeldedMesh) {
    if (invalid() || entry()["format"] != "stl") GTEST_SKIP();
    polyvol::LoadedMesh soup;
    {
        const polyvol::io::ScopedParseOptions scope({.weld_stl = false});
        soup = polyvol::read_mesh_file(corpus_file(GetParam()));
    }
    const auto& l = load(GetParam());
    ASSERT_EQ(soup.mesh.vertex_count(), l.mesh.vertices_in_file);
    ASSERT_LE(l.mesh.mesh.vertex_count(), soup.mesh.vertex_count());
    polyvol::test::expect_same_counts(polyvol::analyze_topology(soup.mesh.view()), l.topology);
    const double a = polyvol::signed_volume(soup.mesh.view()), b = polyvol::signed_volume(l.mesh.mesh.view());
    EXPECT_EQ(std::bit_cast<uint64_t>(a), std::bit_cast<uint64_t>(b)) << std::hexfloat << a << " vs " << b;
}

// The default volume is the exact volume rounded once: bit for bit the
// manifest's correctly rounded double (the cone-rule sum about the origin is
// well defined for open surfaces too, so they are compared as well).
//
// Exception: 3MF build or component transforms. The manifest applies them in
// exact rational arithmetic, so its vertices are not doubles; polyvol rounds
// each transformed coordinate to a double (as every reader that stores
// doubles must) and is then exact for those coordinates, which may differ from
// the manifest's figure in the last bits.
TEST_P(Corpus, VolumeIsCorrectlyRounded) {
    if (invalid() || !entry().value("exact", false)) GTEST_SKIP();
    const auto& l = load(GetParam());
    const auto m = polyvol::mass_properties(l.mesh.mesh.view());
    EXPECT_TRUE(m.volume_correctly_rounded);
    const double want = ref(entry()["volume"]);
    const auto& quirks = entry()["quirks"];
    if (std::find(quirks.begin(), quirks.end(), "3mf-transform") != quirks.end())
        EXPECT_NEAR(m.volume, want, 1e-14 * std::abs(want));
    else
        EXPECT_EQ(m.volume, want) << std::hexfloat << m.volume << " vs " << want;
}

TEST_P(Corpus, MassPropertiesMatch) {
    if (!measurable()) GTEST_SKIP() << "not a closed 2-cycle";
    const auto& l = load(GetParam());
    const auto m = polyvol::mass_properties(l.mesh.mesh.view());
    const json& e = entry();
    const Scale s = scale_of(e);
    const double V = ref(e["volume"]);
    const double aV = std::abs(V);
    for (int k = 0; k < 3; ++k) {
        const char* ax = kSym[k];
        const double key = ref(e["first_moments"][std::string(1, ax[0])]);
        EXPECT_NEAR(m.first_moments[k], key, kRel * std::max(std::abs(key), aV * s.reach)) << "first moment " << k;
        if (V != 0 && e.contains("centroid") && !e["centroid"].is_null()) {
            const double c = ref(e["centroid"][std::string(1, ax[0])]);
            EXPECT_NEAR(m.centroid[k], c, kRel * std::max(std::abs(c), s.reach)) << "centroid " << k;
        }
    }
    auto tensor = [&](const char* name, const std::array<double, 6>& got) {
        double norm = 0;
        for (int k = 0; k < 3; ++k) norm = std::max(norm, std::abs(ref(e[name][kSym[k]])));
        for (int k = 0; k < 6; ++k) {
            const double want = ref(e[name][kSym[k]]);
            EXPECT_NEAR(got[k], want, kRel * std::max(norm, std::abs(want))) << name << "." << kSym[k];
        }
    };
    tensor("second_moments", m.second_moments);
    tensor("inertia_origin", m.inertia_origin);
    if (V != 0 && e.contains("inertia_centroid") && !e["inertia_centroid"].is_null()) tensor("inertia_centroid", m.inertia_centroid);
    const double area = e["surface_area"]["double"].get<double>();
    EXPECT_NEAR(m.area, area, kRel * area);
    const double len = e["edge_length"]["double"].get<double>();
    EXPECT_NEAR(m.edge_length, len, kRel * len);
}

// cone, prism, pyramid and vtnb agree to 1e-12 (relative to |V|, or to the
// bounding box's cube for meshes whose volume cancels to nearly nothing).
TEST_P(Corpus, MethodsAgree) {
    if (!measurable()) GTEST_SKIP() << "not a closed 2-cycle";
    const auto& l = load(GetParam());
    const json& e = entry();
    const double V = ref(e["volume"]);
    const Scale s = scale_of(e);
    const double tol = kRel * std::max(std::abs(V), 1e-9 * s.diagonal * s.diagonal * s.diagonal);
    for (auto method : {polyvol::Method::prism, polyvol::Method::pyramid, polyvol::Method::vtnb}) {
        for (auto acc : {polyvol::Accuracy::correctly_rounded, polyvol::Accuracy::fast}) {
            const double v = polyvol::signed_volume(l.mesh.mesh.view(), method, acc);
            EXPECT_NEAR(v, V, tol) << polyvol::method_name(method);
        }
    }
    EXPECT_NEAR(polyvol::signed_volume(l.mesh.mesh.view(), polyvol::Method::cone, polyvol::Accuracy::fast), V, tol);
}

// Franklin's local formula also gives area and length (closed, manifold meshes).
TEST_P(Corpus, VtnbAreaAndLength) {
    if (!measurable() || !e_manifold()) GTEST_SKIP() << "needs a closed edge-manifold surface";
    const auto& l = load(GetParam());
    const auto m = polyvol::mass_properties(l.mesh.mesh.view(), {.method = polyvol::Method::vtnb});
    const double area = entry()["surface_area"]["double"].get<double>();
    EXPECT_NEAR(m.area, area, kRel * area);
    const double len = entry()["edge_length"]["double"].get<double>();
    EXPECT_NEAR(m.edge_length, len, kRel * len);
}

INSTANTIATE_TEST_SUITE_P(Manifest, Corpus, ::testing::ValuesIn(polyvol::test::manifest_paths()),
                         polyvol::test::corpus_param_name);

}  // namespace
