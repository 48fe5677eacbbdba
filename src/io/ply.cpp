// PLY reader: ascii, binary_little_endian, binary_big_endian.
//
// Header (one statement a line, "\n" or "\r\n"):
//   ply
//   format ascii|binary_little_endian|binary_big_endian 1.0
//   comment ... / obj_info ...
//   element NAME COUNT
//   property TYPE NAME                     scalar
//   property list COUNT_TYPE TYPE NAME     list
//   end_header
// Types: char uchar short ushort int uint float double, or int8 uint8
// int16 uint16 int32 uint32 float32 float64. Lines the header grammar does
// not know are skipped (noted).
//
// Positions are x, y, z of the "vertex" element, of any scalar type, widened
// to double (ASCII values are parsed as doubles whatever the declared type).
// Faces are the "vertex_indices" (or "vertex_index") list of the "face"
// element. Every other element and property, lists included, is skipped.
// Counts are checked against the bytes left before anything is allocated
// from them.
//
// Large bodies are read in parallel (chunks.hpp), with the serial reader's
// results and errors:
//   * ascii: chunks of lines; a first pass counts each chunk's lines that
//     hold a token, so a chunk knows which row of which element it starts
//     at. This needs one row per line (PLY lets rows share or span lines):
//     a chunk meeting anything else is irregular and the file is read
//     serially (PlyChunk).
//   * binary: an element whose rows all have the layout of its first row
//     (lists as long as the first row's: faces of one size) is cut into row
//     ranges; other elements are read serially (parallel_binary_element).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "io/chunks.hpp"
#include "io/readers.hpp"
#include "io/text.hpp"

namespace polyvol::io {

namespace {

using text::found;

enum class Type : uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };

bool parse_type(std::string_view s, Type& t) {
    static constexpr struct {
        std::string_view name;
        Type type;
    } names[] = {{"char", Type::i8},    {"int8", Type::i8},     {"uchar", Type::u8},   {"uint8", Type::u8},
                 {"short", Type::i16},  {"int16", Type::i16},   {"ushort", Type::u16}, {"uint16", Type::u16},
                 {"int", Type::i32},    {"int32", Type::i32},   {"uint", Type::u32},   {"uint32", Type::u32},
                 {"float", Type::f32},  {"float32", Type::f32}, {"double", Type::f64}, {"float64", Type::f64}};
    for (const auto& n : names) {
        if (n.name == s) {
            t = n.type;
            return true;
        }
    }
    return false;
}

std::size_t type_size(Type t) {
    switch (t) {
        case Type::i8:
        case Type::u8: return 1;
        case Type::i16:
        case Type::u16: return 2;
        case Type::i32:
        case Type::u32:
        case Type::f32: return 4;
        case Type::f64: return 8;
    }
    return 1;
}

// A T stored at p in the given byte order (the size is a constant, so the
// compiler turns the reversal into one bswap).
template <class T>
T get(const std::byte* p, bool big_endian) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, p, sizeof(T));
    if (big_endian) {
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    }
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
}

// Loads a value of type t at p as a double; exact for every PLY type.
double load(const std::byte* p, Type t, bool big_endian) {
    switch (t) {
        case Type::i8: return get<int8_t>(p, big_endian);
        case Type::u8: return get<uint8_t>(p, big_endian);
        case Type::i16: return get<int16_t>(p, big_endian);
        case Type::u16: return get<uint16_t>(p, big_endian);
        case Type::i32: return get<int32_t>(p, big_endian);
        case Type::u32: return get<uint32_t>(p, big_endian);
        case Type::f32: return static_cast<double>(get<float>(p, big_endian));
        case Type::f64: return get<double>(p, big_endian);
    }
    return 0;
}

enum class Role : uint8_t { skip, x, y, z, indices };

struct Property {
    std::string_view name;
    bool is_list = false;
    Type count_type = Type::u8;
    Type type = Type::f32;
    Role role = Role::skip;
};

struct Element {
    std::string_view name;
    uint64_t count = 0;
    uint64_t line = 0;
    std::vector<Property> props;
};

