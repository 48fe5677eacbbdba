// The cells' own volumes (polyvol/cells.hpp) and the OpenFOAM polyMesh
// reader (polyvol/cell_mesh_io.hpp), on meshes blockMesh wrote
// (tests/data/openfoam/*/system/blockMeshDict): a graded box, whose cells
// are boxes with a closed form, and a warped block, whose faces are not
// planar, in ASCII and in binary.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gmpxx.h>
#include <string>
#include <vector>

#include "exact/rational.hpp"
#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/cells.hpp"
#include "polyvol/io.hpp"
#include "common/box_overlap.hpp"
#include "common/cell_surfaces.hpp"
#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "polyvol/measure.hpp"

namespace fs = std::filesystem;
using namespace polyvol;
using polyvol::test::boundary_surface;
using polyvol::test::cell_surface;

namespace {

const std::string kData = std::string(POLYVOL_TEST_DATA) + "/openfoam/";



// The box of cell c's points.
void cell_box(const CellMeshView& m, std::size_t c, double* lo, double* hi) {
    for (int k = 0; k < 3; ++k) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (m.owner[f] == c || m.neighbour[f] == c)
            for (const uint32_t p : m.face(f))
                for (int k = 0; k < 3; ++k) {
                    lo[k] = std::min(lo[k], m.points[3 * p + k]);
                    hi[k] = std::max(hi[k], m.points[3 * p + k]);
                }
}

void expect_same_mesh(const CellMesh& a, const CellMesh& b) {
    ASSERT_EQ(a.points.size(), b.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]) << i;
    EXPECT_EQ(a.face_offsets, b.face_offsets);
    EXPECT_EQ(a.face_points, b.face_points);
    EXPECT_EQ(a.owner, b.owner);
    EXPECT_EQ(a.neighbour, b.neighbour);
    EXPECT_EQ(a.cells, b.cells);
}

void gzip_file(const fs::path& from, const fs::path& to) {
    std::ifstream in(from, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    gzFile out = gzopen(to.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    gzwrite(out, bytes.data(), static_cast<unsigned>(bytes.size()));
    gzclose(out);
}

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("polyvol_cells_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// A copy of a case's polyMesh with `file` replaced by `text`.
fs::path with_file(const std::string& name, const std::string& file, const std::string& text) {
    const fs::path d = scratch(name);
    for (const char* f : {"points", "faces", "owner", "neighbour"})
        fs::copy_file(kData + "warped_ascii/constant/polyMesh/" + f, d / f);
    std::ofstream(d / file, std::ios::trunc) << text;
    return d;
}

const char* kHeader =
    "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n    object %s;\n}\n";

std::string header(const std::string& cls, const std::string& object) {
    char buf[256];
    std::snprintf(buf, sizeof buf, kHeader, cls.c_str(), object.c_str());
    return buf;
}

}  // namespace

TEST(PolyMesh, AsciiAndBinaryFilesGiveTheSameMesh) {
    const LoadedCellMesh a = read_polymesh(kData + "warped_ascii");
    const LoadedCellMesh b = read_polymesh(kData + "warped_binary/constant/polyMesh");
    EXPECT_EQ(a.encoding, "ascii");
    EXPECT_EQ(b.encoding, "binary");
    EXPECT_EQ(a.unit, "m");
    EXPECT_EQ(a.mesh.cells, 12u);  // 3 x 2 x 2
    EXPECT_EQ(a.mesh.face_offsets.size() - 1, 3u * 2 * 2 * 3 + 2 * 2 + 3 * 2 + 3 * 2);
    expect_same_mesh(a.mesh, b.mesh);
    EXPECT_FALSE(check_cell_mesh(a.mesh.view()));
}

TEST(PolyMesh, GzipCompressedFilesAreRead) {
    const fs::path d = scratch("gz");
    for (const char* f : {"points", "faces", "owner", "neighbour"})
        gzip_file(kData + "warped_binary/constant/polyMesh/" + f, d / (std::string(f) + ".gz"));
    const LoadedCellMesh z = read_polymesh(d.string());
    EXPECT_TRUE(z.gzip);
    expect_same_mesh(z.mesh, read_polymesh(kData + "warped_binary").mesh);
}

TEST(CellVolumes, GradedBoxCellsAreTheirBoxesCorrectlyRounded) {
    const LoadedCellMesh box = read_polymesh(kData + "graded_box");
    const CellMeshView m = box.mesh.view();
    ASSERT_EQ(m.cell_count(), 24u);
    const CellVolumes v = cell_volumes(m);
    mpq_class sum = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        double lo[3], hi[3];
        cell_box(m, c, lo, hi);
        mpq_class exact = 1;
        for (int k = 0; k < 3; ++k) exact *= mpq_class(hi[k]) - mpq_class(lo[k]);
        sum += exact;
        EXPECT_EQ(v.volumes[c], exact::round_to_double(exact.get_mpq_t())) << "cell " << c;
    }
    // The cells add up exactly: their total is the exact sum rounded once.
    EXPECT_EQ(v.total, exact::round_to_double(sum.get_mpq_t()));
    EXPECT_EQ(v.negative_cells, 0u);
}

TEST(CellVolumes, WarpedCellsAreTheirSurfacesVolumesAndAddUpToTheBoundarys) {
    const LoadedCellMesh warped = read_polymesh(kData + "warped_ascii");
    const CellMeshView m = warped.mesh.view();
    const CellVolumes v = cell_volumes(m);
    ASSERT_EQ(v.volumes.size(), 12u);
    double naive = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        // measure's kernels on the cell's surface (another code path): the same bits.
        const Mesh s = cell_surface(m, c);
        EXPECT_EQ(v.volumes[c], signed_volume(s.view())) << "cell " << c;
        EXPECT_GT(v.volumes[c], 0);
        naive += v.volumes[c];
    }
    // Conservation: internal faces cancel exactly, so the cells' exact sum is
    // the exact volume of the boundary faces.
    const Mesh outside = boundary_surface(m);
    EXPECT_EQ(v.total, signed_volume(outside.view()));
    EXPECT_EQ(covered_volume(m), v.total);  // cells that tile cover each point once
    EXPECT_NEAR(naive, v.total, 1e-13 * v.total);
    EXPECT_EQ(v.face_triangles, 2 * (m.face_count()));
}

