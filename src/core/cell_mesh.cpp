// core/cell_mesh.cpp — cells_subset (polyvol/cell_mesh.hpp).
#include <stdexcept>
#include <string>
#include <vector>

#include "polyvol/cell_mesh.hpp"

namespace polyvol {

CellMesh cells_subset(const CellMeshView& m, std::span<const uint32_t> cells) {
    std::vector<uint32_t> index(m.cell_count(), kNoCell);  // each cell's place in the subset
    for (std::size_t i = 0; i < cells.size(); ++i) {
        if (cells[i] >= m.cell_count())
            throw std::invalid_argument("cells_subset: cell " + std::to_string(cells[i]) + " is not in the mesh");
        if (index[cells[i]] != kNoCell)
            throw std::invalid_argument("cells_subset: cell " + std::to_string(cells[i]) + " is listed twice");
        index[cells[i]] = static_cast<uint32_t>(i);
    }
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (m.owner[f] >= m.cell_count() || (m.neighbour[f] != kNoCell && m.neighbour[f] >= m.cell_count()))
            throw std::invalid_argument("cells_subset: face " + std::to_string(f) + " names a cell out of range");
    CellMesh out;
    out.points.assign(m.points.begin(), m.points.end());
    out.cells = cells.size();
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const uint32_t owner = index[m.owner[f]];
        const uint32_t neighbour = m.neighbour[f] == kNoCell ? kNoCell : index[m.neighbour[f]];
        if (owner == kNoCell && neighbour == kNoCell) continue;
        const std::span<const uint32_t> face = m.face(f);
        if (owner != kNoCell) {
            out.face_points.insert(out.face_points.end(), face.begin(), face.end());
            out.owner.push_back(owner);
            out.neighbour.push_back(neighbour);
        } else {  // only the neighbour is kept: the face turned to point out of it
            out.face_points.insert(out.face_points.end(), face.rbegin(), face.rend());
            out.owner.push_back(neighbour);
            out.neighbour.push_back(kNoCell);
        }
        out.face_offsets.push_back(static_cast<uint32_t>(out.face_points.size()));
    }
    return out;
}

}  // namespace polyvol