enum class Encoding { ascii, binary_le, binary_be };

// The messages of the ascii body, shared by the serial reader and the chunks.
std::string rows_too_many(const Element& e, std::size_t remaining) {
    return "element '" + std::string(e.name) + "' declares " + std::to_string(e.count) + " rows but only " +
           std::to_string(remaining) + " bytes follow";
}
std::string bad_value_message(std::string_view t, const Element& e, uint64_t row, const Property& p) {
    return "expected a number for property '" + std::string(p.name) + "' of " + std::string(e.name) + " " +
           std::to_string(row) + ", found " + found(t);
}
std::string list_too_long(int64_t k, std::size_t remaining) {
    return "list of " + std::to_string(k) + " values but only " + std::to_string(remaining) + " bytes follow";
}
std::string index_out_of_range(uint64_t row, int64_t i, uint64_t nv) {
    return "face " + std::to_string(row) + " index " + std::to_string(i) + " out of range (file has " +
           std::to_string(nv) + " vertices)";
}
std::string non_finite_vertex(uint64_t row) { return "non-finite coordinate in vertex " + std::to_string(row); }
std::string binary_index_message(uint64_t row, const std::string& index, uint64_t nv) {
    return "face " + std::to_string(row) + " index " + index + " out of range (file has " + std::to_string(nv) +
           " vertices)";
}

// An ascii vertex index: an integer, or a double with an integral value.
bool parse_index(std::string_view t, int64_t& i) {
    if (text::parse_int(t, i)) return true;
    double d = 0;
    if (!text::parse_double(t, d) || d != std::floor(d) || !(std::fabs(d) < 1e18)) return false;
    i = static_cast<int64_t>(d);
    return true;
}

// The ascii body's rows of one element: the elements that have properties
// and rows, in order; row r of the body (0-based, over these elements) is
// row r - first of the element.
struct RowSpan {
    const Element* e;
    uint64_t first;
};

// A chunk of the ascii body read on its own. Parallel reading needs the
// body to be line-regular: every line that holds a token holds exactly one
// row with all of its values and nothing else (the serial reader reads
// values across lines, so a row may run onto the next line or start on the
// line of the one before). A chunk that meets a row that is not alone on
// its line is irregular, and the whole file is read serially. The first
// pass counts each chunk's data lines, so a chunk knows its first row.
class PlyChunk {
public:
    struct Stop {};  // thrown once the outcome is decided

    // body: the whole body (rows before a chunk's start are found in it).
    PlyChunk(std::string_view body, std::size_t at, std::size_t size, std::size_t text_end_offset,
             uint64_t first_row, const std::vector<RowSpan>& spans, uint64_t rows, uint64_t nv, double* positions)
        : body_(body), at_(at), cur_(body.substr(at, size)), text_end_(text_end_offset), row_(first_row),
          spans_(spans), rows_(rows), nv_(nv), positions_(positions) {}

    void run() {
        try {
            std::size_t span = 0;
            while (span + 1 < spans_.size() && spans_[span + 1].first <= row_) ++span;
            for (; row_ < rows_; ++row_) {
                const std::size_t before = cur_.offset();
                const uint64_t line_before = cur_.line();
                const std::string_view t = cur_.next();
                if (t.empty()) break;
                while (span + 1 < spans_.size() && spans_[span + 1].first <= row_) ++span;
                const Element& e = *spans_[span].e;
                const uint64_t r = row_ - spans_[span].first;
                if (r == 0) element_start(e, before, line_before);
                read_row(e, r, t);
                if (row_ + 1 == rows_) {
                    // After the last row anything is trailing data.
                    if (!cur_.next_on_line().empty()) trailing = true;
                } else if (!cur_.next_on_line().empty()) {
                    irregular();
                }
            }
        } catch (const Stop&) {
        }
    }

