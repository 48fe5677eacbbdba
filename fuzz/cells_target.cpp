// fuzz/cells_target.cpp — the readers of meshes of cells (polyvol/cell_mesh_io.hpp)
// and what follows them: POLYVOL_FUZZ_CELLS "vtu" reads the input as a .vtu,
// "grdecl" as a GRDECL corner-point grid (of at most 4096 cells),
// "polymesh" as OpenFOAM's four files separated by lines "@@" (points,
// faces, owner, neighbour). A mesh read is checked, and when its cells close,
// measured (cell_volumes). Bad input is ReadError or std::invalid_argument;
// nothing else may escape.
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string_view>

#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/cells.hpp"
#include "polyvol/io.hpp"

namespace {

using Bytes = std::span<const std::byte>;

// Part k (0..3) of the input, the parts separated by "\n@@\n".
Bytes part(Bytes all, int k) {
    const std::string_view text(reinterpret_cast<const char*>(all.data()), all.size());
    std::size_t begin = 0;
    for (int i = 0; i < k; ++i) {
        const std::size_t at = text.find("\n@@\n", begin);
        if (at == std::string_view::npos) return {};
        begin = at + 4;
    }
    const std::size_t end = std::min(text.find("\n@@\n", begin), text.size());
    return all.subspan(begin, end - begin);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    using namespace polyvol;
    const Bytes all(reinterpret_cast<const std::byte*>(data), size);
    LoadedCellMesh m;
    try {
        if (std::string_view(POLYVOL_FUZZ_CELLS) == "vtu")
            m = read_vtu_memory(all, "f.vtu");
        else if (std::string_view(POLYVOL_FUZZ_CELLS) == "grdecl")
            m = read_grdecl_memory(all, "f.grdecl", 4096);
        else
            m = read_polymesh_memory({part(all, 0), part(all, 1), part(all, 2), part(all, 3)}, "case");
    } catch (const ReadError&) {
        return 0;
    }
    if (m.mesh.cells > 4096) return 0;  // the measure's cost, not the reader's, beyond this
    try {
        const CellVolumes v = cell_volumes(m.mesh.view());
        if (v.volumes.size() != m.mesh.cells) __builtin_trap();
    } catch (const std::invalid_argument&) {
    }
    return 0;
}
