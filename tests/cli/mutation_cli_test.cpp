// `polyvol volume` on a closed mesh with one defect of each kind the
// mutation test (tests/corpus/mutation_test.cpp) applies: refused, exit 3,
// "not a closed surface", and no volume printed — as an OBJ (loaded) and as
// a binary STL, loaded (up to 250,000 triangles) and streamed (--stream:
// closedness by fingerprint).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/generate.hpp"
#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using polyvol::Mesh;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("polyvol_mutation_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

struct Soup {  // triangles as corner coordinates, float-exact
    std::vector<std::array<float, 9>> t;
};

Soup soup_of(const Mesh& m) {
    Soup s;
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        std::array<float, 9> t{};
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a) t[3 * c + a] = static_cast<float>(m.positions[3 * m.indices[i + c] + a]);
        s.t.push_back(t);
    }
    return s;
}

void write_stl(const fs::path& p, const Soup& s) {
    std::ofstream out(p, std::ios::binary);
    const std::string header(80, ' ');
    out.write(header.data(), 80);
    const auto n = static_cast<uint32_t>(s.t.size());
    out.write(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : s.t) {
        const float normal[3] = {0, 0, 0};
        out.write(reinterpret_cast<const char*>(normal), 12);
        out.write(reinterpret_cast<const char*>(t.data()), 36);
        out.write("\0\0", 2);
    }
}

void write_obj(const fs::path& p, const Soup& s) {  // welded by bit-identical corners
    std::ofstream out(p);
    out.precision(9);
    std::vector<std::array<float, 3>> v;
    std::string faces;
    for (const auto& t : s.t) {
        faces += "f";
        for (int c = 0; c < 3; ++c) {
            const std::array<float, 3> p3{t[3 * c], t[3 * c + 1], t[3 * c + 2]};
            std::size_t i = 0;
            while (i < v.size() && std::memcmp(v[i].data(), p3.data(), 12) != 0) ++i;
            if (i == v.size()) v.push_back(p3);
            faces += " " + std::to_string(i + 1);
        }
        faces += "\n";
    }
    for (const auto& p3 : v) out << "v " << p3[0] << " " << p3[1] << " " << p3[2] << "\n";
    out << faces;
}

