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
//
// Large bodies are read in parallel (chunks.hpp) when they are
// line-regular -- each line that holds a token holds one whole vertex or
// face -- which a first pass (the lines holding a token, counted per
// chunk) and the chunks themselves check; otherwise, e.g. values running onto the next
// line, the body is read serially (OffChunk).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/chunks.hpp"
#include "io/readers.hpp"
#include "io/text.hpp"

namespace polyvol::io {

namespace {

using text::found;

// The messages of the body, shared by the serial reader and the chunks.
std::string bad_coordinate(int64_t v, int64_t nv, std::string_view t) {
    return "expected a coordinate of vertex " + std::to_string(v) + " of " + std::to_string(nv) + ", found " + found(t);
}
std::string bad_face_size(int64_t f, int64_t nf, std::string_view t) {
    return "expected the vertex count of face " + std::to_string(f) + " of " + std::to_string(nf) + ", found " +
           found(t);
}
std::string face_too_long(int64_t f, int64_t k, std::size_t remaining) {
    return "face " + std::to_string(f) + " declares " + std::to_string(k) + " vertices but only " +
           std::to_string(remaining) + " bytes follow";
}
std::string bad_index(int64_t f, std::string_view t) {
    return "expected a vertex index of face " + std::to_string(f) + ", found " + found(t);
}
std::string index_out_of_range(int64_t f, int64_t i, int64_t nv) {
    return "face " + std::to_string(f) + " index " + std::to_string(i) + " out of range (file has " +
           std::to_string(nv) + " vertices)";
}

// A chunk of the body (vertex lines, face lines, trailing lines) read on its
// own. Parallel reading needs the body to be line-regular: every line that
// holds a token holds exactly one record, with all of the record's values
// (the serial reader lets a record's values run onto the next line). A
// chunk that finds a record running short on its line is irregular, and the
// whole file is read serially. The first pass counts each chunk's data
// lines, so a chunk knows the index of its first record.
class OffChunk {
public:
    struct Stop {};  // thrown once the outcome is decided

    OffChunk(std::string_view chunk, const char* text_end, uint64_t first_record, int64_t nv, int64_t nf,
             double* positions)
        : cur_(chunk, '#'), begin_(chunk.data()), text_end_(text_end), record_(first_record), nv_(nv), nf_(nf),
          positions_(positions) {}

    void run() {
        try {
            const auto records = static_cast<uint64_t>(nv_ + nf_);
            // Records past the faces are trailing data, counted by the first pass.
            for (; record_ < records; ++record_) {
                const std::string_view t = cur_.next();
                if (t.empty()) break;
                if (record_ < static_cast<uint64_t>(nv_)) vertex(t, static_cast<int64_t>(record_));
                else face(t, static_cast<int64_t>(record_) - nv_);
            }
        } catch (const Stop&) {
        }
    }

    Mesh faces;                 // the chunk's faces (global indices)
    std::size_t max_extra = 0;  // most values after x y z on a vertex line
    bool colours = false;       // a face line had values after its indices
    chunks::Outcome outcome;

private:
    void vertex(std::string_view t, int64_t v) {
        double xyz[3];
        for (int c = 0; c < 3; ++c) {
            if (c > 0) t = on_line();
            if (!text::parse_double(t, xyz[c])) fail(bad_coordinate(v, nv_, t));
            if (!std::isfinite(xyz[c])) fail("non-finite coordinate " + text::quote(t));
        }
        double* p = positions_ + 3 * static_cast<std::size_t>(v);
        p[0] = xyz[0];
        p[1] = xyz[1];
        p[2] = xyz[2];
        std::size_t extra = 0;
        while (!cur_.next_on_line().empty()) ++extra;
        if (extra > max_extra) max_extra = extra;
    }

    void face(std::string_view t, int64_t f) {
        int64_t k = 0;
        if (!text::parse_int(t, k) || k < 0) fail(bad_face_size(f, nf_, t));
        const std::size_t remaining = static_cast<std::size_t>(text_end_ - begin_) - cur_.offset();
        if (static_cast<uint64_t>(k) > remaining / 2 + 1) fail(face_too_long(f, k, remaining));
        // The chunk's indices are fewer than half its bytes: reserve once
        // (pages never written cost nothing).
        if (faces.indices.capacity() == 0) faces.indices.reserve((cur_.remaining() + 2) / 2);
        face_.clear();
        for (int64_t j = 0; j < k; ++j) {
            const std::string_view it = on_line();
            int64_t i = 0;
            if (!text::parse_int(it, i)) fail(bad_index(f, it));
            if (i < 0 || i >= nv_) fail(index_out_of_range(f, i, nv_));
            face_.push_back(static_cast<uint32_t>(i));
        }
        if (k == 3) {
            faces.add_triangle(face_[0], face_[1], face_[2]);
        } else {
            faces.add_face(face_);
        }
        if (!cur_.next_on_line().empty()) {
            colours = true;
            while (!cur_.next_on_line().empty()) {
            }
        }
    }

