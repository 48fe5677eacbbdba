// Keys of `--json` that claimed what was not so (issue #21): --volume-only
// gives no shell counts it did not compute, a triangle with a repeated vertex
// is one degenerate triangle (not two), and vtnb's edge length and area on an
// open surface are the surface's (the direct sums), as the cone method's.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

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
    const auto table = cli_test::run_polyvol("volume '" + p.string() + "'");
    EXPECT_NE(table.err.find("no faces"), std::string::npos);
    EXPECT_NE(table.out.find(": no faces"), std::string::npos) << table.out;  // a note under the table too
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

// 3MF transforms are applied in floating point: the volume of the rounded
// coordinates is not the file's. A tetrahedron of volume 500000/3 moved by
// (0.1, 0.2, 0.3) and one also turned by (0.6, 0.8) are reported with a bound
// that holds (|V - 500000/3| <= |V - its double| + half an ulp), not as
// correctly rounded; the same file without the transform keeps the claim.
TEST(JsonKeys, ThreeMfTransformsGiveABoundNotAClaim) {
    auto model = [](const std::string& transform) {
        return std::string(R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <resources><object id="1" type="model"><mesh>
  <vertices><vertex x="0" y="0" z="0"/><vertex x="100" y="0" z="0"/><vertex x="0" y="100" z="0"/><vertex x="0" y="0" z="100"/></vertices>
  <triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/><triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles>
 </mesh></object></resources>
 <build><item objectid="1")") + (transform.empty() ? "" : " transform=\"" + transform + "\"") + "/></build>\n</model>\n";
    };
    const double exact_rounded = 500000.0 / 3, half_ulp = 0.5 * (std::nextafter(exact_rounded, 1e9) - exact_rounded);
    const json plain = run("measure --json '" + scratch("plain.3mf", model("")).string() + "'");
    EXPECT_EQ(plain["accuracy"], "correctly-rounded");
    EXPECT_EQ(plain["volume"], exact_rounded);
    const json moved = run("measure --json '" + scratch("moved.3mf", model("1 0 0 0 1 0 0 0 1 0.1 0.2 0.3")).string() + "'");
    EXPECT_EQ(moved["accuracy"], "error-bound");
    EXPECT_EQ(moved["moments_accuracy"], "error-bound");
    const double v = moved["volume"], bound = moved["volume_error_bound"];
    EXPECT_LE(std::fabs(v - exact_rounded) + half_ulp, bound);
    EXPECT_LT(bound, 1e-8);
    EXPECT_LT(moved["moments_relative_error"].get<double>(), 1e-12);
    // Turned: det M = 0.6² + 0.8² in doubles, within 1e-16 of 1.
    const json turned = run("measure --json '" + scratch("turned.3mf", model("0.6 0.8 0 -0.8 0.6 0 0 0 1 10.1 -3.3 7.7")).string() + "'");
    EXPECT_EQ(turned["accuracy"], "error-bound");
    EXPECT_LE(std::fabs(turned["volume"].get<double>() - exact_rounded), turned["volume_error_bound"].get<double>() + 1e-16 * exact_rounded);
    const auto table = cli_test::run_polyvol("volume '" + scratch("moved2.3mf", model("1 0 0 0 1 0 0 0 1 0.1 0.2 0.3")).string() + "'");
    EXPECT_NE(table.out.find(" ±"), std::string::npos) << table.out;
}

