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
#include "polyvol/measure.hpp"

namespace fs = std::filesystem;
using namespace polyvol;

namespace {

const std::string kData = std::string(POLYVOL_TEST_DATA) + "/openfoam/";

// Cell c as a closed triangle mesh by the same face rule: its owner faces
// as wound, its neighbour faces reversed.
Mesh cell_surface(const CellMeshView& m, std::size_t c) {
    Mesh out;
    out.positions.assign(m.points.begin(), m.points.end());
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const bool owns = m.owner[f] == c, neighbours = m.neighbour[f] == c;
        if (!owns && !neighbours) continue;
        face_triangles(m.face(f), [&](uint32_t a, uint32_t b, uint32_t d) {
            if (owns) out.indices.insert(out.indices.end(), {a, b, d});
            else out.indices.insert(out.indices.end(), {a, d, b});
        });
    }
    return out;
}

// The mesh's boundary faces as a triangle mesh (the surface the cells fill).
Mesh boundary_surface(const CellMeshView& m) {
    Mesh out;
    out.positions.assign(m.points.begin(), m.points.end());
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (m.neighbour[f] == kNoCell)
            face_triangles(m.face(f), [&](uint32_t a, uint32_t b, uint32_t d) {
                out.indices.insert(out.indices.end(), {a, b, d});
            });
    return out;
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
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (std::size_t f = 0; f < m.face_count(); ++f)
            if (m.owner[f] == c || m.neighbour[f] == c)
                for (const uint32_t p : m.face(f))
                    for (int k = 0; k < 3; ++k) {
                        lo[k] = std::min(lo[k], m.points[3 * p + k]);
                        hi[k] = std::max(hi[k], m.points[3 * p + k]);
                    }
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
    EXPECT_NEAR(naive, v.total, 1e-13 * v.total);
    EXPECT_EQ(v.face_triangles, 2 * (m.face_count()));
}

TEST(CellVolumes, TheResultDoesNotDependOnTheFacesStartingPoint) {
    // Rotating each face's point list (same polygon, same winding) keeps the
    // triangles: the fan starts at the smallest point index.
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
