// io/polymesh.cpp — read_polymesh (polyvol/cell_mesh_io.hpp): OpenFOAM's
// constant/polyMesh files.
//
// Each file is a FoamFile header dictionary (format, class, arch) and one
// list (faceCompactList: two, the offsets then the point labels):
//   ASCII   N ( item item ... )   or N{item} (every item equal), items being
//           labels, vectors "(x y z)" or faces "k(a b c ...)";
//   binary  N ( <N raw little-endian items> ), labels of 32 or 64 bits and
//           scalars of 64 or 32 bits as `arch` says ("LSB;label=32;scalar=64").
// Comments (// and /* */) may come anywhere whitespace may in ASCII.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/readers.hpp"
#include "io/text.hpp"
#include "polyvol/cell_mesh_io.hpp"

namespace polyvol {
namespace {

namespace fs = std::filesystem;

// One polyMesh file's bytes (gunzipped), with a cursor that knows its line.
class FoamFile {
public:
    FoamFile(std::vector<std::byte> bytes, std::string name) : bytes_(std::move(bytes)), name_(std::move(name)) {
        text_ = io::text::as_text(bytes_);
    }
    const std::string& name() const { return name_; }

    [[noreturn]] void fail(const std::string& what) const {
        if (in_binary_) throw ReadError::at_byte(name_, pos_, what);
        throw ReadError(name_, line_, what);
    }
    // A defect of the file as a whole, found after reading it.
    [[noreturn]] void fail_whole(const std::string& what) const { throw ReadError::whole_file(name_, what); }

