// STL reader, binary and ASCII.
//
// Binary STL: an 80-byte header, a uint32 little-endian triangle count n at
// byte 80, then n records of 50 bytes (normal, three vertices as float32 LE,
// a 2-byte attribute). A file is binary exactly when its size is 84 + 50 n,
// whatever its header says (many binary files start with "solid").
//
// ASCII STL:
//   solid NAME
//     facet normal nx ny nz
//       outer loop
//         vertex x y z      (any number of these)
//       endloop
//     endfacet
//   endsolid NAME
// Several solid blocks are read one after the other; a missing endsolid, an
// endsolid with another name, a facet without or with an unreadable normal
// are tolerated and noted. Keywords are matched case-insensitively.
//
// Either way the result is a triangle soup: every facet adds its own
// vertices (nothing is welded), and facet normals are ignored. A loop of k
// vertices becomes one face of k vertices (k = 3 almost always; a 4-vertex
// loop is a quad, a 2-vertex loop a face that measures ignore).
#include <cmath>
#include <cstring>
#include <string>

#include "io/readers.hpp"
#include "io/text.hpp"

namespace polyvol::io {

namespace {

using text::found;
using text::iequals;

uint32_t load_u32_le(const std::byte* p) {
    unsigned char b[4];
    std::memcpy(b, p, 4);
    return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 |
           static_cast<uint32_t>(b[2]) << 16 | static_cast<uint32_t>(b[3]) << 24;
}

float load_f32_le(const std::byte* p) {
    const uint32_t bits = load_u32_le(p);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

bool starts_with_solid(std::string_view s) {
    return s.size() >= 5 && iequals(s.substr(0, 5), "solid") &&
           (s.size() == 5 || text::is_space(s[5]));
}

LoadedMesh read_binary_stl(Bytes data, const std::string& name, uint32_t n) {
    LoadedMesh out;
    out.format = Format::stl;
    out.encoding = "binary_le";
    if (std::memcmp(data.data(), "solid", 5) == 0)
        out.notes.emplace_back("binary-stl-header-starts-with-solid");
    Mesh& m = out.mesh;
    // n is trustworthy here: the file size was checked against it.
    m.positions.resize(std::size_t{9} * n);
    m.indices.resize(std::size_t{3} * n);
    bool attributes = false;
    const std::byte* rec = data.data() + 84;
    double* pos = m.positions.data();
    for (uint32_t t = 0; t < n; ++t, rec += 50) {
        for (int k = 0; k < 9; ++k) {
            const float f = load_f32_le(rec + 12 + 4 * k);
            if (!std::isfinite(f)) {
                throw ReadError::at_byte(name, static_cast<uint64_t>(rec + 12 + 4 * k - data.data()),
                                         "non-finite coordinate in triangle " + std::to_string(t));
            }
            pos[k] = static_cast<double>(f);  // exact widening
        }
        pos += 9;
        attributes = attributes || rec[48] != std::byte{0} || rec[49] != std::byte{0};
    }
    for (uint32_t i = 0; i < 3 * n; ++i) m.indices[i] = i;
    if (attributes) out.notes.emplace_back("stl-nonzero-attribute-bytes");
    return out;
}

class AsciiStl {
public:
    AsciiStl(Bytes data, const std::string& name) : cur_(text::as_text(data)), name_(name) {}

    LoadedMesh read() {
        out_.format = Format::stl;
        out_.encoding = "ascii";
        // A rough bound for the soup from the file size (a vertex line takes
        // at least 12 bytes); only a hint for reserve.
        const std::size_t guess = cur_.remaining() / 200;
        out_.mesh.positions.reserve(9 * guess);
        out_.mesh.indices.reserve(3 * guess);

        std::string_view tok = cur_.next();
        std::size_t solids = 0;
        while (!tok.empty()) {
            if (!iequals(tok, "solid")) {
                if (solids > 0 && only_nul_and_space(tok)) {
                    text::add_note(out_, "stl-trailing-nul-bytes");
                    break;
                }
                fail(solids == 0 ? "expected 'solid', found " + found(tok)
                                 : "expected 'solid' or end of file after 'endsolid', found " +
                                       found(tok));
            }
            ++solids;
            tok = read_solid();
        }
        if (solids > 1) out_.notes.push_back("stl-multiple-solids(" + std::to_string(solids) + ")");
        return std::move(out_);
    }

private:
    // After "solid": reads the block; returns the token after it ("solid" of
    // the next block, or empty at the end of the input).
    std::string_view read_solid() {
        const std::string_view solid_name = cur_.rest_of_line();
        for (;;) {
            std::string_view tok = cur_.next();
            if (tok.empty()) {
                text::add_note(out_, "stl-missing-endsolid");
                return tok;
            }
            if (iequals(tok, "endsolid")) {
                const std::string_view end_name = cur_.rest_of_line();
                if (!end_name.empty() && end_name != solid_name)
                    text::add_note(out_, "stl-endsolid-name-mismatch");
                return cur_.next();
            }
            if (iequals(tok, "solid")) {
                text::add_note(out_, "stl-missing-endsolid");
                return tok;
            }
            if (!iequals(tok, "facet")) fail("expected 'facet' or 'endsolid', found " + found(tok));
            read_facet();
        }
    }

    // After "facet".
    void read_facet() {
        std::string_view tok = cur_.next();
        if (iequals(tok, "normal")) {
            // Up to three numbers before "outer"; they are ignored, but an
            // unreadable normal is noted.
            int count = 0;
            bool ok = true;
            for (tok = cur_.next(); !tok.empty() && !iequals(tok, "outer"); tok = cur_.next()) {
                if (++count > 3) fail("expected 'outer loop' after the facet normal, found " + found(tok));
                double v;
                if (!text::parse_double(tok, v)) ok = false;
            }
            if (!ok || count != 3) text::add_note(out_, "stl-unparseable-normal");
        } else if (iequals(tok, "outer")) {
            text::add_note(out_, "stl-facet-without-normal");
        } else {
            fail("expected 'normal' or 'outer loop' after 'facet', found " + found(tok));
        }
        if (!iequals(tok, "outer")) fail("expected 'outer loop', found " + found(tok));
        tok = cur_.next();
        if (!iequals(tok, "loop")) fail("expected 'loop' after 'outer', found " + found(tok));

        Mesh& m = out_.mesh;
        const auto first = static_cast<uint32_t>(m.vertex_count());
        uint32_t k = 0;
        for (tok = cur_.next(); iequals(tok, "vertex"); tok = cur_.next()) {
            double xyz[3];
            for (double& c : xyz) {
                const std::string_view num = cur_.next();
                if (!text::parse_double(num, c)) fail("expected a number after 'vertex', found " + found(num));
                if (!std::isfinite(c)) fail("non-finite coordinate " + text::quote(num));
            }
            if (m.vertex_count() >= UINT32_MAX) fail("too many vertices");
            m.add_vertex(xyz[0], xyz[1], xyz[2]);
            ++k;
        }
        if (!iequals(tok, "endloop")) fail("expected 'endloop', found " + found(tok));
        tok = cur_.next();
        if (!iequals(tok, "endfacet")) fail("expected 'endfacet', found " + found(tok));
        if (k == 3) {
            m.add_triangle(first, first + 1, first + 2);
        } else {
            text::add_note(out_, "stl-loop-with-" + std::to_string(k) + "-vertices");
            face_.clear();
            for (uint32_t i = 0; i < k; ++i) face_.push_back(first + i);
            m.add_face(face_);
        }
    }

    bool only_nul_and_space(std::string_view tok) {
        for (char c : tok)
            if (c != '\0') return false;
        for (char c : cur_.rest())
            if (c != '\0' && !text::is_space(c)) return false;
        return true;
    }

    [[noreturn]] void fail(const std::string& message) const {
        throw ReadError(name_, cur_.line(), message);
    }

    text::Cursor cur_;
    const std::string& name_;
    LoadedMesh out_;
    std::vector<uint32_t> face_;
};

}  // namespace

LoadedMesh read_stl(Bytes data, const std::string& name) {
    const std::size_t size = data.size();
    if (size >= 84) {
        const uint64_t n = load_u32_le(data.data() + 80);
        if (84 + 50 * n == size) return read_binary_stl(data, name, static_cast<uint32_t>(n));
    }
    const std::string_view s = text::as_text(data);
    // ASCII when it starts with "solid" (after blanks) and has no NUL byte
    // in what would be a binary header (a binary file whose header says
    // "solid" but whose size is wrong gets the size error below).
    std::size_t lead = 0;
    while (lead < s.size() && text::is_space(s[lead])) ++lead;
    if (starts_with_solid(s.substr(lead)) && s.substr(0, 84).find('\0') == std::string_view::npos)
        return AsciiStl(data, name).read();
    if (size < 84)
        throw ReadError::whole_file(name, "file too short for binary STL (" + std::to_string(size) +
                                              " bytes) and it does not start with 'solid'");
    const uint64_t n = load_u32_le(data.data() + 80);
    throw ReadError::at_byte(name, 80,
                             "binary STL size mismatch: header declares " + std::to_string(n) +
                                 " triangles (" + std::to_string(84 + 50 * n) +
                                 " bytes) but file has " + std::to_string(size) + " bytes");
}

}  // namespace polyvol::io