TEST(CellVolumes, TheResultDoesNotDependOnTheFacesStartingPoint) {
    // Rotating each face's point list (same polygon, same winding) keeps the
    // triangles: the fan starts at the point first in (x, y, z) order.
    CellMesh rotated = read_polymesh(kData + "warped_ascii").mesh;
    for (std::size_t f = 0; f + 1 < rotated.face_offsets.size(); ++f)
        std::rotate(rotated.face_points.begin() + rotated.face_offsets[f],
                    rotated.face_points.begin() + rotated.face_offsets[f] + 1 + f % 3,
                    rotated.face_points.begin() + rotated.face_offsets[f + 1]);
    const CellVolumes a = cell_volumes(read_polymesh(kData + "warped_ascii").mesh.view());
    const CellVolumes b = cell_volumes(rotated.view());
    EXPECT_EQ(a.volumes, b.volumes);
    EXPECT_EQ(a.total, b.total);
}

TEST(CellVolumes, ARenumberedMeshGivesTheSameBits) {
    // The points numbered backwards: the face rule is one of positions, so
    // every warped face is split alike and every cell's volume is the same.
    const CellMesh original = read_polymesh(kData + "warped_ascii").mesh;
    CellMesh renumbered = original;
    const std::size_t n = original.points.size() / 3;
    for (std::size_t p = 0; p < n; ++p)
        for (int k = 0; k < 3; ++k) renumbered.points[3 * (n - 1 - p) + k] = original.points[3 * p + k];
    for (uint32_t& p : renumbered.face_points) p = static_cast<uint32_t>(n - 1 - p);
    const CellVolumes a = cell_volumes(original.view()), b = cell_volumes(renumbered.view());
    EXPECT_EQ(a.volumes, b.volumes);
    const Mesh sphere = polyvol::generate::uv_sphere(12, 24, 0.7, 1.55, 1.05, 1.1);
    EXPECT_EQ(body_in_cells(original.view(), sphere.view()).volumes,
              body_in_cells(renumbered.view(), sphere.view()).volumes);
}