// A zip of plain meshes (not a 3MF or AMF package) is its members, each
// measured as a file of its own under ARCHIVE:MEMBER (tests/data/archives:
// a 2-cube and a tetrahedron of legs 3, beside a README).
TEST(JsonKeys, AZipOfMeshesIsItsMembers) {
    const std::string zip = std::string(POLYVOL_TEST_DATA) + "/archives/two_meshes.zip";
    const auto r = cli_test::run_polyvol("volume --json '" + zip + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    const json all = json::parse(r.out);
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0]["file"], zip + ":cube.obj");
    EXPECT_EQ(all[0]["volume"], 8.0);
    EXPECT_EQ(all[1]["file"], zip + ":sub/tet.off");
    EXPECT_EQ(all[1]["volume"], 4.5);
    EXPECT_EQ(all[1]["format"], "off");
    const auto table = cli_test::run_polyvol("volume '" + zip + "'");
    EXPECT_NE(table.out.find("two_meshes.zip:sub/tet.off"), std::string::npos) << table.out;
}

// Tar archives, plain or compressed by gzip or bzip2, are their members as a
// zip is; a long member name (a pax header) is read whole; a bzip2 stream
// of one mesh is that mesh (tests/data/archives/make.py).
TEST(JsonKeys, TarArchivesAndBzip2AreReadAsZipsAndGzipAre) {
    const std::string dir = std::string(POLYVOL_TEST_DATA) + "/archives/";
    for (const char* name : {"two_meshes.tar.gz", "two_meshes.tgz", "two_meshes.tar.bz2"}) {
        SCOPED_TRACE(name);
        const auto r = cli_test::run_polyvol("volume --json '" + dir + name + "'");
        ASSERT_EQ(r.code, 0) << r.err;
        const json all = json::parse(r.out);
        ASSERT_EQ(all.size(), 2u);
        EXPECT_EQ(all[0]["file"], dir + name + ":cube.obj");
        EXPECT_EQ(all[0]["volume"], 8.0);
        EXPECT_EQ(all[1]["file"], dir + name + ":sub/tet.off");
        EXPECT_EQ(all[1]["volume"], 4.5);
    }
    const json long_name = json::parse(cli_test::run_polyvol("volume --json '" + dir + "long_name.tar'").out);
    ASSERT_EQ(long_name.size(), 1u);
    EXPECT_EQ(long_name[0]["file"], dir + "long_name.tar:" + std::string(60, 'd') + "/" + std::string(60, 'e') + "/cube.obj");
    EXPECT_EQ(long_name[0]["volume"], 8.0);
    const json bz = json::parse(cli_test::run_polyvol("measure --json '" + dir + "cube.obj.bz2'").out)[0];
    EXPECT_EQ(bz["volume"], 8.0);
    EXPECT_EQ(bz["notes"][0], "bzip2-compressed");
    // A truncated archive is an error with the archive's name, not a crash.
    const fs::path cut = scratch("cut.tar.bz2", "");
    {
        std::ifstream in(dir + "two_meshes.tar.bz2", std::ios::binary);
        const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream(cut, std::ios::binary) << all.substr(0, all.size() / 2);
    }
    const auto bad = cli_test::run_polyvol("volume '" + cut.string() + "'");
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("truncated bzip2 data"), std::string::npos) << bad.err;
    fs::remove(cut);
}