    // Whitespace and comments.
    void skip() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_;
                ++pos_;
            } else if (io::text::is_space(c)) {
                ++pos_;
            } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
                const std::size_t end = text_.find("*/", pos_ + 2);
                if (end == std::string_view::npos) fail("a comment /* that is never closed");
                for (std::size_t i = pos_; i < end; ++i) line_ += text_[i] == '\n';
                pos_ = end + 2;
            } else {
                return;
            }
        }
    }
    bool at(char c) {
        skip();
        return pos_ < text_.size() && text_[pos_] == c;
    }
    void expect(char c, const char* what) {
        if (!at(c)) fail(std::string("expected '") + c + "' " + what);
        ++pos_;
    }
    // A word or number token (up to whitespace, ';', parentheses or braces).
    std::string_view token() {
        skip();
        const std::size_t start = pos_;
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (io::text::is_space(c) || c == ';' || c == '(' || c == ')' || c == '{' || c == '}') break;
            ++pos_;
        }
        return text_.substr(start, pos_ - start);
    }
    uint64_t count(const char* what) {
        const std::string_view t = token();
        uint64_t v = 0;
        if (t.empty() || t.size() > 19) fail(std::string("expected ") + what);
        for (const char c : t) {
            if (c < '0' || c > '9') fail(std::string("expected ") + what + ", found '" + std::string(t) + "'");
            v = 10 * v + static_cast<uint64_t>(c - '0');
        }
        return v;
    }
    double number(const char* what) {
        const std::string_view t = token();
        double v = 0;
        if (!io::text::parse_double(t, v) || !std::isfinite(v))
            fail(std::string("expected ") + what + ", found '" + std::string(t) + "'");
        return v;
    }

    // The header: FoamFile { key value; ... } — the values of format, class, arch.
    void header() {
        if (token() != "FoamFile") fail("expected the FoamFile header");
        expect('{', "after FoamFile");
        while (!at('}')) {
            const std::string key(token());
            if (key.empty()) fail("expected a header entry or '}'");
            skip();
            std::string value;
            if (pos_ < text_.size() && text_[pos_] == '"') {
                const std::size_t end = text_.find('"', pos_ + 1);
                if (end == std::string_view::npos) fail("a quoted header value that is never closed");
                value = std::string(text_.substr(pos_ + 1, end - pos_ - 1));
                pos_ = end + 1;
            } else {
                value = std::string(token());
            }
            expect(';', "after a header entry");
            if (key == "format") format_ = value;
            if (key == "class") class_ = value;
            if (key == "arch") arch_ = value;
        }
        ++pos_;
        if (format_ != "ascii" && format_ != "binary") fail("format is '" + format_ + "': expected ascii or binary");
        if (arch_.find("label=64") != std::string::npos) label_bytes_ = 8;
        if (arch_.find("scalar=32") != std::string::npos) scalar_bytes_ = 4;
        if (arch_.find("MSB") != std::string::npos) fail("big-endian (MSB) binary files are not read");
    }
    bool binary() const { return format_ == "binary"; }
    const std::string& list_class() const { return class_; }

    // The start of a list: its count, then '(' (or '{' for a uniform ASCII
    // list). Returns the count; sets uniform.
    uint64_t list_start(const char* what, bool& uniform) {
        skip();
        uniform = false;
        const uint64_t n = at('(') ? kUnknown : count(what);
        if (at('{') && !binary()) {
            ++pos_;
            uniform = true;
            return n;
        }
        expect('(', "to open the list");
        return n;
    }

    // A binary list body of n items of `size` bytes, then ')'.
    std::string_view raw(uint64_t n, std::size_t size) {
        in_binary_ = true;
        const std::size_t left = text_.size() - pos_;
        if (n > left / size) fail("the list claims " + std::to_string(n) + " items of " + std::to_string(size) +
                                  " bytes, more than the " + std::to_string(left) + " bytes left");
        const std::string_view body = text_.substr(pos_, n * size);
        pos_ += n * size;
        if (pos_ >= text_.size() || text_[pos_] != ')') fail("expected ')' after the binary list");
        ++pos_;
        in_binary_ = false;
        return body;
    }

    // A list of labels (each < limit), ASCII or binary.
    // At most max_items of them (a uniform list allocates from its count).
    std::vector<uint32_t> labels(const char* what, uint64_t limit, uint64_t max_items = kUnknown) {
        bool uniform = false;
        const uint64_t n = list_start("the number of labels", uniform);
        std::vector<uint32_t> out;
        auto check = [&](uint64_t v) {
            if (v >= limit) fail(std::string(what) + " " + std::to_string(v) + " is out of range");
            return static_cast<uint32_t>(v);
        };
        if (uniform) {
            const uint32_t v = check(count(what));
            expect('}', "to close the uniform list");
            if (n == kUnknown || n > max_items || n >= kNoCell)
                fail("a uniform list of " + (n == kUnknown ? std::string("no") : std::to_string(n)) +
                     " items: expected a count of at most " + std::to_string(std::min<uint64_t>(max_items, kNoCell - 1)));
            out.assign(n, v);
            return out;
        }
        if (binary()) {
            if (n == kUnknown) fail("a binary list needs a count");
            const std::string_view body = raw(n, label_bytes_);
            out.resize(n);
            for (uint64_t i = 0; i < n; ++i) {
                uint64_t v = 0;
                if (label_bytes_ == 4) {
                    int32_t x;
                    std::memcpy(&x, body.data() + 4 * i, 4);
                    if (x < 0) fail(std::string("a negative ") + what);
                    v = static_cast<uint64_t>(x);
                } else {
                    int64_t x;
                    std::memcpy(&x, body.data() + 8 * i, 8);
                    if (x < 0) fail(std::string("a negative ") + what);
                    v = static_cast<uint64_t>(x);
                }
                out[i] = check(v);
            }
            return out;
        }
        if (n != kUnknown && n > (text_.size() - pos_) / 2)
            fail("the list claims " + std::to_string(n) + " labels, more than the rest of the file holds");
        if (n != kUnknown) out.reserve(n);
        while (!at(')')) out.push_back(check(count(what)));
        ++pos_;
        if (n != kUnknown && out.size() != n)
            fail("the list holds " + std::to_string(out.size()) + " labels, its count says " + std::to_string(n));
        return out;
    }

    // A list of signed labels, |label| < limit (faceProcAddressing: ±(face + 1)).
    std::vector<int64_t> signed_labels(const char* what, uint64_t limit) {
        bool uniform = false;
        const uint64_t n = list_start("the number of labels", uniform);
        if (uniform) fail("a uniform list of " + std::string(what));
        std::vector<int64_t> out;
        auto check = [&](int64_t v) {
            if (v <= -static_cast<int64_t>(limit) || v >= static_cast<int64_t>(limit))
                fail(std::string(what) + " " + std::to_string(v) + " is out of range");
            return v;
        };
        if (binary()) {
            if (n == kUnknown) fail("a binary list needs a count");
            const std::string_view body = raw(n, label_bytes_);
            out.resize(n);
            for (uint64_t i = 0; i < n; ++i) {
                if (label_bytes_ == 4) {
                    int32_t x;
                    std::memcpy(&x, body.data() + 4 * i, 4);
                    out[i] = check(x);
                } else {
                    int64_t x;
                    std::memcpy(&x, body.data() + 8 * i, 8);
                    out[i] = check(x);
                }
            }
            return out;
        }
        if (n != kUnknown && n > (text_.size() - pos_) / 2)
            fail("the list claims " + std::to_string(n) + " labels, more than the rest of the file holds");
        while (!at(')')) {
            skip();
            const bool negative = pos_ < text_.size() && text_[pos_] == '-';
            if (negative) ++pos_;
            const auto v = static_cast<int64_t>(std::min<uint64_t>(count(what), limit));
            out.push_back(check(negative ? -v : v));
        }
        ++pos_;
        if (n != kUnknown && out.size() != n)
            fail("the list holds " + std::to_string(out.size()) + " labels, its count says " + std::to_string(n));
        return out;
    }

    std::vector<double> vectors() {
        bool uniform = false;
        const uint64_t n = list_start("the number of points", uniform);
        if (uniform) fail("a uniform list of points");
        std::vector<double> out;
        if (binary()) {
            if (n == kUnknown) fail("a binary list needs a count");
            const std::string_view body = raw(n, 3 * scalar_bytes_);
            out.resize(3 * n);
            for (uint64_t i = 0; i < 3 * n; ++i) {
                double v;
                if (scalar_bytes_ == 8) {
                    std::memcpy(&v, body.data() + 8 * i, 8);
                } else {
                    float f;
                    std::memcpy(&f, body.data() + 4 * i, 4);
                    v = f;
                }
                if (!std::isfinite(v)) {
                    pos_ = static_cast<std::size_t>(body.data() - text_.data()) + scalar_bytes_ * i;
                    in_binary_ = true;
                    fail("a coordinate that is not finite");
                }
                out[i] = v;
            }
            return out;
        }
        if (n != kUnknown && n > (text_.size() - pos_) / 8)
            fail("the list claims " + std::to_string(n) + " points, more than the rest of the file holds");
        if (n != kUnknown) out.reserve(3 * n);
        while (!at(')')) {
            expect('(', "to open a point");
            for (int k = 0; k < 3; ++k) out.push_back(number("a coordinate"));
            expect(')', "after a point's three coordinates");
        }
        ++pos_;
        if (n != kUnknown && out.size() != 3 * n)
            fail("the list holds " + std::to_string(out.size() / 3) + " points, its count says " + std::to_string(n));
        return out;
    }

    // faceList (ASCII: k(a b c ...) items) or faceCompactList (two label
    // lists: offsets, then the points), into offsets and points.
    void faces(uint64_t points, std::vector<uint32_t>& offsets, std::vector<uint32_t>& face_points) {
        if (class_ == "faceCompactList") {
            const std::size_t offsets_line = line_;
            offsets = labels("face offset", std::numeric_limits<uint32_t>::max());
            face_points = labels("point label", points);
            if (offsets.empty() || offsets.front() != 0) {
                line_ = offsets_line;
                fail("the face offsets must start with 0");
            }
            for (std::size_t f = 0; f + 1 < offsets.size(); ++f)
                if (offsets[f + 1] < offsets[f] + 3 || offsets[f + 1] > face_points.size())
                    fail("face " + std::to_string(f) + ": its offsets " + std::to_string(offsets[f]) + ".." +
                         std::to_string(offsets[f + 1]) + " do not give 3 or more of the " +
                         std::to_string(face_points.size()) + " point labels");
            if (offsets.back() != face_points.size())
                fail("the face offsets end at " + std::to_string(offsets.back()) + ", the point labels number " +
                     std::to_string(face_points.size()));
            return;
        }
        if (binary()) fail("a binary faceList: expected a faceCompactList");
        bool uniform = false;
        const uint64_t n = list_start("the number of faces", uniform);
        if (uniform) fail("a uniform list of faces");
        if (n != kUnknown && n > (text_.size() - pos_) / 8)
            fail("the list claims " + std::to_string(n) + " faces, more than the rest of the file holds");
        offsets.assign(1, 0);
        while (!at(')')) {
            const uint64_t k = count("a face's number of points");
            if (k < 3) fail("a face of " + std::to_string(k) + " points: expected 3 or more");
            expect('(', "to open a face");
            for (uint64_t i = 0; i < k; ++i) {
                const uint64_t v = count("a point label");
                if (v >= points)
                    fail("face " + std::to_string(offsets.size() - 1) + " names point " + std::to_string(v) +
                         ", but there are " + std::to_string(points) + " points");
                face_points.push_back(static_cast<uint32_t>(v));
            }
            expect(')', "after the face's point labels");
            offsets.push_back(static_cast<uint32_t>(face_points.size()));
        }
        ++pos_;
        if (n != kUnknown && offsets.size() - 1 != n)
            fail("the list holds " + std::to_string(offsets.size() - 1) + " faces, its count says " +
                 std::to_string(n));
    }

    // The boundary file's list: name { type T; ... } per patch.
    std::vector<FoamPatch> patches() {
        bool uniform = false;
        list_start("the number of patches", uniform);
        std::vector<FoamPatch> out;
        while (!at(')')) {
            FoamPatch p;
            p.name = std::string(token());
            if (p.name.empty()) fail("expected a patch name");
            skip();
            if (pos_ >= text_.size() || text_[pos_] != '{') fail("expected '{' after patch " + p.name);
            int depth = 0;
            const std::size_t open = pos_;
            for (; pos_ < text_.size(); ++pos_) {
                line_ += text_[pos_] == '\n';
                if (text_[pos_] == '{') ++depth;
                if (text_[pos_] == '}' && --depth == 0) break;
            }
            if (depth != 0) fail("patch " + p.name + ": '{' never closed");
            const std::string_view body = text_.substr(open, pos_ - open);
            ++pos_;
            std::size_t t = body.find("type");
            while (t != std::string_view::npos && t + 4 < body.size() && !io::text::is_space(body[t + 4]))
                t = body.find("type", t + 4);
            if (t == std::string_view::npos) fail("patch " + p.name + " has no type");
            const std::size_t end = body.find(';', t);
            p.type = std::string(io::text::trim(body.substr(t + 4, end - t - 4)));
            out.push_back(std::move(p));
        }
        return out;
    }

    // The cellLabels of zone `zone` in a cellZones file (each < cells), or
    // nothing; `names` gets every zone's name.
    std::optional<std::vector<uint32_t>> zone_cells(const std::string& zone, uint64_t cells,
                                                    std::vector<std::string>& names) {
        bool uniform = false;
        list_start("the number of zones", uniform);
        std::optional<std::vector<uint32_t>> found;
        while (!at(')')) {
            const std::string name(token());
            if (name.empty()) fail("expected a zone name");
            names.push_back(name);
            expect('{', ("after zone " + name).c_str());
            while (!at('}')) {
                const std::string key(token());
                if (key.empty()) fail("zone " + name + ": expected an entry or '}'");
                if (key == "cellLabels") {
                    if (token() != "List<label>") fail("zone " + name + ": expected List<label> after cellLabels");
                    std::vector<uint32_t> labels_read = this->labels("cell", cells, cells);
                    if (name == zone) found = std::move(labels_read);
                } else {  // any other entry, brackets and braces in it balanced, to its ';'
                    int depth = 0;
                    while (true) {
                        skip();
                        if (pos_ >= text_.size()) fail("zone " + name + ": entry " + key + " is not ended by ';'");
                        const char c = text_[pos_];
                        if (depth == 0 && (c == ';' || c == '}')) break;
                        if (c == '(' || c == '{') ++depth;
                        if (c == ')' || c == '}') --depth;
                        if (c == '(' || c == ')' || c == '{' || c == '}') ++pos_;
                        else if (token().empty()) ++pos_;
                    }
                }
                if (at(';')) ++pos_;
            }
            ++pos_;
        }
        return found;
    }

