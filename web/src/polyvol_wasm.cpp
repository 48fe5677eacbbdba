// web/src/polyvol_wasm.cpp — the WebAssembly module's entry point: one call
// per request, JSON in and JSON out, for the page's worker and the npm
// package (web/js/core.mjs). The figures and their keys are the library's
// (measure_file, report_json): `polyvol volume|measure|check --json` prints
// the same objects.
//
// While a file is measured, Module.onProgress(file, stage, fraction) is
// called if set (FileOptions::progress: "reading", "checking", "measuring").
//
//   request: {"command": "volume" | "measure" | "check" | "overlap",
//             "files": ["a.stl", ...],           (paths in the module's file system; overlap: A and B)
//             "options": {RequestWords' fields}} (polyvol/report.hpp; overlap: OverlapWords')
//   answer:  {"exit_code": 0|1|2|3|4,
//             "stdout": the command's --json output, byte for byte (its text),
//             "messages": ["polyvol: ...", ...], (what the command line prints on stderr)
//             "csv": what `measure --csv` prints (measure only),
//             "note_words": {each reader's note in the results: its words (note_words)}}
//
// polyvol_mesh: a file's triangles and what `check` finds wrong, for a 3D view:
//   request: {"file": "a.stl", "member": "" (an archive's), "edge_limit": N}
//   answer:  a block (see mesh_block) of the header's JSON and typed arrays
#include <emscripten.h>

#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/report.hpp"
#include "polyvol/topology.hpp"

