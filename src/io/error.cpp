// ReadError: where a reader stopped and why, formatted the way compilers do
//   FILE:LINE: message          (text formats, 1-based line)
//   FILE: byte OFFSET: message  (binary formats, offset into the decompressed data)
//   FILE: message               (the file as a whole)
#include <string>
#include <utility>

#include "polyvol/io.hpp"

namespace polyvol {

namespace {

std::string describe(const std::string& file, uint64_t line, bool has_byte_offset,
                     uint64_t byte_offset, const std::string& message) {
    std::string s = file;
    if (has_byte_offset) {
        s += ": byte ";
        s += std::to_string(byte_offset);
    } else if (line != 0) {
        s += ':';
        s += std::to_string(line);
    }
    s += ": ";
    s += message;
    return s;
}

}  // namespace

ReadError::ReadError(std::string file_, uint64_t line_, std::string message_)
    : std::runtime_error(describe(file_, line_, false, 0, message_)),
      file(std::move(file_)),
      line(line_),
      message(std::move(message_)) {}

ReadError ReadError::at_byte(std::string file_name, uint64_t offset, std::string what) {
    ReadError e(std::move(file_name), 0, std::move(what));
    e.byte_offset = offset;
    e.has_byte_offset = true;
    static_cast<std::runtime_error&>(e) =
        std::runtime_error(describe(e.file, 0, true, offset, e.message));
    return e;
}

ReadError ReadError::whole_file(std::string file_name, std::string what) {
    return ReadError(std::move(file_name), 0, std::move(what));
}

}  // namespace polyvol