    // The next value of the record: the serial reader would look on the
    // next line when this one has none.
    std::string_view on_line() {
        const std::string_view t = cur_.next_on_line();
        if (t.empty()) {
            outcome.status = chunks::Outcome::Status::irregular;
            throw Stop{};
        }
        return t;
    }

    [[noreturn]] void fail(std::string message) {
        outcome.fail(static_cast<int64_t>(cur_.line()), std::move(message));
        throw Stop{};
    }

    text::Cursor cur_;
    const char* begin_;
    const char* text_end_;
    uint64_t record_;
    int64_t nv_, nf_;
    double* positions_;
    std::vector<uint32_t> face_;
};

class OffReader {
public:
    OffReader(Bytes data, const std::string& name, const ParseOptions& options)
        : text_(text::as_text(data)), cur_(text_, '#'), name_(name), options_(options) {}

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
        if (parallel_body(nv, nf)) return std::move(out_);

        Mesh& m = out_.mesh;
        m.positions.reserve(3 * static_cast<std::size_t>(nv));
        std::size_t max_extra = 0;
        for (int64_t v = 0; v < nv; ++v) {
            double xyz[3];
            for (double& c : xyz) {
                const std::string_view t = cur_.next();
                if (!text::parse_double(t, c)) fail(bad_coordinate(v, nv, t));
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
            if (!text::parse_int(t, k) || k < 0) fail(bad_face_size(f, nf, t));
            if (static_cast<uint64_t>(k) > cur_.remaining() / 2 + 1) fail(face_too_long(f, k, cur_.remaining()));
            face_.clear();
            for (int64_t j = 0; j < k; ++j) {
                const std::string_view it = cur_.next();
                int64_t i = 0;
                if (!text::parse_int(it, i)) fail(bad_index(f, it));
                if (i < 0 || i >= nv) fail(index_out_of_range(f, i, nv));
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
    // The body (from the cursor, at the start of the line after the counts)
    // read in chunks: see OffChunk. Returns false, having changed nothing,
    // when the body is to be read serially: small, without records, with
    // fewer data lines than records, or not line-regular.
    bool parallel_body(int64_t nv, int64_t nf) {
        const std::size_t body_at = cur_.offset();
        const std::string_view body = text_.substr(body_at);
        if (!chunks::use_parallel(options_, body.size()) || nv + nf == 0) return false;
        const chunks::LineChunks lines = chunks::split_line_body(body, options_.chunk_bytes, '#');
        const std::size_t n = lines.size();
        if (n == 0) return false;
        const auto records = static_cast<uint64_t>(nv + nf);
        if (lines.data_lines < records) return false;  // some record spans lines, or the file is short

        std::vector<double> positions(3 * static_cast<std::size_t>(nv));
        std::vector<OffChunk> pieces;
        pieces.reserve(n);
        uint64_t first = 0;
        for (std::size_t i = 0; i < n; ++i) {
            pieces.emplace_back(lines.chunk(body, i), text_.data() + text_.size(), first, nv, nf, positions.data());
            first += lines.counts[i].data_lines;
        }
        chunks::for_each(n, [&](std::size_t i) { pieces[i].run(); });
        if (!chunks::line_pieces_agree(pieces, lines, cur_.line(), name_)) return false;

        std::size_t max_extra = 0;
        bool colours = false;
        std::vector<Mesh> faces;
        faces.reserve(n);
        for (OffChunk& c : pieces) {
            max_extra = std::max(max_extra, c.max_extra);
            colours = colours || c.colours;
            faces.push_back(std::move(c.faces));
        }
        out_.mesh.positions = std::move(positions);
        chunks::concat(faces, out_.mesh, false);
        if (max_extra > 0) out_.notes.push_back("off-vertex-extra-values(" + std::to_string(max_extra) + ")");
        if (colours) out_.notes.emplace_back("off-face-colors");
        // Every data line after the last face (the serial reader counts them).
        const uint64_t trailing = lines.data_lines - records;
        if (trailing > 0) out_.notes.push_back("off-trailing-data(" + std::to_string(trailing) + " lines)");
        return true;
    }

    int64_t count(std::string_view tok, const char* what) {
        int64_t n = 0;
        if (!text::parse_int(tok, n) || n < 0) fail(std::string("expected the ") + what + ", found " + found(tok));
        return n;
    }

    [[noreturn]] void fail(const std::string& message) const { throw ReadError(name_, cur_.line(), message); }

    std::string_view text_;
    text::Cursor cur_;
    const std::string& name_;
    const ParseOptions& options_;
    LoadedMesh out_;
    std::vector<uint32_t> face_;
};

}  // namespace

LoadedMesh read_off(Bytes data, const std::string& name) { return read_off(data, name, thread_parse_options()); }

LoadedMesh read_off(Bytes data, const std::string& name, const ParseOptions& options) {
    thread_parse_report() = {};
    return OffReader(data, name, options).read();
}

}  // namespace polyvol::io
