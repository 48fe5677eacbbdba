// Wavefront OBJ reader (geometry only).
//
//   v x y z [w] [r g b]   a vertex; w and colours are ignored (noted)
//   f a b c ...           a face; each corner is v, v/vt, v//vn or v/vt/vn,
//                         1-based, or negative = relative to the last vertex
//   l ..., p ...          line and point elements: ignored (counted in a note)
//   o, g                  objects and groups: faces are kept in file order
//   anything else         (vt, vn, s, usemtl, mtllib, ...) ignored
// Comments start with '#'. A backslash at the end of a line continues the
// statement on the next line. Faces of fewer than 3 corners are kept.
//
// A positive index may refer to a vertex defined later in the file (some
// exporters write faces first); it is checked once all vertices are read,
// and reported at the line of its face. Index 0 and negative indices that
// reach before the first vertex are errors at once.
#include <cmath>
#include <string>
#include <vector>

#include "io/readers.hpp"
#include "io/text.hpp"

namespace polyvol::io {

namespace {

using text::found;

bool is_keyword_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
}

// Splits a statement line into blank-separated tokens, a '#' ending it.
class Tokens {
public:
    explicit Tokens(std::string_view line) : s_(line) {}
    std::string_view next() {
        std::size_t i = 0;
        while (i < s_.size() && text::is_space(s_[i])) ++i;
        if (i == s_.size() || s_[i] == '#') {
            s_ = {};
            return {};
        }
        std::size_t j = i;
        while (j < s_.size() && !text::is_space(s_[j]) && s_[j] != '#') ++j;
        const std::string_view tok = s_.substr(i, j - i);
        s_.remove_prefix(j);
        return tok;
    }

private:
    std::string_view s_;
};

class ObjReader {
public:
    ObjReader(Bytes data, const std::string& name) : s_(text::as_text(data)), name_(name) {}

    LoadedMesh read() {
        out_.format = Format::obj;
        out_.encoding = "ascii";
        std::size_t pos = 0;
        uint64_t line_no = 0;
        std::string joined;  // only for statements continued with '\'
        while (pos < s_.size()) {
            // One physical line: [pos, eol), then the line end.
            std::size_t eol = pos;
            while (eol < s_.size() && !text::is_eol(s_[eol])) ++eol;
            std::string_view line = s_.substr(pos, eol - pos);
            pos = skip_eol(eol);
            ++line_no;
            const uint64_t statement_line = line_no;
            std::string_view t = trim_right(line);
            if (!t.empty() && t.back() == '\\') {
                joined.assign(t.substr(0, t.size() - 1));
                for (;;) {
                    joined += ' ';
                    if (pos >= s_.size()) break;
                    eol = pos;
                    while (eol < s_.size() && !text::is_eol(s_[eol])) ++eol;
                    const std::string_view more = trim_right(s_.substr(pos, eol - pos));
                    pos = skip_eol(eol);
                    ++line_no;
                    if (!more.empty() && more.back() == '\\') {
                        joined.append(more.substr(0, more.size() - 1));
                    } else {
                        joined.append(more);
                        break;
                    }
                }
                line = joined;
            }
            statement(line, statement_line);
        }
        finish();
        return std::move(out_);
    }

private:
    static std::string_view trim_right(std::string_view s) {
        while (!s.empty() && text::is_space(s.back())) s.remove_suffix(1);
        return s;
    }

    // Past the line end at eol ("\n", "\r\n" or "\r").
    std::size_t skip_eol(std::size_t eol) const {
        if (eol >= s_.size()) return eol;
        if (s_[eol] == '\r' && eol + 1 < s_.size() && s_[eol + 1] == '\n') return eol + 2;
        return eol + 1;
    }

    void statement(std::string_view line, uint64_t line_no) {
        line_ = line_no;
        Tokens tokens(line);
        const std::string_view kw = tokens.next();
        if (kw.empty()) return;
        if (kw == "v") {
            vertex(tokens);
        } else if (kw == "f" || kw == "fo") {
            face(tokens);
        } else if (kw == "l") {
            ++lines_;
        } else if (kw == "p") {
            ++points_;
        } else if (kw == "o" || kw == "g") {
            ++groups_;
        } else {
            for (char c : kw)
                if (!is_keyword_char(c)) fail("expected an OBJ statement, found " + found(kw));
        }
    }

