// Reading an input file for a command: what cannot be read is reported on
// stderr (the caller exits with Exit::unreadable, 2).
#pragma once

#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "polyvol/io.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/units.hpp"

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

// The meshes in one coordinate system (polyvol::common_unit with --units
// and --to): coordinates converted where units differ (their bound widened,
// LoadedMesh::coordinate_error), what was assumed or converted printed as
// warnings after each name; the common unit ("" when none is known), or
// nothing after printing why they cannot be put together.
inline std::optional<std::string> put_in_common_unit(const std::vector<std::string>& names,
                                                     const std::vector<LoadedMesh*>& meshes, const std::string& units,
                                                     const std::string& to) {
    std::vector<std::string> declared;
    for (const LoadedMesh* m : meshes) declared.push_back(m->unit);
    const CommonUnit c = common_unit(declared, units, to);
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        if (!c.error.empty() && c.notes[i] == c.error) {
            std::cerr << "polyvol: " << names[i] << ": " << c.error << ": --units gives it (" << kLengthUnitNames
                      << ")\n";
            return std::nullopt;
        }
        if (!c.notes[i].empty()) std::cerr << "polyvol: warning: " << names[i] << ": " << c.notes[i] << "\n";
        meshes[i]->coordinate_error = scale_coordinates(meshes[i]->mesh, c.factors[i], meshes[i]->coordinate_error);
    }
    if (!c.error.empty()) {
        std::cerr << "polyvol: " << c.error << "\n";
        return std::nullopt;
    }
    return c.unit;
}

}  // namespace polyvol::cli