    Mesh faces;             // the chunk's faces (global indices)
    bool trailing = false;  // a value after the last row on its line
    chunks::Outcome outcome;

private:
    // The serial reader checks an element's row count against the bytes
    // left where the element starts: just after the last value of the row
    // before (or at the body's start). That is `before` (a position in the
    // chunk) moved back over blanks and line ends, maybe into earlier chunks.
    void element_start(const Element& e, std::size_t before, uint64_t line_before) {
        const std::size_t from = at_ + before;
        std::size_t p = from;
        while (p > 0 && text::is_space(body_[p - 1])) --p;
        const std::size_t remaining = text_end_ - p;
        if (e.count > (remaining + 1) / (2 * e.props.size())) {
            const uint64_t back = chunks::count_line_ends(body_.substr(p, from - p));
            fail(static_cast<int64_t>(line_before) - static_cast<int64_t>(back), rows_too_many(e, remaining));
        }
    }

    void read_row(const Element& e, uint64_t r, std::string_view t) {
        for (std::size_t pi = 0; pi < e.props.size(); ++pi) {
            const Property& p = e.props[pi];
            if (pi > 0) t = on_line();
            if (!p.is_list) {
                double v = 0;
                if (!text::parse_double(t, v)) fail(bad_value_message(t, e, r, p));
                if (p.role != Role::skip) {
                    if (!std::isfinite(v)) fail("non-finite coordinate " + text::quote(t));
                    positions_[3 * r + static_cast<std::size_t>(p.role) - 1] = v;
                }
                continue;
            }
            int64_t k = 0;
            if (!text::parse_int(t, k) || k < 0) fail(bad_value_message(t, e, r, p));
            const std::size_t remaining = text_end_ - at_ - cur_.offset();
            if (static_cast<uint64_t>(k) > remaining / 2 + 1) fail(list_too_long(k, remaining));
            // The chunk's indices are fewer than half its bytes: reserve once
            // (pages never written cost nothing).
            if (p.role == Role::indices && faces.indices.capacity() == 0)
                faces.indices.reserve((cur_.remaining() + 2) / 2);
            face_.clear();
            for (int64_t j = 0; j < k; ++j) {
                t = on_line();
                if (p.role == Role::indices) {
                    int64_t i = 0;
                    if (!parse_index(t, i)) fail(bad_value_message(t, e, r, p));
                    if (i < 0 || static_cast<uint64_t>(i) >= nv_) fail(index_out_of_range(r, i, nv_));
                    face_.push_back(static_cast<uint32_t>(i));
                } else {
                    double d = 0;
                    if (!text::parse_double(t, d)) fail(bad_value_message(t, e, r, p));
                }
            }
            if (p.role == Role::indices) {
                if (face_.size() == 3) faces.add_triangle(face_[0], face_[1], face_[2]);
                else faces.add_face(face_);
            }
        }
    }

    // The next value of the row: the serial reader would look on the next
    // line when this one has none.
    std::string_view on_line() {
        const std::string_view t = cur_.next_on_line();
        if (t.empty()) irregular();
        return t;
    }

    [[noreturn]] void irregular() {
        outcome.status = chunks::Outcome::Status::irregular;
        throw Stop{};
    }
    [[noreturn]] void fail(std::string message) { fail(static_cast<int64_t>(cur_.line()), std::move(message)); }
    [[noreturn]] void fail(int64_t line, std::string message) {
        outcome.fail(line, std::move(message));
        throw Stop{};
    }

    std::string_view body_;
    std::size_t at_;          // the chunk's offset in the body
    text::Cursor cur_;
    std::size_t text_end_;    // the body's size: remaining = text_end_ - offset in the body
    uint64_t row_;
    const std::vector<RowSpan>& spans_;
    uint64_t rows_;
    uint64_t nv_;
    double* positions_;
    std::vector<uint32_t> face_;
};

class PlyReader {
public:
    PlyReader(Bytes data, const std::string& name, const ParseOptions& options)
        : data_(data), s_(text::as_text(data)), name_(name), options_(options) {}

