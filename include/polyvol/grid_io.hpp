// polyvol/grid_io.hpp — writing per-cell arrays of a rectilinear grid:
// NumPy .npy, VTK XML ImageData (.vti) and RectilinearGrid (.vtr), and PNG
// pictures of a 2D slice.
//
// These take plain arrays (io does not depend on the grid module). Cell
// arrays are in polyvol's order (grid.hpp): C order with k fastest,
//     values[((i * ny + j) * nz + k) * components + c],
// i.e. a NumPy array of shape (nx, ny, nz[, components]). The VTK writers
// transpose to VTK's x-fastest order themselves. Every writer throws
// std::runtime_error naming the file when it cannot be written.
#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace polyvol {

// NumPy .npy (format 1.0): little-endian float64 ('<f8'), C order, the given
// shape; the header is padded so the data starts at a multiple of 64 bytes.
void write_npy(const std::string& path, std::span<const double> data, std::span<const std::size_t> shape);

// One cell-data array for the VTK writers.
struct CellArray {
    std::string name;
    std::span<const double> values;  // cells * components, polyvol's order (above)
    int components = 1;
};

// VTK XML ImageData: planes x, y, z (nx + 1, ... values) must be uniformly
// spaced (Origin = first planes, Spacing = (last - first) / n); opens in
// ParaView. Values are written as ASCII decimals that read back exactly.
void write_vti(const std::string& path, std::span<const double> x, std::span<const double> y,
               std::span<const double> z, std::span<const CellArray> arrays);

// VTK XML RectilinearGrid: any strictly increasing planes.
void write_vtr(const std::string& path, std::span<const double> x, std::span<const double> y,
               std::span<const double> z, std::span<const CellArray> arrays);

// A PNG picture of a 2D field: values[row * width + col], row 0 at the top,
// each value drawn as scale × scale pixels in the viridis colour map
// (perceptually uniform), lo -> dark blue, hi -> yellow, clamped; NaN is
// drawn grey.
void write_png_field(const std::string& path, std::span<const double> values, std::size_t width,
                     std::size_t height, double lo, double hi, int scale = 1);

}  // namespace polyvol
