// Parallel parsing of the text formats (ASCII STL, OBJ, OFF, ASCII PLY);
// binary PLY and binary STL use the options and the report too (see
// ply.cpp and stl.cpp).
//
// The buffer is cut into chunks of about ParseOptions::chunk_bytes at line
// starts that a chunk can recognise on its own; one oneTBB task parses each
// chunk into its own arrays and the pieces are joined in file order.
//
// The contract: for every input, valid or not, the parallel path gives what
// the serial reader gives -- the same positions (bit for bit), the same
// faces in the same order, the same notes in the same order, and for bad
// input the same ReadError (file, 1-based line, message). How:
//   * a chunk runs the serial grammar; what depends on earlier chunks (the
//     number of vertices or records before it, the name of the open STL
//     solid) comes from a cheap first pass over every chunk or is resolved
//     when the pieces are joined;
//   * a chunk that meets something it cannot decide alone -- a record that
//     runs past its chunk, a line that does not hold exactly one record --
//     reports "irregular", and the whole input is then read serially;
//   * an error is kept with its chunk-relative line. The first chunk (in
//     file order) that did not parse cleanly decides: if it failed, every
//     chunk before it parsed cleanly, so the serial reader would have
//     stopped at the same place with the same message; its line is made
//     global by counting the line ends before the chunk. If it was
//     irregular, the serial reader runs.
// Line ends are those of text::Cursor: "\n", "\r\n" or a lone "\r".
//
// Where a chunk may start, per format (the reader files say more):
//   ASCII STL   a line whose first token is 'facet' or 'endsolid'
//   OBJ         a line after one that does not end with '\' (a statement)
//   OFF, PLY    any line of the body (the header is read serially)
// Inputs below ParseOptions::min_parallel_bytes are read serially.
//
// The options and the report (ParseOptions, ParseReport) are public:
// polyvol/parse_options.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "polyvol/io.hpp"
#include "polyvol/parse_options.hpp"

namespace polyvol::io {

// The text readers with explicit options (readers.hpp's overloads use
// thread_parse_options()). read_stl still reads binary STL by the size rule.
LoadedMesh read_stl(std::span<const std::byte> data, const std::string& name, const ParseOptions& options);
LoadedMesh read_obj(std::span<const std::byte> data, const std::string& name, const ParseOptions& options);
LoadedMesh read_off(std::span<const std::byte> data, const std::string& name, const ParseOptions& options);
LoadedMesh read_ply(std::span<const std::byte> data, const std::string& name, const ParseOptions& options);

namespace chunks {

// Whether an input of `bytes` bytes goes through the parallel path.
inline bool use_parallel(const ParseOptions& o, std::size_t bytes) {
    return o.parallel && bytes >= o.min_parallel_bytes && bytes > 0;
}

// Where a chunk may start: `pos` is a line start of `text` (pos > 0).
using AcceptFn = bool (*)(std::string_view text, std::size_t pos);

// Chunk boundaries: 0, then line starts at least min(target, size / 8)
// bytes after the previous boundary for which accept holds, then
// text.size(). Chunk i is [result[i], result[i+1]).
std::vector<std::size_t> split(std::string_view text, std::size_t target, AcceptFn accept);

// The bytes per chunk for an input of `bytes` bytes (see ParseOptions).
inline std::size_t chunk_size(std::size_t target, std::size_t bytes) {
    const std::size_t eighth = bytes / 8;
    const std::size_t t = target < eighth ? target : eighth;
    return t > 0 ? t : 1;
}

// The start of the line after the one holding text[p] (text.size() if none).
std::size_t next_line_start(std::string_view text, std::size_t p);

// Line ends in text ("\r\n" counts once). When text ends at a line start,
// this is the number of lines it holds.
uint64_t count_line_ends(std::string_view text);

// Line ends, and lines that hold a token (not only blanks, and when
// `comment` is not '\0', not only blanks then a comment).
struct LineCounts {
    uint64_t line_ends = 0;
    uint64_t data_lines = 0;
};
LineCounts count_lines(std::string_view text, char comment);

// count_lines for the usual body: no '\r', and every line starts with a
// token character (no empty, blank-led or comment line). Then every line
// is a data line and only the '\n' need counting, a vector at a time
// (io/line_scan.cpp). Returns false, with c unspecified, when the text is
// not of that kind.
bool count_plain_lines(std::string_view text, char comment, LineCounts& c);

// How a chunk went. line is relative to the chunk (1 = its first line) and
// may be 0 or negative when the error is at a position before the chunk.
struct Outcome {
    enum class Status { ok, error, irregular };
    Status status = Status::ok;
    int64_t line = 0;
    std::string message;

    void fail(int64_t at, std::string what) {
        status = Status::error;
        line = at;
        message = std::move(what);
    }
};

// Calls f(i) for i in [0, n) on oneTBB's threads.
void for_each(std::size_t n, const std::function<void(std::size_t)>& f);

// A body of one record per line (OFF, ASCII PLY: the header read serially)
// cut at line starts, any line start a chunk may begin at, with the line
// counts of each chunk from a first parallel pass: the data lines before a
// chunk number its first record, its line ends make its errors' lines global.
struct LineChunks {
    std::vector<std::size_t> starts;  // chunk i is [starts[i], starts[i + 1]) of the body
    std::vector<LineCounts> counts;   // per chunk
    uint64_t data_lines = 0;          // of the whole body

    std::size_t size() const { return counts.size(); }
    std::string_view chunk(std::string_view body, std::size_t i) const {
        return body.substr(starts[i], starts[i + 1] - starts[i]);
    }
};

// Cuts body into chunks of about `target` bytes (split) and counts the lines
// of each (count_lines with `comment`). Returns no chunks when there would be
// fewer than two: the body is then read serially. Otherwise the thread's
// ParseReport records the chunks and a serial fallback, which
// line_pieces_agree clears once the pieces decide.
LineChunks split_line_body(std::string_view body, std::size_t target, char comment);

// Whether the pieces parsed from the chunks of a LineChunks (each with an
// Outcome `outcome`) stand for the serial reading: false when one was
// irregular (the body is then read serially); the serial reader's ReadError
// for the first that failed, its line made global from first_line (the line
// of the body's first byte) and the line ends of the chunks before it; true
// when every piece parsed cleanly.
template <class Piece>
bool line_pieces_agree(const std::vector<Piece>& pieces, const LineChunks& chunks, uint64_t first_line,
                       const std::string& name) {
    ParseReport& report = thread_parse_report();
    uint64_t line = first_line;  // the line of the chunk's start
    for (std::size_t i = 0; i < pieces.size(); ++i) {
        const Outcome& o = pieces[i].outcome;
        if (o.status == Outcome::Status::irregular) return false;
        if (o.status == Outcome::Status::error) {
            report.serial_fallback = false;
            throw ReadError(name, static_cast<uint64_t>(static_cast<int64_t>(line) + o.line - 1), o.message);
        }
        line += chunks.counts[i].line_ends;
    }
    report.serial_fallback = false;
    return true;
}

// Appends the parts in order to out: positions concatenated; faces
// concatenated, their indices raised by the number of vertices before the
// part when shift_indices (parts numbered their vertices from 0), and
// compressed rows built exactly as Mesh::add_face would (empty while every
// face is a triangle). The parts are left empty.
void concat(std::vector<Mesh>& parts, Mesh& out, bool shift_indices);

// Adds a note once, keeping the order of first occurrence.
void note_once(std::vector<std::string>& notes, std::string note);

}  // namespace chunks
}  // namespace polyvol::io
