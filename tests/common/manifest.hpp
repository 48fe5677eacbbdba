// The shared corpus (../shared/corpus, POLYVOL_CORPUS_DIR from
// tests/CMakeLists.txt) and its manifest.json, for the test programs that
// check polyvol against it. The manifest is an array with one entry per
// file; the fields used to pick files (the corpus README describes the rest):
//   path      the file, relative to the corpus directory: "meshes/<set>/<name>"
//   category  "valid", "quirky" or "invalid" (every reader must refuse the file)
//   format    "stl", "obj", "off", "ply", "3mf" or "amf"
// Reference figures are given as {"hex": exact double, "double": ...}: see
// corpus_reference().
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace polyvol::test {

// The corpus directory: POLYVOL_CORPUS_DIR, ../shared/corpus unless configured.
inline const std::filesystem::path& corpus_dir() {
    static const std::filesystem::path dir = POLYVOL_CORPUS_DIR;
    return dir;
}

// A corpus file by its manifest path, as read_mesh_file takes it.
inline std::string corpus_file(const std::string& path) { return (corpus_dir() / path).string(); }

// The manifest, read once; an empty array when the corpus is missing (the
// tests that need it fail on that).
inline const nlohmann::json& corpus_manifest() {
    static const nlohmann::json m = [] {
        std::ifstream in(corpus_dir() / "manifest.json");
        return in ? nlohmann::json::parse(in) : nlohmann::json::array();
    }();
    return m;
}

inline bool invalid_entry(const nlohmann::json& e) { return e.value("category", "") == "invalid"; }

// The manifest paths of the entries for which keep(entry) holds, in manifest
// order: the parameters of a corpus TEST_P (short to print).
template <class Keep>
std::vector<std::string> manifest_paths(Keep keep) {
    std::vector<std::string> out;
    for (const nlohmann::json& e : corpus_manifest())
        if (keep(e)) out.push_back(e.at("path").get<std::string>());
    return out;
}

// Every manifest path.
inline std::vector<std::string> manifest_paths() {
    return manifest_paths([](const nlohmann::json&) { return true; });
}

// The paths of the files that read without error (category not "invalid").
inline std::vector<std::string> readable_paths() {
    return manifest_paths([](const nlohmann::json& e) { return !invalid_entry(e); });
}

// The entry with this path; throws when there is none.
inline const nlohmann::json& manifest_entry(const std::string& path) {
    for (const nlohmann::json& e : corpus_manifest())
        if (e.at("path") == path) return e;
    throw std::runtime_error("no manifest entry " + path);
}

// A reference figure as a double: its exact hex spelling when given (the
// correctly rounded value), else its "double" field.
inline double corpus_reference(const nlohmann::json& figure) {
    if (figure.contains("hex")) return std::strtod(figure.at("hex").get<std::string>().c_str(), nullptr);
    return figure.at("double").get<double>();
}

// A test name for a manifest path: the path without "meshes/", every
// character but letters and digits replaced by '_'.
inline std::string corpus_test_name(const std::string& path) {
    std::string s = path.substr(path.find('/') + 1);
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

// The name generator of INSTANTIATE_TEST_SUITE_P over manifest paths.
inline std::string corpus_param_name(const testing::TestParamInfo<std::string>& info) {
    return corpus_test_name(info.param);
}

}  // namespace polyvol::test