    LoadedMesh read() {
        out_.format = Format::ply;
        header();
        if (encoding_ == Encoding::ascii) {
            out_.encoding = "ascii";
            ascii_body();
        } else {
            out_.encoding = encoding_ == Encoding::binary_le ? "binary_le" : "binary_be";
            binary_body();
        }
        return std::move(out_);
    }

private:
    // ---- header ---------------------------------------------------------
    void header() {
        std::size_t pos = 0;
        uint64_t line_no = 0;
        std::string_view eol_seq;  // the first line's line end, used after end_header
        bool have_format = false;
        bool ended = false;
        while (pos < s_.size() && !ended) {
            std::size_t eol = pos;
            while (eol < s_.size() && !text::is_eol(s_[eol])) ++eol;
            const std::string_view line = s_.substr(pos, eol - pos);
            std::size_t next = eol;
            if (next < s_.size()) {
                if (s_[next] == '\r' && next + 1 < s_.size() && s_[next + 1] == '\n') next += 2;
                else next += 1;
            }
            ++line_no;
            line_ = line_no;
            text::Cursor tokens(line);
            const std::string_view kw = tokens.next();
            if (line_no == 1) {
                if (kw != "ply" || !tokens.next().empty())
                    throw ReadError::whole_file(name_, "not a PLY file (expected 'ply' on the first line)");
                eol_seq = s_.substr(eol, next - eol);
            } else if (kw == "format") {
                const std::string_view f = tokens.next();
                if (f == "ascii") encoding_ = Encoding::ascii;
                else if (f == "binary_little_endian") encoding_ = Encoding::binary_le;
                else if (f == "binary_big_endian") encoding_ = Encoding::binary_be;
                else
                    fail_line("unknown PLY format " + found(f) +
                              " (expected ascii, binary_little_endian or binary_big_endian)");
                have_format = true;
            } else if (kw == "comment" || kw == "obj_info" || kw.empty()) {
            } else if (kw == "element") {
                Element e;
                e.name = tokens.next();
                const std::string_view c = tokens.next();
                int64_t n = 0;
                if (e.name.empty() || !text::parse_int(c, n) || n < 0)
                    fail_line("expected 'element NAME COUNT', found a count of " + found(c));
                e.count = static_cast<uint64_t>(n);
                e.line = line_no;
                elements_.push_back(std::move(e));
            } else if (kw == "property") {
                if (elements_.empty()) fail_line("'property' before any 'element'");
                Property p;
                std::string_view t = tokens.next();
                if (t == "list") {
                    p.is_list = true;
                    const std::string_view ct = tokens.next();
                    if (!parse_type(ct, p.count_type)) fail_line("unknown list count type " + found(ct));
                    t = tokens.next();
                }
                if (!parse_type(t, p.type)) fail_line("unknown property type " + found(t));
                p.name = tokens.next();
                if (p.name.empty()) fail_line("expected a property name");
                elements_.back().props.push_back(p);
            } else if (kw == "end_header") {
                ended = true;
                // The body starts after this line's end, read with the
                // convention of the first line (a binary body may start with
                // a byte that looks like a line end).
                body_ = eol;
                if (s_.substr(eol, eol_seq.size()) == eol_seq) body_ = eol + eol_seq.size();
                else body_ = next;
            } else {
                text::add_note(out_, "ply-unknown-header-line-ignored");
            }
            pos = next;
        }
        if (!ended) throw ReadError(name_, line_no, "expected 'end_header', found end of file");
        if (!have_format) throw ReadError(name_, line_no, "missing 'format' line in the PLY header");
        header_lines_ = line_no;
        roles();
    }