TEST(CellVolumes, ACellWhoseFacesDoNotCloseIsNamed) {
    CellMesh m = read_polymesh(kData + "warped_ascii").mesh;
    // Drop one boundary face: the cell that owned it is open.
    const std::size_t f = m.face_offsets.size() - 2;
    const uint32_t open_cell = m.owner[f];
    m.face_points.resize(m.face_offsets[f]);
    m.face_offsets.pop_back();
    m.owner.pop_back();
    m.neighbour.pop_back();
    const auto defect = check_cell_mesh(m.view());
    ASSERT_TRUE(defect);
    EXPECT_EQ(defect->cell, open_cell);
    EXPECT_NE(defect->message.find("cell " + std::to_string(open_cell) + "'s faces do not close"), std::string::npos)
        << defect->message;
    EXPECT_THROW(cell_volumes(m.view()), std::invalid_argument);
}

TEST(PolyMesh, BadFilesNameTheFileAndTheLineOrByte) {
    auto message = [](const fs::path& dir) {
        try {
            read_polymesh(dir.string());
        } catch (const ReadError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    // A face naming a point that is not there: the faces file and its line.
    std::string faces = header("faceList", "faces") + "2\n(\n3(0 1 2)\n3(0 1 999)\n)\n";
    std::string m = message(with_file("missing_point", "faces", faces));
    EXPECT_NE(m.find("faces:11"), std::string::npos) << m;
    EXPECT_NE(m.find("names point 999"), std::string::npos) << m;
    // owner's count disagrees with the faces'.
    m = message(with_file("owner_count", "owner", header("labelList", "owner") + "3\n(\n0\n0\n1\n)\n"));
    EXPECT_NE(m.find("owner lists 3 cells"), std::string::npos) << m;
    // A count larger than the file.
    m = message(with_file("big_count", "points", header("vectorField", "points") + "1000000000\n(\n(0 0 0)\n)\n"));
    EXPECT_NE(m.find("more than the rest of the file holds"), std::string::npos) << m;
    // A binary list cut short: its byte offset.
    const fs::path d = scratch("truncated");
    for (const char* f : {"points", "faces", "owner", "neighbour"})
        fs::copy_file(kData + "warped_binary/constant/polyMesh/" + f, d / f);
    fs::resize_file(d / "points", fs::file_size(d / "points") - 200);
    m = message(d);
    EXPECT_NE(m.find("byte"), std::string::npos) << m;
    EXPECT_NE(m.find("items of 24 bytes"), std::string::npos) << m;
    // Not a mesh directory.
    m = message(scratch("empty"));
    EXPECT_NE(m.find("no OpenFOAM mesh here"), std::string::npos) << m;
}

// ---- A body in the cells ----

namespace {

using test::box_overlap;

}  // namespace

TEST(BodyInCells, ABoxInGradedBoxCellsIsTheirOverlapCorrectlyRounded) {
    const LoadedCellMesh loaded = read_polymesh(kData + "graded_box");
    const CellMeshView m = loaded.mesh.view();
    // A box crossing cell walls and sticking out of the mesh at the top.
    const std::array<double, 3> a{0.05, 0.03, 0.02}, b{0.21, 0.17, 0.2};
    const Mesh body = polyvol::test::box(a, b);
    const BodyInCells r = body_in_cells(m, body.view());
    const CellVolumes own = cell_volumes(m);
    mpq_class sum = 0;
    std::size_t cut = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        double lo[3], hi[3];
        cell_box(m, c, lo, hi);
        const mpq_class exact = box_overlap(lo, hi, a, b);
        sum += exact;
        EXPECT_EQ(r.volumes[c], exact::round_to_double(exact.get_mpq_t())) << "cell " << c;
        const bool is_cut = r.volumes[c] != 0 && r.volumes[c] != own.volumes[c];
        cut += is_cut;
        EXPECT_EQ(r.cell_class[c], is_cut ? CellClass::cut : r.volumes[c] == 0 ? CellClass::empty : CellClass::full);
    }
    EXPECT_EQ(r.total, exact::round_to_double(sum.get_mpq_t()));  // the cells' exact sum, rounded once
    EXPECT_EQ(r.body_volume, signed_volume(body.view()));
    EXPECT_EQ(r.cut_cells, cut);
    EXPECT_GT(r.cut_cells, 0u);
    EXPECT_GT(r.full_cells + r.empty_cells, 0u);
    EXPECT_EQ(r.full_cells + r.cut_cells + r.empty_cells, m.cell_count());
}

TEST(BodyInCells, ASphereInsideWarpedCellsAddsUpToItsVolume) {
    const LoadedCellMesh loaded = read_polymesh(kData + "warped_ascii");
    const CellMeshView m = loaded.mesh.view();
    const Mesh sphere = polyvol::generate::uv_sphere(12, 24, 0.7, 1.55, 1.05, 1.1);
    const BodyInCells r = body_in_cells(m, sphere.view());
    const CellVolumes own = cell_volumes(m);
    // Inside the mesh: the total is the body's volume, bit for bit.
    EXPECT_EQ(r.total, signed_volume(sphere.view()));
    EXPECT_EQ(r.body_volume, r.total);
    double naive = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        EXPECT_GE(r.volumes[c], 0);
        EXPECT_LE(r.volumes[c], own.volumes[c]);
        naive += r.volumes[c];
    }
    EXPECT_NEAR(naive, r.total, 1e-14 * r.total);
    EXPECT_GT(r.cut_cells, 4u);
}