// Inside out (issue #21): a closed shell facing inward and inside nothing is
// turned outward by default, and said so; --signed keeps the signed sums.
// A cavity (an inward shell inside a solid one) stays a cavity.
TEST(JsonKeys, InsideOutShellsAreTurnedOutward) {
    auto box = [](double lo, double hi, int base, bool inward) {
        std::string v, f;
        for (int i = 0; i < 8; ++i)
            v += "v " + std::to_string(i & 1 ? hi : lo) + " " + std::to_string(i >> 1 & 1 ? hi : lo) + " " +
                 std::to_string(i >> 2 & 1 ? hi : lo) + "\n";
        const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& face : q) {
            f += "f";
            for (int k = 0; k < 4; ++k) f += " " + std::to_string(base + 1 + face[inward ? 3 - k : k]);
            f += "\n";
        }
        return std::pair{v, f};
    };
    auto file = [&](const std::string& name, std::vector<std::tuple<double, double, bool>> boxes) {
        std::string v, f;
        int base = 0;
        for (const auto& [lo, hi, inward] : boxes) {
            const auto [bv, bf] = box(lo, hi, base, inward);
            v += bv;
            f += bf;
            base += 8;
        }
        return scratch(name, v + f).string();
    };
    const std::string inward = file("inward.obj", {{0, 2, true}});
    const std::string mixed = file("mixed.obj", {{0, 2, false}, {5, 6, true}});
    const std::string cavity = file("cavity.obj", {{0, 4, false}, {1, 2, true}});
    for (const char* command : {"volume", "measure"}) {
        const auto r = cli_test::run_polyvol(std::string(command) + " --json '" + inward + "'");
        const json j = json::parse(r.out)[0];
        EXPECT_EQ(j["volume"], 8.0) << command;
        EXPECT_EQ(j["turned_outward_faces"], 6);
        EXPECT_NE(r.err.find("inside out: 1 shell turned outward (6 faces reversed)"), std::string::npos) << r.err;
        EXPECT_EQ(run(std::string(command) + " --json '" + mixed + "'")["volume"], 9.0) << command;
        EXPECT_EQ(run(std::string(command) + " --json '" + cavity + "'")["volume"], 63.0) << command;
        EXPECT_EQ(run(std::string(command) + " --json '" + cavity + "'")["turned_outward_faces"], 0);
        EXPECT_EQ(run(std::string(command) + " --json --signed '" + inward + "'")["volume"], -8.0) << command;
    }
    // The table, where no shells are analysed, gives the same numbers.
    const auto table = cli_test::run_polyvol("volume '" + mixed + "'");
    EXPECT_NE(table.out.find("  9  "), std::string::npos) << table.out;
    const json m = run("measure --json '" + inward + "'");
    EXPECT_EQ(m["mass"], 8.0);
    EXPECT_GT(m["inertia"][0][0].get<double>(), 0);
    // Each shell's own figures are those of the turned mesh too.
    const json shells = run("measure --json '" + mixed + "'")["shells"];
    ASSERT_EQ(shells.size(), 2u);
    EXPECT_EQ(shells[0]["volume"], 8.0);
    EXPECT_EQ(shells[1]["volume"], 1.0);
    EXPECT_EQ(shells[1]["centroid"], json::array({5.5, 5.5, 5.5}));
}

// Principal moments and axes (measure, with their bounds): the box 1 x 2 x 3,
// mass 6, has moments 2.5, 5, 6.5 about z, y, x; its bounds and size.
TEST(JsonKeys, PrincipalMomentsAndAxesOfABox) {
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 2 0\nv 1 2 0\nv 0 0 3\nv 1 0 3\nv 0 2 3\nv 1 2 3\n";
    obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    const json j = run("measure --json '" + scratch("box123.obj", obj).string() + "'");
    const double e = j["principal_moment_error"];
    EXPECT_LT(e, 1e-12);
    EXPECT_NEAR(j["principal_moments"][0].get<double>(), 2.5, e);
    EXPECT_NEAR(j["principal_moments"][1].get<double>(), 5, e);
    EXPECT_NEAR(j["principal_moments"][2].get<double>(), 6.5, e);
    EXPECT_EQ(j["principal_axes"][0], json({0.0, 0.0, 1.0}));
    EXPECT_EQ(j["principal_axes"][1], json({0.0, 1.0, 0.0}));
    EXPECT_LT(j["principal_axis_angle_bound"][0].get<double>(), 1e-12);
    EXPECT_EQ(j["bounds"], json({0.0, 0.0, 0.0, 1.0, 2.0, 3.0}));
    EXPECT_EQ(j["size"], json({1.0, 2.0, 3.0}));
    const auto table = cli_test::run_polyvol("measure '" + scratch("box123b.obj", obj).string() + "'");
    EXPECT_NE(table.out.find("principal moments 2.5, 5, 6.5"), std::string::npos) << table.out;
    EXPECT_EQ(table.out.find("-0,"), std::string::npos) << table.out;
}

