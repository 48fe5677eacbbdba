// `polyvol grid` as users run it: the .npy header and shape, the .vti as
// XML with the right extent and values, the JSON summary's keys, the PNG,
// and the exit codes.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "cli/run_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kCorpus = POLYVOL_CORPUS_DIR;

using cli_test::CliRun;

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path scratch_dir() { return fs::temp_directory_path() / ("polyvol_grid_cli_" + std::to_string(::getpid())); }

fs::path scratch(const std::string& name) {
    fs::create_directories(scratch_dir());
    return scratch_dir() / name;
}

// Removes the scratch files when the test program ends.
struct ScratchCleanup {
    ~ScratchCleanup() {
        std::error_code ec;
        fs::remove_all(scratch_dir(), ec);
    }
} scratch_cleanup;

CliRun polyvol(const std::string& args) { return cli_test::run_polyvol(args); }

std::string corpus(const std::string& rel) { return "'" + (kCorpus / "meshes" / rel).string() + "'"; }

struct Npy {
    std::string header;
    std::vector<double> data;
    std::size_t data_offset = 0;
};

Npy read_npy(const fs::path& p) {
    const std::string bytes = slurp(p);
    Npy n;
    EXPECT_GE(bytes.size(), 10u);
    if (bytes.size() < 10) return n;
    EXPECT_EQ(bytes.substr(0, 6), "\x93NUMPY");
    EXPECT_EQ(bytes[6], 1);
    EXPECT_EQ(bytes[7], 0);
    const std::size_t len = static_cast<unsigned char>(bytes[8]) | (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
    n.header = bytes.substr(10, len);
    n.data_offset = 10 + len;
    EXPECT_EQ(n.data_offset % 64, 0u);
    EXPECT_EQ(n.header.back(), '\n');
    EXPECT_EQ((bytes.size() - n.data_offset) % 8, 0u);
    n.data.resize((bytes.size() - n.data_offset) / 8);
    std::memcpy(n.data.data(), bytes.data() + n.data_offset, 8 * n.data.size());
    return n;
}

double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
}

TEST(GridCli, NpyHasTheHeaderShapeAndValues) {
    const fs::path out = scratch("cube.npy");
    const CliRun r = polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " --cells 10 -o '" + out.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    const Npy n = read_npy(out);
    EXPECT_NE(n.header.find("'descr': '<f8'"), std::string::npos) << n.header;
    EXPECT_NE(n.header.find("'fortran_order': False"), std::string::npos) << n.header;
    EXPECT_NE(n.header.find("'shape': (10, 10, 10)"), std::string::npos) << n.header;
    ASSERT_EQ(n.data.size(), 1000u);
    EXPECT_NEAR(sum(n.data), 1.0, 1e-15);
    // the cube [0,1]^3 padded by one cell of 1/8: cell [1][1][1] is full, [0][..] empty
    EXPECT_EQ(n.data[(1 * 10 + 1) * 10 + 1], 1.0 / 512);
    EXPECT_EQ(n.data[0], 0.0);
}

TEST(GridCli, SurfaceHasAreaAndNormalPerCell) {
    // The unit cube padded by one cell of 1/8: each of its 6 faces is cut
    // into 8 x 8 cells; every cell's area is 1/64 or 0, the total 6.
    const fs::path out = scratch("surface.npy");
    const fs::path vti = scratch("surface.vti");
    const CliRun r = polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " --cells 10 -o '" + vti.string() +
                             "' --surface '" + out.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    const Npy n = read_npy(out);
    EXPECT_NE(n.header.find("'shape': (10, 10, 10, 4)"), std::string::npos) << n.header;
    ASSERT_EQ(n.data.size(), 4000u);
    double area = 0, nx = 0;
    for (std::size_t c = 0; c < 1000; ++c) {
        area += n.data[4 * c];
        nx += n.data[4 * c + 1];
    }
    EXPECT_NEAR(area, 6.0, 1e-14);
    EXPECT_NEAR(nx, 0.0, 1e-14);
    // Cell (0, 1, 1) holds nothing; cell (1, 1, 1) a corner of three faces, each 1/64.
    EXPECT_EQ(n.data[4 * ((0 * 10 + 1) * 10 + 1)], 0.0);
    EXPECT_NEAR(n.data[4 * ((1 * 10 + 1) * 10 + 1)], 3.0 / 64, 1e-16);
    const std::string xml = slurp(vti);
    EXPECT_NE(xml.find("Name=\"wetted_area\""), std::string::npos);
    EXPECT_NE(xml.find("Name=\"surface_normal\" NumberOfComponents=\"3\""), std::string::npos) << xml.substr(0, 2000);
}