private:
    static constexpr uint64_t kUnknown = std::numeric_limits<uint64_t>::max();
    std::vector<std::byte> bytes_;
    std::string name_;
    std::string_view text_;
    std::size_t pos_ = 0;
    uint64_t line_ = 1;
    bool in_binary_ = false;
    std::string format_, class_, arch_;
    std::size_t label_bytes_ = 4, scalar_bytes_ = 8;
};

// The directory holding the polyMesh files: path itself, or path/constant/polyMesh.
fs::path polymesh_directory(const std::string& path) {
    const fs::path p(path);
    auto has_points = [](const fs::path& d) {
        std::error_code ec;
        return fs::exists(d / "points", ec) || fs::exists(d / "points.gz", ec);
    };
    if (has_points(p)) return p;
    if (has_points(p / "constant" / "polyMesh")) return p / "constant" / "polyMesh";
    std::error_code ec;
    if (!fs::is_directory(p, ec))
        throw ReadError::whole_file(path, "not a directory: an OpenFOAM case or its constant/polyMesh is one");
    throw ReadError::whole_file(path, "no OpenFOAM mesh here: expected constant/polyMesh/points (or points in it)");
}

// One file (NAME or NAME.gz), its header read.
// One file's bytes (gunzipped when they are gzip), its header read.
FoamFile foam_file(std::vector<std::byte> bytes, const std::string& shown, bool& gzip) {
    if (io::is_gzip(bytes)) {
        bytes = io::gunzip(bytes, shown, io::decompression_limit(bytes.size()));
        gzip = true;
    }
    FoamFile f(std::move(bytes), shown);
    f.header();
    return f;
}

