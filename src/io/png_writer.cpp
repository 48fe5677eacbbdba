// io/png_writer.cpp — a 2D field as a PNG picture, through stb_image_write
// (Debian's libstb: the implementation is in libstb.so, so no
// STB_IMAGE_WRITE_IMPLEMENTATION here).
//
// Colour map: viridis (S. van der Walt and N. Smith for matplotlib, CC0),
// perceptually uniform and readable in grey and by colour-blind readers,
// sampled from matplotlib at 33 points and interpolated linearly (within
// 0.011 of the full map).
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

}  // namespace

void write_png_field(const std::string& path, std::span<const double> values, std::size_t width,
                     std::size_t height, double lo, double hi, int scale) {
    if (width == 0 || height == 0 || values.size() != width * height)
        throw std::invalid_argument(path + ": the picture needs width * height values");
    if (scale < 1) scale = 1;
    const std::size_t s = static_cast<std::size_t>(scale);
    const std::size_t w = width * s, h = height * s;
    if (w > 32768 || h > 32768) throw std::invalid_argument(path + ": picture too large");
    const double span = hi > lo ? hi - lo : 1;
    std::vector<uint8_t> pixels(w * h * 3);
    for (std::size_t r = 0; r < height; ++r)
        for (std::size_t c = 0; c < width; ++c) {
            const double v = values[r * width + c];
            uint8_t rgb[3];
            colour(std::isnan(v) ? v : (v - lo) / span, rgb);
            for (std::size_t dr = 0; dr < s; ++dr)
                for (std::size_t dc = 0; dc < s; ++dc) {
                    uint8_t* p = &pixels[((r * s + dr) * w + c * s + dc) * 3];
                    p[0] = rgb[0];
                    p[1] = rgb[1];
                    p[2] = rgb[2];
                }
        }
    if (stbi_write_png(path.c_str(), static_cast<int>(w), static_cast<int>(h), 3, pixels.data(),
                       static_cast<int>(w * 3)) == 0)
        throw std::runtime_error(path + ": cannot write the PNG");
}

}  // namespace polyvol