TEST(GridCli, SeveralBodiesPutTheBodyAxisFirstAndFractions) {
    const fs::path out = scratch("two.npy");
    const fs::path uni = scratch("union.npy"), inter = scratch("intersection.npy");
    const CliRun r = polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " " +
                          corpus("stl-models/tetrahedron.min.ascii.stl") + " --dims 4 5 6 --bounds 0 0 0 1 1 1" +
                          " --fractions -o '" + out.string() + "' --union '" + uni.string() + "' --intersection '" +
                          inter.string() + "' --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const Npy n = read_npy(out);
    EXPECT_NE(n.header.find("'shape': (2, 4, 5, 6)"), std::string::npos) << n.header;
    ASSERT_EQ(n.data.size(), 240u);
    for (std::size_t c = 0; c < 120; ++c) EXPECT_EQ(n.data[c], 1.0);  // the cube fills the grid
    const Npy u = read_npy(uni), x = read_npy(inter);
    EXPECT_NE(u.header.find("'shape': (4, 5, 6)"), std::string::npos) << u.header;
    EXPECT_NE(x.header.find("'shape': (4, 5, 6)"), std::string::npos) << x.header;
    ASSERT_EQ(u.data.size(), 120u);
    ASSERT_EQ(x.data.size(), 120u);
    for (std::size_t c = 0; c < 120; ++c) {
        EXPECT_EQ(u.data[c], 1.0);              // the union: the cube
        EXPECT_EQ(x.data[c], n.data[120 + c]);  // the intersection: the tetrahedron inside it
    }
    const json j = json::parse(r.out);
    EXPECT_EQ(j["body_volumes"].size(), 2u);
    EXPECT_NEAR(j["body_volumes"][1].get<double>(), 1.0 / 6, 1e-16);
    EXPECT_NEAR(j["union_volume"].get<double>(), 1.0, 1e-15);
    EXPECT_EQ(j["intersection_volume"], j["body_volumes"][1]);
}

