// io/vti_writer.cpp — VTK XML ImageData (.vti) and RectilinearGrid (.vtr)
// with cell data (VTK file formats, "XML File Formats": a VTKFile element
// holding one Piece whose CellData lists DataArrays).
//
// The arrays are VTK's binary form: format="appended", raw encoding, each
// a UInt64 byte count then the little-endian values, after the XML in one
// <AppendedData> block (what ParaView writes; values exact, a tenth of the
// size of decimals and read without parsing). Float64 arrays are doubles;
// integer arrays (cell classes) UInt8. VTK orders cells with x fastest, cell
// (i, j, k) at i + nx (j + ny k); polyvol's arrays have k fastest, so the
// writer transposes. A .vtr's plane coordinates stay inline as decimals.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/grid_io.hpp"

namespace polyvol {
namespace {

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

// A value's bytes, little-endian (this library's hosts are).
template <class T>
void append_le(std::string& out, T v) {
    static_assert(std::endian::native == std::endian::little);
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));
}

void append_number(std::string& out, double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

class Writer {
public:
    explicit Writer(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "wb"), &std::fclose) {
        if (!f_) throw std::runtime_error(path + ": cannot open for writing");
    }
    std::string& buffer() { return buf_; }
    void flush_if_large() {
        if (buf_.size() > (1u << 20)) flush();
    }
    void flush() {
        if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), f_.get()) != buf_.size())
            throw std::runtime_error(path_ + ": write failed");
        buf_.clear();
    }
    void close() {
        flush();
        if (std::fflush(f_.get()) != 0) throw std::runtime_error(path_ + ": write failed");
    }

private:
    std::string path_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f_;
    std::string buf_;
};

void check_arrays(const std::string& path, std::size_t cells, std::span<const CellArray> arrays) {
    for (const CellArray& a : arrays)
        if (a.components < 1 || a.values.size() != cells * static_cast<std::size_t>(a.components))
            throw std::invalid_argument(path + ": array '" + a.name + "' does not have one value per cell");
}

// The CellData element (the arrays' offsets into the appended block), and
// the appended block's bytes, in the same order.
struct CellData {
    std::string xml;
    std::string appended;
};

CellData cell_data(std::size_t nx, std::size_t ny, std::size_t nz, std::span<const CellArray> arrays) {
    CellData d;
    d.xml = "      <CellData";
    if (!arrays.empty()) d.xml += " Scalars=\"" + xml_escape(arrays[0].name) + "\"";
    d.xml += ">\n";
    for (const CellArray& a : arrays) {
        d.xml += std::string("        <DataArray type=\"") + (a.integer ? "UInt8" : "Float64") + "\" Name=\"" +
                 xml_escape(a.name) + "\" NumberOfComponents=\"" + std::to_string(a.components) +
                 "\" format=\"appended\" offset=\"" + std::to_string(d.appended.size()) + "\"/>\n";
        const auto nc = static_cast<std::size_t>(a.components);
        const uint64_t bytes = nx * ny * nz * nc * (a.integer ? 1 : 8);
        append_le(d.appended, bytes);
        for (std::size_t k = 0; k < nz; ++k)
            for (std::size_t j = 0; j < ny; ++j)
                for (std::size_t i = 0; i < nx; ++i)
                    for (std::size_t c = 0; c < nc; ++c) {
                        const double v = a.values[((i * ny + j) * nz + k) * nc + c];
                        if (a.integer) d.appended += static_cast<char>(static_cast<uint8_t>(v));
                        else append_le(d.appended, v);
                    }
    }
    d.xml += "      </CellData>\n";
    return d;
}

void write_appended(Writer& w, const std::string& appended) {
    w.buffer() += "  <AppendedData encoding=\"raw\">\n   _";
    w.flush();
    w.buffer() = appended;
    w.flush();
    w.buffer() += "\n  </AppendedData>\n";
}

std::string extent(std::size_t nx, std::size_t ny, std::size_t nz) {
    return "0 " + std::to_string(nx) + " 0 " + std::to_string(ny) + " 0 " + std::to_string(nz);
}