// One file of dir (NAME or NAME.gz), its header read.
FoamFile open_foam_file(const fs::path& dir, const char* name, bool& gzip) {
    fs::path p = dir / name;
    std::error_code ec;
    if (!fs::exists(p, ec) && fs::exists(dir / (std::string(name) + ".gz"), ec)) p = dir / (std::string(name) + ".gz");
    std::string shown;
    std::vector<std::byte> bytes = io::read_whole_input(p.string(), shown);
    return foam_file(std::move(bytes), shown, gzip);
}

using OpenFoamFile = std::function<FoamFile(const char* name, bool& gzip)>;

// The mesh from its points, faces, owner and neighbour files, each given by open.
void read_polymesh_files(const OpenFoamFile& open, LoadedCellMesh& r) {
    r.format = "openfoam";
    r.unit = "m";
    CellMesh& m = r.mesh;

    FoamFile points = open("points", r.gzip);
    r.encoding = points.binary() ? "binary" : "ascii";
    m.points = points.vectors();
    const uint64_t point_count = m.points.size() / 3;
    if (point_count >= kNoCell) points.fail_whole("more than 2^32 - 2 points");

    FoamFile faces = open("faces", r.gzip);
    faces.faces(point_count, m.face_offsets, m.face_points);
    const std::size_t face_count = m.face_offsets.size() - 1;

    FoamFile owner = open("owner", r.gzip);
    m.owner = owner.labels("owner cell", kNoCell, face_count);
    if (m.owner.size() != face_count)
        owner.fail_whole("owner lists " + std::to_string(m.owner.size()) + " cells, but there are " +
                   std::to_string(face_count) + " faces (" + faces.name() + ")");

    FoamFile neighbour = open("neighbour", r.gzip);
    std::vector<uint32_t> internal = neighbour.labels("neighbour cell", kNoCell, face_count);
    if (internal.size() > face_count)
        neighbour.fail_whole("neighbour lists " + std::to_string(internal.size()) + " cells, more than the " +
                       std::to_string(face_count) + " faces (" + faces.name() + ")");
    // OpenFOAM numbers the internal faces first: neighbour has one entry each.
    m.neighbour.assign(face_count, kNoCell);
    std::copy(internal.begin(), internal.end(), m.neighbour.begin());

    uint32_t last = 0;
    bool any = false;
    for (std::size_t f = 0; f < face_count; ++f) {
        last = std::max(last, m.owner[f]);
        any = true;
        if (m.neighbour[f] != kNoCell) {
            if (m.neighbour[f] == m.owner[f])
                neighbour.fail_whole("face " + std::to_string(f) + " has cell " + std::to_string(m.owner[f]) +
                               " on both sides");
            last = std::max(last, m.neighbour[f]);
        }
    }
    m.cells = any ? std::size_t{last} + 1 : 0;
}

}  // namespace