// Two cubes of side 2 overlapping in a unit cube, with cell faces off
// theirs: the union (15) and the intersection (1) exact in every cell,
// contact cells included, and the union's surface (area 42).
TEST(GridCli, OverlappingBodiesUnionAndIntersectionPerCell) {
    const fs::path a = scratch("a.obj"), b = scratch("b.obj");
    cli_test::write_boxes_obj(a, {{0, 0, 0, 2, 2, 2}});
    cli_test::write_boxes_obj(b, {{1, 1, 1, 3, 3, 3}});
    const fs::path uni = scratch("u.npy"), inter = scratch("i.npy"), surf = scratch("s.npy"), vti = scratch("ab.vti");
    const CliRun r = polyvol("grid '" + a.string() + "' '" + b.string() + "' --dims 4 4 4 --bounds -0.25 -0.25 -0.25 3.25 3.25 3.25 --union '" +
                             uni.string() + "' --intersection '" + inter.string() + "' --surface '" + surf.string() +
                             "' -o '" + vti.string() + "' --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["union_volume"], 15.0);
    EXPECT_EQ(j["intersection_volume"], 1.0);
    EXPECT_GT(j["contact_cells"].get<int>(), 0);
    EXPECT_GT(j["crossing_pairs"].get<int>(), 0);
    // Cells of 0.875: cell (2, 1, 1) = [1.5, 2.375] x [0.625, 1.5]^2 holds A's face x = 2 and
    // B's faces y = 1, z = 1: A has 0.5 x 0.875^2 of it, B 0.875 x 0.5^2, both 0.5^3.
    const Npy u = read_npy(uni), x = read_npy(inter), s = read_npy(surf);
    const std::size_t contact = (2 * 4 + 1) * 4 + 1;
    EXPECT_NEAR(u.data[contact], 0.5 * 0.875 * 0.875 + 0.875 * 0.25 - 0.125, 1e-15);
    EXPECT_NEAR(x.data[contact], 0.125, 1e-15);
    EXPECT_NE(s.header.find("'shape': (3, 4, 4, 4, 4)"), std::string::npos) << s.header;
    double area = 0;
    for (std::size_t cell = 0; cell < 64; ++cell) area += s.data[4 * (2 * 64 + cell)];
    EXPECT_NEAR(area, 42.0, 1e-13);  // 2 x 24, less the 1 x 1 squares of three faces of each inside the other
    const std::string xml = slurp(vti);
    for (const char* name : {"union_volume", "intersection_volume", "cell_class", "wetted_area_union"})
        EXPECT_NE(xml.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
}

TEST(GridCli, JsonSummaryHasEveryKey) {
    const CliRun r = polyvol("grid " + corpus("libcgal-demo/sphere.off") + " --cells 16 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json j = json::parse(r.out);
    for (const char* key : {"grid", "bodies", "body_volumes", "union_volume", "crossing_pairs", "full_cells",
                            "empty_cells", "cut_cells", "contact_cells"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["grid"]["dims"], json::array({16, 16, 16}));
    EXPECT_EQ(j["grid"]["bounds"].size(), 6u);
    EXPECT_NEAR(j["body_volumes"][0].get<double>(), 0.5059521479273688, 1e-15);
    EXPECT_EQ(j["union_volume"], j["body_volumes"][0]);
    EXPECT_EQ(j["contact_cells"], 0);
    EXPECT_EQ(j["full_cells"].get<int>() + j["empty_cells"].get<int>() + j["cut_cells"].get<int>(), 16 * 16 * 16);
    // the same summary in a .json file
    const fs::path out = scratch("summary.json");
    const CliRun f = polyvol("grid " + corpus("libcgal-demo/sphere.off") + " --cells 16 -o '" + out.string() + "'");
    ASSERT_EQ(f.code, 0) << f.err;
    const json k = json::parse(slurp(out));
    EXPECT_EQ(k["body_volumes"], j["body_volumes"]);
}

// The XML of a VTK file written in the appended raw form, and its arrays:
// the document without the appended block, and array `offset`'s doubles.
struct VtkFile {
    pugi::xml_document doc;
    std::string raw;  // the appended block after its "_"
    std::vector<double> doubles(const pugi::xml_node& array) const {
        const std::size_t at = std::stoull(array.attribute("offset").value());
        uint64_t bytes = 0;
        std::memcpy(&bytes, raw.data() + at, 8);
        std::vector<double> v(bytes / 8);
        std::memcpy(v.data(), raw.data() + at + 8, bytes);
        return v;
    }
};
bool read_vtk(const fs::path& path, VtkFile& f) {
    const std::string all = slurp(path);
    const std::size_t block = all.find("<AppendedData encoding=\"raw\">");
    if (block == std::string::npos) return false;
    f.raw = all.substr(all.find('_', block) + 1);
    return static_cast<bool>(f.doc.load_string((all.substr(0, block) + "</VTKFile>").c_str()));
}

TEST(GridCli, VtiIsVtkBinaryWithTheExtentAndOneValuePerCell) {
    const fs::path out = scratch("sphere.vti");
    const CliRun r = polyvol("grid " + corpus("libcgal-demo/sphere.off") + " --dims 7 6 5 -o '" + out.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    VtkFile f;
    ASSERT_TRUE(read_vtk(out, f));
    const pugi::xml_node file = f.doc.child("VTKFile");
    EXPECT_STREQ(file.attribute("type").value(), "ImageData");
    EXPECT_STREQ(file.attribute("header_type").value(), "UInt64");
    const pugi::xml_node image = file.child("ImageData");
    EXPECT_STREQ(image.attribute("WholeExtent").value(), "0 7 0 6 0 5");
    EXPECT_STREQ(image.child("Piece").attribute("Extent").value(), "0 7 0 6 0 5");
    const pugi::xml_node array = image.child("Piece").child("CellData").child("DataArray");
    EXPECT_STREQ(array.attribute("Name").value(), "volume");
    EXPECT_STREQ(array.attribute("format").value(), "appended");
    const std::vector<double> v = f.doubles(array);
    EXPECT_EQ(v.size(), 7u * 6 * 5);
    EXPECT_NEAR(sum(v), 0.5059521479273688, 1e-14);
    // a non-uniform grid cannot be ImageData; .vtr takes it
    const CliRun bad = polyvol("grid " + corpus("libcgal-demo/sphere.off") +
                            " --x-planes -1,-0.2,0.1,1 -o '" + out.string() + "'");
    EXPECT_EQ(bad.code, 1);
    const fs::path vtr = scratch("sphere.vtr");
    const CliRun ok = polyvol("grid " + corpus("libcgal-demo/sphere.off") + " --cells 8 --x-planes -1,-0.2,0.1,1 -o '" +
                           vtr.string() + "'");
    ASSERT_EQ(ok.code, 0) << ok.err;
    VtkFile rect;
    ASSERT_TRUE(read_vtk(vtr, rect));
    EXPECT_STREQ(rect.doc.child("VTKFile").attribute("type").value(), "RectilinearGrid");
    EXPECT_STREQ(rect.doc.child("VTKFile").child("RectilinearGrid").attribute("WholeExtent").value(), "0 3 0 8 0 8");
}

TEST(GridCli, PngSliceIsWritten) {
    const fs::path png = scratch("slice.png");
    const CliRun r = polyvol("grid " + corpus("libcgal-demo/sphere.off") + " --cells 20 --png '" + png.string() +
                          "' --slice z=0.1");
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string bytes = slurp(png);
    ASSERT_GT(bytes.size(), 24u);
    EXPECT_EQ(bytes.substr(0, 8), "\x89PNG\r\n\x1a\n");
    auto be32 = [&](std::size_t at) {
        return (static_cast<uint32_t>(static_cast<unsigned char>(bytes[at])) << 24) |
               (static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + 1])) << 16) |
               (static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + 2])) << 8) |
               static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + 3]));
    };
    // IHDR: a square slice of 640 x 640 pixels, with margins for the axes, the colour bar and the title
    EXPECT_EQ(be32(16), 640u + 90 + 120);
    EXPECT_EQ(be32(20), 640u + 44 + 64);
}

