// web/src/polyvol_wasm.cpp — the WebAssembly module's entry point: one call
// per request, JSON in and JSON out, for the page's worker and the npm
// package (web/js/core.mjs). The figures and their keys are the library's
// (measure_file, report_json): `polyvol volume|measure|check --json` prints
// the same objects.
//
//   request: {"command": "volume" | "measure" | "check" | "overlap",
//             "files": ["a.stl", ...],           (paths in the module's file system; overlap: A and B)
//             "options": {RequestWords' fields}} (polyvol/report.hpp; overlap: OverlapWords')
//   answer:  {"exit_code": 0|1|2|3|4,
//             "stdout": the command's --json output, byte for byte (its text),
//             "messages": ["polyvol: ...", ...], (what the command line prints on stderr)
//             "csv": what `measure --csv` prints (measure only)}
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "polyvol/report.hpp"

namespace {

using nlohmann::json;
using polyvol::Exit;

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
    if (o.contains("weld_tolerance")) w.weld_tolerance = o["weld_tolerance"].get<double>();
    return w;
}

// `polyvol volume|measure|check --json FILES`: what the command line asks of
// measure_file for its JSON (cli/commands/measure.cpp), each file's report.
json measure_files(const std::string& command, const json& request, json& messages, int& code, std::string& csv) {
    const bool check = command == "check";
    const polyvol::ReadRequest read = polyvol::file_options(words_of(request.value("options", json::object())), !check);
    if (!read.options) {
        messages.push_back("polyvol: " + read.error);
        code = Exit::usage;
        return nullptr;
    }
    polyvol::FileOptions options = *read.options;
    options.edge_counts = true;
    // volume's "stream" (--stream): the table's figures, a binary STL streamed
    // in constant memory whatever its size, its shells not checked for overlap.
    const json o = request.value("options", json::object());
    const bool stream = command == "volume" && o.value("stream", false);
    options.table_only = stream;
    options.stream_any_size = stream;
    options.mesh_counts = !stream;
    if (stream) {
        options.measure.second_moments = false;
        options.measure.edge_length = false;
    }
    // A zip archive of plain meshes is its members, "ARCHIVE:MEMBER", as on the command line.
    const auto inputs = polyvol::file_inputs(request.at("files").get<std::vector<std::string>>());
    json out = json::array();
    std::vector<polyvol::FileReport> reports;
    for (const auto& [file, member] : inputs) {
        reports.push_back(polyvol::measure_file(file, options, member));
        const polyvol::FileReport& r = reports.back();
        code = std::max(code, r.exit_code);
        if (!r.error.empty()) messages.push_back("polyvol: " + r.error);
        if (!r.warning.empty()) messages.push_back("polyvol: warning: " + r.warning);
        out.push_back(polyvol::report_json(r, options));
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
    try {
        const json request = json::parse(text);
        const std::string command = request.at("command").get<std::string>();
        if (command == "volume" || command == "measure" || command == "check") {
            result = measure_files(command, request, messages, code, csv);
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
    return answer;
}

}  // namespace

extern "C" {

// The answer to a request as JSON text (UTF-8), to be freed with polyvol_free.
char* polyvol_run(const char* request) {
    const std::string answer = run(request).dump(2);
    char* out = static_cast<char*>(std::malloc(answer.size() + 1));
    if (out) std::memcpy(out, answer.c_str(), answer.size() + 1);
    return out;
}

void polyvol_free(char* p) { std::free(p); }

}  // extern "C"