    void roles() {
        std::string others;
        for (Element& e : elements_) {
            if (e.name == "vertex" && vertex_ == nullptr) {
                vertex_ = &e;
                for (Property& p : e.props) {
                    if (p.name == "x") p.role = Role::x;
                    else if (p.name == "y") p.role = Role::y;
                    else if (p.name == "z") p.role = Role::z;
                    if (p.role != Role::skip && p.is_list) fail_at(e.line, "vertex property '" + std::string(p.name) + "' is a list");
                    if (p.role != Role::skip && p.type == Type::f64) text::add_note(out_, "ply-double-coordinates");
                }
                for (const char* c : {"x", "y", "z"}) {
                    bool found_it = false;
                    for (const Property& p : e.props) found_it = found_it || p.name == c;
                    if (!found_it) fail_at(e.line, std::string("element 'vertex' has no property '") + c + "'");
                }
            } else if (e.name == "face" && face_ == nullptr) {
                face_ = &e;
                Property* list = nullptr;
                for (Property& p : e.props)
                    if (p.is_list && p.name == "vertex_indices" && list == nullptr) list = &p;
                if (list == nullptr) {
                    for (Property& p : e.props)
                        if (p.is_list && p.name == "vertex_index" && list == nullptr) list = &p;
                    if (list != nullptr) text::add_note(out_, "ply-vertex_index-name");
                }
                if (list == nullptr) fail_at(e.line, "element 'face' has no list property 'vertex_indices'");
                list->role = Role::indices;
            } else {
                if (!others.empty()) others += ',';
                others += e.name;
            }
        }
        if (vertex_ == nullptr) fail_at(header_lines_, "no 'vertex' element in the PLY header");
        if (vertex_->count > UINT32_MAX) fail_at(vertex_->line, "too many vertices");
        if (face_ == nullptr) text::add_note(out_, "ply-no-faces");
        if (!others.empty()) out_.notes.push_back("ply-other-elements(" + others + ")");
    }

    // ---- binary body ----------------------------------------------------
    void binary_body() {
        const bool be = encoding_ == Encoding::binary_be;
        std::size_t pos = body_;
        const std::size_t size = data_.size();
        const std::byte* base = data_.data();
        Mesh& m = out_.mesh;
        const uint64_t nv = vertex_->count;
        for (const Element& e : elements_) {
            std::size_t min_row = 0;
            for (const Property& p : e.props) min_row += type_size(p.is_list ? p.count_type : p.type);
            if (min_row == 0 || e.count == 0) continue;
            if (e.count > (size - pos) / min_row)
                throw ReadError::at_byte(name_, pos,
                                         "truncated PLY body: element '" + std::string(e.name) + "' declares " +
                                             std::to_string(e.count) + " rows of at least " +
                                             std::to_string(min_row) + " bytes but only " +
                                             std::to_string(size - pos) + " bytes remain");
            const bool is_vertex = &e == vertex_;
            const bool is_face = &e == face_;
            if (is_vertex) m.positions.resize(3 * e.count);
            if (parallel_binary_element(e, pos)) continue;
            if (is_face) m.indices.reserve(std::min<uint64_t>(3 * e.count, (size - pos) / 2));
            for (uint64_t r = 0; r < e.count; ++r) {
                for (const Property& p : e.props) {
                    if (!p.is_list) {
                        const std::size_t n = type_size(p.type);
                        if (size - pos < n) truncated(pos, e, r, p);
                        if (p.role != Role::skip) {
                            const double v = load(base + pos, p.type, be);
                            if (!std::isfinite(v)) throw ReadError::at_byte(name_, pos, non_finite_vertex(r));
                            m.positions[3 * r + static_cast<std::size_t>(p.role) - 1] = v;
                        }
                        pos += n;
                        continue;
                    }
                    const std::size_t cn = type_size(p.count_type);
                    if (size - pos < cn) truncated(pos, e, r, p);
                    const double cd = load(base + pos, p.count_type, be);
                    if (!(cd >= 0) || cd != std::floor(cd) || cd > 4294967295.0)
                        throw ReadError::at_byte(name_, pos, "bad list length in property '" + std::string(p.name) + "'");
                    const auto k = static_cast<std::size_t>(cd);
                    const std::size_t list_pos = pos;
                    pos += cn;
                    const std::size_t n = type_size(p.type);
                    if (k > (size - pos) / n) truncated(list_pos, e, r, p);
                    if (p.role == Role::indices) {
                        face_buf_.clear();
                        for (std::size_t j = 0; j < k; ++j) {
                            const double iv = load(base + pos + j * n, p.type, be);
                            if (!(iv >= 0 && iv < static_cast<double>(nv)) || iv != std::floor(iv))
                                throw ReadError::at_byte(name_, pos + j * n, binary_index_message(r, index_text(iv), nv));
                            face_buf_.push_back(static_cast<uint32_t>(iv));
                        }
                        add_face();
                    }
                    pos += k * n;
                }
            }
        }
        if (pos < size) text::add_note(out_, "ply-trailing-data");
    }