TEST(GridCli, ExitCodes) {
    // 3: an open surface
    const CliRun open = polyvol("grid " + corpus("stl-models/missingFace.ascii.stl") + " --cells 8");
    EXPECT_EQ(open.code, 3);
    EXPECT_NE(open.err.find("not a closed surface"), std::string::npos) << open.err;
    // 2: unreadable
    const CliRun missing = polyvol("grid /nonexistent/mesh.stl");
    EXPECT_EQ(missing.code, 2);
    // 1: usage
    EXPECT_EQ(polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " -o out.txt").code, 1);
    EXPECT_EQ(polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " --cells 8 --dims 2 2 2").code, 1);
    EXPECT_EQ(polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " --bounds 0 0 0 1 -1 1").code, 1);
    EXPECT_EQ(polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " --png x.png --slice w=3").code, 1);
    EXPECT_EQ(polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") + " --png x.png --slice z=7").code, 1);
    EXPECT_EQ(polyvol("grid").code, 1);
    // 1: planes that disagree with --dims, --bounds or --cells (never a silent choice)
    const std::string cube = corpus("stl-models/unitCube.ascii.stl");
    const CliRun dims = polyvol("grid " + cube + " --dims 4 4 4 --x-planes 0,0.5,1");
    EXPECT_EQ(dims.code, 1);
    EXPECT_NE(dims.err.find("--dims gives 4 cells along x but --x-planes gives 3 planes (2 cells)"), std::string::npos)
        << dims.err;
    EXPECT_EQ(polyvol("grid " + cube + " --dims 2 4 4 --x-planes 0,0.5,1 -o '" + scratch("agree.json").string() + "'").code, 0);
    const CliRun bounds = polyvol("grid " + cube + " --bounds 0 0 0 1 1 1 --y-planes -0.5,0.5,1");
    EXPECT_EQ(bounds.code, 1);
    EXPECT_NE(bounds.err.find("--bounds gives y from 0 to 1 but --y-planes runs from -0.5 to 1"), std::string::npos)
        << bounds.err;
    const CliRun every = polyvol("grid " + cube + " --cells 8 --x-planes 0,1 --y-planes 0,1 --z-planes 0,1");
    EXPECT_EQ(every.code, 1);
    EXPECT_NE(every.err.find("--cells has no effect"), std::string::npos) << every.err;
    // 3: nothing to grid
    EXPECT_EQ(polyvol("grid " + corpus("stl-models/faceless.ascii.stl")).code, 3);
}

