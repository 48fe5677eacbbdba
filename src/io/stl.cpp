// STL reader, binary and ASCII.
//
// Binary STL: an 80-byte header, a uint32 little-endian triangle count n at
// byte 80, then n records of 50 bytes (normal, three vertices as float32 LE,
// a 2-byte attribute). A file is binary exactly when its size is 84 + 50 n,
// whatever its header says (many binary files start with "solid"). Large
// files are read in blocks of records on several threads (read_binary_stl).
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
// Large ASCII files are read in parallel (chunks.hpp) with the serial
// reader's results and errors: chunks start at lines whose first token is
// 'facet' or 'endsolid' and are read as inside a solid (StlPiece); the file
// is read serially when a chunk turns out not to start inside a solid or a
// facet runs past its chunk's end (both happen only in odd files).
//
// Either way every facet adds its own vertices, which are then welded
// (ParseOptions::weld_stl; LoadedMesh in io.hpp says what comes out), and
// facet normals are ignored. A loop of k vertices becomes one face of k
// vertices (k = 3 almost always; a 4-vertex loop is a quad, a 2-vertex loop
// a face that measures ignore).
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "io/chunks.hpp"
#include "core/classes.hpp"
#include "core/prefault.hpp"
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

// Triangles per task of the welding binary reader: 49152 corners, welded
// with one table of 512 KiB, in the core's L2 (weld_vertices' serial
// path). Larger blocks leave fewer copies of a point for the weld across
// blocks: on a 1M-triangle sphere the blocks' points are 1.24 times the
// mesh's vertices with 8192 triangles a block, 1.12 times with 16384.
constexpr std::size_t kBinaryBlock = 16384;

// Vertex ids are uint32 and weld_vertices numbers at most 2^32 - 2
// vertices (UINT32_MAX is no index): the most corners a read may collect.
constexpr std::size_t kMaxVertices = std::size_t{UINT32_MAX} - 1;

// Whether a facet's stated normal n points against the winding of its
// corners p (nine coordinates): n · ((b − a) × (c − a)) < 0, in double. A
// zero or non-finite normal (a writer's "compute it yourself") never counts.
bool normal_against_winding(const double n[3], const double* p) {
    const double u[3] = {p[3] - p[0], p[4] - p[1], p[5] - p[2]};
    const double v[3] = {p[6] - p[0], p[7] - p[1], p[8] - p[2]};
    const double d = n[0] * (u[1] * v[2] - u[2] * v[1]) + n[1] * (u[2] * v[0] - u[0] * v[2]) +
                     n[2] * (u[0] * v[1] - u[1] * v[0]);
    return std::isfinite(n[0] + n[1] + n[2]) && d < 0;
}

// Widens records [t0, t1) into pos (nine doubles a record: exact), and
// counts in `against` the records whose normal points against the winding.
// Returns the byte offset of the first non-finite coordinate, or 0 when
// there is none (no coordinate is at offset 0).
uint64_t widen_records(Bytes data, std::size_t t0, std::size_t t1, double* pos, bool& attributes,
                       std::size_t& against) {
    const std::byte* rec = data.data() + 84 + 50 * t0;
    for (std::size_t t = t0; t < t1; ++t, rec += 50) {
        for (int c = 0; c < 9; ++c) {
            const float f = load_f32_le(rec + 12 + 4 * c);
            if (!std::isfinite(f)) return static_cast<uint64_t>(rec + 12 + 4 * c - data.data());
            pos[c] = static_cast<double>(f);  // exact widening
        }
        const double normal[3] = {load_f32_le(rec), load_f32_le(rec + 4), load_f32_le(rec + 8)};
        against += normal_against_winding(normal, pos);
        pos += 9;
        attributes = attributes || rec[48] != std::byte{0} || rec[49] != std::byte{0};
    }
    return 0;
}

[[noreturn]] void throw_nonfinite(const std::string& name, uint64_t offset) {
    throw ReadError::at_byte(name, offset, "non-finite coordinate in triangle " + std::to_string((offset - 84) / 50));
}

