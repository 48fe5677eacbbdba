// src/io/note_words.cpp — polyvol/io.hpp's note_words: what each reader's
// note (LoadedMesh::notes) means, for people.
#include <string>
#include <string_view>
#include <utility>

#include "polyvol/io.hpp"

namespace polyvol {

std::string note_words(std::string_view note) {
    // A note is "name" or "name(argument)"; the argument goes into the words where "%" is.
    std::string_view name = note, argument;
    if (const auto open = note.find('('); open != std::string_view::npos && note.back() == ')') {
        name = note.substr(0, open);
        argument = note.substr(open + 1, note.size() - open - 2);
    }
    static constexpr std::pair<std::string_view, std::string_view> kWords[] = {
        {"3mf-bare-xml-not-zip", "a 3MF model part as bare XML, not in its zip package"},
        {"3mf-components", "objects built of components (each placed by its transform)"},
        {"3mf-transform", "parts placed by transforms, applied in floating point (the coordinates carry a bound)"},
        {"3mf-unit", "the file's unit is %"},
        {"amf-constellation-ignored", "the constellation (placed copies of objects) was ignored: each object is measured once"},
        {"amf-multiple-objects", "% objects, measured together"},
        {"amf-multiple-volumes", "a mesh with several volumes, measured together"},
        {"amf-unit", "the file's unit is %"},
        {"amf-zip-compressed", "zip-compressed AMF"},
        {"binary-stl-header-starts-with-solid", "a binary STL whose header begins with \"solid\" (read as binary, as its size says)"},
        {"bzip2-compressed", "read from bzip2-compressed data"},
        {"gltf-no-scene-all-meshes", "no scene: every mesh was measured, untransformed"},
        {"gltf-non-triangle-primitives-skipped", "% primitives that are not triangles (points, lines) skipped"},
        {"gltf-transform", "meshes placed by their nodes' transforms"},
        {"gzip-compressed", "read from gzip-compressed data"},
        {"obj-line-elements-ignored", "% line elements ignored"},
        {"obj-multiple-groups-or-objects", "several groups or objects, measured together"},
        {"obj-negative-indices", "relative (negative) vertex indices"},
        {"obj-point-elements-ignored", "% point elements ignored"},
        {"obj-slash-index-syntax", "faces with texture or normal indices (v/vt/vn): the vertex indices were used"},
        {"obj-vertex-colors", "vertex colours ignored"},
        {"obj-vertex-w-not-1", "vertex weights (w) other than 1 ignored"},
        {"off-face-colors", "face colours ignored"},
        {"off-missing-header", "no OFF header line"},
        {"off-trailing-data", "% after the last face ignored"},
        {"off-vertex-extra-values", "% extra values per vertex ignored (colours, normals)"},
        {"ply-double-coordinates", "double-precision coordinates"},
        {"ply-no-faces", "no faces"},
        {"ply-other-elements", "other elements ignored: %"},
        {"ply-trailing-data", "data after the last element ignored"},
        {"ply-vertex_index-name", "face lists named vertex_index (the usual name is vertex_indices)"},
        {"ply-unknown-header-line-ignored", "an unknown header line ignored"},
        {"qhull-fanned-facets", "% facets of more than three vertices fanned into triangles"},
        {"qhull-undecided-orientation", "% facets whose orientation could not be decided"},
        {"stl-endsolid-name-mismatch", "an endsolid line that names another solid"},
        {"stl-facet-without-normal", "facets without a normal"},
        {"stl-missing-endsolid", "no endsolid line at the end"},
        {"stl-multiple-solids", "% solids in one file, measured together"},
        {"stl-nonzero-attribute-bytes", "non-zero attribute bytes (often colours) ignored"},
        {"stl-trailing-nul-bytes", "NUL bytes after the end ignored"},
        {"stl-unparseable-normal", "a facet normal that could not be read (the winding decides the orientation)"},
        {"utf16-be-bom", "UTF-16 text (big-endian), read as UTF-8"},
        {"utf16-le-bom", "UTF-16 text (little-endian), read as UTF-8"},
        {"utf8-bom", "a UTF-8 byte-order mark"},
    };
    for (const auto& [key, words] : kWords) {
        if (key != name) continue;
        std::string out(words);
        if (const auto at = out.find('%'); at != std::string::npos) out.replace(at, 1, argument);
        return out;
    }
    if (name.starts_with("obj-face-with-"))
        return "faces of " + std::string(name.substr(14, name.find('-', 14) - 14)) + " vertices, which bound nothing (ignored)";
    if (name.starts_with("stl-loop-with-"))
        return "facets of " + std::string(name.substr(14, name.find('-', 14) - 14)) + " vertices, read as polygons";
    if (name.starts_with("off-header-")) return "an OFF variant header (" + std::string(name.substr(11)) + "), read as OFF";
    return std::string(note);
}

}  // namespace polyvol
