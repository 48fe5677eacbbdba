// io/vtu.cpp — read_vtu (polyvol/cell_mesh_io.hpp): VTK XML UnstructuredGrid.
//
// The XML (pugixml) up to <AppendedData>, whose bytes may be raw; arrays in
// any of VTK's encodings: ascii, binary (base64 inline) and appended (raw or
// base64), each uncompressed (a byte count, then the values) or compressed
// by vtkZLibDataCompressor (block count, block size, last block's size, each
// block's compressed size, then the zlib blocks); header integers UInt32 or
// UInt64 (header_type). Cells: tetra, voxel, hexahedron, wedge, pyramid and
// polyhedron (its face stream), turned into OpenFOAM's face form: each
// distinct face once (point ids compared as a set), owned by the first cell
// that names it, its neighbour the second, wound outward from the owner.
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "io/readers.hpp"
#include "polyvol/cell_mesh_io.hpp"

namespace polyvol {
namespace {

int base64_value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

// A VTK file being read: its name for messages, the header integers' size,
// whether blocks are zlib-compressed, the appended block and its encoding.
struct Vtu {
    std::string name;
    std::size_t header_bytes = 4;
    bool compressed = false;
    std::string_view appended;
    bool appended_base64 = false;

    [[noreturn]] void fail(const std::string& what) const { throw ReadError::whole_file(name, what); }

    uint64_t header_int(const std::vector<uint8_t>& b, std::size_t i) const {
        if (b.size() < (i + 1) * header_bytes) fail("a data array's header is cut short");
        uint64_t v = 0;
        std::memcpy(&v, b.data() + i * header_bytes, header_bytes);
        return v;
    }

    // The base64 characters of `text` from `pos` (blanks skipped) decoded
    // until `bytes` bytes are had; pos moves past the characters used
    // (and past a group's padding).
    std::vector<uint8_t> base64(std::string_view text, std::size_t& pos, uint64_t bytes) const {
        if (bytes > text.size()) fail("a base64 array claims more bytes than its text holds");
        std::vector<uint8_t> out;
        out.reserve(bytes);
        uint32_t group = 0;
        int have = 0;
        while (out.size() < bytes) {
            if (pos >= text.size()) fail("a base64 array ends early");
            const char c = text[pos++];
            if (c == '=' ) {
                // Padding ends the group: what it holds is complete.
                if (have == 2) out.push_back(static_cast<uint8_t>(group >> 4));
                if (have == 3) {
                    out.push_back(static_cast<uint8_t>(group >> 10));
                    out.push_back(static_cast<uint8_t>(group >> 2));
                }
                while (pos < text.size() && text[pos] == '=') ++pos;
                group = 0;
                have = 0;
                continue;
            }
            const int v = base64_value(c);
            if (v < 0) {
                if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
                fail(std::string("a character that is not base64: '") + c + "'");
            }
            group = (group << 6) | static_cast<uint32_t>(v);
            if (++have == 4) {
                out.push_back(static_cast<uint8_t>(group >> 16));
                out.push_back(static_cast<uint8_t>(group >> 8));
                out.push_back(static_cast<uint8_t>(group));
                group = 0;
                have = 0;
            }
        }
        // A group read part-way (the next item starts there) is the caller's
        // to re-read: only whole groups or padded ones end where we stop.
        out.resize(bytes);
        return out;
    }

    std::vector<uint8_t> inflate(const uint8_t* data, std::size_t size, std::size_t expected) const {
        std::vector<uint8_t> out(expected);
        uLongf got = static_cast<uLongf>(expected);
        if (::uncompress(out.data(), &got, data, static_cast<uLong>(size)) != Z_OK || got != expected)
            fail("a zlib block does not decompress to its stated size");
        return out;
    }

