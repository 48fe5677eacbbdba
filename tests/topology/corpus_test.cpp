// Every readable corpus mesh against its manifest entry: the `counts` that
// topology reports, every `topology` field, the listed `components` (up to
// 20, largest |volume| first) and the `nesting` summary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "polyvol/io.hpp"
#include "polyvol/topology.hpp"

namespace {

using nlohmann::json;
using polyvol::ShellRole;
using polyvol::TopologyReport;
using polyvol::test::corpus_file;
using polyvol::test::manifest_entry;
using polyvol::test::readable_paths;

class CorpusTopology : public testing::TestWithParam<std::string> {
protected:
    static TopologyReport analyze(const json& e) {
        const polyvol::LoadedMesh loaded = polyvol::read_mesh_file(corpus_file(e.at("path").get<std::string>()));
        return polyvol::analyze_topology(loaded.mesh.view());
    }
};

TEST(CorpusTopologyManifest, HasReadableEntries) {
    ASSERT_FALSE(polyvol::test::corpus_manifest().empty()) << "no manifest at " << polyvol::test::corpus_dir();
    EXPECT_GT(readable_paths().size(), 100u);
}

TEST_P(CorpusTopology, CountsAndTopologyMatchManifest) {
    const json& e = manifest_entry(GetParam());
    const TopologyReport r = analyze(e);
    const json& c = e.at("counts");
    EXPECT_EQ(r.faces, c.at("faces").get<std::size_t>());
    EXPECT_EQ(r.faces_with_lt3_vertices, c.at("faces_with_lt3_vertices").get<std::size_t>());
    EXPECT_EQ(r.triangles, c.at("triangles").get<std::size_t>());
    EXPECT_EQ(r.vertices_welded, c.at("vertices_welded").get<std::size_t>());
    EXPECT_EQ(r.vertices_referenced, c.at("vertices_referenced").get<std::size_t>());

    const json& t = e.at("topology");
    EXPECT_EQ(r.edges, t.at("edges").get<std::size_t>());
    EXPECT_EQ(r.boundary_edges, t.at("boundary_edges").get<std::size_t>());
    EXPECT_EQ(r.nonmanifold_edges, t.at("nonmanifold_edges").get<std::size_t>());
    EXPECT_EQ(r.misoriented_edges, t.at("misoriented_edges").get<std::size_t>());
    EXPECT_EQ(r.unbalanced_edges, t.at("unbalanced_edges").get<std::size_t>());
    EXPECT_EQ(r.closed, t.at("closed").get<bool>());
    EXPECT_EQ(r.edge_manifold, t.at("edge_manifold").get<bool>());
    EXPECT_EQ(r.consistently_oriented, t.at("consistently_oriented").get<bool>());
    EXPECT_EQ(r.closed_2_cycle, t.at("closed_2_cycle").get<bool>());
    EXPECT_EQ(r.euler_characteristic, t.at("euler_characteristic").get<int64_t>());
    EXPECT_EQ(r.components_vertex_connected, t.at("components_vertex_connected").get<std::size_t>());
    EXPECT_EQ(r.components_edge_connected, t.at("components_edge_connected").get<std::size_t>());
    EXPECT_EQ(r.triangles_with_repeated_vertex, t.at("triangles_with_repeated_vertex").get<std::size_t>());
    EXPECT_EQ(r.zero_area_triangles, t.at("zero_area_triangles").get<std::size_t>());
    EXPECT_EQ(r.degenerate_edge_uses, t.at("degenerate_edge_uses").get<std::size_t>());
    EXPECT_EQ(r.unbalanced_example.has_value(), r.unbalanced_edges > 0);
    EXPECT_EQ(r.shells.size(), r.components_edge_connected);

    // Edges only (polyvol volume's table): the same edge counts, no shells.
    const polyvol::LoadedMesh loaded = polyvol::read_mesh_file(corpus_file(e.at("path").get<std::string>()));
    const TopologyReport light = polyvol::analyze_topology(loaded.mesh.view(), {.shells = false});
    EXPECT_EQ(light.vertices_welded, r.vertices_welded);
    EXPECT_EQ(light.edges, r.edges);
    EXPECT_EQ(light.boundary_edges, r.boundary_edges);
    EXPECT_EQ(light.nonmanifold_edges, r.nonmanifold_edges);
    EXPECT_EQ(light.misoriented_edges, r.misoriented_edges);
    EXPECT_EQ(light.unbalanced_edges, r.unbalanced_edges);
    EXPECT_EQ(light.closed_2_cycle, r.closed_2_cycle);
    EXPECT_EQ(light.euler_characteristic, r.euler_characteristic);
    EXPECT_EQ(light.unbalanced_example, r.unbalanced_example);
    EXPECT_TRUE(light.shells.empty());
    EXPECT_EQ(light.components_edge_connected, 0u);
}

// Shell volumes are correctly rounded (corpus coordinates are in the safe
// range), so they equal the manifest's doubles and come in the same order;
// shells of equal |volume| may come in either order, so each listed
// component is matched with an unused shell of the same |volume|. The
// exception: 3MF transforms, which the reference applies in rational
// arithmetic and the reader in doubles (corpus README), so coordinates and
// volumes may differ in the last bits there.
bool transformed(const json& e) {
    for (const json& q : e.at("quirks"))
        if (q.get<std::string>().rfind("3mf-transform", 0) == 0) return true;
    return false;
}

TEST_P(CorpusTopology, ComponentsMatchManifest) {
    const json& e = manifest_entry(GetParam());
    const TopologyReport r = analyze(e);
    if (!e.contains("components")) {  // listed whenever there is a face
        EXPECT_TRUE(r.shells.empty());
        return;
    }
    const json& listed = e.at("components");
    ASSERT_GE(r.shells.size(), listed.size());
    std::vector<bool> used(r.shells.size(), false);
    for (std::size_t i = 0; i < listed.size(); ++i) {
        const json& want = listed[i];
        const double volume = want.at("signed_volume").get<double>();
        const double tolerance = transformed(e) ? 1e-12 * std::abs(volume) : 0.0;
        const auto same_size = [&](double v) { return std::abs(std::abs(v) - std::abs(volume)) <= tolerance; };
        const auto matches = [&](const polyvol::Shell& s) {
            return std::abs(s.signed_volume - volume) <= tolerance && s.faces == want.at("faces").get<std::size_t>() &&
                   s.boundary_edges == want.at("boundary_edges").get<std::size_t>() &&
                   s.unbalanced_edges == want.at("unbalanced_edges").get<std::size_t>() &&
                   (!want.contains("winding_of_other_components") ||
                    std::abs(s.winding_of_others - want.at("winding_of_other_components").get<double>()) <= 1.5e-6);
        };
        std::size_t found = r.shells.size();
        for (std::size_t k = 0; k < r.shells.size() && found == r.shells.size(); ++k)
            if (!used[k] && same_size(r.shells[k].signed_volume) && matches(r.shells[k])) found = k;
        ASSERT_LT(found, r.shells.size())
            << "component " << i << " " << want.dump() << " not found; at rank " << i << ": volume "
            << r.shells[i].signed_volume << " faces " << r.shells[i].faces << " boundary "
            << r.shells[i].boundary_edges << " unbalanced " << r.shells[i].unbalanced_edges
            << " winding " << r.shells[i].winding_of_others;
        EXPECT_TRUE(same_size(r.shells[i].signed_volume)) << "rank " << i << ": " << r.shells[i].signed_volume;
        used[found] = true;
    }
}

TEST_P(CorpusTopology, NestingMatchesManifest) {
    const json& e = manifest_entry(GetParam());
    const TopologyReport r = analyze(e);
    if (!e.contains("nesting") || e.at("nesting").is_null()) {  // given for 2 shells or more
        EXPECT_LE(r.shells.size(), 1u);
        return;
    }
    const json& n = e.at("nesting");
    std::size_t closed = 0, inside = 0;
    for (const polyvol::Shell& s : r.shells) {
        closed += s.role != ShellRole::open;
        inside += s.role == ShellRole::cavity || s.role == ShellRole::nested;
    }
    EXPECT_EQ(closed, n.at("closed_components").get<std::size_t>());
    EXPECT_EQ(inside, n.at("inside_another_component").get<std::size_t>());
    EXPECT_EQ(r.cavities, n.at("negative_inside_positive(cavities)").get<std::size_t>());
    EXPECT_EQ(r.inside_out_shells, n.at("negative_not_inside(inverted_shells)").get<std::size_t>());
    EXPECT_EQ(r.nested_shells, n.at("positive_inside_positive(overlapping_or_nested_solids)").get<std::size_t>());
}

INSTANTIATE_TEST_SUITE_P(Manifest, CorpusTopology, testing::ValuesIn(readable_paths()),
                         polyvol::test::corpus_param_name);

}  // namespace