    void vertex(Tokens& tokens) {
        double xyz[3];
        for (double& c : xyz) {
            const std::string_view tok = tokens.next();
            if (!text::parse_double(tok, c)) fail("expected a coordinate after 'v', found " + found(tok));
            if (!std::isfinite(c)) fail("non-finite coordinate " + text::quote(tok));
        }
        double extra[4];
        int n_extra = 0;
        for (std::string_view tok = tokens.next(); !tok.empty(); tok = tokens.next()) {
            double v = 0;
            if (!text::parse_double(tok, v)) fail("expected a number in the vertex, found " + found(tok));
            if (n_extra < 4) extra[n_extra] = v;
            ++n_extra;
        }
        if (n_extra == 1 || n_extra == 4) {
            if (extra[0] != 1.0) text::add_note(out_, "obj-vertex-w-not-1(ignored)");
        }
        if (n_extra >= 3) text::add_note(out_, "obj-vertex-colors");
        if (out_.mesh.vertex_count() >= UINT32_MAX) fail("too many vertices");
        out_.mesh.add_vertex(xyz[0], xyz[1], xyz[2]);
    }

    void face(Tokens& tokens) {
        face_.clear();
        const auto n = static_cast<int64_t>(out_.mesh.vertex_count());
        int64_t forward = 0;  // largest index past the vertices read so far
        for (std::string_view tok = tokens.next(); !tok.empty(); tok = tokens.next()) {
            const std::size_t slash = tok.find('/');
            const std::string_view num = tok.substr(0, slash);
            if (slash != std::string_view::npos) slash_ = true;
            int64_t i = 0;
            if (!text::parse_int(num, i)) fail("expected a vertex index, found " + found(tok));
            if (i == 0) fail("index 0 (OBJ indices start at 1)");
            if (i < 0) {
                negative_ = true;
                if (-i > n)
                    fail("index " + std::to_string(i) + " out of range (" + std::to_string(n) +
                         " vertices so far)");
                i = n + i;
            } else {
                if (i > UINT32_MAX) fail("index " + std::to_string(i) + " out of range");
                if (i > n && i > forward) forward = i;
                i -= 1;
            }
            face_.push_back(static_cast<uint32_t>(i));
        }
        if (face_.empty()) fail("expected vertex indices after 'f'");
        if (forward > 0) pending_.push_back({out_.mesh.face_count(), line_, forward});
        if (face_.size() < 3) text::add_note(out_, "obj-face-with-" + std::to_string(face_.size()) + "-vertices");
        if (face_.size() == 3) {
            out_.mesh.add_triangle(face_[0], face_[1], face_[2]);
        } else {
            out_.mesh.add_face(face_);
        }
    }

    void finish() {
        const auto n = static_cast<int64_t>(out_.mesh.vertex_count());
        for (const Pending& p : pending_) {
            if (p.max_index > n) {
                throw ReadError(name_, p.line,
                                "index " + std::to_string(p.max_index) + " out of range (file has " +
                                    std::to_string(n) + " vertices)");
            }
        }
        if (slash_) out_.notes.emplace_back("obj-slash-index-syntax");
        if (negative_) out_.notes.emplace_back("obj-negative-indices");
        if (groups_ > 1) out_.notes.emplace_back("obj-multiple-groups-or-objects");
        if (lines_ > 0) out_.notes.push_back("obj-line-elements-ignored(" + std::to_string(lines_) + ")");
        if (points_ > 0) out_.notes.push_back("obj-point-elements-ignored(" + std::to_string(points_) + ")");
    }

    [[noreturn]] void fail(const std::string& message) const { throw ReadError(name_, line_, message); }

    struct Pending {
        std::size_t face;
        uint64_t line;
        int64_t max_index;
    };

    std::string_view s_;
    const std::string& name_;
    LoadedMesh out_;
    uint64_t line_ = 0;
    std::vector<uint32_t> face_;
    std::vector<Pending> pending_;
    std::size_t lines_ = 0, points_ = 0, groups_ = 0;
    bool slash_ = false, negative_ = false;
};

}  // namespace

LoadedMesh read_obj(Bytes data, const std::string& name) { return ObjReader(data, name).read(); }

}  // namespace polyvol::io
