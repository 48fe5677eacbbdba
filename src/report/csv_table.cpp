// src/report/csv_table.cpp — the CSV of files' reports (polyvol/report.hpp),
// what `polyvol volume --csv` and `measure --csv` print and the web page copies.
#include <array>
#include <cstdlib>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "polyvol/number_text.hpp"
#include "polyvol/report.hpp"

namespace polyvol {

// The length and mass units every measured file shares ("" for a unit they
// do not share, or that no file knows), for the headers of tables.
std::pair<std::string, std::string> common_units(const std::vector<FileReport>& results) {
    const FileReport* first = nullptr;
    bool same = true;
    for (const FileReport& r : results) {
        if (!r.mass) continue;
        if (!first) first = &r;
        same = same && r.length_unit == first->length_unit && r.mass_unit == first->mass_unit;
    }
    if (!first || !same) return {};
    return {first->length_unit, first->mass_unit};
}


std::string csv_table(const std::vector<FileReport>& results, bool inertia, double density_error) {
    // RFC 4180: a field with a comma, quote or line break is quoted, quotes doubled.
    const auto field = [](const std::string& f) {
        if (f.find_first_of(",\"\r\n") == std::string::npos) return f;
        std::string q = "\"";
        for (char c : f) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    };
    // Bounds with every digit; each figure with the digits its bound supports
    // (number_text, as the table shows it), every digit where correctly rounded.
    const auto num = [](double v) { return std::isfinite(v) ? shortest(v + 0.0) : std::string(); };
    const auto within = [](double v, double bound) { return std::isfinite(v) ? number_text(v, bound, 0) : std::string(); };
    // The header names the units when every measured file has the same
    // (volume_cm3, mass_kg); the last two columns name each row's.
    const std::pair<std::string, std::string> units = common_units(results);
    const std::string &unit = units.first, &mass_unit = units.second;
    const auto in = [&](int power) {
        return unit.empty() ? std::string() : "_" + unit + (power > 1 ? std::to_string(power) : std::string());
    };
    const std::string m_in = mass_unit.empty() ? std::string() : "_" + mass_unit;
    const std::string i_in = mass_unit.empty() || unit.empty() ? std::string() : "_" + mass_unit + "_" + unit + "2";
    std::ostringstream out;
    out << "file,exit_code,triangles,volume" << in(3) << ",volume_error_bound" << in(3) << ",mass" << m_in << ",area"
        << in(2) << ",area_relative_error,centroid_x" << in(1) << ",centroid_y" << in(1) << ",centroid_z" << in(1)
        << ",centroid_error_bound" << in(1);
    if (inertia) {
        for (const char* name : {"ixx", "iyy", "izz", "ixy", "iyz", "izx", "inertia_error_bound"}) out << "," << name << i_in;
        out << ",edge_length" << in(1) << ",edge_length_relative_error";
        for (const char* name : {"xmin", "ymin", "zmin", "xmax", "ymax", "zmax"}) out << "," << name << in(1);
    }
    out << ",length_unit,mass_unit\r\n";
    for (const FileReport& r : results) {
        out << field(r.file) << "," << r.exit_code << ",";
        if (r.mass) {
            const MassProperties& m = *r.mass;
            const double volume_error = m.volume_correctly_rounded ? 0.0 : m.volume_error_bound;
            const double centroid_error = moments_error_bound(m, m.centroid);
            const double density = m.volume != 0 ? std::fabs(m.mass / m.volume) : 0.0;  // as the table's mass
            out << r.triangles << "," << within(m.volume, volume_error) << "," << num(volume_error) << ","
                << mass_text(m.mass, density * volume_error, density_error, 0) << "," << within(m.area, m.area * m.area_relative_error)
                << "," << num(m.area_relative_error);
            for (double c : m.centroid) out << "," << within(c, centroid_error);
            out << "," << num(centroid_error);
            if (inertia) {
                const double inertia_error = moments_error_bound(m, m.inertia_centroid);
                for (double e : m.inertia_centroid) out << "," << within(e, inertia_error);
                out << "," << num(inertia_error) << "," << within(m.edge_length, m.edge_length * m.edge_length_relative_error)
                    << "," << num(m.edge_length_relative_error);
                const std::array<double, 6> b = r.loaded ? report_bounds(r) : std::array<double, 6>{NAN, NAN, NAN, NAN, NAN, NAN};
                for (double x : b) out << "," << num(x);
            }
            out << "," << field(r.length_unit) << "," << field(r.mass_unit);
        } else {
            out << (r.loaded ? std::to_string(r.triangles) : std::string()) << ",,,,,,,,,";
            if (inertia) out << ",,,,,,,,,,,,,,,";
            out << ",,";
        }
        out << "\r\n";
    }
    return out.str();
}

}  // namespace polyvol