// Welded (options.weld_stl): blocks of records read and welded on their own
// in parallel, joined in file order, then welded across blocks. Welding each
// block first while its positions are in cache leaves about a sixth of the
// corners for the join and the last weld, and the result is the same as
// welding the whole soup (each block keeps its classes' first corners, in
// order). Each thread widens its blocks into one reused buffer, and a block
// keeps only its classes' positions; its corners' class numbers go straight
// into the mesh's indices, raised by the classes before the block when the
// blocks are joined. The error is that of the first bad coordinate in the
// file.
LoadedMesh read_binary_stl(Bytes data, const std::string& name, uint32_t n, const ParseOptions& options) {
    LoadedMesh out;
    out.format = Format::stl;
    out.encoding = "binary_le";
    if (std::memcmp(data.data(), "solid", 5) == 0)
        out.notes.emplace_back("binary-stl-header-starts-with-solid");
    // n is trustworthy here: the file size was checked against it.
    out.vertices_in_file = std::size_t{3} * n;
    const auto too_many = [&](const char* what) {
        return ReadError::at_byte(name, 80,
                                  std::to_string(n) + " triangles have more " + what +
                                      " than 32-bit vertex ids can number (2^32 - 2)");
    };
    Mesh& m = out.mesh;
    bool attributes = false;
    if (!options.weld_stl) {
        if (out.vertices_in_file > kMaxVertices) throw too_many("corners");
        core::resize_for_filling(m.positions, std::size_t{9} * n);
        std::size_t against = 0;
        if (const uint64_t bad = widen_records(data, 0, n, m.positions.data(), attributes, against))
            throw_nonfinite(name, bad);
        out.facet_normals_against_winding = against;
        core::resize_for_filling(m.indices, std::size_t{3} * n);
        for (std::size_t i = 0; i < m.indices.size(); ++i) m.indices[i] = static_cast<uint32_t>(i);
    } else {
        const std::size_t blocks = (std::size_t{n} + kBinaryBlock - 1) / kBinaryBlock;
        std::vector<std::vector<double>> xyz(blocks);  // each block's classes' positions
        std::vector<uint64_t> bad(blocks, 0);
        std::vector<char> block_attributes(blocks, 0);
        std::vector<std::size_t> block_against(blocks, 0);
        core::resize_for_filling(m.indices, std::size_t{3} * n);
        tbb::enumerable_thread_specific<std::vector<double>> soups;
        // The first block known to hold a bad coordinate: the blocks after it
        // are skipped (the error is that block's or an earlier one's).
        std::atomic<std::size_t> first_bad{blocks};
        const auto read_block = [&](std::size_t b) {
            if (b > first_bad.load(std::memory_order_relaxed)) return;
            const std::size_t t0 = b * kBinaryBlock, t1 = std::min<std::size_t>(n, t0 + kBinaryBlock);
            std::vector<double>& soup = soups.local();
            soup.resize(9 * (t1 - t0));
            bool a = false;
            bad[b] = widen_records(data, t0, t1, soup.data(), a, block_against[b]);
            block_attributes[b] = a;
            if (bad[b] != 0) {
                std::size_t f = first_bad.load();
                while (b < f && !first_bad.compare_exchange_weak(f, b)) {
                }
                return;
            }
            // Isolated: while this block's passes wait for their own oneTBB
            // work, the thread takes no other block, which would reuse `soup`.
            tbb::this_task_arena::isolate([&] {
                std::vector<uint32_t> id;
                core::number_classes(weld_vertices(soup), soup, id, xyz[b]);  // corner i is soup vertex i
                std::copy(id.begin(), id.end(), m.indices.begin() + static_cast<std::ptrdiff_t>(3 * t0));
            });
        };
        const bool parallel = chunks::use_parallel(options, data.size()) && blocks > 1;
        const auto for_each_block = [&](const std::function<void(std::size_t)>& f) {
            if (parallel) {
                chunks::for_each(blocks, f);
            } else {
                for (std::size_t b = 0; b < blocks; ++b) f(b);
            }
        };
        if (parallel) thread_parse_report().chunks = blocks;
        for_each_block(read_block);
        std::vector<std::size_t> base(blocks + 1, 0);  // the blocks' classes before block b
        for (std::size_t b = 0; b < blocks; ++b) {
            if (bad[b] != 0) throw_nonfinite(name, bad[b]);
            attributes = attributes || block_attributes[b] != 0;
            out.facet_normals_against_winding += block_against[b];
            base[b + 1] = base[b] + xyz[b].size() / 3;
        }
        if (base[blocks] > kMaxVertices) throw too_many("distinct points in their blocks");
        core::resize_for_filling(m.positions, 3 * base[blocks]);
        for_each_block([&](std::size_t b) {
            std::copy(xyz[b].begin(), xyz[b].end(), m.positions.begin() + static_cast<std::ptrdiff_t>(3 * base[b]));
            std::vector<double>().swap(xyz[b]);
            const auto shift = static_cast<uint32_t>(base[b]);
            const std::size_t end = std::min<std::size_t>(3 * std::size_t{n}, 3 * (b + 1) * kBinaryBlock);
            for (std::size_t i = 3 * b * kBinaryBlock; i < end; ++i) m.indices[i] += shift;
        });
        if (blocks > 1) weld_in_place(m);
    }
    if (attributes) out.notes.emplace_back("stl-nonzero-attribute-bytes");
    return out;
}

