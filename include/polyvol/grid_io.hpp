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
    bool integer = false;            // written as UInt8 (values 0 .. 255: cell classes), else Float64
};

// VTK XML ImageData: planes x, y, z (nx + 1, ... values) must be uniformly
// spaced (Origin = first planes, Spacing = (last - first) / n); opens in
// ParaView. The arrays are VTK's binary appended form (raw), exact.
void write_vti(const std::string& path, std::span<const double> x, std::span<const double> y,
               std::span<const double> z, std::span<const CellArray> arrays);

// VTK XML RectilinearGrid: any strictly increasing planes.
void write_vtr(const std::string& path, std::span<const double> x, std::span<const double> y,
               std::span<const double> z, std::span<const CellArray> arrays);

// A PNG figure of a 2D field as people open it: the field in world
// coordinates (its aspect ratio kept, within 640 pixels), in the viridis
// colour map (perceptually uniform; lo dark blue, hi yellow, clamped; NaN
// grey), axes with labelled ticks, a colour bar from lo to hi, and a title.
struct FieldPicture {
    std::span<const double> values;   // values[j * (columns.size() - 1) + i]: column i, row j (j = 0 at the bottom)
    std::span<const double> columns;  // the planes between the columns, increasing (world coordinates)
    std::span<const double> rows;     // the planes between the rows, increasing upwards
    double lo = 0, hi = 1;
    std::string title, column_label, row_label, value_label;
};
void write_png_picture(const std::string& path, const FieldPicture& picture);

}  // namespace polyvol
