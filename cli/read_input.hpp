// Reading an input file for a command: what cannot be read is reported on
// stderr (the caller exits with Exit::unreadable, 2).
#pragma once

#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "polyvol/io.hpp"
#include "polyvol/solid.hpp"

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

// The solid `mesh` means (polyvol/solid.hpp), its notes printed as warnings
// after `name`; nothing after printing why it is not one (the caller exits
// with Exit::invalid, 3).
inline std::optional<MeshSolid> solid_or_report(const std::string& name, Mesh& mesh, const SolidOptions& options) {
    MeshSolid s = make_solid(mesh, options);
    for (const SolidNote& n : s.notes) std::cerr << "polyvol: warning: " << name << ": " << n.text << "\n";
    if (s.status == SolidStatus::ok) return s;
    std::cerr << "polyvol: " << name << ": " << s.message << "\n";
    return std::nullopt;
}

}  // namespace polyvol::cli