    // A binary element read in row ranges on several threads, when every row
    // has the layout of its first: scalar properties, and list properties as
    // long as in the first row (faces of one size, the usual case). Row r
    // then starts at pos + r * row_bytes. A range that finds a list of
    // another length is irregular: the element is then read serially (its
    // faces dropped first). Otherwise the first range that failed has the
    // error the serial loop meets first. Returns false, having changed
    // nothing that the serial loop does not redo, when the element is read
    // serially; else advances pos past it.
    bool parallel_binary_element(const Element& e, std::size_t& pos) {
        const std::size_t size = data_.size();
        if (!chunks::use_parallel(options_, size - pos) || e.count < 2) return false;
        const bool be = encoding_ == Encoding::binary_be;
        const std::byte* base = data_.data();
        // The layout of row 0, checked as the serial loop checks it; row_bytes
        // never exceeds the bytes left, so no difference below wraps around.
        const std::size_t left = size - pos;
        std::vector<std::size_t> lens;  // per list property
        std::size_t row_bytes = 0;
        std::size_t face_size = 0;
        for (const Property& p : e.props) {
            if (!p.is_list) {
                row_bytes += type_size(p.type);
                if (row_bytes > left) return false;
                continue;
            }
            const std::size_t cn = type_size(p.count_type), n = type_size(p.type);
            if (left - row_bytes < cn) return false;
            const double cd = load(base + pos + row_bytes, p.count_type, be);
            if (!(cd >= 0) || cd != std::floor(cd) || cd > 4294967295.0) return false;
            const auto k = static_cast<std::size_t>(cd);
            row_bytes += cn;
            if (k > (left - row_bytes) / n) return false;
            row_bytes += k * n;
            lens.push_back(k);
            if (p.role == Role::indices) face_size = k;
        }
        if (row_bytes == 0 || e.count > (size - pos) / row_bytes) return false;  // not all rows of this layout fit

        const bool is_face = &e == face_;
        Mesh& m = out_.mesh;
        if (is_face) {
            // What add_face / add_triangle build for count faces of one size.
            m.indices.resize(static_cast<std::size_t>(e.count) * face_size);
            if (face_size != 3) {
                m.face_offsets.resize(static_cast<std::size_t>(e.count) + 1);
                for (std::size_t f = 0; f <= e.count; ++f) m.face_offsets[f] = static_cast<uint32_t>(f * face_size);
            }
        }
        const uint64_t rows_per =
            std::max<uint64_t>(1, chunks::chunk_size(options_.chunk_bytes, size - pos) / row_bytes);
        const std::size_t ranges = static_cast<std::size_t>((e.count + rows_per - 1) / rows_per);
        struct RangeOutcome {
            chunks::Outcome::Status status = chunks::Outcome::Status::ok;
            std::size_t offset = 0;
            std::string message;
        };
        std::vector<RangeOutcome> outcomes(ranges);
        const uint64_t nv = vertex_->count;
        const std::size_t start = pos;
        chunks::for_each(ranges, [&](std::size_t i) {
            RangeOutcome& o = outcomes[i];
            const uint64_t r0 = i * rows_per, r1 = std::min<uint64_t>(e.count, r0 + rows_per);
            std::size_t at = start + static_cast<std::size_t>(r0) * row_bytes;
            for (uint64_t r = r0; r < r1; ++r) {
                std::size_t li = 0;
                for (const Property& p : e.props) {
                    if (!p.is_list) {
                        if (p.role != Role::skip) {
                            const double v = load(base + at, p.type, be);
                            if (!std::isfinite(v)) {
                                o = {chunks::Outcome::Status::error, at, non_finite_vertex(r)};
                                return;
                            }
                            m.positions[3 * r + static_cast<std::size_t>(p.role) - 1] = v;
                        }
                        at += type_size(p.type);
                        continue;
                    }
                    const std::size_t k = lens[li++];
                    if (load(base + at, p.count_type, be) != static_cast<double>(k)) {
                        o.status = chunks::Outcome::Status::irregular;
                        return;
                    }
                    at += type_size(p.count_type);
                    const std::size_t n = type_size(p.type);
                    if (p.role == Role::indices) {
                        uint32_t* out = m.indices.data() + static_cast<std::size_t>(r) * k;
                        for (std::size_t j = 0; j < k; ++j) {
                            const double iv = load(base + at + j * n, p.type, be);
                            if (!(iv >= 0 && iv < static_cast<double>(nv)) || iv != std::floor(iv)) {
                                o = {chunks::Outcome::Status::error, at + j * n,
                                     binary_index_message(r, index_text(iv), nv)};
                                return;
                            }
                            out[j] = static_cast<uint32_t>(iv);
                        }
                    }
                    at += k * n;
                }
            }
        });
        ParseReport& report = thread_parse_report();
        report.chunks = std::max(report.chunks, ranges);
        for (const RangeOutcome& o : outcomes) {
            if (o.status == chunks::Outcome::Status::error) throw ReadError::at_byte(name_, o.offset, o.message);
            if (o.status == chunks::Outcome::Status::irregular) {
                report.serial_fallback = true;
                if (is_face) {
                    m.indices.clear();
                    m.face_offsets.clear();
                }
                return false;
            }
        }
        pos += static_cast<std::size_t>(e.count) * row_bytes;
        return true;
    }

