// Eclipse corner-point grids (read_grdecl, write_grdecl_keyword): the
// keywords' syntax, the cells against closed forms and against the grid's
// numbers on a rectilinear grid, faults, and bad files named by line.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/box_overlap.hpp"
#include "common/cell_surfaces.hpp"
#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "exact/rational.hpp"
#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/cells.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"

namespace fs = std::filesystem;
using namespace polyvol;

namespace {

// A corner-point grid as its keywords: pillar (i, j) from `top(i, j)` to
// `bottom(i, j)`, corner depths from `depth(i, j, k, a, b, c)`.
struct CornerGrid {
    int nx = 0, ny = 0, nz = 0;
    std::function<std::array<double, 3>(int, int)> top, bottom;
    std::function<double(int, int, int, int, int, int)> depth;
    std::vector<int> actnum;
    std::string head = "GRIDUNIT\n'METRES  ' /\n";

    std::string text() const {
        std::ostringstream s;
        s.precision(17);
        s << "-- a test grid\n" << head << "SPECGRID\n" << nx << " " << ny << " " << nz << " 1 F /\nCOORD\n";
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const auto t = top(i, j), b = bottom(i, j);
                s << t[0] << " " << t[1] << " " << t[2] << " " << b[0] << " " << b[1] << " " << b[2] << "\n";
            }
        s << "/\nZCORN\n";
        for (int k = 0; k < nz; ++k)
            for (int c = 0; c < 2; ++c)
                for (int j = 0; j < ny; ++j)
                    for (int b = 0; b < 2; ++b) {
                        for (int i = 0; i < nx; ++i)
                            for (int a = 0; a < 2; ++a) s << depth(i, j, k, a, b, c) << " ";
                        s << "\n";
                    }
        s << "/\n";
        if (!actnum.empty()) {
            s << "ACTNUM\n";
            for (const int a : actnum) s << a << " ";
            s << "/\n";
        }
        return s.str();
    }
};

// Box cells: x = 10 i, y = 20 j, depth 1000 + 5 k, vertical pillars.
CornerGrid box_grid(int nx, int ny, int nz) {
    CornerGrid g;
    g.nx = nx, g.ny = ny, g.nz = nz;
    g.top = [](int i, int j) { return std::array<double, 3>{10.0 * i, 20.0 * j, 1000}; };
    g.bottom = [](int i, int j) { return std::array<double, 3>{10.0 * i, 20.0 * j, 1100}; };
    g.depth = [](int, int, int k, int, int, int c) { return 1000.0 + 5.0 * (k + c); };
    return g;
}

fs::path write(const std::string& name, const std::string& text) {
    const fs::path d = fs::temp_directory_path() / "polyvol_grdecl";
    fs::create_directories(d);
    std::ofstream(d / name, std::ios::trunc) << text;
    return d / name;
}

LoadedCellMesh read_text(const std::string& text) {
    return read_grdecl_memory(std::as_bytes(std::span(text.data(), text.size())), "grid.grdecl");
}

mpq_class box_overlap(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                      const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return test::box_overlap(lo.data(), hi.data(), a, b);
}

