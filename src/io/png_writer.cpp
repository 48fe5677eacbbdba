// io/png_writer.cpp — a 2D field as a PNG figure, through stb_image_write
// (Debian's libstb: the implementation is in libstb.so, so no
// STB_IMAGE_WRITE_IMPLEMENTATION here) and stb_easy_font (header-only, its
// functions static) for the labels.
//
// Colour map: viridis (S. van der Walt and N. Smith for matplotlib, CC0),
// perceptually uniform and readable in grey and by colour-blind readers,
// sampled from matplotlib at 33 points and interpolated linearly (within
// 0.011 of the full map).
#include <stb/stb_image_write.h>
#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <stdexcept>
#include <vector>

#include "polyvol/grid_io.hpp"

namespace polyvol {
namespace {

constexpr float kViridis[33][3] = {
    {0.2670f, 0.0049f, 0.3294f}, {0.2770f, 0.0503f, 0.3757f}, {0.2823f, 0.0950f, 0.4173f}, {0.2829f, 0.1359f, 0.4534f},
    {0.2788f, 0.1755f, 0.4834f}, {0.2706f, 0.2141f, 0.5071f}, {0.2590f, 0.2515f, 0.5247f}, {0.2450f, 0.2877f, 0.5373f},
    {0.2297f, 0.3224f, 0.5457f}, {0.2143f, 0.3556f, 0.5512f}, {0.1994f, 0.3876f, 0.5546f}, {0.1856f, 0.4186f, 0.5568f},
    {0.1727f, 0.4488f, 0.5579f}, {0.1607f, 0.4785f, 0.5581f}, {0.1490f, 0.5081f, 0.5573f}, {0.1378f, 0.5375f, 0.5549f},
    {0.1276f, 0.5669f, 0.5506f}, {0.1206f, 0.5964f, 0.5436f}, {0.1206f, 0.6258f, 0.5335f}, {0.1323f, 0.6550f, 0.5197f},
    {0.1579f, 0.6838f, 0.5017f}, {0.1966f, 0.7118f, 0.4792f}, {0.2461f, 0.7389f, 0.4520f}, {0.3041f, 0.7647f, 0.4199f},
    {0.3692f, 0.7889f, 0.3829f}, {0.4401f, 0.8111f, 0.3410f}, {0.5160f, 0.8312f, 0.2943f}, {0.5958f, 0.8487f, 0.2433f},
    {0.6785f, 0.8637f, 0.1895f}, {0.7624f, 0.8764f, 0.1371f}, {0.8456f, 0.8873f, 0.0997f}, {0.9261f, 0.8973f, 0.1041f},
    {0.9932f, 0.9062f, 0.1439f}};

void colour(double t, uint8_t rgb[3]) {
    if (std::isnan(t)) {
        rgb[0] = rgb[1] = rgb[2] = 128;
        return;
    }
    t = std::clamp(t, 0.0, 1.0) * 32;
    const int i = std::min(31, static_cast<int>(t));
    const double f = t - i;
    for (int c = 0; c < 3; ++c) {
        const double v = kViridis[i][c] * (1 - f) + kViridis[i + 1][c] * f;
        rgb[c] = static_cast<uint8_t>(std::lround(255 * v));
    }
}

// An RGB canvas with the few drawing operations a figure needs.
class Canvas {
public:
    Canvas(std::size_t w, std::size_t h) : w_(w), h_(h), px_(w * h * 3, 255) {}
    std::size_t width() const { return w_; }
    void set(long x, long y, const uint8_t rgb[3]) {
        if (x < 0 || y < 0 || static_cast<std::size_t>(x) >= w_ || static_cast<std::size_t>(y) >= h_) return;
        uint8_t* p = &px_[(static_cast<std::size_t>(y) * w_ + static_cast<std::size_t>(x)) * 3];
        p[0] = rgb[0];
        p[1] = rgb[1];
        p[2] = rgb[2];
    }
    void fill(long x0, long y0, long x1, long y1, const uint8_t rgb[3]) {  // [x0, x1) x [y0, y1)
        for (long y = y0; y < y1; ++y)
            for (long x = x0; x < x1; ++x) set(x, y, rgb);
    }
    // Text with stb_easy_font's segments, `zoom` pixels per font unit; (x, y)
    // its top left, or its centre when centred.
    void text(const std::string& s, double x, double y, int zoom, bool centred = false) {
        std::string t = s;
        if (centred) {
            x -= 0.5 * zoom * stb_easy_font_width(t.data());
            y -= 3.5 * zoom;
        }
        std::vector<char> buf(64 * t.size() * 4 * 16 + 1024);
        const int quads = stb_easy_font_print(0, 0, t.data(), nullptr, buf.data(), static_cast<int>(buf.size()));
        static const uint8_t black[3] = {0, 0, 0};
        for (int q = 0; q < quads; ++q) {
            float v[4][4];
            std::memcpy(v, buf.data() + static_cast<std::size_t>(q) * 64, 64);  // 4 vertices of x, y, z, colour
            const auto xs = std::minmax({v[0][0], v[1][0], v[2][0], v[3][0]});
            const auto ys = std::minmax({v[0][1], v[1][1], v[2][1], v[3][1]});
            const double z = zoom;
            fill(std::lround(x + z * double{xs.first}), std::lround(y + z * double{ys.first}),
                 std::lround(x + z * double{xs.second}), std::lround(y + z * double{ys.second}), black);
        }
    }
    void save(const std::string& path) const {
        if (stbi_write_png(path.c_str(), static_cast<int>(w_), static_cast<int>(h_), 3, px_.data(),
                           static_cast<int>(w_ * 3)) == 0)
            throw std::runtime_error(path + ": cannot write the PNG");
    }

private:
    std::size_t w_, h_;
    std::vector<uint8_t> px_;
};

// About five "nice" ticks (1, 2 or 5 times a power of ten) within [lo, hi].
std::vector<double> ticks(double lo, double hi) {
    std::vector<double> t;
    if (!(hi > lo) || !std::isfinite(hi - lo)) return {lo};
    const double raw = (hi - lo) / 5, p = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / p < 1.5 ? p : raw / p < 3.5 ? 2 * p : raw / p < 7.5 ? 5 * p : 10 * p;
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step && t.size() < 20; v += step)
        t.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
    return t;
}

std::string label(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v + 0.0);
    return buf;
}