namespace {

// The whole mesh of a decomposed case, put together from its processors'
// meshes by their point, face and cell addressing (decomposePar's
// pointProcAddressing, faceProcAddressing: ±(face + 1), negative where the
// processor holds the face reversed, as its neighbour cell's; and
// cellProcAddressing): the undecomposed case's points, faces and cells in
// its own order. A point two processors share must have the same coordinates.
LoadedCellMesh read_decomposed_case(const fs::path& case_dir, const std::vector<std::string>& dirs) {
    struct Piece {
        LoadedCellMesh mesh;
        std::vector<uint32_t> points;
        std::vector<int64_t> faces;
    };
    std::vector<Piece> pieces(dirs.size());
    uint64_t points = 0, faces = 0, cells = 0, local_points = 0, local_faces = 0, local_cells = 0;
    for (std::size_t p = 0; p < dirs.size(); ++p) {
        Piece& piece = pieces[p];
        piece.mesh = read_polymesh(dirs[p]);
        const fs::path dir = piece.mesh.location;
        bool gzip = false;
        std::error_code exists;
        if (!fs::exists(dir / "cellProcAddressing", exists) && !fs::exists(dir / "cellProcAddressing.gz", exists))
            throw ReadError::whole_file(dir.string(), "no cellProcAddressing: decomposePar writes it");
        FoamFile point_file = open_foam_file(dir, "pointProcAddressing", gzip);
        piece.points = point_file.labels("point", kNoCell, piece.mesh.mesh.points.size() / 3);
        if (piece.points.size() != piece.mesh.mesh.points.size() / 3)
            point_file.fail_whole("pointProcAddressing does not list one point per point of the mesh");
        FoamFile face_file = open_foam_file(dir, "faceProcAddressing", gzip);
        piece.faces = face_file.signed_labels("face", kNoCell);
        if (piece.faces.size() != piece.mesh.mesh.owner.size())
            face_file.fail_whole("faceProcAddressing does not list one face per face of the mesh");
        for (const uint32_t v : piece.points) points = std::max<uint64_t>(points, v + uint64_t{1});
        for (const int64_t v : piece.faces) {
            if (v == 0) face_file.fail_whole("faceProcAddressing holds 0 (faces are numbered from 1, signed)");
            faces = std::max<uint64_t>(faces, static_cast<uint64_t>(v < 0 ? -v : v));
        }
        for (const uint64_t v : piece.mesh.case_index) cells = std::max<uint64_t>(cells, v + 1);
        local_points += piece.points.size();
        local_faces += piece.faces.size();
        local_cells += piece.mesh.mesh.cells;
    }
    const std::string name = case_dir.string();
    if (points > local_points || faces > local_faces || cells != local_cells)
        throw ReadError::whole_file(name, "the processors' addressing names more points, faces or cells than they hold");
    std::vector<uint8_t> cell_seen(cells, 0);  // each cell in exactly one processor
    for (const Piece& piece : pieces)
        for (const uint64_t c : piece.mesh.case_index)
            if (cell_seen[c]++ != 0)
                throw ReadError::whole_file(name, "cell " + std::to_string(c) + " is in two processors");
    LoadedCellMesh r;
    r.format = "openfoam";
    r.unit = "m";
    r.location = name;
    r.encoding = pieces.empty() ? "ascii" : pieces[0].mesh.encoding;
    r.notes.push_back("a decomposed case: " + std::to_string(dirs.size()) + " processors' meshes put together");
    CellMesh& m = r.mesh;
    m.points.assign(3 * points, 0.0);
    std::vector<uint8_t> point_set(points, 0);
    constexpr uint64_t kNone = ~uint64_t{0};
    std::vector<uint64_t> source(faces, kNone);  // the processor and local face that gives each face's points
    m.owner.assign(faces, kNoCell);
    m.neighbour.assign(faces, kNoCell);
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        const Piece& piece = pieces[p];
        const CellMesh& local = piece.mesh.mesh;
        r.gzip = r.gzip || piece.mesh.gzip;
        for (std::size_t i = 0; i < piece.points.size(); ++i) {
            double* at = &m.points[3 * std::size_t{piece.points[i]}];
            if (point_set[piece.points[i]] != 0 &&
                (at[0] != local.points[3 * i] || at[1] != local.points[3 * i + 1] || at[2] != local.points[3 * i + 2]))
                throw ReadError::whole_file(dirs[p], "point " + std::to_string(piece.points[i]) +
                                                         " has other coordinates in another processor");
            std::copy_n(&local.points[3 * i], 3, at);
            point_set[piece.points[i]] = 1;
        }
        for (std::size_t f = 0; f < piece.faces.size(); ++f) {
            const bool reversed = piece.faces[f] < 0;
            const auto g = static_cast<std::size_t>((reversed ? -piece.faces[f] : piece.faces[f]) - 1);
            const auto cell = static_cast<uint32_t>(piece.mesh.case_index[local.owner[f]]);
            uint32_t& side = reversed ? m.neighbour[g] : m.owner[g];
            if (side != kNoCell && side != cell)
                throw ReadError::whole_file(dirs[p], "face " + std::to_string(g) + " is given two cells on one side");
            side = cell;
            if (!reversed) {
                source[g] = (uint64_t{p} << 32) | f;
                if (local.neighbour[f] != kNoCell) {
                    const auto other = static_cast<uint32_t>(piece.mesh.case_index[local.neighbour[f]]);
                    if (m.neighbour[g] != kNoCell && m.neighbour[g] != other)
                        throw ReadError::whole_file(dirs[p], "face " + std::to_string(g) +
                                                                 " is given two cells on one side");
                    m.neighbour[g] = other;
                }
            }
        }
    }
    for (std::size_t g = 0; g < faces; ++g) {
        if (source[g] == kNone || m.owner[g] == kNoCell)
            throw ReadError::whole_file(name, "face " + std::to_string(g) + " is in no processor as its owner's");
        const Piece& piece = pieces[source[g] >> 32];
        const std::span<const uint32_t> face = piece.mesh.mesh.view().face(source[g] & 0xFFFFFFFFu);
        if (m.face_points.size() + face.size() > UINT32_MAX)
            throw ReadError::whole_file(name, "more than 2^32 face points: the case is too large to read whole");
        for (const uint32_t v : face) m.face_points.push_back(piece.points[v]);
        m.face_offsets.push_back(static_cast<uint32_t>(m.face_points.size()));
    }
    m.cells = cells;
    return r;
}

}  // namespace

