// body_in_cells against an exact oracle: CGAL's corefinement (Epeck) of each
// cell's closed surface (its faces split by the mesh's rule) with the body,
// measured exactly and rounded once, equal to polyvol's value bit for bit —
// on tetrahedra read from a .vtu and on hexahedra with moved points.
#include <gtest/gtest.h>

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "boolean_oracle/cgal_support.hpp"
#include "common/cell_surfaces.hpp"
#include "common/generate.hpp"
#include "exact/rational.hpp"
#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/cells.hpp"

namespace polyvol {
namespace {

using namespace oracle;


std::array<double, 6> box_of(const Mesh& m) {
    std::array<double, 6> b{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        for (int k = 0; k < 3; ++k) {
            b[k] = std::min(b[k], m.positions[3 * v + k]);
            b[3 + k] = std::max(b[3 + k], m.positions[3 * v + k]);
        }
    return b;
}

// Every cell's volume of the body against CGAL's exact intersection.
void expect_cells_match_cgal(const CellMeshView& m, const Mesh& body) {
    const BodyInCells r = body_in_cells(m, body.view());
    std::string why;
    const auto cgal_body = to_cgal(body, why);
    ASSERT_TRUE(cgal_body) << why;
    const std::array<double, 6> bb = box_of(body);
    std::size_t compared = 0, cut = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        const Mesh cell = test::cell_surface(m, c);
        const std::array<double, 6> cb = box_of(cell);
        const bool apart = cb[3] < bb[0] || cb[0] > bb[3] || cb[4] < bb[1] || cb[1] > bb[4] || cb[5] < bb[2] ||
                           cb[2] > bb[5];
        if (apart) {
            EXPECT_EQ(r.volumes[c], 0.0) << "cell " << c;
            continue;
        }
        auto p = to_cgal(cell, why);
        ASSERT_TRUE(p) << "cell " << c << ": " << why;
        CgalMesh q = *cgal_body, out;
        ASSERT_TRUE(PMP::corefine_and_compute_intersection(*p, q, out)) << "cell " << c;
        const mpq_class exact = exact_volume(out);
        EXPECT_EQ(r.volumes[c], exact::round_to_double(exact.get_mpq_t())) << "cell " << c;
        ++compared;
        cut += r.cell_class[c] == CellClass::cut;
    }
    EXPECT_GT(compared, 50u);
    EXPECT_GT(cut, 20u);
}

// A sphere of 320 triangles in general position in [-1, 1]^3.
Mesh body() {
    Mesh s = transformed(icosphere(2), {0.3, -0.5, 0.8}, 0.7, {0.053, -0.071, 0.109});
    for (double& x : s.positions) x *= 0.5;
    return s;
}

// An n^3 grid's cubes over [-1, 1]^3, inner points moved by up to 10 % of a
// cell, each cube split into the 6 tetrahedra around its main diagonal
// (Kuhn's split, conforming across cubes), written as a VTK .vtu (ascii).
std::string tetrahedra_vtu(int n) {
    const CellMesh grid = generate::hex_cells(n, -1.0, 1.0, 0.1);
    auto p = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    std::ostringstream points, connectivity, offsets, types;
    points.precision(17);
    for (const double x : grid.points) points << x << " ";
    int cells = 0;
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (int t = 0; t < 6; ++t) {
                    int at[3] = {i, j, k};
                    int v[4];
                    v[0] = p(at[0], at[1], at[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++at[perms[t][s]];
                        v[s + 1] = p(at[0], at[1], at[2]);
                    }
                    if (t == 1 || t == 2 || t == 5) std::swap(v[1], v[2]);  // odd permutations: positive tetrahedra
                    connectivity << v[0] << " " << v[1] << " " << v[2] << " " << v[3] << " ";
                    offsets << 4 * ++cells << " ";
                    types << "10 ";
                }
    std::ostringstream f;
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid><Piece NumberOfPoints=\"" << grid.points.size() / 3 << "\" NumberOfCells=\"" << cells
      << "\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">" << points.str()
      << "</DataArray></Points>\n<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
      << connectivity.str() << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
      << offsets.str() << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" << types.str()
      << "</DataArray></Cells>\n</Piece></UnstructuredGrid></VTKFile>\n";
    return f.str();
}

TEST(CellsCgalOracle, TetrahedraFromAVtu) {
    const std::string text = tetrahedra_vtu(4);
    const LoadedCellMesh loaded = read_vtu_memory(std::as_bytes(std::span(text.data(), text.size())), "tets.vtu");
    ASSERT_EQ(loaded.mesh.cells, 6u * 64);
    const CellVolumes own = cell_volumes(loaded.mesh.view());
    ASSERT_EQ(own.negative_cells, 0u);
    EXPECT_EQ(own.total, 8.0);  // the cube, whatever the inner points
    expect_cells_match_cgal(loaded.mesh.view(), body());
}

TEST(CellsCgalOracle, HexahedraWithMovedPoints) {
    const CellMesh cells = generate::hex_cells(6, -1.0, 1.0, 0.25);
    expect_cells_match_cgal(cells.view(), body());
}

}  // namespace
}  // namespace polyvol