TEST(BodyInCells, AMeshInsideTheBodyIsFullAndAFarBodyLeavesItEmpty) {
    const LoadedCellMesh loaded = read_polymesh(kData + "warped_ascii");
    const CellMeshView m = loaded.mesh.view();
    const CellVolumes own = cell_volumes(m);
    const BodyInCells in = body_in_cells(m, polyvol::test::box({-1, -1, -1}, {5, 5, 5}).view());
    EXPECT_EQ(in.volumes, own.volumes);
    EXPECT_EQ(in.full_cells, m.cell_count());
    EXPECT_EQ(in.total, own.total);
    EXPECT_EQ(in.touched_cells, 0u);
    const BodyInCells far = body_in_cells(m, polyvol::test::box({10, 10, 10}, {11, 11, 11}).view());
    EXPECT_EQ(far.empty_cells, m.cell_count());
    EXPECT_EQ(far.total, 0.0);
}

TEST(BodyInCells, AnOpenBodyOrAnInwardCellIsRefused) {
    const LoadedCellMesh loaded = read_polymesh(kData + "warped_ascii");
    const CellMeshView m = loaded.mesh.view();
    Mesh open = polyvol::test::box({0.5, 0.5, 0.5}, {1, 1, 1});
    open.indices.erase(open.indices.end() - 3, open.indices.end());
    try {
        body_in_cells(m, open.view());
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("not a closed surface"), std::string::npos) << e.what();
    }
    CellMesh inward = read_polymesh(kData + "warped_ascii").mesh;
    for (std::size_t f = 0; f + 1 < inward.face_offsets.size(); ++f)  // every face wound the other way
        std::reverse(inward.face_points.begin() + inward.face_offsets[f],
                     inward.face_points.begin() + inward.face_offsets[f + 1]);
    ASSERT_FALSE(check_cell_mesh(inward.view()));  // still closed cells, but inside out
    try {
        body_in_cells(inward.view(), polyvol::test::box({0.5, 0.5, 0.5}, {1, 1, 1}).view());
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("cell 0 is wound inward"), std::string::npos) << e.what();
    }
}

// ---- The prepared path against the reference, cell by cell ----

namespace {

void expect_prepared_equals_reference(const CellMesh& cells, const Mesh& body, const std::string& what) {
    const BodyInCells fast = body_in_cells(cells.view(), body.view());
    const BodyInCells reference = body_in_cells(cells.view(), body.view(), {.reference = true});
    ASSERT_EQ(fast.volumes.size(), reference.volumes.size());
    for (std::size_t c = 0; c < fast.volumes.size(); ++c)
        ASSERT_EQ(fast.volumes[c], reference.volumes[c]) << what << ": cell " << c;
    EXPECT_EQ(fast.total, reference.total) << what;
    EXPECT_EQ(fast.cut_cells, reference.cut_cells) << what;
    EXPECT_EQ(fast.full_cells, reference.full_cells) << what;
}

}  // namespace

