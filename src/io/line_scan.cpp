// io/line_scan.cpp — count_plain_lines (io/chunks.hpp) compiled once per
// instruction set (Highway's foreach_target), chosen at run time by the
// library's dispatch (core/hwy_dispatch.hpp): a text's '\n' counted a
// vector of bytes at a time, with the check that makes the count the
// number of data lines (no '\r', and every line starting with a token).
#include "core/hwy_targets.hpp"  // before Highway

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "io/line_scan.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "io/chunks.hpp"
#include "io/text.hpp"

HWY_BEFORE_NAMESPACE();
namespace polyvol::io::chunks::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// a: bytes i .. i + N - 1; b: the bytes after them (the starts of the lines
// that the '\n' in a end). A '\r' anywhere, or a '\n' followed by a blank,
// another line end or the comment character, and the text is not plain.
bool CountPlainLines(std::string_view text, char comment, LineCounts& c) {
    const std::size_t n = text.size();
    const auto* s = reinterpret_cast<const uint8_t*>(text.data());
    auto bad_start = [&](uint8_t ch) {
        return text::is_blank(static_cast<char>(ch)) || text::is_eol(static_cast<char>(ch)) ||
               (comment != '\0' && static_cast<char>(ch) == comment);
    };
    if (n == 0) return true;
    if (bad_start(s[0])) return false;
    const hn::ScalableTag<uint8_t> d;
    const std::size_t lanes = hn::Lanes(d);
    const auto nl = hn::Set(d, '\n'), cr = hn::Set(d, '\r'), sp = hn::Set(d, ' '), tab = hn::Set(d, '\t');
    const auto vt = hn::Set(d, '\v'), ff = hn::Set(d, '\f');
    const auto hash = hn::Set(d, static_cast<uint8_t>(comment != '\0' ? comment : '\n'));
    uint64_t ends = 0;
    std::size_t i = 0;
    for (; i + lanes + 1 <= n; i += lanes) {
        const auto a = hn::LoadU(d, s + i), b = hn::LoadU(d, s + i + 1);
        const auto is_nl = hn::Eq(a, nl);
        const auto next_bad = hn::Or(hn::Or(hn::Or(hn::Eq(b, nl), hn::Eq(b, sp)), hn::Or(hn::Eq(b, tab), hn::Eq(b, vt))),
                                     hn::Or(hn::Eq(b, ff), hn::Eq(b, hash)));
        if (!hn::AllFalse(d, hn::Or(hn::And(is_nl, next_bad), hn::Eq(a, cr)))) return false;
        ends += hn::CountTrue(d, is_nl);
    }
    for (; i < n; ++i) {
        if (s[i] == '\r') return false;
        if (s[i] == '\n') {
            ++ends;
            if (i + 1 < n && bad_start(s[i + 1])) return false;
        }
    }
    c.line_ends = ends;
    c.data_lines = s[n - 1] == '\n' ? ends : ends + 1;
    return true;
}

}  // namespace polyvol::io::chunks::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "core/hwy_dispatch.hpp"

namespace polyvol::io::chunks {

bool count_plain_lines(std::string_view text, char comment, LineCounts& c) {
    return POLYVOL_DISPATCH(CountPlainLines)(text, comment, c);
}

}  // namespace polyvol::io::chunks
#endif  // HWY_ONCE
