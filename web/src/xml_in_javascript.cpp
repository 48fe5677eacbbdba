// web/src/xml_in_javascript.cpp — pugi::xml_document::load_buffer for the
// WebAssembly build (web/src/pugixml_on_javascript/pugixml.hpp): the bytes are
// parsed by web/js/xml.mjs (Module.xmlTables) and come back as one malloc'ed
// block of tables, which the document keeps.
#include <emscripten.h>

#include <cstring>
#include <string>

#include <pugixml.hpp>

namespace {

// The block: int32 {encoding, nodes, attributes, string bytes, strings}, then
// the nodes' fields, the attributes' pairs and the NUL-terminated strings.
// Null on failure, with a malloc'ed message in *error and the byte offset in
// *error_offset.
EM_JS(void*, polyvol_js_parse_xml, (const void* data, size_t size, char** error, double* error_offset), {
    // Pointers past 2 GiB arrive negative: read them unsigned.
    data >>>= 0; size >>>= 0; error >>>= 0; error_offset >>>= 0;
    const fail = (text, offset) => {
        const n = lengthBytesUTF8(text) + 1;
        const p = _malloc(n) >>> 0;
        if (p) stringToUTF8(text, p, n);
        HEAPU32[error >>> 2] = p;
        HEAPF64[error_offset >>> 3] = offset;
        return 0;
    };
    let t;
    try {
        const tables = Module['xmlTables'];
        if (!tables) return fail('3MF and AMF need an XML parser (web/js/core.mjs passes it to the module)', 0);
        t = tables(HEAPU8.subarray(data, data + size));
    } catch (e) {
        return fail(String(e && e.message ? e.message : e), 0);
    }
    if (!t.ok) return fail(t.message, t.offset);
    const header = 5 * 4;
    const total = header + 4 * (t.nodes.length + t.attributes.length) + t.strings.length;
    const p = _malloc(total) >>> 0;
    if (!p) return fail('out of memory for the parsed XML (' + total + ' bytes)', 0);
    HEAP32.set([t.encoding, t.nodes.length / 8, t.attributes.length / 2, t.strings.length, t.stringCount], p >>> 2);
    HEAP32.set(t.nodes, (p + header) >>> 2);
    HEAP32.set(t.attributes, (p + header + 4 * t.nodes.length) >>> 2);
    HEAPU8.set(t.strings, p + header + 4 * (t.nodes.length + t.attributes.length));
    return p;
});

}  // namespace

namespace pugi {

xml_parse_result xml_document::load_buffer(const void* contents, std::size_t size, unsigned int, xml_encoding) {
    tree_ = detail::Tree{};
    xml_parse_result r;
    char* error = nullptr;
    double error_offset = 0;
    void* block = polyvol_js_parse_xml(contents, size, &error, &error_offset);
    if (block == nullptr) {
        r.message = error ? error : "out of memory";
        std::free(error);
        r.offset = static_cast<std::ptrdiff_t>(error_offset);
        return r;
    }
    tree_.block.reset(block);
    const auto* header = static_cast<const int32_t*>(block);
    const int32_t string_bytes = header[3];
    const int32_t string_count = header[4];
    tree_.nodes_held = header[1];
    tree_.attributes_held = header[2];
    tree_.nodes = header + 5;
    tree_.attributes = tree_.nodes + std::size_t(tree_.nodes_held) * detail::Tree::kFields;
    tree_.text = reinterpret_cast<const char*>(tree_.attributes + 2 * std::size_t(tree_.attributes_held));
    // Each string's start: the strings are separated by NULs (XML text holds none).
    tree_.string_at = std::make_unique<uint32_t[]>(std::size_t(string_count));
    int32_t k = 0, at = 0;
    for (; at < string_bytes && k < string_count; ++k) {
        tree_.string_at[std::size_t(k)] = static_cast<uint32_t>(at);
        const void* nul = std::memchr(tree_.text + at, 0, std::size_t(string_bytes - at));
        at = nul ? static_cast<int32_t>(static_cast<const char*>(nul) - tree_.text) + 1 : string_bytes + 1;
    }
    if (k != string_count || at != string_bytes || tree_.nodes_held < 1) {
        tree_ = detail::Tree{};
        r.message = "the XML parser's tables are inconsistent (a NUL in the text?)";
        return r;
    }
    r.status = status_ok;
    r.encoding = static_cast<xml_encoding>(header[0]);
    return r;
}

}  // namespace pugi