// The cell of each pixel along an axis: planes in world coordinates, `n`
// pixels over [planes.front(), planes.back()].
std::vector<std::size_t> cells_along(std::span<const double> planes, std::size_t n) {
    std::vector<std::size_t> cell(n);
    const double lo = planes.front(), span = planes.back() - planes.front();
    for (std::size_t p = 0; p < n; ++p) {
        const double w = lo + (static_cast<double>(p) + 0.5) / static_cast<double>(n) * span;
        const auto it = std::upper_bound(planes.begin(), planes.end(), w);
        cell[p] = std::min<std::size_t>(it == planes.begin() ? 0 : static_cast<std::size_t>(it - planes.begin()) - 1,
                                        planes.size() - 2);
    }
    return cell;
}

}  // namespace

void write_png_picture(const std::string& path, const FieldPicture& f) {
    const std::size_t nc = f.columns.size() - 1, nr = f.rows.size() - 1;
    if (f.columns.size() < 2 || f.rows.size() < 2 || f.values.size() != nc * nr)
        throw std::invalid_argument(path + ": the picture needs one value per cell");
    const double cw = f.columns.back() - f.columns.front(), rh = f.rows.back() - f.rows.front();
    if (!(cw > 0) || !(rh > 0) || !std::isfinite(cw) || !std::isfinite(rh))
        throw std::invalid_argument(path + ": the picture's planes must increase");
    // The plot keeps the world's aspect ratio within 640 pixels (64 at least a side).
    constexpr double kSide = 640, kMin = 64;
    double pw = kSide, ph = kSide;
    (cw >= rh ? ph : pw) = std::max(kMin, kSide * std::min(cw, rh) / std::max(cw, rh));
    const auto W = static_cast<std::size_t>(pw), H = static_cast<std::size_t>(ph);
    const long left = 90, top = 44, right = 120, bottom = 64;
    Canvas c(W + static_cast<std::size_t>(left + right), H + static_cast<std::size_t>(top + bottom));
    const double span = f.hi > f.lo ? f.hi - f.lo : 1;
    const std::vector<std::size_t> col = cells_along(f.columns, W), row = cells_along(f.rows, H);
    for (std::size_t y = 0; y < H; ++y)
        for (std::size_t x = 0; x < W; ++x) {
            const double v = f.values[row[H - 1 - y] * nc + col[x]];
            uint8_t rgb[3];
            colour(std::isnan(v) ? v : (v - f.lo) / span, rgb);
            c.set(left + static_cast<long>(x), top + static_cast<long>(y), rgb);
        }
    static const uint8_t black[3] = {0, 0, 0};
    const long L = left, T = top, R = left + static_cast<long>(W), B = top + static_cast<long>(H);
    c.fill(L - 1, T - 1, R + 1, T, black);
    c.fill(L - 1, B, R + 1, B + 1, black);
    c.fill(L - 1, T, L, B, black);
    c.fill(R, T, R + 1, B, black);
    // Axes: ticks and labels in world coordinates.
    for (double t : ticks(f.columns.front(), f.columns.back())) {
        const long x = L + std::lround((t - f.columns.front()) / cw * static_cast<double>(W));
        c.fill(x, B, x + 1, B + 6, black);
        c.text(label(t), static_cast<double>(x), static_cast<double>(B + 16), 2, true);
    }
    for (double t : ticks(f.rows.front(), f.rows.back())) {
        const long y = B - std::lround((t - f.rows.front()) / rh * static_cast<double>(H));
        c.fill(L - 6, y, L, y + 1, black);
        const std::string s = label(t);
        c.text(s, static_cast<double>(L - 10) - 2.0 * stb_easy_font_width(const_cast<char*>(s.c_str())),
               static_cast<double>(y - 6), 2);
    }
    c.text(f.column_label, static_cast<double>(L) + 0.5 * static_cast<double>(W), static_cast<double>(B + 44), 2, true);
    c.text(f.row_label, 8, static_cast<double>(T - 22), 2);
    c.text(f.title, 0.5 * static_cast<double>(c.width()), 16, 2, true);
    // The colour bar: lo at the bottom, hi at the top, with ticks.
    const long bx = R + 24;
    for (long y = T; y < B; ++y) {
        uint8_t rgb[3];
        colour(static_cast<double>(B - 1 - y) / static_cast<double>(B - 1 - T), rgb);
        c.fill(bx, y, bx + 20, y + 1, rgb);
    }
    c.fill(bx - 1, T - 1, bx + 21, T, black);
    c.fill(bx - 1, B, bx + 21, B + 1, black);
    c.fill(bx - 1, T, bx, B, black);
    c.fill(bx + 20, T, bx + 21, B, black);
    for (double t : ticks(f.lo, f.hi)) {
        const long y = B - std::lround((t - f.lo) / span * static_cast<double>(H));
        c.fill(bx + 20, y, bx + 26, y + 1, black);
        c.text(label(t), static_cast<double>(bx + 30), static_cast<double>(y - 6), 2);
    }
    c.text(f.value_label, static_cast<double>(bx - 10), static_cast<double>(T - 22), 2);
    c.save(path);
}

}  // namespace polyvol
