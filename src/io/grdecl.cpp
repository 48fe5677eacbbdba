// io/grdecl.cpp — read_grdecl and write_grdecl_keyword
// (polyvol/cell_mesh_io.hpp): Eclipse corner-point grids.
//
// The file is keywords, each at the start of a line, most followed by data
// ended by '/': numbers, repeats N*v, quoted strings; "--" starts a comment.
// A corner-point grid is I×J×K hexahedra on (I+1)(J+1) straight pillars:
//   COORD  6 numbers per pillar (top x y z, bottom x y z), pillar (i, j) at
//          6(i + (I+1) j);
//   ZCORN  8 depths per cell, corner (i, j, k; a, b, c ∈ {0, 1}) at
//          (2i + a) + 2I (2j + b) + 4IJ (2k + c);
//   ACTNUM 0 for an inactive cell (all active without it).
// A corner is the point of its pillar at its depth z: with t = (z − z_top)
// / (z_bot − z_top), (x_top + t (x_bot − x_top), y_top + t (y_bot − y_top), z)
// — one formula, so two cells naming the same pillar and depth get the
// same point, the same double.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/readers.hpp"
#include "io/text.hpp"
#include "polyvol/cell_mesh_io.hpp"

namespace polyvol {
namespace {

namespace fs = std::filesystem;

struct Token {
    std::string_view text;
    uint64_t line = 0;
    bool line_start = false;  // the first token of its line
    bool quoted = false;
    bool slash = false;  // the '/' that ends a keyword's data
};

// The tokens of one GRDECL text. Comments are dropped: "--" to the end of
// the line, and the rest of a line after a '/' (Eclipse reads no further).
// "\n", "\r\n" and a lone "\r" each end a line.
std::vector<Token> tokenize(std::string_view s) {
    std::vector<Token> out;
    uint64_t line = 1;
    bool fresh = true;
    std::size_t p = 0;
    auto to_line_end = [&] {
        while (p < s.size() && s[p] != '\n' && s[p] != '\r') ++p;
    };
    while (p < s.size()) {
        const char c = s[p];
        if (c == '\n' || c == '\r') {
            ++line;
            fresh = true;
            p += (c == '\r' && p + 1 < s.size() && s[p + 1] == '\n') ? 2 : 1;
        } else if (io::text::is_space(c)) {
            ++p;
        } else if (c == '-' && p + 1 < s.size() && s[p + 1] == '-') {
            to_line_end();
        } else if (c == '/') {
            out.push_back({s.substr(p, 1), line, fresh, false, true});
            fresh = false;
            to_line_end();
        } else if (c == '\'' || c == '"') {
            const std::size_t end = s.find(c, p + 1);
            const std::size_t stop = end == std::string_view::npos ? s.size() : end;
            out.push_back({s.substr(p + 1, stop - p - 1), line, fresh, true, false});
            for (std::size_t i = p; i < stop; ++i) line += s[i] == '\n';
            fresh = false;
            p = stop + 1;
        } else {
            const std::size_t start = p;
            while (p < s.size() && !io::text::is_space(s[p]) && s[p] != '/') ++p;
            out.push_back({s.substr(start, p - start), line, fresh, false, false});
            fresh = false;
        }
    }
    return out;
}

bool is_keyword(const Token& t) {
    if (!t.line_start || t.quoted || t.slash || t.text.empty()) return false;
    const char c = t.text[0];
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

std::string upper(std::string_view s) {
    std::string u(s);
    for (char& c : u)
        if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
    return u;
}

// The keywords a grid needs, and the facts about the file.
struct Deck {
    std::array<uint64_t, 3> dims{};
    bool has_dims = false;
    std::vector<double> coord, zcorn, actnum, mapaxes;
    bool map_coordinates = false;  // GRIDUNIT's second item MAP: COORD is in map coordinates already
    std::string unit;  // from GRIDUNIT, else METRIC / FIELD / LAB / PVT-M
    bool unit_by_gridunit = false;
};

class Reader {
public:
    // INCLUDE paths are relative to the main file's directory (as OPM and
    // Eclipse resolve them).
    Reader(Deck& deck, bool files, uint64_t max_cells, fs::path root)
        : deck_(deck), files_(files), max_cells_(max_cells), root_(std::move(root)) {}

    void read(std::string_view text, const std::string& name, int depth) {
        bytes_ += text.size();
        const std::vector<Token> tokens = tokenize(text);
        std::size_t i = 0;
        while (i < tokens.size()) {
            const Token& k = tokens[i];
            if (!is_keyword(k)) {
                if (k.slash) {  // a stray '/' (an empty record) is harmless
                    ++i;
                    continue;
                }
                throw ReadError(name, k.line, "expected a keyword at the start of a line, found '" +
                                                  std::string(k.text) + "'");
            }
            const std::string word = upper(k.text);
            ++i;
            if (word == "METRIC" || word == "FIELD" || word == "LAB" || word == "PVT-M") {
                if (!deck_.unit_by_gridunit) deck_.unit = word == "FIELD" ? "ft" : word == "LAB" ? "cm" : "m";
                continue;
            }
            const bool wanted = word == "SPECGRID" || word == "DIMENS" || word == "COORD" || word == "ZCORN" ||
                                word == "ACTNUM" || word == "MAPAXES" || word == "GRIDUNIT" || word == "INCLUDE";
            const std::size_t start = i;
            if (!wanted) {
                // Any other keyword: its records (several for FAULTS, EQUALS,
                // ...) up to the next keyword's line. Those that would change
                // the grid's arrays are refused rather than ignored.
                while (i < tokens.size() && !is_keyword(tokens[i])) ++i;
                other_keyword(word, std::span(tokens.data() + start, i - start), k.line, name);
                continue;
            }
            while (i < tokens.size() && !tokens[i].slash) ++i;
            if (i == tokens.size()) throw ReadError(name, k.line, word + ": its data is not ended by '/'");
            const std::span<const Token> data(tokens.data() + start, i - start);
            ++i;
            if (box_ && word != "INCLUDE" && word != "GRIDUNIT" && word != "MAPAXES")
                throw ReadError(name, k.line, word + " inside a BOX (a part of the grid) is not read");
            keyword(word, data, k.line, name, depth);
        }
    }

private:
    [[noreturn]] static void fail(const std::string& name, uint64_t line, const std::string& what) {
        throw ReadError(name, line, what);
    }

    // BOX ... ENDBOX limits what follows to part of the grid; EQUALS, COPY,
    // ADD, MULTIPLY and the like change arrays: one that names a grid array
    // would change the cells, so it is refused.
    void other_keyword(const std::string& word, std::span<const Token> data, uint64_t line, const std::string& name) {
        if (word == "BOX") box_ = true;
        if (word == "ENDBOX") box_ = false;
        for (const Token& t : data) {
            const std::string u = upper(io::text::trim(t.text));
            if (u == "ACTNUM" || u == "ZCORN" || u == "COORD")
                fail(name, line, word + " changes " + u + ": not read (write the array out in full)");
        }
    }

    void keyword(const std::string& word, std::span<const Token> data, uint64_t line, const std::string& name,
                 int depth) {
        if (word == "INCLUDE") {
            if (data.empty()) fail(name, line, "INCLUDE: expected a file name");
            if (!files_) fail(name, line, "INCLUDE: a grid read from memory cannot include files");
            if (depth >= 16) fail(name, line, "INCLUDE: nested more than 16 deep");
            if (++includes_ > 1000) fail(name, line, "INCLUDE: more than 1000 files included");
            const fs::path target = root_ / fs::path(std::string(io::text::trim(data[0].text)));
            std::string shown;
            const std::vector<std::byte> bytes = io::read_whole_input(target.string(), shown);
            read(io::text::as_text(bytes), shown, depth + 1);
            return;
        }
        if (word == "GRIDUNIT") {
            if (data.empty()) fail(name, line, "GRIDUNIT: expected a unit (METRES, FEET or CM)");
            const std::string u = upper(io::text::trim(data[0].text));
            deck_.unit = u == "METRES" || u == "METERS" || u == "M" ? "m"
                         : u == "FEET" || u == "FT"                   ? "ft"
                         : u == "CM"                                  ? "cm"
                                                                      : "";
            if (deck_.unit.empty()) fail(name, line, "GRIDUNIT '" + u + "': expected METRES, FEET or CM");
            deck_.unit_by_gridunit = true;
            deck_.map_coordinates = data.size() >= 2 && upper(io::text::trim(data[1].text)) == "MAP";
            return;
        }
        if (word == "SPECGRID" || word == "DIMENS") {
            // I J K; SPECGRID's NUMRES (1) and coordinate type (F: Cartesian).
            const std::vector<double> v = numbers(data.first(std::min<std::size_t>(data.size(), 3)), 3, name, line, word);
            if (v.size() < 3) fail(name, line, word + ": expected the grid's size I J K");
            for (int a = 0; a < 3; ++a) {
                if (!(v[a] >= 1 && v[a] <= 1e9 && v[a] == std::floor(v[a])))
                    fail(name, line, word + ": the grid's size must be whole numbers of 1 or more");
                deck_.dims[a] = static_cast<uint64_t>(v[a]);
            }
            if (word == "SPECGRID" && data.size() >= 4 && data[3].text != "1" && data[3].text != "1*")
                fail(name, line, "SPECGRID: NUMRES " + std::string(data[3].text) + ": only one reservoir is read");
            if (word == "SPECGRID" && data.size() >= 5 && upper(data[4].text) == "T")
                fail(name, line, "SPECGRID: a radial grid (T) is not read");
            // Cells, their points and face lists are numbered in 32 bits.
            const uint64_t nx = deck_.dims[0], ny = deck_.dims[1], nz = deck_.dims[2];
            if (nx * ny > max_cells_ || nx * ny * nz > max_cells_)
                fail(name, line, word + ": " + std::to_string(nx) + "×" + std::to_string(ny) + "×" +
                                     std::to_string(nz) + " cells: at most " + std::to_string(max_cells_) +
                                     " are read");
            deck_.has_dims = true;
            return;
        }
        if (word == "MAPAXES") {
            deck_.mapaxes = numbers(data, 6, name, line, word);
            if (deck_.mapaxes.size() != 6) fail(name, line, "MAPAXES: expected 6 numbers (X1 Y1 X2 Y2 X3 Y3)");
            return;
        }
        if (!deck_.has_dims) fail(name, line, word + " before SPECGRID or DIMENS: the grid's size must come first");
        const uint64_t nx = deck_.dims[0], ny = deck_.dims[1], nz = deck_.dims[2];
        if (word == "COORD") deck_.coord = numbers(data, 6 * (nx + 1) * (ny + 1), name, line, word);
        else if (word == "ZCORN") deck_.zcorn = numbers(data, 8 * nx * ny * nz, name, line, word);
        else if (word == "ACTNUM") deck_.actnum = numbers(data, nx * ny * nz, name, line, word);
    }

    // The numbers of a keyword's data, repeats expanded, at most `limit`
    // of them (the grid's size says how many it needs), and repeats
    // expanding to no more than max(2^22, 8 × the bytes read) values in all
    // (no huge allocation for a small file).
    std::vector<double> numbers(std::span<const Token> data, uint64_t limit, const std::string& name,
                                uint64_t line, const std::string& word) {
        std::vector<double> out;
        const uint64_t cap = std::max<uint64_t>(uint64_t{1} << 22, 8 * bytes_);
        for (const Token& t : data) {
            std::string_view s = t.text;
            uint64_t repeat = 1;
            if (const std::size_t star = s.find('*'); star != std::string_view::npos) {
                int64_t n = 0;
                if (!io::text::parse_int(s.substr(0, star), n) || n < 1)
                    fail(name, t.line, word + ": '" + std::string(s) + "' is not a repeat count N*value");
                if (star + 1 == s.size())
                    fail(name, t.line, word + ": '" + std::string(s) + "' asks for default values, which " + word +
                                           " does not have");
                repeat = static_cast<uint64_t>(n);
                s.remove_prefix(star + 1);
            }
            double v = 0;
            if (!io::text::parse_double(s, v) || !std::isfinite(v))
                fail(name, t.line, word + ": '" + std::string(t.text) + "' is not a number");
            if (repeat > limit - out.size())
                fail(name, line, word + ": more than the " + std::to_string(limit) + " values the grid's size needs");
            if (repeat > cap - std::min(cap, expanded_))
                fail(name, t.line, word + ": the repeats expand to more than " + std::to_string(cap) +
                                       " values, 8 times the file's size: refused");
            expanded_ += repeat;
            out.insert(out.end(), repeat, v);
        }
        return out;
    }

    Deck& deck_;
    bool files_;
    uint64_t max_cells_;
    fs::path root_;
    uint64_t bytes_ = 0, expanded_ = 0;
    int includes_ = 0;
    bool box_ = false;
};

// A corner's point id, one per (pillar, depth).
// MAPAXES: (X1, Y1) on the map's y axis, (X2, Y2) its origin, (X3, Y3) on
// its x axis; grid coordinates (x, y) are the map point
//   O + x e_x + y e_y,  e_x = (P3 − O) / |P3 − O|,  e_y = (P1 − O) / |P1 − O|,
// each product and sum rounded. Identity when not applied.
struct MapAxes {
    double origin[2] = {0, 0}, ex[2] = {1, 0}, ey[2] = {0, 1};
    bool identity = true;
    static MapAxes from(const std::vector<double>& m, const std::string& name) {
        MapAxes a;
        const double x[2] = {m[4] - m[2], m[5] - m[3]}, y[2] = {m[0] - m[2], m[1] - m[3]};
        const double lx = std::hypot(x[0], x[1]), ly = std::hypot(y[0], y[1]);
        if (!(lx > 0) || !(ly > 0) || !std::isfinite(lx) || !std::isfinite(ly) ||
            std::fabs(x[0] * y[1] - x[1] * y[0]) < 1e-12 * lx * ly)
            throw ReadError::whole_file(name, "MAPAXES: its axes are not two independent directions");
        a.origin[0] = m[2], a.origin[1] = m[3];
        a.ex[0] = x[0] / lx, a.ex[1] = x[1] / lx;
        a.ey[0] = y[0] / ly, a.ey[1] = y[1] / ly;
        a.identity = false;
        return a;
    }
    void apply(double& x, double& y) const {
        if (identity) return;
        const double mx = origin[0] + (x * ex[0] + y * ey[0]), my = origin[1] + (x * ex[1] + y * ey[1]);
        x = mx;
        y = my;
    }
};

class Corners {
public:
    Corners(CellMesh& m, const std::vector<double>& coord, const std::string& name, const MapAxes& axes)
        : m_(m), coord_(coord), name_(name), axes_(axes) {}
    uint32_t at(uint64_t pillar, double z) {
        z += 0.0;  // -0 and +0 are one depth
        uint64_t bits;
        std::memcpy(&bits, &z, 8);
        const auto [it, fresh] = ids_.try_emplace(Key{pillar, bits}, static_cast<uint32_t>(m_.points.size() / 3));
        if (fresh) {
            const double* c = coord_.data() + 6 * pillar;  // x_top y_top z_top x_bot y_bot z_bot
            double x = c[0], y = c[1];
            // The point of the pillar at depth z; a vertical pillar's x and y
            // exactly (and a pillar whose top and bottom have one depth: its top's).
            const bool vertical = c[0] == c[3] && c[1] == c[4];
            if (!vertical && c[5] != c[2]) {
                const double t = (z - c[2]) / (c[5] - c[2]);
                x = c[0] + t * (c[3] - c[0]);
                y = c[1] + t * (c[4] - c[1]);
            }
            axes_.apply(x, y);  // a function of the pillar's x, y: a vertical pillar's points keep one x, y
            if (!std::isfinite(x) || !std::isfinite(y))
                throw ReadError::whole_file(name_, "pillar " + std::to_string(pillar) + " at depth " +
                                                       std::to_string(z) + ": the point is not finite (COORD)");
            m_.points.insert(m_.points.end(), {x, y, z});
        }
        return it->second;
    }

private:
    struct Key {
        uint64_t pillar, z;
        bool operator==(const Key&) const = default;
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            return std::hash<uint64_t>()(k.z * 0x9E3779B97F4A7C15ull ^ k.pillar);
        }
    };
    CellMesh& m_;
    const std::vector<double>& coord_;
    const std::string& name_;
    const MapAxes& axes_;
    std::unordered_map<Key, uint32_t, Hash> ids_;
};

// Corner n = a + 2b + 4c of a cell (a along I, b along J, c down K); the
// six faces as corner lists, wound outward when (I, J, K) is right-handed:
// −I, +I, −J, +J, −K (top), +K (bottom).
constexpr std::array<std::array<int, 4>, 6> kFaces{{{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};

LoadedCellMesh build_grid(const Deck& deck, const std::string& name, bool map_axes) {
    if (!deck.has_dims) throw ReadError::whole_file(name, "no SPECGRID or DIMENS: the grid's size is not given");
    const uint64_t nx = deck.dims[0], ny = deck.dims[1], nz = deck.dims[2];  // not a structured binding: clang 14 cannot capture one
    const uint64_t cells = nx * ny * nz;
    auto need = [&](const std::vector<double>& v, uint64_t n, const char* word, const char* rule) {
        if (v.size() != n)
            throw ReadError::whole_file(name, std::string(word) + " holds " + std::to_string(v.size()) +
                                                  " values; the grid " + std::to_string(nx) + "×" +
                                                  std::to_string(ny) + "×" + std::to_string(nz) + " needs " + rule +
                                                  " = " + std::to_string(n));
    };
    need(deck.coord, 6 * (nx + 1) * (ny + 1), "COORD", "6(I+1)(J+1)");
    need(deck.zcorn, 8 * cells, "ZCORN", "8·I·J·K");
    if (!deck.actnum.empty()) need(deck.actnum, cells, "ACTNUM", "I·J·K");

    LoadedCellMesh r;
    r.format = "grdecl";
    r.encoding = "ascii";
    r.location = name;
    r.unit = deck.unit;
    r.grid_dims = deck.dims;
    CellMesh& m = r.mesh;
    // Each grid cell's index among the active cells (kNoCell: inactive).
    std::vector<uint32_t> cell_of(cells, kNoCell);
    for (uint64_t c = 0; c < cells; ++c)
        if (deck.actnum.empty() || deck.actnum[c] != 0) {
            cell_of[c] = static_cast<uint32_t>(r.grid_index.size());
            r.grid_index.push_back(c);
        }
    m.cells = r.grid_index.size();
    auto cell_at = [&](uint64_t i, uint64_t j, uint64_t k) { return cell_of[i + nx * (j + ny * k)]; };
    // The depth of corner n = a + 2b + 4c of cell (i, j, k).
    auto depth = [&](uint64_t i, uint64_t j, uint64_t k, int n) {
        const uint64_t a = n & 1, b = (n >> 1) & 1, c = (n >> 2) & 1;
        return deck.zcorn[(2 * i + a) + 2 * nx * (2 * j + b) + 4 * nx * ny * (2 * k + c)];
    };

    // Each active cell's 8 corner ids, numbered in the order cells first name them.
    const bool mapped = map_axes && !deck.mapaxes.empty() && !deck.map_coordinates;
    const MapAxes axes = mapped ? MapAxes::from(deck.mapaxes, name) : MapAxes{};
    Corners corners(m, deck.coord, name, axes);
    std::vector<std::array<uint32_t, 8>> corner_ids(m.cells);
    for (uint32_t c = 0; c < m.cells; ++c) {
        const uint64_t g = r.grid_index[c], i = g % nx, j = g / nx % ny, k = g / (nx * ny);
        for (int n = 0; n < 8; ++n) {
            const uint64_t a = n & 1, b = (n >> 1) & 1;
            corner_ids[c][n] = corners.at((i + a) + (nx + 1) * (j + b), depth(i, j, k, n));
        }
    }
    // Face f of a cell as point ids, repeated corners (a pinched cell) once.
    auto face_of = [&](const std::array<uint32_t, 8>& ids, int f) {
        std::vector<uint32_t> face;
        for (const int n : kFaces[f])
            if (face.empty() || face.back() != ids[n]) face.push_back(ids[n]);
        while (face.size() > 1 && face.front() == face.back()) face.pop_back();
        return face;
    };
    // The same face seen from both cells: one cyclic sequence (from its
    // smallest id) equal to the other reversed.
    auto canonical = [](std::vector<uint32_t> f) {
        std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
        return f;
    };
    auto emit = [&](std::vector<uint32_t> face, uint32_t owner, uint32_t neighbour) {
        if (face.size() < 3) return;  // collapsed to an edge or a point: no area
        if (m.face_points.size() + face.size() > UINT32_MAX)
            throw ReadError::whole_file(name, "more than 2^32 face points: the grid is too large to read");
        m.face_points.insert(m.face_points.end(), face.begin(), face.end());
        m.face_offsets.push_back(static_cast<uint32_t>(m.face_points.size()));
        m.owner.push_back(owner);
        m.neighbour.push_back(neighbour);
    };
    auto vertical = [&](uint64_t i, uint64_t j) {
        const double* c = deck.coord.data() + 6 * (i + (nx + 1) * j);
        return c[0] == c[3] && c[1] == c[4];
    };
    // Each active cell's +I, +J, +K face is shared with the next cell when
    // both name the same corners (no fault), else each keeps its own; its
    // −I, −J, −K face is its own where no active cell precedes it.
    const std::array<std::array<uint64_t, 3>, 3> step{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for (uint64_t k = 0; k < nz; ++k)
        for (uint64_t j = 0; j < ny; ++j)
            for (uint64_t i = 0; i < nx; ++i) {
                const uint32_t c = cell_at(i, j, k);
                if (c == kNoCell) continue;
                const std::array<uint32_t, 8>& ids = corner_ids[c];
                const std::array<uint64_t, 3> at{i, j, k};
                for (int axis = 0; axis < 3; ++axis) {
                    if (at[axis] == 0 || cell_at(i - step[axis][0], j - step[axis][1], k - step[axis][2]) == kNoCell)
                        emit(face_of(ids, 2 * axis), c, kNoCell);
                    const uint64_t ni = i + step[axis][0], nj = j + step[axis][1], nk = k + step[axis][2];
                    const uint32_t n = at[axis] + 1 == deck.dims[axis] ? kNoCell : cell_at(ni, nj, nk);
                    if (n == kNoCell) {
                        emit(face_of(ids, 2 * axis + 1), c, kNoCell);
                        continue;
                    }
                    std::vector<uint32_t> mine = face_of(ids, 2 * axis + 1), theirs = face_of(corner_ids[n], 2 * axis);
                    std::reverse(theirs.begin(), theirs.end());
                    if (canonical(mine) == canonical(theirs)) {
                        emit(std::move(mine), c, n);
                    } else if (mine.size() < 3 && theirs.size() < 3) {
                        continue;  // both collapsed: no face on either side
                    } else {  // a fault: the two faces differ; each bounds its own cell
                        ++r.fault_faces;
                        // On two vertical pillars both faces lie in their plane (every corner
                        // has its pillar's x and y exactly) and the cells still tile; else
                        // they may overlap or leave slivers.
                        const bool on_vertical_pillars =
                            axis == 0 ? vertical(i + 1, j) && vertical(i + 1, j + 1)
                            : axis == 1 ? vertical(i, j + 1) && vertical(i + 1, j + 1)
                                        : true;  // layers: by their depths, below
                        if (!on_vertical_pillars) r.cells_tile = false;
                        emit(std::move(mine), c, kNoCell);
                        std::reverse(theirs.begin(), theirs.end());
                        emit(std::move(theirs), n, kNoCell);
                    }
                }
            }
    // Layers that do not meet (a mismatch between two active cells of a
    // column, next to each other or with inactive cells between) tile when
    // the space between them is no cell turned inside out: at each pillar
    // the lower cell's top is not above the upper cell's bottom, "above"
    // taken along the upper cell's own top → bottom direction. (Cells are
    // taken to be embedded, their faces not crossing each other, here as
    // everywhere.)
    for (uint64_t j = 0; j < ny && r.cells_tile; ++j)
        for (uint64_t i = 0; i < nx && r.cells_tile; ++i) {
            uint64_t upper = nz;  // the last active cell of the column, none yet
            for (uint64_t k = 0; k < nz; ++k) {
                if (cell_at(i, j, k) == kNoCell) continue;
                if (upper != nz) {
                    double down = 0;  // the upper cell's direction, top to bottom
                    for (int n = 0; n < 4; ++n) down += depth(i, j, upper, n + 4) - depth(i, j, upper, n);
                    const double sign = down < 0 ? -1.0 : 1.0;
                    for (int n = 0; n < 4; ++n)
                        if (sign * (depth(i, j, k, n) - depth(i, j, upper, n + 4)) < 0) r.cells_tile = false;
                }
                upper = k;
            }
        }
    // Wound outward when the grid's signed volume (Σ over the boundary faces'
    // fans of det/6, in doubles from the first point, so that coordinates far
    // from the origin do not drown it: only its sign is used) is positive; a
    // left-handed (I, J, K), as depth downward usually makes it, turns every face.
    double volume = 0;
    const CellMeshView v = m.view();
    const double o[3] = {m.points.empty() ? 0 : m.points[0], m.points.empty() ? 0 : m.points[1],
                         m.points.empty() ? 0 : m.points[2]};
    for (std::size_t f = 0; f < v.face_count(); ++f) {
        if (v.neighbour[f] != kNoCell) continue;
        face_triangles(v.face(f), v.points, [&](uint32_t a, uint32_t b, uint32_t d) {
            const double p[3] = {m.points[3 * a] - o[0], m.points[3 * a + 1] - o[1], m.points[3 * a + 2] - o[2]};
            const double q[3] = {m.points[3 * b] - o[0], m.points[3 * b + 1] - o[1], m.points[3 * b + 2] - o[2]};
            const double s[3] = {m.points[3 * d] - o[0], m.points[3 * d + 1] - o[1], m.points[3 * d + 2] - o[2]};
            volume += p[0] * (q[1] * s[2] - q[2] * s[1]) - p[1] * (q[0] * s[2] - q[2] * s[0]) +
                      p[2] * (q[0] * s[1] - q[1] * s[0]);
        });
    }
    if (volume < 0) {
        for (std::size_t f = 0; f + 1 < m.face_offsets.size(); ++f)
            std::reverse(m.face_points.begin() + m.face_offsets[f], m.face_points.begin() + m.face_offsets[f + 1]);
        r.notes.push_back("the grid's axes (I, J, K) are left-handed (depth downward): every face turned outward");
    }
    if (mapped)
        r.notes.push_back("MAPAXES applied: the points are in the map's coordinates");
    else if (!deck.mapaxes.empty())
        r.notes.push_back(deck.map_coordinates ? "MAPAXES not applied: GRIDUNIT says COORD is in map coordinates"
                                               : "MAPAXES not applied (as asked): the points are in the grid's own "
                                                 "coordinates");
    return r;
}

}  // namespace

LoadedCellMesh read_grdecl(const std::string& path, uint64_t max_cells, bool map_axes) {
    std::string shown;
    const std::vector<std::byte> bytes = io::read_whole_input(path, shown);
    Deck deck;
    Reader(deck, true, max_cells, fs::path(shown).parent_path()).read(io::text::as_text(bytes), shown, 0);
    return build_grid(deck, shown, map_axes);
}

LoadedCellMesh read_grdecl_memory(std::span<const std::byte> bytes, const std::string& name, uint64_t max_cells,
                                  bool map_axes) {
    Deck deck;
    Reader(deck, false, max_cells, {}).read(io::text::as_text(bytes), name, 0);
    return build_grid(deck, name, map_axes);
}

void write_grdecl_keyword(const std::string& path, const std::string& keyword, std::span<const double> values,
                          const LoadedCellMesh& grid) {
    const uint64_t cells = grid.grid_dims[0] * grid.grid_dims[1] * grid.grid_dims[2];
    if (grid.format != "grdecl" || cells == 0)
        throw std::invalid_argument("a GRDECL keyword is written for a corner-point grid (read from GRDECL) only");
    if (values.size() != grid.grid_index.size())
        throw std::invalid_argument("a GRDECL keyword needs one value per active cell (" +
                                    std::to_string(grid.grid_index.size()) + "), not " +
                                    std::to_string(values.size()));
    if (keyword.empty() || keyword.size() > 8 ||
        !std::all_of(keyword.begin(), keyword.end(), [](char c) {
            return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        }) || !(keyword[0] >= 'A' && keyword[0] <= 'Z'))
        throw std::invalid_argument("GRDECL keyword '" + keyword + "': 1 to 8 capitals, digits or '_', a capital first");
    std::vector<double> all(cells, 0.0);  // inactive cells 0
    for (std::size_t c = 0; c < values.size(); ++c) {
        if (!std::isfinite(values[c]))
            throw std::invalid_argument("a GRDECL keyword's values must be finite (cell " + std::to_string(c) + ")");
        if (grid.grid_index[c] >= cells) throw std::invalid_argument("grid_index out of the grid");
        all[grid.grid_index[c]] = values[c];
    }
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw std::runtime_error("cannot write " + tmp);
        out << "-- written by polyvol: one value per cell of the " << grid.grid_dims[0] << "x" << grid.grid_dims[1]
            << "x" << grid.grid_dims[2] << " grid, I fastest; inactive cells 0\n"
            << keyword << "\n";
        // Runs of equal values as N*v; each value the shortest decimal that
        // reads back as the same double; lines of at most 100 characters
        // (Eclipse reads 132).
        std::size_t width = 0;
        for (uint64_t c = 0; c < cells;) {
            uint64_t run = 1;
            while (c + run < cells && all[c + run] == all[c] && std::signbit(all[c + run]) == std::signbit(all[c]))
                ++run;
            char buffer[64];
            char* end = buffer;
            if (run > 1) {
                end = std::to_chars(end, buffer + sizeof buffer, run).ptr;
                *end++ = '*';
            }
            end = std::to_chars(end, buffer + sizeof buffer, all[c]).ptr;
            const auto size = static_cast<std::size_t>(end - buffer);
            if (width > 0 && width + 1 + size > 100) {
                out << '\n';
                width = 0;
            } else if (width > 0) {
                out << ' ';
                ++width;
            }
            out.write(buffer, end - buffer);
            width += size;
            c += run;
        }
        out << (width > 0 ? " " : "");
        out << "/\n";
        if (!out.flush()) throw std::runtime_error("cannot write " + tmp);
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw std::runtime_error("cannot write " + path + ": " + ec.message());
}

}  // namespace polyvol