TEST(BodyInCells, ThePreparedPathGivesTheReferencesBitsOnWarpedCells) {
    const CellMesh warped = polyvol::generate::hex_cells(6, -1.0, 1.0, 0.25);
    ASSERT_FALSE(check_cell_mesh(warped.view()));
    // A sphere partly outside the mesh, a torus inside, a box whose faces lie
    // on the cells' planes (touching and coincident faces: the perturbation).
    expect_prepared_equals_reference(warped, polyvol::generate::uv_sphere(10, 20, 0.9, 0.3, -0.2, 0.4), "sphere");
    expect_prepared_equals_reference(warped, polyvol::generate::torus(24, 12, 0.6, 0.2), "torus");
    const CellMesh straight = polyvol::generate::hex_cells(4, -1.0, 1.0, 0.0);
    expect_prepared_equals_reference(straight, polyvol::test::box({-0.5, -0.5, 0.0}, {0.5, 1.0, 0.5}), "aligned box");
    expect_prepared_equals_reference(straight, polyvol::test::box({-0.7, -0.3, -0.9}, {0.2, 0.6, 0.3}), "box");
}

TEST(CellVolumes, FilteredOrExactEveryCellIsItsSurfacesVolume) {
    // Slivers, a far-away tiny mesh and a flat one: the filter decides or the exact sums do.
    struct Shape {
        int n;
        double lo, hi, jitter;
    };
    for (const Shape& s : {Shape{3, 0.0, 1.0, 0.49}, Shape{3, 1e6, 1e6 + 1e-3, 0.3}, Shape{2, -1.0, 1.0, 0.0}}) {
        const CellMesh m = polyvol::generate::hex_cells(s.n, s.lo, s.hi, s.jitter);
        const CellVolumes v = cell_volumes(m.view());
        for (std::size_t c = 0; c < m.cells; ++c)
            EXPECT_EQ(v.volumes[c], signed_volume(cell_surface(m.view(), c).view())) << "cell " << c;
        EXPECT_EQ(v.total, signed_volume(boundary_surface(m.view()).view()));
    }
    CellMesh flat = polyvol::generate::hex_cells(2, 0.0, 1.0, 0.0);
    for (std::size_t p = 0; p < flat.points.size() / 3; ++p) flat.points[3 * p + 2] *= 0x1p-100;  // thin
    const CellVolumes thin = cell_volumes(flat.view());
    for (std::size_t c = 0; c < flat.cells; ++c)
        EXPECT_EQ(thin.volumes[c], signed_volume(cell_surface(flat.view(), c).view())) << "thin cell " << c;
    // Every point on a tilted plane (rounded): volumes of rounding size, left undecided by the filter.
    for (std::size_t p = 0; p < flat.points.size() / 3; ++p)
        flat.points[3 * p + 2] = 0.3 * flat.points[3 * p] + 0.7 * flat.points[3 * p + 1];
    const CellVolumes v = cell_volumes(flat.view());
    for (std::size_t c = 0; c < flat.cells; ++c)
        EXPECT_EQ(v.volumes[c], signed_volume(cell_surface(flat.view(), c).view())) << "flat cell " << c;
}

TEST(Vtu, OurVtuReadsBackAsTheSameCells) {
    const CellMesh warped = polyvol::generate::hex_cells(3, -1.0, 1.0, 0.3);
    const CellVolumes own = cell_volumes(warped.view());
    const std::string path = (scratch("vtu") / "cells.vtu").string();
    const CellArray arrays[1] = {{"cell_volume", own.volumes, 1, false}};
    write_vtu(path, warped.view(), arrays);
    const LoadedCellMesh back = read_cell_mesh(path);
    EXPECT_EQ(back.format, "vtu");
    EXPECT_EQ(back.mesh.points, warped.points);
    EXPECT_EQ(back.mesh.cells, warped.cells);
    EXPECT_EQ(back.mesh.owner.size(), warped.owner.size());  // every shared face matched once
    EXPECT_EQ(cell_volumes(back.mesh.view()).volumes, own.volumes);
    // A file cut short names what is missing.
    fs::resize_file(path, fs::file_size(path) - 300);
    EXPECT_THROW(read_vtu(path), ReadError);
}