LoadedCellMesh read_polymesh(const std::string& path) {
    {
        std::error_code ec;
        const fs::path p(path);
        auto has_points = [&](const fs::path& d) { return fs::exists(d / "points", ec) || fs::exists(d / "points.gz", ec); };
        if (!has_points(p) && !has_points(p / "constant" / "polyMesh"))
            if (const std::vector<std::string> dirs = foam_processor_dirs(path); !dirs.empty())
                return read_decomposed_case(p, dirs);
    }
    const fs::path dir = polymesh_directory(path);
    LoadedCellMesh r;
    r.location = dir.string();
    read_polymesh_files([&](const char* name, bool& gzip) { return open_foam_file(dir, name, gzip); }, r);
    // A processor's piece of a decomposed case: its cells' places in the whole.
    std::error_code ec;
    if (fs::exists(dir / "cellProcAddressing", ec) || fs::exists(dir / "cellProcAddressing.gz", ec)) {
        FoamFile addressing = open_foam_file(dir, "cellProcAddressing", r.gzip);
        const std::vector<uint32_t> cells = addressing.labels("cell", kNoCell, r.mesh.cells);
        if (cells.size() != r.mesh.cells)
            addressing.fail_whole("cellProcAddressing lists " + std::to_string(cells.size()) + " cells; the mesh has " +
                                  std::to_string(r.mesh.cells));
        r.case_index.assign(cells.begin(), cells.end());
    }
    return r;
}

