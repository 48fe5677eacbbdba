// io/chain.cpp — readers for n-D boundary chains (.chain), qhull's OFF output
// (`qconvex o Qt`) and plane polygons (one loop per line); see
// include/polyvol/chain.hpp and docs/chain-format.md.
//
// All three are line-structured: '#' starts a comment up to the end of the
// line, blank lines are skipped, every record is one line. Counts are checked
// against the bytes left before anything is allocated from them (every number
// takes at least two bytes: a digit and a separator).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "io/readers.hpp"
#include "io/text.hpp"
#include "polyvol/chain_io.hpp"

namespace polyvol {

std::string_view chain_format_name(ChainFormat f) { return f == ChainFormat::qhull ? "qhull" : "chain"; }

namespace {

using io::text::Cursor;
using io::text::found;
using io::text::parse_double;
using io::text::parse_int;

constexpr int kMaxDimension = 64;

std::vector<std::byte> slurp(const std::string& path, std::string& name) { return io::read_whole_input(path, name); }

bool is_gzip(std::span<const std::byte> d) {
    return d.size() >= 2 && d[0] == std::byte{0x1f} && d[1] == std::byte{0x8b};
}

// One line's tokens at a time, comments and blank lines skipped.
class Lines {
public:
    Lines(std::string_view text, std::string name) : cur_(text, '#'), name_(std::move(name)) {}

    // The next line with tokens; false at the end of the input.
    bool next() {
        for (;;) {
            if (cur_.at_end()) {
                toks_.clear();
                line_ = cur_.line();
                return false;
            }
            toks_.clear();
            line_ = cur_.line();
            for (auto t = cur_.next_on_line(); !t.empty(); t = cur_.next_on_line()) toks_.push_back(t);
            cur_.skip_line();
            if (!toks_.empty()) return true;
        }
    }
    const std::vector<std::string_view>& tokens() const { return toks_; }
    uint64_t line() const { return line_; }
    std::size_t remaining() const { return cur_.remaining(); }
    [[noreturn]] void fail(const std::string& what) const { throw ReadError(name_, line_, what); }