TEST(Vtu, TheRegressionsAreReadErrors) {
    // tests/data/regressions/*.vtu: inputs the fuzz_vtu target found.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(std::string(POLYVOL_TEST_DATA) + "/regressions")) {
        if (entry.path().extension() != ".vtu") continue;
        ++files;
        EXPECT_THROW(read_vtu(entry.path().string()), ReadError) << entry.path();
    }
    EXPECT_GE(files, 1);
}

TEST(BodyInCells, TwoBoxesUnionIsCorrectlyRoundedAndTheirIntersectionBounded) {
    const LoadedCellMesh loaded = read_polymesh(kData + "graded_box");
    const CellMeshView m = loaded.mesh.view();
    const std::array<double, 3> a0{0.05, 0.03, 0.02}, a1{0.21, 0.17, 0.2};
    const std::array<double, 3> b0{0.11, 0.01, 0.07}, b1{0.3, 0.13, 0.16};
    const std::array<double, 3> i0{0.11, 0.03, 0.07}, i1{0.21, 0.13, 0.16};  // A ∩ B, a box
    const Mesh A = polyvol::test::box(a0, a1), B = polyvol::test::box(b0, b1);
    const MeshView both[2] = {A.view(), B.view()};
    const BodyInCells ra = body_in_cells(m, A.view()), rb = body_in_cells(m, B.view());
    const BodyInCells u = union_in_cells(m, both);
    const BodyInCells each[2] = {ra, rb};
    EXPECT_EQ(union_in_cells(m, both, each).volumes, u.volumes);  // from the bodies' own results, the same bits
    EXPECT_EQ(union_in_cells(m, both, each).total, u.total);
    const IntersectionInCells x = intersection_in_cells(ra, rb, u);
    mpq_class union_sum = 0, meet_sum = 0;
    std::size_t cells_in_both = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        double lo[3], hi[3];
        cell_box(m, c, lo, hi);
        const mpq_class meet = box_overlap(lo, hi, i0, i1);
        const mpq_class joined = box_overlap(lo, hi, a0, a1) + box_overlap(lo, hi, b0, b1) - meet;
        union_sum += joined;
        meet_sum += meet;
        EXPECT_EQ(u.volumes[c], exact::round_to_double(joined.get_mpq_t())) << "cell " << c;
        const double cell = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
        const double ulp = std::nextafter(cell, INFINITY) - cell;
        EXPECT_LE(std::abs(mpq_class(mpq_class(x.volumes[c]) - meet).get_d()), 2 * ulp) << "cell " << c;
        cells_in_both += meet > 0;
    }
    EXPECT_GT(cells_in_both, 3u);
    EXPECT_EQ(u.total, exact::round_to_double(union_sum.get_mpq_t()));
    EXPECT_LE(std::abs(mpq_class(mpq_class(x.total) - meet_sum).get_d()),
              2 * (std::nextafter(u.total, INFINITY) - u.total));
    // The union of a body with itself is the body.
    const MeshView twice[2] = {A.view(), A.view()};
    EXPECT_EQ(union_in_cells(m, twice).volumes, ra.volumes);
}