// One piece of ASCII STL text read on its own: the whole text when serial,
// else a chunk (chunks.hpp). A chunk other than the first starts at a line
// whose first token is 'facet' or 'endsolid', and is read as the serial
// reader reads inside a solid; the join checks that the chunk before it
// ended inside a solid (else the file is read serially). Its vertices are
// numbered from 0; the join shifts them.
class StlPiece {
public:
    // Where the piece's tokens ran out.
    enum class End { in_solid, top_level, done };
    // A note, or (name_check) the name after an 'endsolid' that closes a
    // solid opened before the piece, to compare with that solid's name.
    struct Event {
        bool name_check = false;
        std::string text;
    };

    StlPiece(std::string_view piece, const char* text_end, bool first, bool last)
        : cur_(piece), begin_(piece.data()), text_end_(text_end), first_(first), last_(last) {}

    void run() {
        // Facets from the size, only a hint for reserve: a triangle facet
        // as usually written takes 150 to 300 bytes, so this guess seldom
        // needs a second allocation (pages reserved and never written cost
        // nothing).
        const std::size_t guess = cur_.remaining() / 128;
        mesh.positions.reserve(9 * guess);
        mesh.indices.reserve(3 * guess);
        try {
            top_level(first_ ? cur_.next() : solid_body(false, {}));
        } catch (const ReadError& e) {
            // Stopped by the end of the chunk: the serial reader would have
            // read on into the next one.
            if (!last_ && cur_.at_end()) outcome.status = chunks::Outcome::Status::irregular;
            else outcome.fail(static_cast<int64_t>(e.line), e.message);
        }
        vertices_read = mesh.vertex_count();
    }

    Mesh mesh;                              // welded after run() when the reader welds
    std::size_t vertices_read = 0;          // corners read (before any welding)
    std::vector<Event> events;
    std::size_t solids = 0;                 // solids opened in the piece
    std::size_t normals_against = 0;        // triangle facets whose normal points against their winding
    bool named = false;                     // whether a solid was opened (last_name is set)
    std::string_view last_name;             // the name of the last solid opened
    End end = End::in_solid;
    chunks::Outcome outcome;

private:
    void top_level(std::string_view tok) {
        while (!tok.empty()) {
            if (!iequals(tok, "solid")) {
                // A piece after the first starts inside a solid: one was opened.
                const bool after_solid = !first_ || solids > 0;
                if (after_solid && only_nul_and_space(tok)) {
                    note("stl-trailing-nul-bytes");
                    end = End::done;
                    return;
                }
                fail(!after_solid ? "expected 'solid', found " + found(tok)
                                  : "expected 'solid' or end of file after 'endsolid', found " + found(tok));
            }
            ++solids;
            last_name = cur_.rest_of_line();
            named = true;
            tok = solid_body(true, last_name);
        }
    }

