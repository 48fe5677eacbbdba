// Reading an input file for a command: what cannot be read is reported on
// stderr (the caller exits with Exit::unreadable, 2).
#pragma once

#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "polyvol/io.hpp"

namespace polyvol::cli {

// read() (a reader of `file`), or nothing after printing why it failed: the
// ReadError's message, or that memory ran out.
template <class Read>
auto read_or_report(const std::string& file, Read read) -> std::optional<decltype(read())> {
    try {
        return read();
    } catch (const ReadError& e) {
        std::cerr << "polyvol: " << e.what() << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << "polyvol: " << file << ": out of memory while reading\n";
    }
    return std::nullopt;
}

}  // namespace polyvol::cli