// measure --format urdf|sdf: the <inertial> element. The box 1 x 2 x 3 at
// density 2 (mass 12): origin at (0.5, 1, 1.5), ixx = m (b² + c²)/12 = 13,
// iyy = 10, izz = 5; turned by the 3-4-5 rotation R about z (c = 0.6,
// s = 0.8), the tensor is R I R^T: ixx = 13 c² + 10 s², ixy = (13 - 10) c s.
TEST(JsonKeys, UrdfAndSdfInertialOfABox) {
    auto box_obj = [](double c, double s) {
        std::string obj;
        for (int k = 0; k < 8; ++k) {
            const double x = k & 1 ? 1 : 0, y = k >> 1 & 1 ? 2 : 0, z = k >> 2 & 1 ? 3 : 0;
            char line[128];
            std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", c * x - s * y, s * x + c * y, z);
            obj += line;
        }
        return obj + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    };
    const std::string plain = scratch("urdf_box.obj", box_obj(1, 0)).string();
    // Without --density the mass would be a guess: refused (exit 1), never written.
    const auto guess = cli_test::run_polyvol("measure --format urdf '" + plain + "'");
    EXPECT_EQ(guess.code, 1);
    EXPECT_NE(guess.err.find("--format urdf needs --density"), std::string::npos) << guess.err;
    EXPECT_EQ(guess.out, "");
    const auto urdf = cli_test::run_polyvol("measure --format urdf --density 2 '" + plain + "'");
    ASSERT_EQ(urdf.code, 0) << urdf.err;
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(urdf.out.c_str())) << urdf.out;
    const pugi::xml_node in = doc.child("inertial");
    EXPECT_STREQ(in.child("origin").attribute("xyz").value(), "0.5 1 1.5");
    EXPECT_EQ(in.child("mass").attribute("value").as_double(), 12.0);
    const pugi::xml_node inertia = in.child("inertia");
    EXPECT_EQ(inertia.attribute("ixx").as_double(), 13.0);
    EXPECT_EQ(inertia.attribute("iyy").as_double(), 10.0);
    EXPECT_EQ(inertia.attribute("izz").as_double(), 5.0);
    EXPECT_STREQ(inertia.attribute("ixy").value(), "0");
    // Turned: R diag(13, 10, 5) R^T about the turned centroid.
    const double c = 0.6, s = 0.8;
    const std::string turned = scratch("sdf_box.obj", box_obj(c, s)).string();
    const auto sdf = cli_test::run_polyvol("measure --format sdf --density 2 '" + turned + "'");
    ASSERT_EQ(sdf.code, 0) << sdf.err;
    ASSERT_TRUE(doc.load_string(sdf.out.c_str())) << sdf.out;
    const pugi::xml_node t = doc.child("inertial").child("inertia");
    auto value = [&](const char* name) { return std::stod(t.child(name).child_value()); };
    EXPECT_NEAR(value("ixx"), 13 * c * c + 10 * s * s, 1e-12);
    EXPECT_NEAR(value("iyy"), 13 * s * s + 10 * c * c, 1e-12);
    EXPECT_NEAR(value("ixy"), (13 - 10) * c * s, 1e-12);
    EXPECT_NEAR(value("izz"), 5, 1e-12);
    EXPECT_NEAR(value("ixz"), 0, 1e-12);
    EXPECT_NEAR(std::stod(doc.child("inertial").child("mass").child_value()), 12, 1e-12);
}