    // After "solid NAME" (or at the start of a later chunk, where the name
    // is not known): reads the block; returns the token after it ("solid"
    // of the next block, or empty at the end of the piece).
    std::string_view solid_body(bool name_known, std::string_view solid_name) {
        for (;;) {
            std::string_view tok = cur_.next();
            if (tok.empty()) {
                end = End::in_solid;
                if (last_) note("stl-missing-endsolid");
                return tok;
            }
            if (iequals(tok, "endsolid")) {
                const std::string_view end_name = cur_.rest_of_line();
                if (!end_name.empty()) {
                    if (!name_known) events.push_back({true, std::string(end_name)});
                    else if (end_name != solid_name) note("stl-endsolid-name-mismatch");
                }
                end = End::top_level;
                return cur_.next();
            }
            if (iequals(tok, "solid")) {
                note("stl-missing-endsolid");
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
                if (!text::parse_double(tok, normal_[count - 1])) ok = false;
            }
            if (!ok || count != 3) note("stl-unparseable-normal");
            has_normal = ok && count == 3;
        } else if (iequals(tok, "outer")) {
            has_normal = false;
            note("stl-facet-without-normal");
        } else {
            fail("expected 'normal' or 'outer loop' after 'facet', found " + found(tok));
        }
        if (!iequals(tok, "outer")) fail("expected 'outer loop', found " + found(tok));
        tok = cur_.next();
        if (!iequals(tok, "loop")) fail("expected 'loop' after 'outer', found " + found(tok));

        Mesh& m = mesh;
        const auto first = static_cast<uint32_t>(m.vertex_count());
        uint32_t k = 0;
        for (tok = cur_.next(); iequals(tok, "vertex"); tok = cur_.next()) {
            double xyz[3];
            for (double& c : xyz) {
                if (cur_.next_finite_number(c)) continue;  // the usual case
                const std::string_view num = cur_.next();
                if (!text::parse_double(num, c)) fail("expected a number after 'vertex', found " + found(num));
                if (!std::isfinite(c)) fail("non-finite coordinate " + text::quote(num));
            }
            // The count is the piece's; the join reads serially when all
            // pieces together pass the limit.
            if (m.vertex_count() >= kMaxVertices) fail("too many vertices");
            m.add_vertex(xyz[0], xyz[1], xyz[2]);
            ++k;
        }
        if (!iequals(tok, "endloop")) fail("expected 'endloop', found " + found(tok));
        tok = cur_.next();
        if (!iequals(tok, "endfacet")) fail("expected 'endfacet', found " + found(tok));
        if (k == 3) {
            if (has_normal) normals_against += normal_against_winding(normal_, m.positions.data() + 3 * std::size_t{first});
            m.add_triangle(first, first + 1, first + 2);
        } else {
            note("stl-loop-with-" + std::to_string(k) + "-vertices");
            face_.clear();
            for (uint32_t i = 0; i < k; ++i) face_.push_back(first + i);
            m.add_face(face_);
        }
    }

    // tok and everything after it in the whole text is NUL bytes and blanks.
    bool only_nul_and_space(std::string_view tok) const {
        for (char c : tok)
            if (c != '\0') return false;
        for (const char* p = begin_ + cur_.offset(); p < text_end_; ++p)
            if (*p != '\0' && !text::is_space(*p)) return false;
        return true;
    }

    void note(std::string n) {
        for (const Event& e : events)
            if (!e.name_check && e.text == n) return;
        events.push_back({false, std::move(n)});
    }

    [[noreturn]] void fail(const std::string& message) const { throw ReadError(std::string(), cur_.line(), message); }

    text::Cursor cur_;
    const char* begin_;
    const char* text_end_;
    bool first_, last_;
    std::vector<uint32_t> face_;
    bool has_normal = false;
    double normal_[3] = {0, 0, 0};
};

// Whether a chunk may start at pos: its line's first token is 'facet' or
// 'endsolid' (between facets, whatever the case).
bool stl_chunk_start(std::string_view s, std::size_t pos) {
    while (pos < s.size() && text::is_blank(s[pos])) ++pos;
    for (std::string_view kw : {std::string_view("facet"), std::string_view("endsolid")}) {
        if (s.size() - pos >= kw.size() && iequals(s.substr(pos, kw.size()), kw) &&
            (s.size() - pos == kw.size() || text::is_space(s[pos + kw.size()])))
            return true;
    }
    return false;
}

// Whether the pieces read like the serial reader: each piece after the
// first starts inside a solid, none is irregular, and together they stay
// below the vertex limit. Returns false when the file must be read serially
// instead; throws the serial reader's error when a piece failed.
bool pieces_agree(const std::vector<StlPiece>& pieces, std::string_view s, const std::vector<std::size_t>& starts,
                  const std::string& name) {
    std::size_t vertices = 0;
    for (const StlPiece& p : pieces) vertices += p.vertices_read;
    if (vertices >= kMaxVertices) return false;  // the serial reader says where it stops
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        if (i > 0 && pieces[i - 1].end != StlPiece::End::in_solid) return false;
        const chunks::Outcome& o = pieces[i].outcome;
        if (o.status == chunks::Outcome::Status::irregular) return false;
        if (o.status == chunks::Outcome::Status::error) {
            const auto before = static_cast<int64_t>(chunks::count_line_ends(s.substr(0, starts[i])));
            throw ReadError(name, static_cast<uint64_t>(before + o.line), o.message);
        }
    }
    return true;
}