    int64_t integer(std::size_t i, const char* what) const {
        int64_t v = 0;
        if (!parse_int(toks_[i], v)) fail(std::string("expected ") + what + ", found " + found(toks_[i]));
        return v;
    }
    double real(std::size_t i, const char* what) const {
        double v = 0;
        if (!parse_double(toks_[i], v)) fail(std::string("expected ") + what + ", found " + found(toks_[i]));
        return v;
    }
    void expect_count(std::size_t want, const char* what) const {
        if (toks_.size() != want)
            fail("expected " + std::to_string(want) + " " + what + " on this line, found " +
                 std::to_string(toks_.size()));
    }

private:
    Cursor cur_;
    std::string name_;
    std::vector<std::string_view> toks_;
    uint64_t line_ = 0;
};

void read_points(Lines& in, int n, std::size_t m, std::vector<double>& out, const char* what) {
    out.reserve(m * n);
    for (std::size_t v = 0; v < m; ++v) {
        if (!in.next())
            in.fail("expected " + std::to_string(m) + " " + what + ", found end of file after " + std::to_string(v));
        in.expect_count(static_cast<std::size_t>(n), "coordinates");
        for (int i = 0; i < n; ++i) out.push_back(in.real(static_cast<std::size_t>(i), "a coordinate"));
    }
}

uint32_t index_at(const Lines& in, std::size_t i, std::size_t m) {
    const int64_t v = in.integer(i, "a vertex index");
    if (v < 0 || static_cast<uint64_t>(v) >= m)
        in.fail("vertex index " + std::to_string(v) + " out of range 0.." +
                (m == 0 ? std::string("(no vertices)") : std::to_string(m - 1)));
    return static_cast<uint32_t>(v);
}

void check_room(const Lines& in, uint64_t numbers, const std::string& what) {
    if (numbers > in.remaining() / 2 + 1)
        in.fail("the file is too short for " + what + " (" + std::to_string(in.remaining()) + " bytes left)");
}

LoadedChain read_dot_chain(Lines& in) {
    LoadedChain out;
    out.format = ChainFormat::chain;
    const int64_t n = in.integer(0, "the dimension n");
    const int64_t m = in.integer(1, "the vertex count m");
    const int64_t k = in.integer(2, "the simplex count k");
    if (n < 2 || n > kMaxDimension)
        in.fail("dimension " + std::to_string(n) + " outside 2.." + std::to_string(kMaxDimension));
    if (m < 0 || k < 0 || m >= 0xFFFFFFFFll || k >= 0xFFFFFFFFll) in.fail("vertex or simplex count out of range");
    const auto un = static_cast<uint64_t>(n), um = static_cast<uint64_t>(m), uk = static_cast<uint64_t>(k);
    check_room(in, un * (um + uk), std::to_string(m) + " vertices and " + std::to_string(k) + " simplices in R^" +
                                       std::to_string(n));
    Chain& c = out.chain;
    c.dimension = static_cast<int>(n);
    read_points(in, c.dimension, um, c.coordinates, "vertices");
    c.simplices.reserve(uk * un);
    for (uint64_t s = 0; s < uk; ++s) {
        if (!in.next())
            in.fail("expected " + std::to_string(k) + " simplices, found end of file after " + std::to_string(s));
        in.expect_count(un, "vertex indices");
        for (std::size_t i = 0; i < un; ++i) c.simplices.push_back(index_at(in, i, um));
    }
    if (in.next()) in.fail("unexpected data after the " + std::to_string(k) + " simplices: " + found(in.tokens()[0]));
    return out;
}

// The sign of det(a_0 - p, ..., a_{n-1} - p) when it is certain, else 0 (a
// flat facet). Gaussian elimination with partial pivoting has backward error
// |E| <= gamma_n |L||U| with |L| <= 1, so ||E e_c|| <= gamma_n n ||U e_c||;
// forming a - p adds at most 2u ||a_c - p|| per column; by Hadamard's
// inequality |det^ - det| <= H expm1(sum_c rel_c) with H = prod ||a_c - p||
// and rel_c those column errors over ||a_c - p|| (plus the rounding of the
// product of the pivots).
int orientation(const std::vector<double>& pts, const uint32_t* idx, int n, const std::vector<double>& p) {
    std::vector<double> m(static_cast<std::size_t>(n) * n);
    std::vector<double> norm(n);
    for (int c = 0; c < n; ++c) {
        double s = 0;
        for (int r = 0; r < n; ++r) {
            const double x = pts[std::size_t{idx[c]} * n + r] - p[r];
            m[r * n + c] = x;
            s += x * x;
        }
        norm[c] = std::sqrt(s);
    }
    int sign = 1;
    for (int k = 0; k < n; ++k) {
        int piv = k;
        for (int r = k + 1; r < n; ++r)
            if (std::abs(m[r * n + k]) > std::abs(m[piv * n + k])) piv = r;
        if (m[piv * n + k] == 0) return 0;
        if (piv != k) {
            for (int c = 0; c < n; ++c) std::swap(m[k * n + c], m[piv * n + c]);
            sign = -sign;
        }
        for (int r = k + 1; r < n; ++r) {
            const double l = m[r * n + k] / m[k * n + k];
            for (int c = k + 1; c < n; ++c) m[r * n + c] -= l * m[k * n + c];
        }
    }
    // Relative to Hadamard's bound, with |L| <= 1: ||E e_c|| <= gamma_n n ||U e_c||,
    // and the subtraction a - p adds u ||a_c - p|| per column.
    const double u = 0x1p-53;
    const double gn = n * u / (1 - n * u);
    double rel = 0, hadamard_log = 0, det_log = 0;
    for (int c = 0; c < n; ++c) {
        double s = 0;
        for (int r = 0; r <= c; ++r) s += m[r * n + c] * m[r * n + c];
        if (norm[c] == 0) return 0;
        rel += (gn * n * std::sqrt(s) + 2 * u * norm[c]) / norm[c];
        hadamard_log += std::log(norm[c]);
        det_log += std::log(std::abs(m[c * n + c]));
    }
    // |det - det^| <= H expm1(rel) (1 + small): decided when |det^| is larger by a margin.
    const double ratio_log = det_log - hadamard_log;  // log(|det^| / H)
    if (ratio_log <= std::log(std::expm1(rel * 1.01) * 1.01 + 4 * n * u)) return 0;
    for (int c = 0; c < n; ++c) sign = m[c * n + c] < 0 ? -sign : sign;
    return sign;
}

LoadedChain read_qhull(Lines& in) {
    LoadedChain out;
    out.format = ChainFormat::qhull;
    const int64_t n = in.integer(0, "the dimension");
    if (n < 2 || n > kMaxDimension)
        in.fail("dimension " + std::to_string(n) + " outside 2.." + std::to_string(kMaxDimension));
    if (!in.next()) in.fail("expected 'points facets ridges', found end of file");
    if (in.tokens().size() < 2 || in.tokens().size() > 3)
        in.fail("expected 'points facets ridges' (qhull's OFF output), found " + std::to_string(in.tokens().size()) +
                " numbers");
    const int64_t m = in.integer(0, "the point count");
    const int64_t f = in.integer(1, "the facet count");
    if (m < 0 || f < 0 || m >= 0xFFFFFFFFll || f >= 0xFFFFFFFFll) in.fail("point or facet count out of range");
    const auto un = static_cast<uint64_t>(n), um = static_cast<uint64_t>(m), uf = static_cast<uint64_t>(f);
    check_room(in, un * um + (un + 1) * uf, std::to_string(m) + " points and " + std::to_string(f) + " facets in R^" +
                                               std::to_string(n));
    Chain& c = out.chain;
    c.dimension = static_cast<int>(n);
    read_points(in, c.dimension, um, c.coordinates, "points");
    std::vector<uint32_t> facets;  // listed as read (fanned for n = 3)
    facets.reserve(uf * un);
    std::size_t fanned = 0;
    std::vector<uint32_t> idx;
    for (uint64_t s = 0; s < uf; ++s) {
        if (!in.next())
            in.fail("expected " + std::to_string(f) + " facets, found end of file after " + std::to_string(s));
        const auto& t = in.tokens();
        const int64_t count = in.integer(0, "a facet's vertex count");
        if (count < 0 || static_cast<std::size_t>(count) + 1 != t.size())
            in.fail("facet: the count " + std::to_string(count) + " does not match the " + std::to_string(t.size() - 1) +
                    " indices on the line");
        if (count < n || (count > n && n != 3))
            in.fail("facet of " + std::to_string(count) + " vertices in R^" + std::to_string(n) +
                    ": expected simplicial facets of " + std::to_string(n) + " (run qconvex with the option Qt)");
        idx.clear();
        for (int64_t i = 0; i < count; ++i) idx.push_back(index_at(in, static_cast<std::size_t>(i + 1), um));
        if (count == n) {
            facets.insert(facets.end(), idx.begin(), idx.end());
        } else {  // n = 3, a convex polygon in cyclic order: its fan
            ++fanned;
            for (std::size_t i = 1; i + 1 < idx.size(); ++i) {
                facets.push_back(idx[0]);
                facets.push_back(idx[i]);
                facets.push_back(idx[i + 1]);
            }
        }
    }
    if (in.next()) in.fail("unexpected data after the " + std::to_string(f) + " facets: " + found(in.tokens()[0]));
    out.qhull_facets = uf;
    if (fanned > 0) out.notes.push_back("qhull-fanned-facets(" + std::to_string(fanned) + ")");

    // Orient outward from the mean of the points the facets use.
    std::vector<uint8_t> used(um, 0);
    for (uint32_t v : facets) used[v] = 1;
    std::vector<double> p(un, 0.0);
    std::size_t nused = 0;
    for (std::size_t v = 0; v < um; ++v) {
        if (!used[v]) continue;
        ++nused;
        for (std::size_t i = 0; i < un; ++i) p[i] += c.coordinates[v * un + i];
    }
    if (nused > 0)
        for (double& x : p) x /= static_cast<double>(nused);
    for (std::size_t s = 0; s * un < facets.size(); ++s) {
        uint32_t* f0 = &facets[s * un];
        const int o = orientation(c.coordinates, f0, c.dimension, p);
        if (o < 0) {
            std::swap(f0[0], f0[1]);
            ++out.facets_reoriented;
        } else if (o == 0) {
            ++out.facets_undecided;
        }
    }
    if (out.facets_undecided > 0) out.notes.push_back("qhull-undecided-orientation(" + std::to_string(out.facets_undecided) + ")");
    c.simplices = std::move(facets);
    return out;
}

}  // namespace

LoadedChain read_chain_memory(std::span<const std::byte> data, const std::string& name) {
    if (is_gzip(data)) {  // one level, as for meshes' limit
        const std::vector<std::byte> plain = io::gunzip(data, name, io::decompression_limit(data.size()));
        if (is_gzip(plain)) throw ReadError::whole_file(name, "gzip nested in gzip: not read");
        LoadedChain r = read_chain_memory(plain, name);
        r.notes.push_back("gzip-compressed");
        return r;
    }
    Lines in(io::text::as_text(data), name);
    if (!in.next()) in.fail("empty: expected 'n m k' (.chain) or a dimension line (qhull output)");
    const std::size_t count = in.tokens().size();
    if (count == 3) return read_dot_chain(in);
    if (count == 1) return read_qhull(in);
    in.fail("expected 'n m k' (a .chain header) or one number (the dimension line of qhull's output), found " +
            std::to_string(count) + " tokens");
}

LoadedChain read_chain_file(const std::string& path) {
    std::string name;
    const std::vector<std::byte> data = slurp(path, name);
    return read_chain_memory(data, name);
}

Polygons read_polygons_memory(std::span<const std::byte> data, const std::string& name) {
    if (is_gzip(data)) {
        const std::vector<std::byte> plain = io::gunzip(data, name, io::decompression_limit(data.size()));
        if (is_gzip(plain)) throw ReadError::whole_file(name, "gzip nested in gzip: not read");
        return read_polygons_memory(plain, name);
    }
    Lines in(io::text::as_text(data), name);
    Polygons out;
    std::vector<double> xy;
    while (in.next()) {
        const auto& t = in.tokens();
        if (t.size() % 2 != 0)
            in.fail("expected pairs of coordinates x y, found " + std::to_string(t.size()) + " numbers");
        if (out.vertex_count() + t.size() / 2 >= 0xFFFFFFFFu) in.fail("too many vertices");
        xy.clear();
        for (std::size_t i = 0; i < t.size(); ++i) xy.push_back(in.real(i, "a coordinate"));
        out.add_loop(xy);
    }
    return out;
}

Polygons read_polygons_file(const std::string& path) {
    std::string name;
    const std::vector<std::byte> data = slurp(path, name);
    return read_polygons_memory(data, name);
}

}  // namespace polyvol
