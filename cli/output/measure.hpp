// cli/output/measure.hpp — what `polyvol volume`, `measure` and `check`
// print for the files the library measured (polyvol/report.hpp): a table or report for
// people, JSON (one schema for every route) and CSV for programs, URDF/SDF
// <inertial> elements.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "request.hpp"

namespace polyvol::cli {

// The <inertial> element of a URDF link (sdf: of an SDF link) for the file:
// mass, pose at the centroid, the inertia tensor about it (ixy = -∫ρxy, the
// tensor's own entries, as both formats take them), in the file's units.
std::string inertial_element(const FileResult& r, const Request& request, bool sdf);

// Table for `polyvol volume` (one row per file), and the reports of
// `polyvol measure` and `polyvol check` for one file.
std::string volume_table(const std::vector<FileResult>& results, const Request& request);
std::string measure_report(const FileResult& r, const Request& request);
std::string check_report(const FileResult& r);
// --csv: polyvol::csv_table (polyvol/report.hpp).

// A sentence stating the guarantee of the printed volume.
std::string volume_guarantee(const MassProperties& m);

}  // namespace polyvol::cli