// The pieces joined: the mesh (welded when `weld`: across the pieces of a
// parallel read, each welded on its own first, see read_binary_stl; the
// whole soup of a serial one), and the notes in the serial reader's order.
void join_stl(std::vector<StlPiece>& pieces, LoadedMesh& out, bool weld) {
    std::string_view open_name;  // the solid open at the start of the piece
    std::size_t solids = 0;
    for (const StlPiece& p : pieces) {
        for (const StlPiece::Event& e : p.events) {
            if (!e.name_check) text::add_note(out, e.text);
            else if (e.text != open_name) text::add_note(out, "stl-endsolid-name-mismatch");
        }
        if (p.named) open_name = p.last_name;
        solids += p.solids;
        out.facet_normals_against_winding += p.normals_against;
    }
    if (solids > 1) out.notes.push_back("stl-multiple-solids(" + std::to_string(solids) + ")");
    std::vector<Mesh> parts;
    parts.reserve(pieces.size());
    for (StlPiece& p : pieces) {
        out.vertices_in_file += p.vertices_read;
        parts.push_back(std::move(p.mesh));
    }
    chunks::concat(parts, out.mesh, true);
    if (weld) weld_in_place(out.mesh);
}

LoadedMesh read_ascii_stl(Bytes data, const std::string& name, const ParseOptions& options) {
    const std::string_view s = text::as_text(data);
    LoadedMesh out;
    out.format = Format::stl;
    out.encoding = "ascii";
    ParseReport& report = thread_parse_report();
    if (chunks::use_parallel(options, s.size())) {
        const std::vector<std::size_t> starts = chunks::split(s, options.chunk_bytes, stl_chunk_start);
        const std::size_t n = starts.size() - 1;
        if (n > 1) {
            std::vector<StlPiece> pieces;
            pieces.reserve(n);
            for (std::size_t i = 0; i < n; ++i)
                pieces.emplace_back(s.substr(starts[i], starts[i + 1] - starts[i]), s.data() + s.size(), i == 0,
                                    i + 1 == n);
            report.chunks = n;
            chunks::for_each(n, [&](std::size_t i) {
                StlPiece& p = pieces[i];
                p.run();
                // Welded while its positions are in cache (see read_binary_stl).
                if (options.weld_stl && p.outcome.status == chunks::Outcome::Status::ok) weld_in_place(p.mesh);
            });
            if (pieces_agree(pieces, s, starts, name)) {
                join_stl(pieces, out, options.weld_stl);
                return out;
            }
            report.serial_fallback = true;
        }
    }
    std::vector<StlPiece> whole;
    whole.emplace_back(s, s.data() + s.size(), true, true);
    whole[0].run();
    const chunks::Outcome& o = whole[0].outcome;
    if (o.status != chunks::Outcome::Status::ok) throw ReadError(name, static_cast<uint64_t>(o.line), o.message);
    join_stl(whole, out, options.weld_stl);
    return out;
}

}  // namespace

LoadedMesh read_stl(Bytes data, const std::string& name) { return read_stl(data, name, thread_parse_options()); }

LoadedMesh read_stl(Bytes data, const std::string& name, const ParseOptions& options) {
    thread_parse_report() = {};
    const std::size_t size = data.size();
    if (size >= 84) {
        const uint64_t n = load_u32_le(data.data() + 80);
        if (84 + 50 * n == size) return read_binary_stl(data, name, static_cast<uint32_t>(n), options);
    }
    const std::string_view s = text::as_text(data);
    // ASCII when it starts with "solid" (after blanks) and has no NUL byte
    // in what would be a binary header (a binary file whose header says
    // "solid" but whose size is wrong gets the size error below).
    std::size_t lead = 0;
    while (lead < s.size() && text::is_space(s[lead])) ++lead;
    if (starts_with_solid(s.substr(lead)) && s.substr(0, 84).find('\0') == std::string_view::npos)
        return read_ascii_stl(data, name, options);
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