LoadedCellMesh cell_zone(const LoadedCellMesh& mesh, const std::string& zone) {
    const fs::path dir(mesh.location);
    if (mesh.format != "openfoam" || dir.filename() != "polyMesh" || !mesh.case_index.empty())
        throw ReadError::whole_file(mesh.location, "cellZone " + zone + ": zones are read from an OpenFOAM case's "
                                                   "constant/polyMesh/cellZones (not of a decomposed case or its processors)");
    bool gzip = false;
    FoamFile file = open_foam_file(dir, "cellZones", gzip);
    std::vector<std::string> names;
    const auto cells = file.zone_cells(zone, mesh.mesh.cells, names);
    if (!cells) {
        std::string listed;
        for (const std::string& n : names) listed += (listed.empty() ? "" : ", ") + n;
        file.fail_whole("no cellZone " + zone + (names.empty() ? std::string(" (there are none)")
                                                                : " (the zones: " + listed + ")"));
    }
    LoadedCellMesh r;
    r.format = mesh.format;
    r.encoding = mesh.encoding;
    r.gzip = mesh.gzip;
    r.unit = mesh.unit;
    r.location = mesh.location;
    try {
        r.mesh = cells_subset(mesh.mesh.view(), *cells);
    } catch (const std::invalid_argument& e) {
        file.fail_whole("cellZone " + zone + ": " + e.what());
    }
    r.case_index.assign(cells->begin(), cells->end());
    r.case_cells = mesh.mesh.cells;
    r.notes.push_back("cellZone " + zone + ": " + std::to_string(cells->size()) + " of the case's " +
                      std::to_string(mesh.mesh.cells) + " cells");
    return r;
}

std::vector<double> in_case_cells(const LoadedCellMesh& mesh, std::span<const double> values) {
    if (mesh.case_cells == 0) return {values.begin(), values.end()};
    std::vector<double> all(mesh.case_cells, 0.0);
    for (std::size_t c = 0; c < values.size() && c < mesh.case_index.size(); ++c) all[mesh.case_index[c]] = values[c];
    return all;
}

std::vector<std::string> foam_processor_dirs(const std::string& case_dir) {
    std::vector<std::pair<uint64_t, std::string>> found;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(fs::path(case_dir), ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("processor", 0) != 0 || name.size() == 9) continue;
        const std::string digits = name.substr(9);
        if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
            digits.size() > 9)
            continue;
        if (!fs::exists(entry.path() / "constant" / "polyMesh", ec)) continue;
        found.emplace_back(std::stoull(digits), entry.path().string());
    }
    std::sort(found.begin(), found.end());
    std::vector<std::string> out;
    for (auto& f : found) out.push_back(std::move(f.second));
    return out;
}

LoadedCellMesh read_polymesh_memory(const PolyMeshBytes& files, const std::string& name) {
    LoadedCellMesh r;
    r.location = name;
    read_polymesh_files(
        [&](const char* file, bool& gzip) {
            const std::string f(file);
            const std::span<const std::byte> b = f == "points" ? files.points
                                                 : f == "faces" ? files.faces
                                                 : f == "owner" ? files.owner
                                                                : files.neighbour;
            return foam_file(std::vector<std::byte>(b.begin(), b.end()), name + "/" + f, gzip);
        },
        r);
    return r;
}


}  // namespace polyvol