std::string numbers(std::initializer_list<double> v) {
    std::string s;
    for (double x : v) {
        if (!s.empty()) s += ' ';
        append_number(s, x);
    }
    return s;
}

void check_planes(const std::string& path, std::span<const double> c) {
    if (c.size() < 2) throw std::invalid_argument(path + ": each axis needs at least 2 planes");
}

struct CellCounts {
    std::size_t nx, ny, nz;
};

// The cells along each axis between the planes x, y, z; throws
// std::invalid_argument unless every axis has 2 planes or more and every
// array one value (of its components) per cell.
CellCounts checked_cells(const std::string& path, std::span<const double> x, std::span<const double> y,
                         std::span<const double> z, std::span<const CellArray> arrays) {
    check_planes(path, x);
    check_planes(path, y);
    check_planes(path, z);
    const CellCounts n{x.size() - 1, y.size() - 1, z.size() - 1};
    check_arrays(path, n.nx * n.ny * n.nz, arrays);
    return n;
}

}  // namespace

void write_vti(const std::string& path, std::span<const double> x, std::span<const double> y,
               std::span<const double> z, std::span<const CellArray> arrays) {
    const auto [nx, ny, nz] = checked_cells(path, x, y, z, arrays);
    Writer w(path);
    const std::string ext = extent(nx, ny, nz);
    const double sx = (x.back() - x.front()) / static_cast<double>(nx);
    const double sy = (y.back() - y.front()) / static_cast<double>(ny);
    const double sz = (z.back() - z.front()) / static_cast<double>(nz);
    w.buffer() += "<?xml version=\"1.0\"?>\n"
                  "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                  "  <ImageData WholeExtent=\"" + ext + "\" Origin=\"" + numbers({x.front(), y.front(), z.front()}) +
                  "\" Spacing=\"" + numbers({sx, sy, sz}) + "\">\n"
                  "    <Piece Extent=\"" + ext + "\">\n";
    const CellData d = cell_data(nx, ny, nz, arrays);
    w.buffer() += d.xml;
    w.buffer() += "    </Piece>\n  </ImageData>\n";
    write_appended(w, d.appended);
    w.buffer() += "</VTKFile>\n";
    w.close();
}

void write_vtr(const std::string& path, std::span<const double> x, std::span<const double> y,
               std::span<const double> z, std::span<const CellArray> arrays) {
    const auto [nx, ny, nz] = checked_cells(path, x, y, z, arrays);
    Writer w(path);
    const std::string ext = extent(nx, ny, nz);
    w.buffer() += "<?xml version=\"1.0\"?>\n"
                  "<VTKFile type=\"RectilinearGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                  "header_type=\"UInt64\">\n"
                  "  <RectilinearGrid WholeExtent=\"" + ext + "\">\n"
                  "    <Piece Extent=\"" + ext + "\">\n";
    const CellData d = cell_data(nx, ny, nz, arrays);
    std::string& b = w.buffer();
    b += d.xml;
    b += "      <Coordinates>\n";
    const char* names[3] = {"x", "y", "z"};
    const std::span<const double> axes[3] = {x, y, z};
    for (int a = 0; a < 3; ++a) {
        b += std::string("        <DataArray type=\"Float64\" Name=\"") + names[a] + "\" format=\"ascii\">\n";
        for (double v : axes[a]) {
            append_number(b, v);
            b += ' ';
        }
        b += "\n        </DataArray>\n";
    }
    b += "      </Coordinates>\n    </Piece>\n  </RectilinearGrid>\n";
    write_appended(w, d.appended);
    w.buffer() += "</VTKFile>\n";
    w.close();
}

}  // namespace polyvol