TEST(GridCli, CentroidsOfACube) {
    const fs::path out = scratch("centroids.npy");
    const CliRun r = polyvol("grid " + corpus("stl-models/unitCube.ascii.stl") +
                          " --dims 2 2 2 --bounds 0 0 0 1 1 1 --centroids '" + out.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    const Npy n = read_npy(out);
    EXPECT_NE(n.header.find("'shape': (2, 2, 2, 3)"), std::string::npos) << n.header;
    ASSERT_EQ(n.data.size(), 24u);
    EXPECT_EQ(n.data[0], 0.25);
    EXPECT_EQ(n.data[23], 0.75);
}

// A grid whose arrays exceed the memory limit is refused before anything is
// allocated, with the estimate (issue #21: it ended in std::bad_alloc, exit 4).
TEST(GridCli, TooLargeForMemoryIsRefusedWithTheEstimate) {
    const std::string cube = corpus("stl-models/unitCube.ascii.stl");
    // 8e9 cells: 59.6 GiB, beyond the default limit on machines of up to 79 GiB.
    const double memory = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
    if (memory > 0 && memory < 0x1p36) {
        const CliRun huge = polyvol("grid " + cube + " --dims 2000 2000 2000");
        EXPECT_EQ(huge.code, 1) << huge.err;
        EXPECT_NE(huge.err.find("needs about 59.6 GiB for its arrays, more than three quarters of this machine"),
                  std::string::npos)
            << huge.err;
    }
    const CliRun capped = polyvol("grid " + cube + " --dims 64 64 64 --max-memory 1M");  // 2 MiB
    EXPECT_EQ(capped.code, 1) << capped.err;
    EXPECT_NE(capped.err.find("needs about 2 MiB for its arrays, more than --max-memory 1 MiB"), std::string::npos)
        << capped.err;
    EXPECT_EQ(polyvol("grid " + cube + " --dims 64 64 64 --max-memory 3M").code, 0);
    const CliRun bad = polyvol("grid " + cube + " --max-memory lots");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("--max-memory takes a size such as 8G or 512M, not 'lots'"), std::string::npos) << bad.err;
}

// A body inside out has no union with the others: the bodies' cells are still
// given, with a warning, unless an output needs the union (exit 3).
// An inside-out body is turned outward, as `volume` turns it (the union is
// then defined); --signed keeps it, and then the union is undefined.
TEST(GridCli, AnInsideOutBodyIsTurnedOutwardUnlessSigned) {
    const fs::path a = scratch("outward.obj"), b = scratch("inward.obj");
    cli_test::write_boxes_obj(a, {{0, 0, 0, 2, 2, 2}});
    cli_test::write_boxes_obj(b, {{1, 1, 1, 3, 3, 3}});
    {  // reverse every face of b
        std::string text = slurp(b), flipped;
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);) {
            if (line.rfind("f ", 0) == 0) {
                std::istringstream f(line.substr(2));
                std::vector<std::string> v{std::istream_iterator<std::string>(f), std::istream_iterator<std::string>()};
                line = "f";
                for (auto it = v.rbegin(); it != v.rend(); ++it) line += " " + *it;
            }
            flipped += line + "\n";
        }
        std::ofstream(b) << flipped;
    }
    const std::string files = "'" + a.string() + "' '" + b.string() + "' --dims 4 4 4";
    const CliRun turned = polyvol("grid " + files + " --json");
    ASSERT_EQ(turned.code, 0) << turned.err;
    EXPECT_NE(turned.err.find("inside out: 1 shell turned outward (6 faces reversed)"), std::string::npos) << turned.err;
    const json t = json::parse(turned.out);
    EXPECT_EQ(t["body_volumes"][0], 8.0);
    EXPECT_EQ(t["body_volumes"][1], 8.0);
    EXPECT_EQ(t["union_volume"], 15.0);
    const CliRun r = polyvol("grid " + files + " --json --signed");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: grid: the union is undefined: body 2 is inside out"), std::string::npos) << r.err;
    const json j = json::parse(r.out);
    EXPECT_TRUE(j["union_volume"].is_null());
    EXPECT_NE(j["union_error"].get<std::string>().find("inside out"), std::string::npos);
    EXPECT_EQ(j["body_volumes"][0], 8.0);
    EXPECT_EQ(j["body_volumes"][1], -8.0);
    const CliRun needs = polyvol("grid " + files + " --signed --union '" + scratch("u2.npy").string() + "'");
    EXPECT_EQ(needs.code, 3);
    EXPECT_NE(needs.err.find("inside out"), std::string::npos) << needs.err;
}

}  // namespace

namespace {
// A 3MF body whose transform is applied in floating point: the grid says its
// cells are exact for the rounded coordinates, not for the file's.
TEST(GridCli, TransformedBodiesAreSaidToBeRounded) {
    const fs::path p = scratch("moved_tet.3mf");
    std::ofstream(p) << R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <resources><object id="1" type="model"><mesh>
  <vertices><vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/></vertices>
  <triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/><triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles>
 </mesh></object></resources>
 <build><item objectid="1" transform="1 0 0 0 1 0 0 0 1 0.1 0.2 0.3"/></build>
</model>
)";
    const CliRun r = polyvol("grid --cells 4 '" + p.string() + "' -o '" + scratch("moved_tet.json").string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("the cells are exact for the coordinates so rounded"), std::string::npos) << r.err;
}
}  // namespace