namespace {

using nlohmann::json;
using polyvol::Exit;

// FileOptions::progress handed to the caller's Module.onProgress(file,
// stage, fraction), if any (the page's worker posts it to the page); what
// it throws is dropped, the measuring goes on.
EM_JS(void, polyvol_js_progress, (const char* file, int stage, double fraction), {
    const report = Module['onProgress'];
    if (!report) return;
    try {
        report(UTF8ToString(file >>> 0), ['reading', 'checking', 'measuring'][stage], fraction);
    } catch (e) {
    }
});

// RequestWords from the request's "options" (absent keys keep their defaults).
polyvol::RequestWords words_of(const json& o) {
    polyvol::RequestWords w;
    auto text = [&](const char* key, std::string& out) {
        if (o.contains(key)) out = o[key].is_string() ? o[key].get<std::string>() : o[key].dump();
    };
    auto flag = [&](const char* key, bool& out) {
        if (o.contains(key)) out = o[key].get<bool>();
    };
    text("method", w.method);
    text("accuracy", w.accuracy);
    text("density", w.density);
    text("mass_unit", w.mass_unit);
    text("units", w.units);
    text("to", w.to);
    text("scale", w.scale);
    flag("allow_open", w.allow_open);
    flag("solid", w.solid);
    flag("orient", w.orient);
    flag("keep_signed", w.keep_signed);
    flag("units_where_unstated", w.units_where_unstated);
    flag("stream", w.stream);
    flag("volume_only", w.volume_only);
    if (o.contains("weld_tolerance")) w.weld_tolerance = o["weld_tolerance"].get<double>();
    return w;
}

// `polyvol volume|measure|check --json FILES`: what the command line asks of
// measure_file for its JSON (cli/commands/measure.cpp), each file's report.
json measure_files(const std::string& command, const json& request, json& messages, int& code, std::string& csv,
                   json& note_words) {
    const polyvol::ReportOf of = command == "volume"    ? polyvol::ReportOf::volume
                                 : command == "measure" ? polyvol::ReportOf::measure
                                                        : polyvol::ReportOf::check;
    const polyvol::ReadRequest read = polyvol::file_options(words_of(request.value("options", json::object())), of, true);
    if (!read.options) {
        messages.push_back("polyvol: " + read.error);
        code = Exit::usage;
        return nullptr;
    }
    polyvol::FileOptions options = *read.options;
    // A zip archive of plain meshes is its members, "ARCHIVE:MEMBER", as on the command line.
    const auto inputs = polyvol::file_inputs(request.at("files").get<std::vector<std::string>>());
    json out = json::array();
    std::vector<polyvol::FileReport> reports;
    for (const auto& [file, member] : inputs) {
        const std::string name = member.empty() ? file : file + ":" + member;  // as the report names it
        options.progress = [name](polyvol::FileStage stage, double fraction) {
            polyvol_js_progress(name.c_str(), static_cast<int>(stage), fraction);
        };
        polyvol::FileReport r = polyvol::measure_file(file, options, member);
        code = std::max(code, r.exit_code);
        if (!r.error.empty()) messages.push_back("polyvol: " + r.error);
        if (!r.warning.empty()) messages.push_back("polyvol: warning: " + r.warning);
        out.push_back(polyvol::report_json(r, options));
        if (r.loaded)
            for (const std::string& n : r.loaded->notes) note_words[n] = polyvol::note_words(n);
        if (command == "measure") reports.push_back(std::move(r));  // for the CSV
    }
    // measure --csv asks the same of measure_file as --json (but the mesh's
    // counts, which the CSV has not).
    if (command == "measure") csv = polyvol::csv_table(reports, true, options.density_relative_error);
    return out;
}

// `polyvol overlap --json A B` (cli/commands/overlap.cpp prints the same report).
json overlap(const json& request, json& messages, int& code) {
    const auto files = request.at("files").get<std::vector<std::string>>();
    if (files.size() != 2) {
        messages.push_back("polyvol: overlap takes two files, A and B");
        code = Exit::usage;
        return nullptr;
    }
    // The options read once, as for the other commands; overlap takes its words of them.
    const polyvol::RequestWords words = words_of(request.value("options", json::object()));
    polyvol::OverlapWords w;
    w.units = words.units;
    w.to = words.to;
    w.orient = words.orient;
    w.keep_signed = words.keep_signed;
    w.units_where_unstated = words.units_where_unstated;
    w.weld_tolerance = words.weld_tolerance;
    const polyvol::OverlapReport r = polyvol::overlap_files(files[0], files[1], w);
    for (const std::string& m : r.messages) messages.push_back("polyvol: " + m);
    code = r.exit_code;
    return r.volumes ? polyvol::overlap_json(files[0], files[1], r) : json(nullptr);
}

json run(const std::string& text) {
    json messages = json::array();
    int code = Exit::ok;
    json result;
    std::string csv;
    json note_words = json::object();
    try {
        const json request = json::parse(text);
        const std::string command = request.at("command").get<std::string>();
        if (command == "volume" || command == "measure" || command == "check") {
            result = measure_files(command, request, messages, code, csv, note_words);
        } else if (command == "overlap") {
            result = overlap(request, messages, code);
        } else {
            messages.push_back("polyvol: unknown command '" + command + "' (volume, measure, check or overlap)");
            code = Exit::usage;
        }
    } catch (const std::bad_alloc&) {
        messages.push_back("polyvol: out of memory");
        code = 4;
    } catch (const std::exception& e) {
        messages.push_back(std::string("polyvol: ") + e.what());
        code = 4;
    }
    json answer{{"exit_code", code}, {"stdout", result.is_null() ? "" : result.dump(2) + "\n"}, {"messages", messages}};
    if (!csv.empty()) answer["csv"] = csv;
    if (!note_words.empty()) answer["note_words"] = note_words;
    return answer;
}

// A file's mesh for a 3D view, as one malloc'ed block: uint32 n, n bytes of
// JSON (exit_code, error, and counts and byte offsets of the arrays), then,
// each 8-byte aligned, float32 positions[3 v], uint32 triangles[3 t] (the
// faces' fans), uint32 triangle_shell[t] (index in "shells", largest volume
// first; "crosses": it crosses another shell), float32 problem_edges[6 e]
// (end points), uint8 problems[e] (EdgeProblem bits). The mesh is the
// file's as read (no welding tolerance, no orienting); the edges are
// analyze_topology's, the first edge_limit.
struct Block {
    char* data = nullptr;  // malloc'ed
    std::size_t size = 0;
};
Block mesh_block(const char* request_text) {
    json header{{"exit_code", 0}};
    polyvol::LoadedMesh loaded;
    polyvol::TopologyReport topo;
    std::vector<uint32_t> triangles, triangle_shell;
    try {
        const json request = json::parse(request_text);
        const std::string file = request.at("file").get<std::string>();
        const std::string member = request.value("member", "");
        loaded = member.empty() ? polyvol::read_mesh_file(file) : polyvol::read_archive_member(file, member);
        polyvol::TopologyOptions options;
        options.face_shells = true;
        options.problem_edges = request.value("edge_limit", std::size_t{200000});
        const polyvol::MeshView view = loaded.mesh.view();
        topo = polyvol::analyze_topology(view, options);
        triangles.reserve(3 * view.triangle_count());
        triangle_shell.reserve(view.triangle_count());
        for (std::size_t f = 0; f < view.face_count(); ++f) {
            const auto c = view.face(f);
            for (std::size_t k = 2; k < c.size(); ++k) {
                triangles.insert(triangles.end(), {c[0], c[k - 1], c[k]});
                triangle_shell.push_back(topo.face_shell[f]);
            }
        }
    } catch (const polyvol::ReadError& e) {
        header = {{"exit_code", Exit::unreadable}, {"error", e.what()}};
    } catch (const std::bad_alloc&) {
        header = {{"exit_code", 4}, {"error", "out of memory"}};
    } catch (const std::exception& e) {
        header = {{"exit_code", 4}, {"error", e.what()}};
    }
    // Shells that cross another (solid_volume's face_crosses), where there are several closed ones.
    std::vector<uint8_t> crosses(topo.shells.size(), 0);
    if (topo.closed_2_cycle && topo.shells.size() > 1) {
        try {
            const polyvol::SolidVolume solid = polyvol::solid_volume(loaded.mesh.view());
            for (std::size_t f = 0; f < solid.face_crosses.size(); ++f)
                if (solid.face_crosses[f] && topo.face_shell[f] != polyvol::TopologyReport::kNoShell) crosses[topo.face_shell[f]] = 1;
        } catch (const std::exception&) {
            // the view goes without: nothing is claimed
        }
    }
    json shells = json::array();
    for (std::size_t i = 0; i < topo.shells.size(); ++i) {
        const polyvol::Shell& sh = topo.shells[i];
        shells.push_back({{"role", polyvol::shell_role_name(sh.role)}, {"faces", sh.faces},
                          {"volume", polyvol::json_number(sh.signed_volume)}, {"crosses", crosses[i] != 0}});
    }
    const std::size_t v = loaded.mesh.vertex_count(), t = triangle_shell.size(), e = topo.problem_edges.size();
    header["vertices"] = v;
    header["triangles"] = t;
    header["shells"] = shells;
    header["problem_edges"] = e;
    header["boundary_edges"] = topo.boundary_edges;
    header["nonmanifold_edges"] = topo.nonmanifold_edges;
    header["misoriented_edges"] = topo.misoriented_edges;
    header["unbalanced_edges"] = topo.unbalanced_edges;
    // The arrays after the header, whose "arrays" (five offsets) fit in 200 more bytes.
    const auto align = [](std::size_t n) { return (n + 7) & ~std::size_t{7}; };
    // (An error's text may hold bytes that are not UTF-8: replaced.)
    const auto text_of = [&] { return header.dump(-1, ' ', false, json::error_handler_t::replace); };
    std::size_t at = align(4 + text_of().size() + 200);
    const auto place = [&](std::size_t bytes) {
        const std::size_t here = at;
        at = align(at + bytes);
        return here;
    };
    const json arrays{{"positions", place(12 * v)}, {"triangles", place(12 * t)}, {"triangle_shell", place(4 * t)},
                      {"problem_edges", place(24 * e)}, {"problems", place(e)}};
    header["arrays"] = arrays;
    const std::string text = text_of();
    Block out{static_cast<char*>(std::calloc(at, 1)), at};
    if (out.data == nullptr) return {};
    char* const block = out.data;
    const auto n = static_cast<uint32_t>(text.size());
    std::memcpy(block, &n, 4);
    std::memcpy(block + 4, text.data(), text.size());
    auto* positions = reinterpret_cast<float*>(block + arrays["positions"].get<std::size_t>());
    for (std::size_t i = 0; i < 3 * v; ++i) positions[i] = static_cast<float>(loaded.mesh.positions[i]);
    std::memcpy(block + arrays["triangles"].get<std::size_t>(), triangles.data(), 4 * triangles.size());
    std::memcpy(block + arrays["triangle_shell"].get<std::size_t>(), triangle_shell.data(), 4 * t);
    auto* ends = reinterpret_cast<float*>(block + arrays["problem_edges"].get<std::size_t>());
    auto* kinds = reinterpret_cast<uint8_t*>(block + arrays["problems"].get<std::size_t>());
    for (std::size_t i = 0; i < e; ++i) {
        for (int k = 0; k < 6; ++k) ends[6 * i + k] = static_cast<float>(topo.problem_edges[i].ends[k]);
        kinds[i] = topo.problem_edges[i].problems;
    }
    return out;
}

}  // namespace

extern "C" {

// The answer to a request as JSON text (UTF-8), to be freed with polyvol_free.
char* polyvol_run(const char* request) {
    // A message may quote bytes that are not UTF-8 (a file's): replaced, not thrown on.
    const std::string answer = run(request).dump(2, ' ', false, json::error_handler_t::replace);
    char* out = static_cast<char*>(std::malloc(answer.size() + 1));
    if (out) std::memcpy(out, answer.c_str(), answer.size() + 1);
    return out;
}

// mesh_block for a request (JSON text; its errors are the header's), to be
// freed with polyvol_free; its size in *size. Null when the block found no memory.
char* polyvol_mesh(const char* request, uint32_t* size) {
    try {
        const Block b = mesh_block(request);
        *size = static_cast<uint32_t>(b.size);
        return b.data;
    } catch (const std::exception&) {
        return nullptr;  // out of memory for the header's arrays
    }
}

void polyvol_free(char* p) { std::free(p); }

}  // extern "C"
