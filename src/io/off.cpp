// OFF reader (Geomview's Object File Format, ASCII).
//
//   [ST][C][N][4][n]OFF          header keyword (may be missing, see below)
//   [dim]                        only with the 'n' prefix
//   nv nf [ne]                   counts; the edge count is optional and ignored
//   x y z [extra values]         nv vertex lines; colours, normals, texture
//                                coordinates after x y z are ignored
//   k i1 .. ik [colour values]   nf face lines, 0-based indices
// '#' starts a comment anywhere. Values are whitespace-separated: a vertex or
// a face whose values run short on its line continues on the next one; what
// is left on a line after a complete vertex or face is its extra data.
// A file whose first line is its three counts (no keyword) is read when the
// caller decided it is OFF (extension hint), with the note
// "off-missing-header". 4OFF and nOFF with a dimension other than 3 are not
// 3D meshes and are rejected. Data after the declared faces is tolerated
// and noted.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/readers.hpp"
#include "io/text.hpp"

namespace polyvol::io {

namespace {

using text::found;

class OffReader {
public:
    OffReader(Bytes data, const std::string& name) : cur_(text::as_text(data), '#'), name_(name) {}

    LoadedMesh read() {
        out_.format = Format::off;
        out_.encoding = "ascii";
        std::string_view tok = cur_.next();
        if (tok.empty()) fail("empty OFF file (expected 'OFF' or the vertex and face counts)");
        int64_t nv = 0, nf = 0;
        const text::OffKeyword h = text::parse_off_keyword(tok);
        if (h.valid) {
            if (tok != "OFF") out_.notes.push_back("off-header-" + std::string(tok));
            const std::string_view more = cur_.next_on_line();
            if (more == "BINARY") fail("binary OFF is not supported");
            int64_t dim = h.has4 ? 4 : 3;
            std::string_view first_count = more;
            if (h.has_n) {
                const std::string_view d = more.empty() ? cur_.next() : more;
                if (!text::parse_int(d, dim)) fail("expected the dimension after 'nOFF', found " + found(d));
                if (h.has4) dim += 1;
                first_count = {};
            }
            if (dim != 3)
                fail("OFF with " + std::to_string(dim) + "-dimensional vertices (not a 3D mesh)");
            nv = count(first_count.empty() ? cur_.next() : first_count, "vertex count");
            nf = count(cur_.next(), "face count");
        } else {
            // No keyword: the first line must be the three counts.
            int64_t ne = 0;
            if (!text::parse_int(tok, nv)) fail("expected 'OFF' or the vertex count, found " + found(tok));
            const std::string_view f = cur_.next_on_line();
            const std::string_view e = cur_.next_on_line();
            if (!text::parse_int(f, nf) || !text::parse_int(e, ne) || !cur_.next_on_line().empty())
                fail("expected 'OFF' or a line of three counts");
            if (nv < 0 || nf < 0) fail("negative count");
            out_.notes.emplace_back("off-missing-header");
        }
        const uint64_t counts_line = cur_.line();
        cur_.next_on_line();  // the optional edge count (ignored)
        cur_.skip_line();

        // Counts against the bytes that are there: a vertex takes at least
        // 6 bytes ("0 0 0\n"), a face 2 ("0\n"), the last one without its
        // line end.
        const auto rem = static_cast<uint64_t>(cur_.remaining());
        if (static_cast<uint64_t>(nv) > rem || static_cast<uint64_t>(nf) > rem ||
            6 * static_cast<uint64_t>(nv) + 2 * static_cast<uint64_t>(nf) > rem + 1)
            throw ReadError(name_, counts_line,
                            "header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                " faces but only " + std::to_string(cur_.remaining()) + " bytes follow");
        if (nv > static_cast<int64_t>(UINT32_MAX)) fail("too many vertices");

        Mesh& m = out_.mesh;
        m.positions.reserve(3 * static_cast<std::size_t>(nv));
        std::size_t max_extra = 0;
        for (int64_t v = 0; v < nv; ++v) {
            double xyz[3];
            for (double& c : xyz) {
                const std::string_view t = cur_.next();
                if (!text::parse_double(t, c))
                    fail("expected a coordinate of vertex " + std::to_string(v) + " of " +
                         std::to_string(nv) + ", found " + found(t));
                if (!std::isfinite(c)) fail("non-finite coordinate " + text::quote(t));
            }
            m.add_vertex(xyz[0], xyz[1], xyz[2]);
            std::size_t extra = 0;
            while (!cur_.next_on_line().empty()) ++extra;
            if (extra > max_extra) max_extra = extra;
        }
        if (max_extra > 0) out_.notes.push_back("off-vertex-extra-values(" + std::to_string(max_extra) + ")");

        // Faces: at most remaining/2 of them, so this reserve is bounded by the file.
        m.indices.reserve(std::min<std::size_t>(3 * static_cast<std::size_t>(nf), cur_.remaining() / 2 + 3));
        bool colours = false;
        for (int64_t f = 0; f < nf; ++f) {
            const std::string_view t = cur_.next();
            int64_t k = 0;
            if (!text::parse_int(t, k) || k < 0)
                fail("expected the vertex count of face " + std::to_string(f) + " of " + std::to_string(nf) +
                     ", found " + found(t));
            if (static_cast<uint64_t>(k) > cur_.remaining() / 2 + 1)
                fail("face " + std::to_string(f) + " declares " + std::to_string(k) + " vertices but only " +
                     std::to_string(cur_.remaining()) + " bytes follow");
            face_.clear();
            for (int64_t j = 0; j < k; ++j) {
                const std::string_view it = cur_.next();
                int64_t i = 0;
                if (!text::parse_int(it, i))
                    fail("expected a vertex index of face " + std::to_string(f) + ", found " + found(it));
                if (i < 0 || i >= nv)
                    fail("face " + std::to_string(f) + " index " + std::to_string(i) +
                         " out of range (file has " + std::to_string(nv) + " vertices)");
                face_.push_back(static_cast<uint32_t>(i));
            }
            if (k == 3) {
                m.add_triangle(face_[0], face_[1], face_[2]);
            } else {
                m.add_face(face_);
            }
            if (!cur_.next_on_line().empty()) {
                colours = true;
                while (!cur_.next_on_line().empty()) {
                }
            }
        }
        if (colours) out_.notes.emplace_back("off-face-colors");

        // Anything left over: count the lines that hold data.
        std::size_t trailing = 0;
        for (;;) {
            cur_.skip_line();
            if (cur_.at_end()) break;
            if (!cur_.next_on_line().empty()) ++trailing;
        }
        if (trailing > 0) out_.notes.push_back("off-trailing-data(" + std::to_string(trailing) + " lines)");
        return std::move(out_);
    }

private:
    int64_t count(std::string_view tok, const char* what) {
        int64_t n = 0;
        if (!text::parse_int(tok, n) || n < 0) fail(std::string("expected the ") + what + ", found " + found(tok));
        return n;
    }

    [[noreturn]] void fail(const std::string& message) const { throw ReadError(name_, cur_.line(), message); }

    text::Cursor cur_;
    const std::string& name_;
    LoadedMesh out_;
    std::vector<uint32_t> face_;
};

}  // namespace

LoadedMesh read_off(Bytes data, const std::string& name) { return OffReader(data, name).read(); }

}  // namespace polyvol::io