TEST(BodyInCells, TheWettedAreaAndNormalOfABoxAreItsFacesInEachCell) {
    const LoadedCellMesh loaded = read_polymesh(kData + "graded_box");
    const CellMeshView m = loaded.mesh.view();
    const std::array<double, 3> a{0.0531, 0.0317, 0.0219}, b{0.2093, 0.1687, 0.1571};
    const Mesh body = polyvol::test::box(a, b);
    BodyInCellsOptions o;
    o.surface = true;
    const BodyInCells r = body_in_cells(m, body.view(), o);
    ASSERT_EQ(r.wetted_area.size(), m.cell_count());
    double total = 0, total_bound = 0, net[3] = {0, 0, 0};
    std::size_t wet = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        double lo[3], hi[3];
        cell_box(m, c, lo, hi);
        // The box's six faces inside the cell: for the face at x = a[0]
        // (normal -x), the rectangle in y, z clipped to the cell, if a[0] is
        // inside the cell's x range.
        double area = 0, normal[3] = {0, 0, 0};
        for (int axis = 0; axis < 3; ++axis)
            for (const int side : {0, 1}) {
                const double at = side == 0 ? a[axis] : b[axis];
                if (!(at > lo[axis] && at < hi[axis])) continue;
                double piece = 1;
                for (int k = 0; k < 3; ++k)
                    if (k != axis) piece *= std::max(0.0, std::min(hi[k], b[k]) - std::max(lo[k], a[k]));
                area += piece;
                normal[axis] += side == 0 ? -piece : piece;
            }
        const double bound = r.surface_bound[c] + 1e-15 * area;  // the closed form's own rounding
        EXPECT_NEAR(r.wetted_area[c], area, bound) << "cell " << c;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.surface_normal[3 * c + k], normal[k], bound) << "cell " << c;
        EXPECT_LT(r.surface_bound[c], 1e-12 * (area + 0.01));  // the box's faces are about 0.02 m²
        total += r.wetted_area[c] - area;
        total_bound += r.surface_bound[c] + 1e-15 * area;
        for (int k = 0; k < 3; ++k) net[k] += r.surface_normal[3 * c + k] - normal[k];
        wet += area > 0;
    }
    EXPECT_GT(wet, 10u);
    // The sums over the cells: the faces' parts inside the mesh (it ends below b's top).
    EXPECT_NEAR(total, 0.0, total_bound);
    for (const double n : net) EXPECT_NEAR(n, 0.0, total_bound);
}

TEST(BodyInCells, ASpheresWettedAreaAddsUpToItsAreaOverWarpedCells) {
    const LoadedCellMesh loaded = read_polymesh(kData + "warped_ascii");
    const CellMeshView m = loaded.mesh.view();
    const Mesh sphere = polyvol::generate::uv_sphere(12, 24, 0.7, 1.55, 1.05, 1.1);
    BodyInCellsOptions o;
    o.surface = true;
    const BodyInCells r = body_in_cells(m, sphere.view(), o);
    double total = 0, bound = 0, net[3] = {0, 0, 0};
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        total += r.wetted_area[c];
        bound += r.surface_bound[c];
        for (int k = 0; k < 3; ++k) net[k] += r.surface_normal[3 * c + k];
        EXPECT_EQ(r.wetted_area[c] > 0, r.cell_class[c] == CellClass::cut) << "cell " << c;
    }
    EXPECT_NEAR(total, surface_area(sphere.view()), bound + 1e-14);
    for (const double n : net) EXPECT_NEAR(n, 0.0, bound + 1e-14);
    EXPECT_LT(bound, 1e-12 * total);
}

TEST(CellVolumes, ASubsetOfTheCellsKeepsEachCellsVolumeAndCloses) {
    const CellMesh whole = read_polymesh(kData + "warped_ascii").mesh;
    std::vector<uint32_t> some;
    for (uint32_t c = static_cast<uint32_t>(whole.cells); c-- > 0;)
        if (c % 3 != 1) some.push_back(c);  // every third cell left out, the rest in reverse order
    const CellMesh part = cells_subset(whole.view(), some);
    ASSERT_EQ(part.cells, some.size());
    EXPECT_FALSE(check_cell_mesh(part.view()).has_value());
    const CellVolumes a = cell_volumes(whole.view()), b = cell_volumes(part.view());
    for (std::size_t i = 0; i < some.size(); ++i) EXPECT_EQ(b.volumes[i], a.volumes[some[i]]) << i;
    EXPECT_EQ(b.total, signed_volume(boundary_surface(part.view()).view()));
    const uint32_t twice[2] = {0, 0}, outside[1] = {static_cast<uint32_t>(whole.cells)};
    EXPECT_THROW(cells_subset(whole.view(), twice), std::invalid_argument);
    EXPECT_THROW(cells_subset(whole.view(), outside), std::invalid_argument);
}