    [[noreturn]] void truncated(std::size_t pos, const Element& e, uint64_t row, const Property& p) const {
        throw ReadError::at_byte(name_, pos,
                                 "truncated PLY body: expected property '" + std::string(p.name) + "' of " +
                                     std::string(e.name) + " " + std::to_string(row) + ", found end of file");
    }

    // ---- ascii body -----------------------------------------------------
    // The ascii body read in chunks: see PlyChunk. Returns false, having
    // changed nothing, when the body is to be read serially: small, without
    // rows, with fewer data lines than rows, or not line-regular.
    bool parallel_ascii_body() {
        const std::string_view body = s_.substr(body_);
        if (!chunks::use_parallel(options_, body.size())) return false;
        const chunks::LineChunks lines = chunks::split_line_body(body, options_.chunk_bytes, '\0');
        const std::size_t n = lines.size();
        if (n == 0) return false;
        std::vector<RowSpan> spans;
        uint64_t rows = 0;
        for (const Element& e : elements_) {
            if (e.props.empty() || e.count == 0) continue;
            if (e.count > lines.data_lines - rows) return false;  // some row spans lines, or the file is short
            spans.push_back({&e, rows});
            rows += e.count;
        }
        if (rows == 0) return false;

        const uint64_t nv = vertex_->count;  // <= rows <= data lines
        std::vector<double> positions(3 * static_cast<std::size_t>(vertex_->props.empty() ? 0 : nv));
        std::vector<PlyChunk> pieces;
        pieces.reserve(n);
        uint64_t first = 0;
        for (std::size_t i = 0; i < n; ++i) {
            pieces.emplace_back(body, lines.starts[i], lines.starts[i + 1] - lines.starts[i], body.size(), first, spans,
                                rows, nv, positions.data());
            first += lines.counts[i].data_lines;
        }
        chunks::for_each(n, [&](std::size_t i) { pieces[i].run(); });
        if (!chunks::line_pieces_agree(pieces, lines, header_lines_ + 1, name_)) return false;
        bool trailing = lines.data_lines > rows;
        std::vector<Mesh> faces;
        faces.reserve(n);
        for (PlyChunk& c : pieces) {
            trailing = trailing || c.trailing;
            faces.push_back(std::move(c.faces));
        }
        out_.mesh.positions = std::move(positions);
        chunks::concat(faces, out_.mesh, false);
        if (trailing) text::add_note(out_, "ply-trailing-data");
        return true;
    }