    // The bytes of one array whose encoded form starts at text[pos] (base64)
    // or at bytes[pos] (raw).
    std::vector<uint8_t> decode(std::string_view text, std::size_t pos, bool is_base64) const {
        std::vector<uint8_t> out;
        if (!compressed) {
            std::vector<uint8_t> head;
            if (is_base64) {
                std::size_t p = pos;
                head = base64(text, p, header_bytes);
                const uint64_t n = header_int(head, 0);
                if (n > text.size()) fail("a base64 array claims more bytes than its text holds");
                p = pos;  // header and values are one base64 stream
                std::vector<uint8_t> all = base64(text, p, header_bytes + n);
                out.assign(all.begin() + static_cast<std::ptrdiff_t>(header_bytes), all.end());
                return out;
            }
            if (pos + header_bytes > text.size()) fail("an appended array's offset is past the data");
            head.assign(text.begin() + static_cast<std::ptrdiff_t>(pos),
                        text.begin() + static_cast<std::ptrdiff_t>(pos + header_bytes));
            const uint64_t n = header_int(head, 0);
            if (n > text.size() - pos - header_bytes) fail("an appended array claims more bytes than there are");
            const auto* first = reinterpret_cast<const uint8_t*>(text.data() + pos + header_bytes);
            out.assign(first, first + n);
            return out;
        }
        // Compressed: nblocks, block size, last block's size, sizes[nblocks].
        std::size_t p = pos;
        std::vector<uint8_t> head;
        if (is_base64) {
            head = base64(text, p, header_bytes);
            const uint64_t blocks = header_int(head, 0);
            if (blocks > text.size()) fail("a compressed array claims too many blocks");
            p = pos;
            head = base64(text, p, header_bytes * (3 + blocks));  // the header is its own base64 stream
        } else {
            if (p + 3 * header_bytes > text.size()) fail("an appended array's offset is past the data");
            head.assign(text.begin() + static_cast<std::ptrdiff_t>(p),
                        text.begin() + static_cast<std::ptrdiff_t>(p + 3 * header_bytes));
            const uint64_t blocks = header_int(head, 0);
            if (blocks > text.size() || p + (3 + blocks) * header_bytes > text.size())
                fail("a compressed array's header is past the data");
            head.assign(text.begin() + static_cast<std::ptrdiff_t>(p),
                        text.begin() + static_cast<std::ptrdiff_t>(p + (3 + blocks) * header_bytes));
            p += (3 + blocks) * header_bytes;
        }
        const uint64_t blocks = header_int(head, 0), block = header_int(head, 1), last = header_int(head, 2);
        uint64_t compressed_total = 0;
        for (uint64_t b = 0; b < blocks; ++b) {
            const uint64_t size = header_int(head, 3 + b);
            if (size > text.size()) fail("a compressed block claims more bytes than there are");
            compressed_total += size;
        }
        std::vector<uint8_t> data;
        if (is_base64) {
            data = base64(text, p, compressed_total);
        } else {
            if (compressed_total > text.size() - p) fail("a compressed array claims more bytes than there are");
            const auto* first = reinterpret_cast<const uint8_t*>(text.data() + p);
            data.assign(first, first + compressed_total);
        }
        // No allocation from a count the bytes cannot back (readers.hpp's bound on decompression).
        const uint64_t limit = io::decompression_limit(text.size());
        if (blocks > limit || block > limit || (blocks > 0 && (blocks - 1) * block + last > limit))
            fail("a compressed array claims to expand to more than " + std::to_string(limit) + " bytes");
        std::size_t at = 0;
        for (uint64_t b = 0; b < blocks; ++b) {
            const uint64_t size = header_int(head, 3 + b);
            const uint64_t expected = (b + 1 == blocks && last != 0) ? last : block;
            const std::vector<uint8_t> chunk = inflate(data.data() + at, size, expected);
            out.insert(out.end(), chunk.begin(), chunk.end());
            at += size;
        }
        return out;
    }

    // A DataArray's values as doubles (integers are exact below 2^53).
    std::vector<double> values(const pugi::xml_node& array) const {
        const std::string type = array.attribute("type").as_string();
        const std::string format = array.attribute("format").as_string("ascii");
        std::vector<double> out;
        if (format == "ascii") {
            const std::string_view text = array.child_value();
            std::size_t p = 0;
            while (p < text.size()) {
                while (p < text.size() && (text[p] == ' ' || text[p] == '\n' || text[p] == '\r' || text[p] == '\t'))
                    ++p;
                if (p >= text.size()) break;
                double v = 0;
                const auto r = std::from_chars(text.data() + p, text.data() + text.size(), v);
                if (r.ec != std::errc()) fail("DataArray '" + std::string(array.attribute("Name").as_string()) +
                                              "': not a number in its ascii values");
                out.push_back(v);
                p = static_cast<std::size_t>(r.ptr - text.data());
            }
            return out;
        }
        std::vector<uint8_t> bytes;
        if (format == "binary") {
            const std::string_view text = array.child_value();
            std::size_t p = 0;
            bytes = decode(text, p, true);
        } else if (format == "appended") {
            bytes = decode(appended, static_cast<std::size_t>(array.attribute("offset").as_ullong()), appended_base64);
        } else {
            fail("DataArray format '" + format + "': expected ascii, binary or appended");
        }
        auto convert = [&](auto zero) {
            using T = decltype(zero);
            if (bytes.size() % sizeof(T) != 0) fail("a " + type + " array's bytes are not whole values");
            out.resize(bytes.size() / sizeof(T));
            for (std::size_t i = 0; i < out.size(); ++i) {
                T v;
                std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
                out[i] = static_cast<double>(v);
            }
        };
        if (type == "Float64") convert(double{});
        else if (type == "Float32") convert(float{});
        else if (type == "Int64") convert(int64_t{});
        else if (type == "UInt64") convert(uint64_t{});
        else if (type == "Int32") convert(int32_t{});
        else if (type == "UInt32") convert(uint32_t{});
        else if (type == "Int16") convert(int16_t{});
        else if (type == "UInt16") convert(uint16_t{});
        else if (type == "Int8") convert(int8_t{});
        else if (type == "UInt8") convert(uint8_t{});
        else fail("DataArray type '" + type + "' is not read");
        return out;
    }
};

// The outward faces of VTK's linear cells, as positions in the cell's point list.
const std::vector<std::vector<int>>& cell_faces_of(int type) {
    static const std::map<int, std::vector<std::vector<int>>> faces = {
        {10, {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}}},                                  // tetra
        {11, {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}},  // voxel
        {12, {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}}},  // hexahedron
        {13, {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}}},              // wedge
        {14, {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}},                    // pyramid
    };
    static const std::vector<std::vector<int>> none;
    const auto it = faces.find(type);
    return it == faces.end() ? none : it->second;
}

