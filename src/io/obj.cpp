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
//
// Large files are read in parallel (chunks.hpp) with the serial reader's
// results and errors: chunks start at statements; a first pass counts
// each chunk's vertices, which gives every chunk the number defined before
// it (read_obj at the end of this file).
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io/chunks.hpp"
#include "io/readers.hpp"
#include "io/text.hpp"

namespace polyvol::io {

namespace {

using text::found;

bool is_keyword_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
}

std::string_view trim_right(std::string_view s) {
    while (!s.empty() && text::is_space(s.back())) s.remove_suffix(1);
    return s;
}

// Past the line end at eol ("\n", "\r\n" or "\r").
std::size_t skip_eol(std::string_view s, std::size_t eol) {
    if (eol >= s.size()) return eol;
    if (s[eol] == '\r' && eol + 1 < s.size() && s[eol + 1] == '\n') return eol + 2;
    return eol + 1;
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

// Statement lines of OBJ text: calls f(statement, line) for each, line being
// the 1-based line of its first physical line. A statement continued with
// '\' is joined (with a blank) into `joined`.
template <class F>
void for_each_statement(std::string_view s, std::string& joined, F&& f) {
    // The end of the line at pos: with no '\r' in s, the next '\n' (memchr).
    const bool has_cr = std::memchr(s.data(), '\r', s.size()) != nullptr;
    auto find_eol = [&](std::size_t pos) {
        if (has_cr) {
            while (pos < s.size() && !text::is_eol(s[pos])) ++pos;
            return pos;
        }
        if (pos >= s.size()) return s.size();
        const void* nl = std::memchr(s.data() + pos, '\n', s.size() - pos);
        return nl == nullptr ? s.size() : static_cast<std::size_t>(static_cast<const char*>(nl) - s.data());
    };
    std::size_t pos = 0;
    uint64_t line_no = 0;
    while (pos < s.size()) {
        // One physical line: [pos, eol), then the line end.
        std::size_t eol = find_eol(pos);
        std::string_view line = s.substr(pos, eol - pos);
        pos = skip_eol(s, eol);
        ++line_no;
        const uint64_t statement_line = line_no;
        std::string_view t = trim_right(line);
        if (!t.empty() && t.back() == '\\') {
            joined.assign(t.substr(0, t.size() - 1));
            for (;;) {
                joined += ' ';
                if (pos >= s.size()) break;
                eol = find_eol(pos);
                const std::string_view more = trim_right(s.substr(pos, eol - pos));
                pos = skip_eol(s, eol);
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
        f(line, statement_line);
    }
}

// Whether a chunk may start at pos: the line before it does not end with
// '\' (so pos starts a statement).
bool obj_chunk_start(std::string_view s, std::size_t pos) {
    std::size_t i = pos;
    if (i > 0 && s[i - 1] == '\n') --i;
    if (i > 0 && s[i - 1] == '\r') --i;
    while (i > 0 && text::is_blank(s[i - 1])) --i;
    return !(i > 0 && s[i - 1] == '\\');
}

// OBJ text read on its own: the whole text when serial, else a chunk
// starting at a statement (chunks.hpp), with the number of vertices defined
// before it (`base`, counted by count_vertices in a first pass). Positions
// are the piece's; indices are global.
class ObjPiece {
public:
    ObjPiece(std::string_view s, uint64_t base) : s_(s), base_(static_cast<int64_t>(base)) {}

    // The vertex statements of the piece (what run() adds when it succeeds).
    uint64_t count_vertices() {
        // Without '\r' or continued lines, a statement is a line ending at
        // the next '\n' (memchr) and its keyword is the line's first token.
        if (std::memchr(s_.data(), '\r', s_.size()) == nullptr) {
            uint64_t n = 0;
            const char* p = s_.data();
            const char* const end = p + s_.size();
            bool continued = false;
            while (p < end) {
                const char* q = p;
                while (q < end && text::is_blank(*q)) ++q;
                if (q == end) break;  // blanks to the end
                const bool v = *q == 'v' && (q + 1 == end || text::is_space(q[1]) || q[1] == '#');
                const auto rest = static_cast<std::size_t>(end - q);
                const void* nl = std::memchr(q, '\n', rest);
                const char* e = nl == nullptr ? end : static_cast<const char*>(nl);
                const char* t = e;
                while (t > p && text::is_blank(t[-1])) --t;
                if (t > p && t[-1] == '\\') {
                    continued = true;
                    break;
                }
                n += static_cast<uint64_t>(v);
                p = e + 1;
            }
            if (!continued) return n;
        }
        uint64_t n = 0;
        for_each_statement(s_, joined_, [&](std::string_view line, uint64_t) {
            Tokens tokens(line);
            n += static_cast<uint64_t>(tokens.next() == "v");
        });
        return n;
    }

    // Vertices go to out[3 * i ...] (the piece's i-th vertex) instead of
    // mesh.positions; out holds every vertex the first pass counted.
    void write_positions_to(double* out) { out_ = out; }

    void run() {
        try {
            for_each_statement(s_, joined_, [&](std::string_view line, uint64_t line_no) { statement(line, line_no); });
        } catch (const ReadError& e) {
            outcome.fail(static_cast<int64_t>(e.line), e.message);
        }
    }

    // A face with a positive index past the vertices read before it: checked
    // once all vertices are known.
    struct Pending {
        uint64_t line;  // the piece's line
        int64_t max_index;
    };

    Mesh mesh;
    std::vector<std::string> notes;  // first occurrences, in order
    std::vector<Pending> pending;
    std::size_t lines = 0, points = 0, groups = 0;
    bool slash = false, negative = false;
    chunks::Outcome outcome;

private:
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
            ++lines;
        } else if (kw == "p") {
            ++points;
        } else if (kw == "o" || kw == "g") {
            ++groups;
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
            if (extra[0] != 1.0) chunks::note_once(notes, "obj-vertex-w-not-1(ignored)");
        }
        if (n_extra >= 3) chunks::note_once(notes, "obj-vertex-colors");
        if (vertices() >= UINT32_MAX) fail("too many vertices");
        if (out_ != nullptr) {
            double* p = out_ + 3 * added_;
            p[0] = xyz[0];
            p[1] = xyz[1];
            p[2] = xyz[2];
        } else {
            mesh.add_vertex(xyz[0], xyz[1], xyz[2]);
        }
        ++added_;
    }

    void face(Tokens& tokens) {
        face_.clear();
        const int64_t n = vertices();
        int64_t forward = 0;  // largest index past the vertices read so far
        for (std::string_view tok = tokens.next(); !tok.empty(); tok = tokens.next()) {
            const std::size_t slash_at = tok.find('/');
            const std::string_view num = tok.substr(0, slash_at);
            if (slash_at != std::string_view::npos) slash = true;
            int64_t i = 0;
            if (!text::parse_int(num, i)) fail("expected a vertex index, found " + found(tok));
            if (i == 0) fail("index 0 (OBJ indices start at 1)");
            if (i < 0) {
                negative = true;
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
        if (forward > 0) pending.push_back({line_, forward});
        if (face_.size() < 3) chunks::note_once(notes, "obj-face-with-" + std::to_string(face_.size()) + "-vertices");
        if (face_.size() == 3) {
            mesh.add_triangle(face_[0], face_[1], face_[2]);
        } else {
            mesh.add_face(face_);
        }
    }

    // Vertices defined so far in the file.
    int64_t vertices() const { return base_ + static_cast<int64_t>(added_); }

    [[noreturn]] void fail(const std::string& message) const { throw ReadError(std::string(), line_, message); }

    std::string_view s_;
    int64_t base_;
    double* out_ = nullptr;
    std::size_t added_ = 0;  // vertices the piece added
    uint64_t line_ = 0;
    std::string joined_;  // only for statements continued with '\'
    std::vector<uint32_t> face_;
};

// The pieces joined in order (each parsed cleanly): the mesh, the notes in
// the serial reader's order, and the forward references checked.
LoadedMesh join_obj(std::vector<ObjPiece>& pieces, std::string_view s, const std::vector<std::size_t>& starts,
                    const std::string& name, std::vector<double> positions) {
    LoadedMesh out;
    out.mesh.positions = std::move(positions);
    out.format = Format::obj;
    out.encoding = "ascii";
    std::size_t lines = 0, points = 0, groups = 0;
    bool slash = false, negative = false;
    std::vector<Mesh> parts;
    parts.reserve(pieces.size());
    for (ObjPiece& p : pieces) {
        for (std::string& note : p.notes) text::add_note(out, std::move(note));
        lines += p.lines;
        points += p.points;
        groups += p.groups;
        slash = slash || p.slash;
        negative = negative || p.negative;
        parts.push_back(std::move(p.mesh));
    }
    chunks::concat(parts, out.mesh, false);
    const auto n = static_cast<int64_t>(out.mesh.vertex_count());
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        for (const ObjPiece::Pending& p : pieces[i].pending) {
            if (p.max_index > n) {
                const uint64_t before = chunks::count_line_ends(s.substr(0, starts[i]));
                throw ReadError(name, before + p.line,
                                "index " + std::to_string(p.max_index) + " out of range (file has " +
                                    std::to_string(n) + " vertices)");
            }
        }
    }
    if (slash) out.notes.emplace_back("obj-slash-index-syntax");
    if (negative) out.notes.emplace_back("obj-negative-indices");
    if (groups > 1) out.notes.emplace_back("obj-multiple-groups-or-objects");
    if (lines > 0) out.notes.push_back("obj-line-elements-ignored(" + std::to_string(lines) + ")");
    if (points > 0) out.notes.push_back("obj-point-elements-ignored(" + std::to_string(points) + ")");
    return out;
}

// The error of the first piece that failed, with its line in the file.
void throw_first_error(const std::vector<ObjPiece>& pieces, std::string_view s,
                       const std::vector<std::size_t>& starts, const std::string& name) {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        const chunks::Outcome& o = pieces[i].outcome;
        if (o.status != chunks::Outcome::Status::ok) {
            const auto before = static_cast<int64_t>(chunks::count_line_ends(s.substr(0, starts[i])));
            throw ReadError(name, static_cast<uint64_t>(before + o.line), o.message);
        }
    }
}

}  // namespace

LoadedMesh read_obj(Bytes data, const std::string& name) { return read_obj(data, name, thread_parse_options()); }

// Parallel: chunks start at statements (not after a line ending with '\');
// a first pass counts each chunk's vertex statements, whose prefix sums give
// every chunk the number of vertices before it (for negative indices and
// messages); the second pass parses. Forward references are checked when
// all pieces are joined, as the serial reader checks them at the end.
LoadedMesh read_obj(Bytes data, const std::string& name, const ParseOptions& options) {
    ParseReport& report = thread_parse_report();
    report = {};
    const std::string_view s = text::as_text(data);
    std::vector<std::size_t> starts{0, s.size()};
    if (chunks::use_parallel(options, s.size())) starts = chunks::split(s, options.chunk_bytes, obj_chunk_start);
    const std::size_t n = starts.size() - 1;
    std::vector<ObjPiece> pieces;
    std::vector<double> positions;  // when the pieces write them in place
    pieces.reserve(n);
    for (std::size_t i = 0; i < n; ++i) pieces.emplace_back(s.substr(starts[i], starts[i + 1] - starts[i]), 0);
    if (n > 1) {
        report.chunks = n;
        std::vector<uint64_t> counts(n);
        chunks::for_each(n, [&](std::size_t i) { counts[i] = pieces[i].count_vertices(); });
        uint64_t base = 0;
        for (std::size_t i = 0; i < n; ++i) {
            pieces[i] = ObjPiece(s.substr(starts[i], starts[i + 1] - starts[i]), base);
            base += counts[i];
        }
        if (base >= UINT32_MAX) {  // the serial reader says where it stops
            report.serial_fallback = true;
            pieces.clear();
            pieces.emplace_back(s, 0);
            starts = {0, s.size()};
        } else {
            // Sized from the vertex statements found; each piece fills its rows.
            positions.resize(3 * static_cast<std::size_t>(base));
            uint64_t first = 0;
            for (std::size_t i = 0; i < n; ++i) {
                pieces[i].write_positions_to(positions.data() + 3 * first);
                first += counts[i];
            }
        }
    }
    chunks::for_each(pieces.size(), [&](std::size_t i) { pieces[i].run(); });
    throw_first_error(pieces, s, starts, name);
    return join_obj(pieces, s, starts, name, std::move(positions));
}

}  // namespace polyvol::io