    void ascii_body() {
        if (parallel_ascii_body()) return;
        text::Cursor cur(s_.substr(body_));
        Mesh& m = out_.mesh;
        const uint64_t nv = vertex_->count;
        for (const Element& e : elements_) {
            if (e.props.empty() || e.count == 0) continue;
            // Each value takes at least 2 bytes (a digit and a separator).
            if (e.count > (cur.remaining() + 1) / (2 * e.props.size())) fail_text(cur, rows_too_many(e, cur.remaining()));
            const bool is_vertex = &e == vertex_;
            const bool is_face = &e == face_;
            if (is_vertex) m.positions.resize(3 * e.count);
            if (is_face) m.indices.reserve(std::min<uint64_t>(3 * e.count, cur.remaining() / 2));
            for (uint64_t r = 0; r < e.count; ++r) {
                for (const Property& p : e.props) {
                    std::string_view t = cur.next();
                    if (!p.is_list) {
                        double v = 0;
                        if (!text::parse_double(t, v)) bad_value(cur, t, e, r, p);
                        if (p.role != Role::skip) {
                            if (!std::isfinite(v)) fail_text(cur, "non-finite coordinate " + text::quote(t));
                            m.positions[3 * r + static_cast<std::size_t>(p.role) - 1] = v;
                        }
                        continue;
                    }
                    int64_t k = 0;
                    if (!text::parse_int(t, k) || k < 0) bad_value(cur, t, e, r, p);
                    if (static_cast<uint64_t>(k) > cur.remaining() / 2 + 1) fail_text(cur, list_too_long(k, cur.remaining()));
                    face_buf_.clear();
                    for (int64_t j = 0; j < k; ++j) {
                        t = cur.next();
                        if (p.role == Role::indices) {
                            int64_t i = 0;
                            if (!parse_index(t, i)) bad_value(cur, t, e, r, p);
                            if (i < 0 || static_cast<uint64_t>(i) >= nv) fail_text(cur, index_out_of_range(r, i, nv));
                            face_buf_.push_back(static_cast<uint32_t>(i));
                        } else {
                            double d = 0;
                            if (!text::parse_double(t, d)) bad_value(cur, t, e, r, p);
                        }
                    }
                    if (p.role == Role::indices) add_face();
                }
            }
        }
        if (!cur.next().empty()) text::add_note(out_, "ply-trailing-data");
    }

    [[noreturn]] void bad_value(const text::Cursor& cur, std::string_view t, const Element& e, uint64_t row,
                                const Property& p) const {
        fail_text(cur, bad_value_message(t, e, row, p));
    }

    [[noreturn]] void fail_text(const text::Cursor& cur, const std::string& message) const {
        // The body starts on the line after end_header.
        throw ReadError(name_, header_lines_ + cur.line(), message);
    }

    void add_face() {
        if (face_buf_.size() == 3) out_.mesh.add_triangle(face_buf_[0], face_buf_[1], face_buf_[2]);
        else out_.mesh.add_face(face_buf_);
    }

    static std::string index_text(double v) {
        if (v == std::floor(v) && std::fabs(v) < 1e18) return std::to_string(static_cast<int64_t>(v));
        return std::to_string(v);
    }

    [[noreturn]] void fail_line(const std::string& message) const { throw ReadError(name_, line_, message); }
    [[noreturn]] void fail_at(uint64_t line, const std::string& message) const { throw ReadError(name_, line, message); }

    Bytes data_;
    std::string_view s_;
    const std::string& name_;
    const ParseOptions& options_;
    LoadedMesh out_;
    Encoding encoding_ = Encoding::ascii;
    std::vector<Element> elements_;
    const Element* vertex_ = nullptr;
    const Element* face_ = nullptr;
    std::size_t body_ = 0;
    uint64_t line_ = 0;
    uint64_t header_lines_ = 0;
    std::vector<uint32_t> face_buf_;
};

}  // namespace

LoadedMesh read_ply(Bytes data, const std::string& name) { return read_ply(data, name, thread_parse_options()); }

LoadedMesh read_ply(Bytes data, const std::string& name, const ParseOptions& options) {
    thread_parse_report() = {};
    return PlyReader(data, name, options).read();
}

}  // namespace polyvol::io