// Distinct faces, each owned by the first cell naming it and neighboured by the second.
class FaceTable {
public:
    explicit FaceTable(CellMesh& m) : m_(m) {}
    void add(const std::vector<uint32_t>& face, uint32_t cell, const Vtu& vtu) {
        std::vector<uint32_t> key = face;
        std::sort(key.begin(), key.end());
        const auto [it, fresh] = index_.try_emplace(key, static_cast<uint32_t>(m_.owner.size()));
        if (fresh) {
            m_.face_points.insert(m_.face_points.end(), face.begin(), face.end());
            m_.face_offsets.push_back(static_cast<uint32_t>(m_.face_points.size()));
            m_.owner.push_back(cell);
            m_.neighbour.push_back(kNoCell);
            return;
        }
        const uint32_t f = it->second;
        if (m_.neighbour[f] != kNoCell)
            vtu.fail("a face is shared by three cells or more (cells " + std::to_string(m_.owner[f]) + ", " +
                     std::to_string(m_.neighbour[f]) + ", " + std::to_string(cell) + ")");
        m_.neighbour[f] = cell;
    }

private:
    CellMesh& m_;
    std::map<std::vector<uint32_t>, uint32_t> index_;
};

}  // namespace

LoadedCellMesh read_vtu(const std::string& path) {
    std::string shown;
    const std::vector<std::byte> bytes = io::read_whole_input(path, shown);
    return read_vtu_memory(bytes, shown);
}