TEST(MutationCli, EveryDefectIsRefusedWithoutAVolume) {
    const Soup base = soup_of(polyvol::generate::uv_sphere(6, 10));
    std::vector<std::pair<std::string, Soup>> cases;
    Soup s = base;
    s.t.erase(s.t.begin() + 7);
    cases.emplace_back("delete", s);
    s = base;
    std::swap(s.t[7][0], s.t[7][3]), std::swap(s.t[7][1], s.t[7][4]), std::swap(s.t[7][2], s.t[7][5]);
    cases.emplace_back("flip", s);
    s = base;
    s.t.push_back(s.t[7]);
    cases.emplace_back("duplicate", s);
    s = base;
    s.t[7][0] = std::nextafter(s.t[7][0], 1e30f);
    cases.emplace_back("ulp", s);
    s = base;
    {  // split triangle 7 at the midpoints of two edges
        const auto t = s.t[7];
        auto mid = [&](int a, int b) {
            return std::array<float, 3>{(t[3 * a] + t[3 * b]) / 2, (t[3 * a + 1] + t[3 * b + 1]) / 2,
                                        (t[3 * a + 2] + t[3 * b + 2]) / 2};
        };
        const auto ab = mid(0, 1), bc = mid(1, 2);
        auto tri = [](const float* p, const std::array<float, 3>& q, const float* r) {
            return std::array<float, 9>{p[0], p[1], p[2], q[0], q[1], q[2], r[0], r[1], r[2]};
        };
        s.t[7] = tri(&t[0], ab, &t[6]);
        s.t.push_back(std::array<float, 9>{ab[0], ab[1], ab[2], bc[0], bc[1], bc[2], t[6], t[7], t[8]});
        s.t.push_back(std::array<float, 9>{ab[0], ab[1], ab[2], t[3], t[4], t[5], bc[0], bc[1], bc[2]});
    }
    cases.emplace_back("tjunction", s);
    // The intact sphere is measured (the files are right).
    write_obj(scratch("intact.obj"), base);
    ASSERT_EQ(cli_test::run_polyvol("volume '" + scratch("intact.obj").string() + "'").code, 0);
    for (const auto& [kind, soup] : cases) {
        for (const char* ext : {".obj", ".stl"}) {
            const fs::path p = scratch(kind + ext);
            if (std::string(ext) == ".obj") write_obj(p, soup); else write_stl(p, soup);
            const auto table = cli_test::run_polyvol("volume '" + p.string() + "'");
            EXPECT_EQ(table.code, 3) << kind << ext << table.out << table.err;
            if (std::string(ext) == ".stl") {  // the streamed route refuses it alike
                const auto streamed = cli_test::run_polyvol("volume --stream '" + p.string() + "'");
                EXPECT_EQ(streamed.code, 3) << kind << streamed.out << streamed.err;
                EXPECT_NE(streamed.out.find("open surface: not measured"), std::string::npos) << kind << streamed.out;
            }
            // A flip leaves the surface closed, wound inconsistently: the message says so and names --orient.
            const std::string words = kind == "flip" ? "closed, but 3 edges are misoriented" : "not a closed surface";
            EXPECT_NE(table.err.find(words), std::string::npos) << kind << ext << table.err;
            if (kind == "flip") {
                EXPECT_NE(table.err.find("--orient"), std::string::npos) << table.err;
            }
            EXPECT_NE(table.out.find("open surface: not measured"), std::string::npos) << kind << ext << table.out;
            const auto j = nlohmann::json::parse(cli_test::run_polyvol("volume --json '" + p.string() + "'").out)[0];
            EXPECT_EQ(j["exit_code"], 3) << kind << ext;
            EXPECT_TRUE(!j.contains("volume") || j["volume"].is_null()) << kind << ext << j.dump();
        }
    }
    // --orient winds the flipped triangle back: the intact sphere's volume in
    // the same format (an OBJ's decimals are not the STL's float32 values), bit for bit.
    write_stl(scratch("intact.stl"), base);
    for (const char* ext : {".obj", ".stl"}) {
        const auto intact =
            nlohmann::json::parse(cli_test::run_polyvol("volume --json '" + scratch(std::string("intact") + ext).string() + "'").out)[0];
        const fs::path p = scratch(std::string("flip") + ext);
        const auto r = cli_test::run_polyvol("volume --orient --json '" + p.string() + "'");
        ASSERT_EQ(r.code, 0) << ext << r.err;
        const auto j = nlohmann::json::parse(r.out)[0];
        EXPECT_EQ(j["oriented_faces_flipped"], 1) << ext;
        EXPECT_EQ(j["volume"].get<double>(), intact["volume"].get<double>()) << ext;
        const auto table = cli_test::run_polyvol("measure --orient '" + p.string() + "'");
        EXPECT_EQ(table.code, 0);
        EXPECT_NE(table.out.find("oriented: 1 face flipped"), std::string::npos) << table.out;
    }
}

// --orient on whole shells: a box turned inside out comes out outward, and a
// cavity wound outward comes out inward (by nesting): the solid's volume.
TEST(MutationCli, OrientTurnsShellsOutwardAndCavitiesInward) {
    const fs::path inside_out = scratch("inside_out.obj"), cavity = scratch("cavity.obj");
    cli_test::write_boxes_obj(inside_out, {{0, 0, 0, 2, 3, 4}});
    {  // reverse every face of the box
        std::ifstream in(inside_out);
        std::string line, text;
        while (std::getline(in, line)) {
            if (line.rfind("f ", 0) == 0) {
                std::istringstream w(line.substr(2));
                std::vector<std::string> v{std::istream_iterator<std::string>(w), {}};
                line = "f " + v[0] + " " + v[3] + " " + v[2] + " " + v[1];
            }
            text += line + "\n";
        }
        std::ofstream(inside_out) << text;
    }
    cli_test::write_boxes_obj(cavity, {{0, 0, 0, 4, 4, 4}, {1, 1, 1, 2, 3, 2}});  // both outward
    const auto a = nlohmann::json::parse(cli_test::run_polyvol("measure --orient --json '" + inside_out.string() + "'").out)[0];
    EXPECT_EQ(a["volume"].get<double>(), 24.0);
    EXPECT_EQ(a["oriented_faces_flipped"], 6);
    const auto b = nlohmann::json::parse(cli_test::run_polyvol("measure --orient --json '" + cavity.string() + "'").out)[0];
    EXPECT_EQ(b["volume"].get<double>(), 64.0 - 2.0);
    EXPECT_EQ(b["oriented_faces_flipped"], 6);
    EXPECT_EQ(b["cavities"], 1);
    const auto plain = nlohmann::json::parse(cli_test::run_polyvol("measure --json '" + cavity.string() + "'").out)[0];
    EXPECT_EQ(plain["volume"].get<double>(), 64.0);  // without --orient: the solid of the overlapping shells
}

}  // namespace
