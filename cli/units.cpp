#include "units.hpp"

#include <charconv>
#include <cmath>
#include <utility>

namespace polyvol::cli {
namespace {

constexpr double kU = 0x1p-53;

// x is exactly the double the decimal text meant when it is an integer below
// 2^53 or a power of two: --scale 2, 10, 0.5 are exact, 0.1 is not. (A text
// with more digits than the double keeps, "1.0000000000000001", is caught by
// the caller: scale_only's text.)
bool exact_decimal(double x) {
    int e = 0;
    return (x == std::floor(x) && std::fabs(x) < 0x1p53) || std::frexp(x, &e) == 0.5;
}

}  // namespace

std::optional<LengthUnit> length_unit(std::string_view name) {
    static const std::pair<std::string_view, LengthUnit> kUnits[] = {
        {"micron", {"micron", 1, 1000000}}, {"um", {"micron", 1, 1000000}}, {"mm", {"mm", 1, 1000}},
        {"cm", {"cm", 1, 100}},             {"m", {"m", 1, 1}},               {"in", {"in", 254, 10000}},
        {"ft", {"ft", 3048, 10000}}};
    for (const auto& [n, u] : kUnits)
        if (n == name) return u;
    return std::nullopt;
}

LengthFactor scale_only(double scale, bool scale_typed_exactly) {
    return {scale, exact_decimal(scale) && scale_typed_exactly ? 0.0 : kU};
}

bool typed_exactly(const std::string& text, double value) {
    std::string t = !text.empty() && text[0] == '+' ? text.substr(1) : text;
    if (t.find('.') != std::string::npos && t.find_first_of("eE") == std::string::npos) {
        while (!t.empty() && t.back() == '0') t.pop_back();
        if (!t.empty() && t.back() == '.') t.pop_back();
    }
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, value);
    return t == std::string(buf, r.ptr);
}

LengthFactor length_factor(const LengthUnit& from, const LengthUnit& to, double scale, bool scale_typed_exactly) {
    // from / to = (from_num to_den) / (from_den to_num): integers far below 2^53.
    const long long p = from.metre_num * to.metre_den, q = from.metre_den * to.metre_num;
    const double ratio = static_cast<double>(p) / static_cast<double>(q);
    const bool ratio_exact = p % q == 0;
    LengthFactor f = scale_only(scale, scale_typed_exactly);
    f.relative_error += ratio_exact ? 0.0 : kU;
    const bool product_exact = ratio == 1 || scale == 1;
    f.factor = ratio * scale;
    f.relative_error += product_exact ? 0.0 : kU;
    return f;
}

std::optional<Density> parse_density(const std::string& text) {
    static const std::pair<std::string_view, double> kUnits[] = {
        {"kg/m3", 1},    {"kg/m^3", 1},    {"kg/m\u00b3", 1},
        {"g/cm3", 1000}, {"g/cm^3", 1000}, {"g/cm\u00b3", 1000}};
    double v = 0;
    const char* first = text.data() + (!text.empty() && text[0] == '+');
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || !std::isfinite(v) || !(v > 0)) return std::nullopt;
    std::string_view rest(end, static_cast<std::size_t>(last - end));
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
    Density d;
    d.value = v;
    if (rest.empty()) return d;
    for (const auto& [unit, to_si] : kUnits)
        if (rest == unit) {
            d.si = true;
            d.kg_per_m3 = v * to_si;
            return d;
        }
    return std::nullopt;
}

}  // namespace polyvol::cli