// A 3MF model of the cube [0, 2]^3 (object 1) with these build items.
std::string cube_3mf(const std::string& items) {
    return std::string(R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <resources><object id="1" type="model"><mesh>
  <vertices><vertex x="0" y="0" z="0"/><vertex x="2" y="0" z="0"/><vertex x="0" y="2" z="0"/><vertex x="2" y="2" z="0"/>
   <vertex x="0" y="0" z="2"/><vertex x="2" y="0" z="2"/><vertex x="0" y="2" z="2"/><vertex x="2" y="2" z="2"/></vertices>
  <triangles><triangle v1="0" v2="2" v3="3"/><triangle v1="0" v2="3" v3="1"/><triangle v1="4" v2="5" v3="7"/>
   <triangle v1="4" v2="7" v3="6"/><triangle v1="0" v2="1" v3="5"/><triangle v1="0" v2="5" v3="4"/>
   <triangle v1="2" v2="6" v3="7"/><triangle v1="2" v2="7" v3="3"/><triangle v1="0" v2="4" v3="6"/>
   <triangle v1="0" v2="6" v3="2"/><triangle v1="1" v2="3" v3="7"/><triangle v1="1" v2="7" v3="5"/></triangles>
 </mesh></object></resources>
 <build>)") + items + "</build>\n</model>\n";
}

// Two overlapping build items of one cube, one moved by (0.1, 0.2, 0.3): the
// solid's volume (15 + ... of the rounded coordinates) is given with a bound,
// and neither the table nor the shells' sentence calls it correctly rounded.
TEST(JsonKeys, TheSolidOfTransformedItemsIsNotClaimedCorrectlyRounded) {
    const std::string model = cube_3mf(R"(<item objectid="1"/><item objectid="1" transform="1 0 0 0 1 0 0 0 1 1.1 1.2 1.3"/>)");
    const std::string path = scratch("two_items.3mf", model).string();
    const json j = run("measure --json '" + path + "'");
    EXPECT_GT(j["overlapping_shells"].get<int>(), 0);
    EXPECT_EQ(j["accuracy"], "error-bound");
    // 16 - 0.9 * 0.8 * 0.7 exactly, within the bound.
    EXPECT_LE(std::fabs(j["volume"].get<double>() - (16 - 0.9 * 0.8 * 0.7)), j["volume_error_bound"].get<double>() + 1e-14);
    const auto table = cli_test::run_polyvol("measure '" + path + "'");
    EXPECT_EQ(table.out.find("correctly rounded"), std::string::npos) << table.out;
    const auto volume = cli_test::run_polyvol("volume '" + path + "'");
    EXPECT_NE(volume.out.find("winding number >= 1, within "), std::string::npos) << volume.out;
}

// overlap of a cube and one moved by a 3MF transform: the volumes come with a
// bound, not as correctly rounded, and the bound holds.
TEST(JsonKeys, OverlapOfTransformedOperandsIsABound) {
    auto cube = [](const std::string& transform) { return cube_3mf("<item objectid=\"1\"" + transform + "/>"); };
    const std::string a = scratch("cube_a.3mf", cube("")).string();
    const std::string b = scratch("cube_b.3mf", cube(R"( transform="1 0 0 0 1 0 0 0 1 1.1 1.2 1.3")")).string();
    const json plain = json::parse(cli_test::run_polyvol("overlap --json '" + a + "' '" + a + "'").out);
    EXPECT_EQ(plain["accuracy"], "correctly-rounded");
    const json j = json::parse(cli_test::run_polyvol("overlap --json '" + a + "' '" + b + "'").out);
    EXPECT_EQ(j["accuracy"], "error-bound");
    const double bound = j["volume_error_bound"];
    EXPECT_GT(bound, 0);
    EXPECT_LT(bound, 1e-10);
    EXPECT_LE(std::fabs(j["intersection"].get<double>() - 0.9 * 0.8 * 0.7), bound + 1e-15);
    const auto table = cli_test::run_polyvol("overlap '" + a + "' '" + b + "'");
    EXPECT_NE(table.out.find("volumes: within the ± shown"), std::string::npos) << table.out;
    EXPECT_NE(table.out.find("A ∩ B   0.504 ±"), std::string::npos) << table.out;
}
