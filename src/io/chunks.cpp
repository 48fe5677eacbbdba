// The shared pieces of the parallel text readers (chunks.hpp).
#include "io/chunks.hpp"

#include <algorithm>
#include <cstring>

#include <tbb/parallel_for.h>

#include "core/prefault.hpp"
#include "io/text.hpp"

namespace polyvol::io {

ParseOptions& thread_parse_options() {
    thread_local ParseOptions options;
    return options;
}

ParseReport& thread_parse_report() {
    thread_local ParseReport report;
    return report;
}

namespace chunks {

using text::is_blank;
using text::is_eol;

std::size_t next_line_start(std::string_view text, std::size_t p) {
    const std::size_t n = text.size();
    while (p < n && !is_eol(text[p])) ++p;
    if (p >= n) return n;
    if (text[p] == '\r' && p + 1 < n && text[p + 1] == '\n') return p + 2;
    return p + 1;
}

std::vector<std::size_t> split(std::string_view text, std::size_t target, AcceptFn accept) {
    const std::size_t n = text.size();
    const std::size_t step = chunk_size(target, n);
    std::vector<std::size_t> starts{0};
    for (;;) {
        const std::size_t want = starts.back() + step;
        if (want >= n) break;
        // A line start exactly at `want` counts: search from the byte before.
        std::size_t p = next_line_start(text, want - 1);
        while (p < n && !accept(text, p)) p = next_line_start(text, p);
        if (p >= n) break;
        starts.push_back(p);
    }
    starts.push_back(n);
    return starts;
}

uint64_t count_line_ends(std::string_view text) {
    uint64_t ends = 0;
    const std::size_t n = text.size();
    for (std::size_t i = 0; i < n; ++i) {
        const char c = text[i];
        ends += static_cast<uint64_t>(c == '\n' || (c == '\r' && (i + 1 == n || text[i + 1] != '\n')));
    }
    return ends;
}

LineCounts count_lines(std::string_view text, char comment) {
    LineCounts c;
    if (count_plain_lines(text, comment, c)) return c;
    c = {};
    const char* p = text.data();
    const char* const end = p + text.size();
    // Without any '\r' a line ends at the next '\n', found with memchr.
    const bool has_cr = std::memchr(p, '\r', text.size()) != nullptr;
    while (p < end) {
        while (p < end && is_blank(*p)) ++p;
        if (p == end) break;
        if (!is_eol(*p) && !(comment != '\0' && *p == comment)) ++c.data_lines;
        if (has_cr) {
            while (p < end && !is_eol(*p)) ++p;
        } else {
            const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
            p = nl == nullptr ? end : static_cast<const char*>(nl);
        }
        if (p == end) break;
        if (*p == '\r' && p + 1 < end && p[1] == '\n') ++p;
        ++p;
        ++c.line_ends;
    }
    return c;
}

void for_each(std::size_t n, const std::function<void(std::size_t)>& f) {
    if (n == 1) return f(0);  // the serial readers: no task
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) { f(i); });
}

LineChunks split_line_body(std::string_view body, std::size_t target, char comment) {
    LineChunks c;
    c.starts = split(body, target, [](std::string_view, std::size_t) { return true; });
    const std::size_t n = c.starts.size() - 1;
    if (n < 2) return {};
    ParseReport& report = thread_parse_report();
    report.chunks = n;
    report.serial_fallback = true;  // until the pieces agree
    c.counts.resize(n);
    for_each(n, [&](std::size_t i) { c.counts[i] = count_lines(c.chunk(body, i), comment); });
    for (const LineCounts& k : c.counts) c.data_lines += k.data_lines;
    return c;
}

void concat(std::vector<Mesh>& parts, Mesh& out, bool shift_indices) {
    if (parts.size() == 1 && out.positions.empty() && out.indices.empty()) {
        // One part, nothing before it: its vertex numbering is already global.
        out.positions = std::move(parts[0].positions);
        out.indices = std::move(parts[0].indices);
        out.face_offsets = std::move(parts[0].face_offsets);
        parts[0] = Mesh{};
        return;
    }
    const std::size_t k = parts.size();
    // Where each part goes: vertex, position, index and face bases.
    std::vector<std::size_t> pos_base(k + 1), idx_base(k + 1), face_base(k + 1);
    pos_base[0] = out.positions.size();
    idx_base[0] = out.indices.size();
    face_base[0] = out.face_count();
    bool polygons = !out.face_offsets.empty();
    for (std::size_t i = 0; i < k; ++i) {
        pos_base[i + 1] = pos_base[i] + parts[i].positions.size();
        idx_base[i + 1] = idx_base[i] + parts[i].indices.size();
        face_base[i + 1] = face_base[i] + parts[i].face_count();
        polygons = polygons || !parts[i].face_offsets.empty();
    }
    if (polygons && out.face_offsets.empty()) {
        // What Mesh::add_face does on leaving the all-triangle path.
        out.face_offsets.resize(face_base[0] + 1);
        for (std::size_t f = 0; f <= face_base[0]; ++f) out.face_offsets[f] = static_cast<uint32_t>(3 * f);
    }
    core::resize_for_filling(out.positions, pos_base[k]);
    core::resize_for_filling(out.indices, idx_base[k]);
    if (polygons) out.face_offsets.resize(face_base[k] + 1);
    for_each(k, [&](std::size_t i) {
        Mesh& part = parts[i];
        std::copy(part.positions.begin(), part.positions.end(), out.positions.begin() + static_cast<std::ptrdiff_t>(pos_base[i]));
        const auto shift = static_cast<uint32_t>(shift_indices ? pos_base[i] / 3 : 0);
        uint32_t* idx = out.indices.data() + idx_base[i];
        for (std::size_t j = 0; j < part.indices.size(); ++j) idx[j] = part.indices[j] + shift;
        if (polygons) {
            uint32_t* off = out.face_offsets.data() + face_base[i] + 1;
            const std::size_t nf = part.face_count();
            const auto ib = static_cast<uint32_t>(idx_base[i]);
            if (part.face_offsets.empty()) {
                for (std::size_t f = 0; f < nf; ++f) off[f] = ib + static_cast<uint32_t>(3 * (f + 1));
            } else {
                for (std::size_t f = 0; f < nf; ++f) off[f] = ib + part.face_offsets[f + 1];
            }
        }
        part = Mesh{};
    });
}

void note_once(std::vector<std::string>& notes, std::string note) {
    if (std::find(notes.begin(), notes.end(), note) == notes.end()) notes.push_back(std::move(note));
}

}  // namespace chunks
}  // namespace polyvol::io