std::string read_error(const std::string& text) {
    try {
        read_text(text);
    } catch (const ReadError& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(Grdecl, RepeatsCommentsIncludesAndInactiveCells) {
    CornerGrid g = box_grid(3, 2, 2);
    g.actnum = {1, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0};
    // The depths as repeats, in an included file, with comments between.
    std::string text = g.text();
    const std::size_t z = text.find("ZCORN"), end = text.find("/\n", z);
    text.replace(z, end + 2 - z,
                 "INCLUDE\n 'depths.inc' / -- the depths\n");
    write("depths.inc", "ZCORN -- top of layer 0\n24*1000 48*1005 -- the middle\n 24*1010\n/\n");
    const fs::path main = write("main.grdecl", "ECHO\n" + text + "PORO\n 12*0.2 /\nNOECHO\n");
    const LoadedCellMesh r = read_grdecl(main.string());
    EXPECT_EQ(r.format, "grdecl");
    EXPECT_EQ(r.unit, "m");
    EXPECT_EQ(r.grid_dims, (std::array<uint64_t, 3>{3, 2, 2}));
    EXPECT_EQ(r.grid_index, (std::vector<uint64_t>{0, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
    EXPECT_EQ(r.fault_faces, 0u);
    const CellVolumes v = cell_volumes(r.mesh.view());
    ASSERT_EQ(v.volumes.size(), 10u);
    for (const double x : v.volumes) EXPECT_EQ(x, 1000.0);  // 10 × 20 × 5
    EXPECT_EQ(v.total, 10000.0);
    // Neighbours share points: 4×3 pillars at 3 depths, but for the grid's
    // corner that only the inactive last cell names.
    EXPECT_EQ(r.mesh.view().point_count(), 4u * 3 * 3 - 1);

    // The unit keywords, GRIDUNIT first.
    g.head = "FIELD\n";
    EXPECT_EQ(read_text(g.text()).unit, "ft");
    g.head = "";
    EXPECT_EQ(read_text(g.text()).unit, "");
    g.head = "LAB\nGRIDUNIT\nMETRES /\n";
    EXPECT_EQ(read_text(g.text()).unit, "m");
}

TEST(Grdecl, InclinedPillarsAndWarpedLayersTileExactly) {
    // Pillars leaning apart, depths varying per corner (warped faces), J
    // running south (a left-handed I, J, K: the faces are turned).
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.8, 0.8);
    std::vector<double> bump(4 * 4 * 4);
    for (double& b : bump) b = jitter(rng);
    CornerGrid g;
    g.nx = 3, g.ny = 3, g.nz = 3;
    g.top = [](int i, int j) { return std::array<double, 3>{10.0 * i, -10.0 * j, 1000}; };
    g.bottom = [](int i, int j) {
        return std::array<double, 3>{10.0 * i + 1.5 * i, -10.0 * j - 0.5 * j * j, 1100};
    };
    g.depth = [&](int i, int j, int k, int a, int b, int c) {
        return 1000.0 + 6.0 * (k + c) + bump[static_cast<std::size_t>((i + a) + 4 * ((j + b) + 4 * (k + c)))];
    };
    const LoadedCellMesh r = read_text(g.text());
    const CellMeshView m = r.mesh.view();
    EXPECT_EQ(r.fault_faces, 0u);
    EXPECT_TRUE(std::any_of(r.notes.begin(), r.notes.end(),
                            [](const std::string& n) { return n.find("left-handed") != std::string::npos; }));
    const CellVolumes v = cell_volumes(m);
    EXPECT_EQ(v.negative_cells, 0u);
    for (std::size_t c = 0; c < m.cell_count(); ++c)
        EXPECT_EQ(v.volumes[c], signed_volume(test::cell_surface(m, c).view())) << "cell " << c;
    // The boundary faces' volume is the cells' exact total.
    EXPECT_EQ(v.total, signed_volume(test::boundary_surface(m).view()));
    // A body inside the grid: the cells add up to its volume, bit for bit.
    const Mesh sphere = generate::uv_sphere(10, 20, 7.0, 16, -15, 1009);
    const BodyInCells b = body_in_cells(m, sphere.view());
    EXPECT_EQ(b.total, signed_volume(sphere.view()));
    EXPECT_GT(b.cut_cells, 0u);
}

TEST(Grdecl, ARectilinearGridGivesTheGridsNumbers) {
    // 4×3×3 box cells; a sphere cutting many of them. The grid's cells are
    // within 3.5e-16 of the cell's volume (docs/grid.md) of the exact value,
    // the cells' correctly rounded.
    const CornerGrid g = box_grid(4, 3, 3);
    const LoadedCellMesh r = read_text(g.text());
    const Mesh sphere = generate::uv_sphere(16, 32, 13.0, 21, 29, 1007);
    const BodyInCells b = body_in_cells(r.mesh.view(), sphere.view());
    GridAxes axes;
    for (int i = 0; i <= 4; ++i) axes.x.push_back(10.0 * i);
    for (int j = 0; j <= 3; ++j) axes.y.push_back(20.0 * j);
    for (int k = 0; k <= 3; ++k) axes.z.push_back(1000.0 + 5.0 * k);
    std::vector<double> grid(4 * 3 * 3);
    const MeshView body = sphere.view();
    grid_volumes(std::span(&body, 1), axes, {.volumes = grid});
    std::size_t cut = 0;
    for (std::size_t c = 0; c < r.grid_index.size(); ++c) {
        const uint64_t g_index = r.grid_index[c], i = g_index % 4, j = g_index / 4 % 3, k = g_index / 12;
        const double cell = axes.cell_volume(i, j, k);
        EXPECT_NEAR(b.volumes[c], grid[axes.cell(i, j, k)], 3.5e-16 * cell + 0.5 * (std::nextafter(cell, INFINITY) - cell)) << c;
        cut += b.cell_class[c] == CellClass::cut;
    }
    EXPECT_GT(cut, 10u);
}

TEST(Grdecl, FaultsKeepEachCellsOwnFacesAndTheCellsStillTile) {
    // Columns i >= 2 thrown down by 2 (a fault between i = 1 and 2);
    // vertical pillars, so the thrown cells still fill space without overlap.
    CornerGrid g = box_grid(4, 2, 3);
    g.depth = [](int i, int, int k, int, int, int c) {
        return 1000.0 + 5.0 * (k + c) + (i >= 2 ? 2.0 : 0.0);
    };
    const LoadedCellMesh r = read_text(g.text());
    const CellMeshView m = r.mesh.view();
    EXPECT_EQ(r.fault_faces, 2u * 3);  // per j and k, the faces between columns 1 and 2
    EXPECT_TRUE(r.cells_tile);         // on vertical pillars
    const std::array<double, 3> a{5, 3, 1001}, bb{33, 31, 1012.5};
    const BodyInCells b = body_in_cells(m, test::box(a, bb).view());
    mpq_class sum = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        const auto i = static_cast<double>(r.grid_index[c] % 4), j = static_cast<double>(r.grid_index[c] / 4 % 2),
                   k = static_cast<double>(r.grid_index[c] / 8);
        const double throw_ = i >= 2 ? 2.0 : 0.0;
        const std::array<double, 3> lo{10.0 * i, 20.0 * j, 1000 + 5.0 * k + throw_},
            hi{10.0 * (i + 1), 20.0 * (j + 1), 1005 + 5.0 * k + throw_};
        const mpq_class exact = box_overlap(lo, hi, a, bb);
        sum += exact;
        EXPECT_EQ(b.volumes[c], exact::round_to_double(exact.get_mpq_t())) << "cell " << c;
    }
    EXPECT_EQ(b.total, exact::round_to_double(sum.get_mpq_t()));
}

TEST(Grdecl, BadFilesNameTheFileAndTheLine) {
    const std::string good = box_grid(2, 2, 1).text();
    auto expect = [](const std::string& message, const std::string& what) {
        EXPECT_NE(message.find(what), std::string::npos) << message;
        EXPECT_NE(message.find("grid.grdecl"), std::string::npos) << message;
    };
    std::string short_z = good;
    short_z.replace(short_z.find("ZCORN\n") + 6, 5, "");  // one depth fewer
    expect(read_error(short_z), "ZCORN holds 31 values; the grid 2×2×1 needs 8·I·J·K = 32");
    std::string bad_number = good;
    bad_number.replace(bad_number.find("ZCORN\n") + 6, 4, "1o00");
    expect(read_error(bad_number), ":18: ZCORN: '1o00' is not a number");
    std::string too_many = good;
    too_many.replace(too_many.find("ZCORN\n") + 6, 0, "1000000000000*1 ");
    expect(read_error(too_many), "ZCORN: more than the 32 values the grid's size needs");
    std::string defaults = good;
    defaults.replace(defaults.find("ZCORN\n") + 6, 0, "3* ");
    expect(read_error(defaults), "'3*' asks for default values");
    expect(read_error("COORD\n 1 2 3 /\n"), ":1: COORD before SPECGRID or DIMENS");
    expect(read_error("SPECGRID\n 2 2 /\n"), "expected the grid's size I J K");
    expect(read_error("SPECGRID\n 2 2 1 /\nCOORD\n 1 2 3\n"), ":3: COORD: its data is not ended by '/'");
    expect(read_error("SPECGRID\n 100000 100000 100 /\n"), "100000×100000×100 cells: at most 134217728 are read");
    expect(read_error("SPECGRID\n 4194304 4194304 1048576 /\n"), "cells: at most 134217728 are read");
    expect(read_error("SPECGRID\n 1000 1000 100 /\nZCORN\n 400000000*1 /\n"),
           "ZCORN: the repeats expand to more than 4194304 values, 8 times the file's size: refused");
    expect(read_error("SPECGRID\n 2 2 1 1e300 F /\n"), ":1: SPECGRID: NUMRES 1e300: only one reservoir is read");
    expect(read_error("SPECGRID\n 2 2 1 1 T /\n"), "a radial grid (T) is not read");
    expect(read_error("SPECGRID\n 2 2 1 /\nEQUALS\n 'ACTNUM' 0 1 1 1 1 1 1 /\n/\n"),
           ":3: EQUALS changes ACTNUM: not read");
    expect(read_error("SPECGRID\n 2 2 1 /\nBOX\n 1 1 1 1 1 1 /\nACTNUM\n 0 /\nENDBOX\n"),
           ":5: ACTNUM inside a BOX (a part of the grid) is not read");
    std::string far = good;  // a vertical pillar with top and bottom 5e-324 apart
    far.replace(far.find("COORD\n") + 6, far.find("\n", far.find("COORD\n") + 6) - far.find("COORD\n") - 6,
                "0 0 0 1 1 5e-324");
    expect(read_error(far), "is not finite (COORD)");
    expect(read_error("DIMENS\n 2 2 1 /\n"), "COORD holds 0 values");
    expect(read_error("SPECGRID\n 2 2 1 /\nINCLUDE\n 'x.inc' /\n"), ":3: INCLUDE: a grid read from memory");
    expect(read_error("  12 13 /\n"), ":1: expected a keyword at the start of a line, found '12'");
    EXPECT_THROW(read_grdecl(write("grid.grdecl", "INCLUDE\n 'missing.inc' /\n").string()), ReadError);
}

TEST(Grdecl, AKeywordFileHoldsEveryCellInGridOrder) {
    CornerGrid g = box_grid(3, 1, 2);
    g.actnum = {1, 1, 0, 1, 1, 1};
    const LoadedCellMesh r = read_text(g.text());
    const std::vector<double> values{0.1, 1.0 / 3, 1.0 / 3, 1.0 / 3, 0};
    const fs::path out = fs::temp_directory_path() / "polyvol_grdecl" / "frac.grdecl";
    write_grdecl_keyword(out.string(), "BODYFRAC", values, r);
    std::ifstream in(out);
    std::string line, all;
    while (std::getline(in, line))
        if (line.rfind("--", 0) != 0) all += line + "\n";
    EXPECT_EQ(all, "BODYFRAC\n0.1 0.3333333333333333 0 2*0.3333333333333333 0 /\n");
    EXPECT_THROW(write_grdecl_keyword(out.string(), "bodyfrac", values, r), std::invalid_argument);
    EXPECT_THROW(write_grdecl_keyword(out.string(), "BODYFRAC", std::vector<double>(6), r), std::invalid_argument);
}

TEST(Grdecl, FaultsOnLeaningPillarsCountTheBodyInTheCoveredRegionOnce) {
    // Leaning pillars that are not parallel, and a throw: cells across the
    // fault overlap or leave slivers. Each cell is still its exact
    // intersection (the reference's bits); the total is the body in the
    // region the cells cover, each point once, and the cells' sum exceeds
    // it by the body in the overlaps (in_overlaps).
    CornerGrid g = box_grid(3, 2, 2);
    g.bottom = [](int i, int j) { return std::array<double, 3>{15.0 * i + 3.0 * j, 24.0 * j, 1100}; };
    g.depth = [](int i, int, int k, int, int, int c) { return 1000.0 + 5.0 * (k + c) + (i >= 2 ? 3.0 : 0.0); };
    const LoadedCellMesh r = read_text(g.text());
    EXPECT_GT(r.fault_faces, 0u);
    EXPECT_FALSE(r.cells_tile);
    const CellMeshView m = r.mesh.view();
    const Mesh sphere = generate::uv_sphere(12, 24, 6.0, 20.5, 20, 1006);
    BodyInCellsOptions o;
    o.cells_tile = false;
    const BodyInCells b = body_in_cells(m, sphere.view(), o);
    o.reference = true;
    const BodyInCells ref = body_in_cells(m, sphere.view(), o);
    for (std::size_t c = 0; c < m.cell_count(); ++c) EXPECT_EQ(b.volumes[c], ref.volumes[c]) << "cell " << c;
    EXPECT_EQ(b.body_volume, signed_volume(sphere.view()));
    mpq_class sum = 0;
    for (const double v : b.volumes) sum += mpq_class(v);
    EXPECT_EQ(b.cells_sum, exact::round_to_double(sum.get_mpq_t()));
    EXPECT_GT(b.cut_cells, 4u);
    // The overlaps pair by pair (no point is in three cells here): the
    // covered region is Σ|c| − Σ|c1 ∩ c2|, and the body in it Σ|B ∩ c| −
    // Σ|B ∩ c1 ∩ c2|, with |B ∩ c1 ∩ c2| = |B ∩ c1| + |B ∩ c2| − |B ∩ (c1 ∪ c2)|.
    const CellVolumes own = cell_volumes(m);
    double cells_overlap = 0, body_overlap = 0;
    std::size_t pairs = 0;
    for (std::size_t c1 = 0; c1 < m.cell_count(); ++c1)
        for (std::size_t c2 = c1 + 1; c2 < m.cell_count(); ++c2) {
            const Mesh s1 = test::cell_surface(m, c1), s2 = test::cell_surface(m, c2);
            const double both = boolean_volumes(s1.view(), s2.view()).intersection;
            if (both == 0) continue;
            ++pairs;
            cells_overlap += both;
            Mesh either = s1;
            either.append(s2);
            const BooleanVolumes in_either = solid_boolean_volumes(either.view(), sphere.view());
            ASSERT_EQ(in_either.status, BooleanStatus::ok);
            body_overlap += b.volumes[c1] + b.volumes[c2] - in_either.intersection;
        }
    EXPECT_GT(pairs, 0u);
    EXPECT_GT(cells_overlap, 1.0);
    const double covered = covered_volume(m);
    EXPECT_LT(covered, own.total);
    EXPECT_NEAR(covered, own.total - cells_overlap, 1e-12 * own.total);
    EXPECT_GT(body_overlap, 0.01);
    EXPECT_NEAR(b.total, b.cells_sum - body_overlap, 1e-12 * b.cells_sum);
    EXPECT_NEAR(b.in_overlaps, body_overlap, 1e-12 * b.cells_sum);
}

TEST(Grdecl, OtherKeywordsRecordsCommentsAndLineEndsAreSkipped) {
    // FAULTS with several records, text after '/', a lone CR line end, a
    // section header without data.
    std::string text = box_grid(2, 2, 1).text();
    text = "RUNSPEC\nGRID\nFAULTS\n 'F1' 1 1 1 2 1 1 'X' / the first\n 'F2' 2 2 1 2 1 1 'Y' /\n/\n" + text +
           "PORO\r 4*0.25 / porosity\rMULTFLT\n 'F1' 0.1 /\n/\nEDIT\n";
    const LoadedCellMesh r = read_text(text);
    EXPECT_EQ(r.mesh.cells, 4u);
    EXPECT_EQ(cell_volumes(r.mesh.view()).total, 4000.0);
}

TEST(Grdecl, PinchedCellsAndMismatchedNeighboursStayClosed) {
    // Column i = 1 pinched to nothing at its right pillar in layer 0 (top =
    // bottom there), and a neighbour whose depths at the shared pillar are
    // the reverse of this cell's (the same corner set, another face).
    CornerGrid g = box_grid(2, 1, 2);
    g.depth = [](int i, int, int k, int a, int, int c) {
        if (k == 0 && i == 1 && a == 1) return 1000.0;  // pinched
        return 1000.0 + 5.0 * (k + c);
    };
    LoadedCellMesh r = read_text(g.text());
    EXPECT_FALSE(check_cell_mesh(r.mesh.view()).has_value());
    const CellVolumes v = cell_volumes(r.mesh.view());
    EXPECT_EQ(v.volumes[1], 10.0 * 20 * 5 / 2);  // a wedge: half the box
    EXPECT_EQ(v.total, 4 * 1000.0 - 500);
    g = box_grid(2, 1, 1);
    g.depth = [](int i, int, int, int a, int, int c) {
        // Cell 1's depths at the shared pillar (a = 0) swapped: top 1005, bottom 1000.
        if (i == 1 && a == 0) return c == 0 ? 1005.0 : 1000.0;
        return 1000.0 + 5.0 * c;
    };
    r = read_text(g.text());
    EXPECT_EQ(r.fault_faces, 1u);
    EXPECT_FALSE(check_cell_mesh(r.mesh.view()).has_value());
}

TEST(Grdecl, LayersOverlappingAcrossAnInactiveCellAreNotTakenToTile) {
    CornerGrid g = box_grid(1, 1, 3);
    g.actnum = {1, 0, 1};
    EXPECT_TRUE(read_text(g.text()).cells_tile);  // a hole where the inactive cell is
    // The inactive middle cell inside out (1005 down to 1004): cell 0 (1000
    // to 1005) and cell 2 (1004 to 1015) overlap by 1.
    g.depth = [](int, int, int k, int, int, int c) {
        const double z[3][2] = {{1000, 1005}, {1005, 1004}, {1004, 1015}};
        return z[k][c];
    };
    const LoadedCellMesh r = read_text(g.text());
    EXPECT_FALSE(r.cells_tile);
    EXPECT_EQ(cell_volumes(r.mesh.view()).total, 200.0 * (5 + 11));
}

TEST(Grdecl, TheKeywordFilesLinesStayShort) {
    CornerGrid g = box_grid(40, 1, 1);
    const LoadedCellMesh r = read_text(g.text());
    std::vector<double> values(40);
    for (std::size_t c = 0; c < values.size(); ++c) values[c] = 1.0 / static_cast<double>(c + 3);
    const fs::path out = fs::temp_directory_path() / "polyvol_grdecl" / "long.grdecl";
    write_grdecl_keyword(out.string(), "VALUES", values, r);
    std::ifstream in(out);
    std::string line;
    std::size_t lines = 0;
    while (std::getline(in, line)) {
        EXPECT_LE(line.size(), 100u) << line;
        ++lines;
    }
    EXPECT_GT(lines, 5u);
    values[3] = NAN;
    EXPECT_THROW(write_grdecl_keyword(out.string(), "VALUES", values, r), std::invalid_argument);
}

TEST(Grdecl, MapAxesTakeThePointsToTheMapsCoordinates) {
    // The map's origin at (1000, 2000), e_x = (0, 1) and e_y = (-1, 0): a
    // grid point (x, y) is the map's (1000 - y, 2000 + x), a quarter turn
    // (every product exact).
    CornerGrid g = box_grid(2, 2, 1);
    g.head = "MAPAXES\n 999 2000 1000 2000 1000 2001 /\n";
    const LoadedCellMesh mapped = read_text(g.text());
    const std::string text = g.text();
    const LoadedCellMesh kept = read_grdecl_memory(std::as_bytes(std::span(text.data(), text.size())), "grid.grdecl",
                                                   kMaxGridCells, false);
    ASSERT_EQ(mapped.mesh.points.size(), kept.mesh.points.size());
    for (std::size_t p = 0; p < kept.mesh.points.size(); p += 3) {
        const double x = kept.mesh.points[p], y = kept.mesh.points[p + 1];
        EXPECT_EQ(mapped.mesh.points[p], 1000 - y) << p;
        EXPECT_EQ(mapped.mesh.points[p + 1], 2000 + x) << p;
        EXPECT_EQ(mapped.mesh.points[p + 2], kept.mesh.points[p + 2]);
    }
    EXPECT_EQ(cell_volumes(mapped.mesh.view()).volumes, cell_volumes(kept.mesh.view()).volumes);
    // GRIDUNIT's MAP: COORD is in map coordinates already.
    g.head = "MAPAXES\n 999 2000 1000 2000 1000 2001 /\nGRIDUNIT\n 'METRES' 'MAP' /\n";
    EXPECT_EQ(read_text(g.text()).mesh.points, kept.mesh.points);
    g.head = "MAPAXES\n 0 0 0 0 1 0 /\n";
    EXPECT_NE(read_error(g.text()).find("MAPAXES: its axes are not two independent directions"), std::string::npos);
}