LoadedCellMesh read_vtu_memory(std::span<const std::byte> bytes, const std::string& shown) {
    const std::string_view all(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    Vtu vtu;
    vtu.name = shown;
    // The XML ends where <AppendedData> begins (its bytes may be raw).
    std::string xml(all);
    const std::size_t appended_at = all.find("<AppendedData");
    if (appended_at != std::string_view::npos) {
        const std::size_t underscore = all.find('_', appended_at);
        const std::size_t end = all.rfind("</AppendedData>");
        if (underscore == std::string_view::npos || end == std::string_view::npos || end < underscore)
            vtu.fail("<AppendedData> without its '_' and </AppendedData>");
        vtu.appended = all.substr(underscore + 1, end - underscore - 1);
        const std::string_view tag = all.substr(appended_at, underscore - appended_at);
        vtu.appended_base64 = tag.find("base64") != std::string_view::npos;
        xml = std::string(all.substr(0, appended_at)) + "</VTKFile>";
    }
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed = doc.load_buffer(xml.data(), xml.size());
    if (!parsed)
        throw ReadError::at_byte(shown, static_cast<uint64_t>(parsed.offset), std::string("XML: ") + parsed.description());
    const pugi::xml_node file = doc.child("VTKFile");
    if (!file || std::string(file.attribute("type").as_string()) != "UnstructuredGrid")
        vtu.fail("not a VTK UnstructuredGrid file (VTKFile type=\"UnstructuredGrid\")");
    if (std::string(file.attribute("byte_order").as_string("LittleEndian")) != "LittleEndian")
        vtu.fail("big-endian VTK files are not read");
    vtu.header_bytes = std::string(file.attribute("header_type").as_string("UInt32")) == "UInt64" ? 8 : 4;
    const std::string compressor = file.attribute("compressor").as_string();
    if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
        vtu.fail("compressor " + compressor + ": only vtkZLibDataCompressor is read");
    vtu.compressed = !compressor.empty();
    const pugi::xml_node piece = file.child("UnstructuredGrid").child("Piece");
    if (!piece) vtu.fail("no <UnstructuredGrid><Piece>");
    if (piece.next_sibling("Piece")) vtu.fail("several pieces: only one <Piece> is read");

    LoadedCellMesh r;
    r.format = "vtu";
    r.encoding = vtu.compressed ? "zlib" : appended_at != std::string_view::npos ? "appended" : "inline";
    r.location = shown;
    CellMesh& m = r.mesh;
    m.points = vtu.values(piece.child("Points").child("DataArray"));
    const uint64_t points = piece.attribute("NumberOfPoints").as_ullong();
    if (m.points.size() != 3 * points) vtu.fail("Points holds " + std::to_string(m.points.size()) +
                                                 " numbers, NumberOfPoints says " + std::to_string(points));
    std::map<std::string, std::vector<double>> cells;
    for (const pugi::xml_node a : piece.child("Cells").children("DataArray"))
        cells[a.attribute("Name").as_string()] = vtu.values(a);
    const std::vector<double>& connectivity = cells["connectivity"];
    const std::vector<double>& offsets = cells["offsets"];
    const std::vector<double>& types = cells["types"];
    const std::vector<double>& faces = cells["faces"];
    const std::vector<double>& face_offsets = cells["faceoffsets"];
    const uint64_t n = piece.attribute("NumberOfCells").as_ullong();
    if (offsets.size() != n || types.size() != n)
        vtu.fail("Cells: offsets and types need one entry per cell (" + std::to_string(n) + ")");
    // A whole number in [0, limit] from an array of doubles, or the reason it is not.
    auto whole = [&](double v, std::size_t limit, std::size_t c, const char* what) {
        if (!(v >= 0 && v <= static_cast<double>(limit) && v == std::floor(v)))
            vtu.fail("cell " + std::to_string(c) + ": " + what + " " + std::to_string(v) + " is out of range");
        return static_cast<std::size_t>(v);
    };
    auto point_id = [&](double v, std::size_t c) {
        return static_cast<uint32_t>(whole(v, points - 1, c, "point"));
    };
    if (points == 0 && !connectivity.empty()) vtu.fail("cells name points, but there are none");
    FaceTable table(m);
    std::size_t start = 0, face_start = 0;
    for (std::size_t c = 0; c < n; ++c) {
        const std::size_t end = whole(offsets[c], connectivity.size(), c, "offset");
        if (end < start) vtu.fail("cell " + std::to_string(c) + ": its offset is below the cell before's");
        const double type_value = types[c];
        const int type = type_value >= 0 && type_value <= 255 ? static_cast<int>(type_value) : -1;
        const auto cell = static_cast<uint32_t>(c);
        if (type == 42) {
            if (face_offsets.size() <= c)
                vtu.fail("cell " + std::to_string(c) + ": a polyhedron without its faces (faces, faceoffsets)");
            const std::size_t fend = whole(face_offsets[c], faces.size(), c, "face offset");
            if (fend <= face_start) vtu.fail("cell " + std::to_string(c) + ": its face stream is empty");
            std::size_t p = face_start;
            const double count_value = faces[p++];
            const std::size_t count = whole(count_value, fend - p, c, "face count");
            for (std::size_t f = 0; f < count; ++f) {
                if (p >= fend) vtu.fail("cell " + std::to_string(c) + ": its face stream ends early");
                const double size_value = faces[p++];
                const std::size_t k = whole(size_value, fend - p, c, "face size");
                if (k < 3) vtu.fail("cell " + std::to_string(c) + ": a face of fewer than 3 points");
                std::vector<uint32_t> face;
                for (std::size_t i = 0; i < k; ++i) face.push_back(point_id(faces[p++], c));
                table.add(face, cell, vtu);
            }
            face_start = fend;
        } else {
            const auto& local = cell_faces_of(type);
            if (local.empty())
                vtu.fail("cell " + std::to_string(c) + ": VTK cell type " +
                         (type >= 0 ? std::to_string(type) : std::to_string(type_value)) +
                         " is not read (tetra, voxel, hexahedron, wedge, pyramid, polyhedron are)");
            const std::size_t corners = type == 10 ? 4 : type == 13 ? 6 : type == 14 ? 5 : 8;
            if (end - start != corners)
                vtu.fail("cell " + std::to_string(c) + ": " + std::to_string(end - start) + " points for type " +
                         std::to_string(type));
            for (const auto& lf : local) {
                std::vector<uint32_t> face;
                for (const int i : lf) face.push_back(point_id(connectivity[start + static_cast<std::size_t>(i)], c));
                table.add(face, cell, vtu);
            }
            if (face_offsets.size() > c && face_offsets[c] >= 0)
                face_start = whole(face_offsets[c], faces.size(), c, "face offset");
        }
        start = end;
    }
    m.cells = n;
    return r;
}

LoadedCellMesh read_cell_mesh(const std::string& path, bool map_axes) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (e == ".vtu") return read_vtu(path);
    if (e == ".grdecl") return read_grdecl(path, kMaxGridCells, map_axes);
    return read_polymesh(path);
}

}  // namespace polyvol