namespace polyvol {
namespace {

// The brace-balanced block that starts at text[open] == '{', through its '}'.
std::string_view braced(std::string_view text, std::size_t open) {
    int depth = 0;
    for (std::size_t i = open; i < text.size(); ++i) {
        if (text[i] == '{') ++depth;
        if (text[i] == '}' && --depth == 0) return text.substr(open, i + 1 - open);
    }
    return {};
}

// The patch types whose fields take the same type (a zeroGradient there is
// an error): empty, wedge, symmetry, symmetryPlane, and the processor and
// cyclic families (processorCyclic where decomposePar splits a cyclic,
// cyclicAMI, cyclicSlip, ...) and nonConformal ones.
bool constrained_patch(const std::string& type) {
    for (const char* t : {"empty", "wedge", "symmetry", "symmetryPlane"})
        if (type == t) return true;
    return type.rfind("processor", 0) == 0 || type.rfind("cyclic", 0) == 0 || type.rfind("nonConformal", 0) == 0;
}

}  // namespace

std::vector<FoamPatch> read_foam_patches(const std::string& polymesh_dir) {
    bool gzip = false;
    FoamFile file = open_foam_file(fs::path(polymesh_dir), "boundary", gzip);
    return file.patches();
}

std::string write_foam_field(const std::string& polymesh_dir, const std::string& name, std::span<const double> values,
                             const std::string& time) {
    // A decomposed case (read_polymesh of its directory): each processor's
    // cells' values into its own field, as a parallel run reads them.
    if (fs::path(polymesh_dir).filename() != "polyMesh")
        if (const std::vector<std::string> dirs = foam_processor_dirs(polymesh_dir); !dirs.empty()) {
            for (const std::string& d : dirs) {
                const fs::path mesh = fs::path(d) / "constant" / "polyMesh";
                bool gzip = false;
                FoamFile file = open_foam_file(mesh, "cellProcAddressing", gzip);
                const std::vector<uint32_t> cells = file.labels("cell", values.size(), values.size());
                std::vector<double> local(cells.size());
                for (std::size_t c = 0; c < cells.size(); ++c) local[c] = values[cells[c]];
                write_foam_field(mesh.string(), name, local, time);
            }
            return (fs::path(polymesh_dir) / "processor*" / time / name).string();
        }
    const fs::path mesh_dir = fs::absolute(fs::path(polymesh_dir)).lexically_normal();
    const fs::path constant = mesh_dir.parent_path();
    if (mesh_dir.filename() != "polyMesh" || constant.filename() != "constant")
        throw std::runtime_error(polymesh_dir + ": the mesh is not in an OpenFOAM case (CASE/constant/polyMesh), "
                                                "so there is no case to write a field into");
    const fs::path dir = constant.parent_path() / time;
    const fs::path target = dir / name;
    // The boundary conditions: the existing file's, else one per patch.
    std::string boundary;
    std::error_code ec;
    if (fs::exists(target, ec)) {
        std::string shown;
        const std::vector<std::byte> old = io::read_whole_input(target.string(), shown);
        const std::string_view text = io::text::as_text(old);
        const std::size_t at = text.find("boundaryField");
        const std::size_t open = at == std::string_view::npos ? at : text.find('{', at);
        const std::string_view block = open == std::string_view::npos ? std::string_view() : braced(text, open);
        if (block.empty())
            throw ReadError::whole_file(shown, "no boundaryField { ... } to keep in the existing field file");
        boundary = "boundaryField\n" + std::string(block) + "\n";
    } else {
        boundary = "boundaryField\n{\n";
        for (const FoamPatch& p : read_foam_patches(mesh_dir.string()))
            boundary += "    " + p.name + "\n    {\n        type            " +
                        (constrained_patch(p.type) ? p.type : std::string("zeroGradient")) + ";\n    }\n";
        boundary += "}\n";
    }
    fs::create_directories(dir, ec);
    const fs::path temporary = dir / (name + ".polyvol-tmp");
    {
        std::FILE* f = std::fopen(temporary.c_str(), "wb");
        if (f == nullptr)
            throw std::runtime_error(temporary.string() + ": cannot write: " + std::strerror(errno));
        std::string head = "FoamFile\n{\n    version     2.0;\n    format      ascii;\n"
                           "    class       volScalarField;\n    location    \"" + time + "\";\n    object      " + name +
                           ";\n}\n// written by polyvol cells\n\ndimensions      [0 0 0 0 0 0 0];\n\n"
                           "internalField   nonuniform List<scalar>\n" + std::to_string(values.size()) + "\n(\n";
        bool ok = std::fputs(head.c_str(), f) >= 0;
        char buf[40];
        for (const double v : values) {
            std::snprintf(buf, sizeof buf, "%.17g\n", v);
            ok = ok && std::fputs(buf, f) >= 0;
        }
        ok = ok && std::fputs(")\n;\n\n", f) >= 0 && std::fputs(boundary.c_str(), f) >= 0;
        ok = std::fclose(f) == 0 && ok;
        if (!ok) throw std::runtime_error(temporary.string() + ": cannot write: " + std::strerror(errno));
    }
    fs::rename(temporary, target);
    return target.string();
}

}  // namespace polyvol