namespace polyvol {
namespace {

// Cell c's faces outward (its owner faces as wound, its neighbour faces
// reversed), for the VTK polyhedron's face stream.
struct CellFaceStream {
    std::vector<int64_t> connectivity, offsets, faces, face_offsets;
};

CellFaceStream face_streams(const CellMeshView& m) {
    std::vector<std::vector<uint32_t>> of_cell(m.cell_count());
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        of_cell[m.owner[f]].push_back(static_cast<uint32_t>(2 * f));
        if (m.neighbour[f] != kNoCell) of_cell[m.neighbour[f]].push_back(static_cast<uint32_t>(2 * f + 1));
    }
    CellFaceStream s;
    std::vector<int64_t> points;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        points.clear();
        s.faces.push_back(static_cast<int64_t>(of_cell[c].size()));
        for (const uint32_t entry : of_cell[c]) {
            const std::span<const uint32_t> face = m.face(entry / 2);
            s.faces.push_back(static_cast<int64_t>(face.size()));
            for (std::size_t i = 0; i < face.size(); ++i) {
                const uint32_t p = (entry & 1u) != 0 ? face[face.size() - 1 - i] : face[i];
                s.faces.push_back(p);
                if (std::find(points.begin(), points.end(), int64_t{p}) == points.end()) points.push_back(p);
            }
        }
        s.face_offsets.push_back(static_cast<int64_t>(s.faces.size()));
        s.connectivity.insert(s.connectivity.end(), points.begin(), points.end());
        s.offsets.push_back(static_cast<int64_t>(s.connectivity.size()));
    }
    return s;
}

template <class T>
void append_array(std::string& xml, std::string& appended, const char* type, const std::string& name, int components,
                  std::span<const T> values, const char* indent) {
    xml += std::string(indent) + "<DataArray type=\"" + type + "\"" +
           (name.empty() ? std::string() : " Name=\"" + xml_escape(name) + "\"") + " NumberOfComponents=\"" +
           std::to_string(components) + "\" format=\"appended\" offset=\"" + std::to_string(appended.size()) +
           "\"/>\n";
    append_le(appended, static_cast<uint64_t>(values.size() * sizeof(T)));
    for (const T v : values) append_le(appended, v);
}

}  // namespace

void write_vtu(const std::string& path, const CellMeshView& m, std::span<const CellArray> arrays) {
    check_arrays(path, m.cell_count(), arrays);
    const CellFaceStream s = face_streams(m);
    const std::vector<uint8_t> types(m.cell_count(), 42);  // VTK_POLYHEDRON
    std::string xml, appended;
    xml += "<?xml version=\"1.0\"?>\n"
           "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
           "  <UnstructuredGrid>\n"
           "    <Piece NumberOfPoints=\"" + std::to_string(m.point_count()) + "\" NumberOfCells=\"" +
           std::to_string(m.cell_count()) + "\">\n      <Points>\n";
    append_array<double>(xml, appended, "Float64", "", 3, m.points, "        ");
    xml += "      </Points>\n      <Cells>\n";
    append_array<int64_t>(xml, appended, "Int64", "connectivity", 1, s.connectivity, "        ");
    append_array<int64_t>(xml, appended, "Int64", "offsets", 1, s.offsets, "        ");
    append_array<uint8_t>(xml, appended, "UInt8", "types", 1, types, "        ");
    append_array<int64_t>(xml, appended, "Int64", "faces", 1, s.faces, "        ");
    append_array<int64_t>(xml, appended, "Int64", "faceoffsets", 1, s.face_offsets, "        ");
    xml += "      </Cells>\n      <CellData";
    if (!arrays.empty()) xml += " Scalars=\"" + xml_escape(arrays[0].name) + "\"";
    xml += ">\n";
    for (const CellArray& a : arrays) {
        if (a.integer) {
            std::vector<uint8_t> bytes(a.values.size());
            for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(a.values[i]);
            append_array<uint8_t>(xml, appended, "UInt8", a.name, a.components, bytes, "        ");
        } else {
            append_array<double>(xml, appended, "Float64", a.name, a.components, a.values, "        ");
        }
    }
    xml += "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n";
    Writer w(path);
    w.buffer() = std::move(xml);
    write_appended(w, appended);
    w.buffer() += "</VTKFile>\n";
    w.close();
}

}  // namespace polyvol
