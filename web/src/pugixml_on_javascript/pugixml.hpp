// web/src/pugixml_on_javascript/pugixml.hpp — the part of pugixml's interface
// the 3MF and AMF readers (src/io/threemf.cpp, amf.cpp, xml_names.hpp) use, over
// a document parsed in JavaScript (web/js/xml.mjs, @rgrove/parse-xml from npm):
// Debian builds pugixml for no wasm target, and has no source package of it.
// The readers are compiled unchanged against this header.
//
// What pugixml's parse_default keeps is kept: elements, text (pcdata) that is
// not all white space, CDATA sections; comments, processing instructions and
// the declaration are dropped. Names are as written (prefix included).
// offset_debug() is the byte offset of the node in the buffer given, as
// pugixml's is, when the encoding is UTF-8 (what the readers check).
// Parse errors carry the parser's own words, not pugixml's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>

namespace pugi {

enum xml_node_type { node_null, node_document, node_element, node_pcdata, node_cdata };
enum xml_encoding { encoding_auto, encoding_utf8, encoding_utf16_le, encoding_utf16_be, encoding_latin1 };
enum xml_parse_status { status_ok, status_parse_error };
constexpr unsigned int parse_default = 0x0074;  // pugixml's value; the only mode there is

namespace detail {
// The parsed document as tables (laid out by web/js/xml.mjs): node 0 is the
// document; each node is kFields int32s; each attribute is (name, value);
// a string is an ordinal into the NUL-separated UTF-8 text.
struct Tree {
    enum Field { type, name, value, first_child, next_sibling, first_attribute, attribute_count, offset, kFields };
    std::unique_ptr<void, decltype(&std::free)> block{nullptr, &std::free};  // from JavaScript's malloc
    const int32_t* nodes = nullptr;
    const int32_t* attributes = nullptr;
    std::unique_ptr<uint32_t[]> string_at;  // byte position of each string in `text`
    const char* text = nullptr;
    int32_t nodes_held = 0;
    int32_t attributes_held = 0;

    int32_t field(int32_t node, Field f) const { return nodes[node * kFields + f]; }
    const char* string(int32_t ordinal) const { return text + string_at[ordinal]; }
};
}  // namespace detail

class xml_attribute {
public:
    xml_attribute() = default;
    xml_attribute(const detail::Tree* t, int32_t i) : t_(t), i_(i) {}
    explicit operator bool() const { return t_ != nullptr; }
    bool operator!() const { return t_ == nullptr; }
    const char* name() const { return t_ ? t_->string(t_->attributes[2 * i_]) : ""; }
    const char* value() const { return t_ ? t_->string(t_->attributes[2 * i_ + 1]) : ""; }

private:
    const detail::Tree* t_ = nullptr;
    int32_t i_ = 0;
};

class xml_node;

// A range of nodes (next_sibling links) or of attributes (consecutive), for range-for.
template <class T>
class xml_range {
public:
    class iterator {
    public:
        iterator(const detail::Tree* t, int32_t i, bool nodes) : t_(t), i_(i), nodes_(nodes) {}
        T operator*() const { return T(t_, i_); }
        iterator& operator++() {
            i_ = nodes_ ? t_->field(i_, detail::Tree::next_sibling) : i_ + 1;
            return *this;
        }
        bool operator!=(const iterator& o) const { return i_ != o.i_; }

    private:
        const detail::Tree* t_;
        int32_t i_;
        bool nodes_;
    };
    xml_range(iterator b, iterator e) : b_(b), e_(e) {}
    iterator begin() const { return b_; }
    iterator end() const { return e_; }

private:
    iterator b_, e_;
};

class xml_node {
public:
    xml_node() = default;
    xml_node(const detail::Tree* t, int32_t i) : t_(t), i_(i) {}
    explicit operator bool() const { return t_ != nullptr; }
    bool operator!() const { return t_ == nullptr; }

    xml_node_type type() const { return t_ ? static_cast<xml_node_type>(f(detail::Tree::type)) : node_null; }
    const char* name() const { return t_ ? t_->string(f(detail::Tree::name)) : ""; }
    const char* value() const { return t_ ? t_->string(f(detail::Tree::value)) : ""; }
    std::ptrdiff_t offset_debug() const { return t_ ? f(detail::Tree::offset) : -1; }

    xml_range<xml_node> children() const {
        using It = xml_range<xml_node>::iterator;
        const int32_t first = t_ ? f(detail::Tree::first_child) : -1;
        return {It(t_, first, true), It(t_, -1, true)};
    }
    xml_range<xml_attribute> attributes() const {
        using It = xml_range<xml_attribute>::iterator;
        const int32_t first = t_ ? f(detail::Tree::first_attribute) : 0;
        const int32_t n = t_ ? f(detail::Tree::attribute_count) : 0;
        return {It(t_, first, false), It(t_, first + n, false)};
    }
    // The attribute named `n` exactly, or a null attribute.
    xml_attribute attribute(const char* n) const {
        for (xml_attribute a : attributes())
            if (std::string_view(a.name()) == n) return a;
        return {};
    }
    // The text of the first pcdata or CDATA child, or "".
    const char* child_value() const {
        for (xml_node c : children())
            if (c.type() == node_pcdata || c.type() == node_cdata) return c.value();
        return "";
    }

private:
    int32_t f(detail::Tree::Field k) const { return t_->field(i_, k); }
    const detail::Tree* t_ = nullptr;
    int32_t i_ = 0;
};

struct xml_parse_result {
    xml_parse_status status = status_parse_error;
    std::ptrdiff_t offset = 0;  // bytes into the buffer
    xml_encoding encoding = encoding_auto;
    std::string message;
    explicit operator bool() const { return status == status_ok; }
    const char* description() const { return message.c_str(); }
};

class xml_document {
public:
    xml_document() = default;
    xml_document(const xml_document&) = delete;
    xml_document& operator=(const xml_document&) = delete;

    // Parses contents[0, size) (copied; `contents` may go after the call), as
    // pugixml::load_buffer with parse_default and encoding_auto does.
    xml_parse_result load_buffer(const void* contents, std::size_t size, unsigned int options = parse_default,
                                 xml_encoding encoding = encoding_auto);

    // The first element child of the document, or a null node.
    xml_node document_element() const {
        if (tree_.nodes_held == 0) return {};
        for (xml_node c : xml_node(&tree_, 0).children())
            if (c.type() == node_element) return c;
        return {};
    }

private:
    detail::Tree tree_;
};

}  // namespace pugi
