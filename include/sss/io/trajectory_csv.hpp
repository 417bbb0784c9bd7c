#pragma once
/// \file
/// Reads a trajectory from a CSV text file into `sss::motion::trajectory_samples`.
///
/// Format. Fields are separated by ',' or ';' (or, on a line with neither, by blanks), as in every sss text
/// reader (io/detail/text.hpp); '#' starts a comment that runs to the end of the line; blank lines are skipped;
/// spaces and tabs around fields are ignored; a UTF-8 byte-order mark and CRLF line ends are accepted. The
/// first line that is not blank or a comment is the header naming the columns, in any order (names are
/// case-insensitive; a unit suffix is optional):
///
/// | column                       | meaning                                                     | unit        |
/// |------------------------------|-------------------------------------------------------------|-------------|
/// | `time`, `time_s`             | sample time                                                 | s           |
/// | `ping`                       | ping number (when present, the key: one sample per ping)    | -           |
/// | `x`, `x_m`                   | world east                                                  | m           |
/// | `y`, `y_m`                   | world north                                                 | m           |
/// | `z`, `z_m`                   | world up (altitude above a seabed at z = 0)                 | m           |
/// | `roll`, `roll_deg`, `roll_rad` | starboard down positive                                   | deg (`_rad`: rad) |
/// | `pitch`, `pitch_deg`, `pitch_rad` | bow up positive                                        | deg (`_rad`: rad) |
/// | `yaw`, `heading` (+ `_deg`, `_rad`) | clockwise from north                                 | deg (`_rad`: rad) |
/// | `heave`, `heave_m`           | vertical offset added to z, positive up                     | m           |
/// | `sway`, `sway_m`             | offset along the horizontal starboard direction             | m           |
///
/// x, y, z and at least one of time and ping are required; angles are in degrees unless the name ends in
/// `_rad`. Unknown or repeated columns are errors (a misspelt column would otherwise be silently dropped).
/// Every data row holds one finite number per column (finite in the scalar type read into: 1e39 is not a float;
/// angles within 10^6 degrees; in float, x and y within 131 km of the origin, where it holds them to 1.6 cm), roll
/// and pitch lie within 90 degrees of level (after wrapping
/// to (-180, 180] degrees), and the key (ping if present, else time) and the time strictly increase. Any fault throws sss::file_error naming the file and the line; nothing is returned
/// partially loaded.

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/io/detail/text.hpp"
#include "sss/io/detail/trajectory_columns.hpp"
#include "sss/motion/trajectory.hpp"

namespace sss::io {

/// Reads trajectory samples from a CSV stream; `name` (a file name or a description) locates errors.
/// Throws sss::file_error(name, line, why) on any malformed content, and when fewer than 2 samples are found.
template <Real T>
[[nodiscard]] motion::trajectory_samples<T> read_trajectory_csv(std::istream& in, std::string_view name) {
    namespace d = detail::trajectory_csv;
    constexpr std::size_t ncol = static_cast<std::size_t>(d::column::count);
    std::vector<d::column_spec> columns;
    std::array<bool, ncol> present{};
    std::array<bool, ncol> radians{};
    std::array<std::vector<double>, ncol> data{};
    bool header_seen = false;
    std::size_t rows = 0;
    std::size_t key = 0, time = 0;

    const std::string text = sss::detail::read_stream(in, name);
    for (const sss::detail::text_line& line : sss::detail::content_lines(text)) {
        const std::size_t line_no = line.number;
        const std::vector<sss::detail::text_field> fields = sss::detail::split_fields(line);

        if (!header_seen) {
            header_seen = true;
            for (const sss::detail::text_field& field : fields) {
                const std::string_view f = field.text;
                const std::optional<d::column_spec> spec = d::parse_column(f);
                if (!spec)
                    throw sss::detail::error_at(name, line_no, field.column,
                                     "unknown column '" + std::string(f) +
                                         "' (known: time, ping, x, y, z, roll, pitch, yaw or heading, heave, sway; "
                                         "optional unit suffixes _s, _m, _deg, _rad)");
                const std::size_t c = static_cast<std::size_t>(spec->which);
                if (present[c])
                    throw sss::detail::error_at(name, line_no, field.column, "column '" + std::string(f) + "' repeats the " +
                                                        d::column_name(spec->which) + " column");
                present[c] = true;
                radians[c] = spec->radians;
                columns.push_back(*spec);
            }
            for (d::column c : {d::column::x, d::column::y, d::column::z})
                if (!present[static_cast<std::size_t>(c)])
                    throw file_error(name, line_no, std::string("missing column '") + d::column_name(c) + "'");
            if (!present[static_cast<std::size_t>(d::column::time)] && !present[static_cast<std::size_t>(d::column::ping)])
                throw file_error(name, line_no, "missing column: one of 'time' or 'ping' is needed");
            key = static_cast<std::size_t>(present[static_cast<std::size_t>(d::column::ping)] ? d::column::ping : d::column::time);
            time = static_cast<std::size_t>(d::column::time);
            continue;
        }

        if (fields.size() != columns.size())
            throw file_error(name, line_no, "expected " + std::to_string(columns.size()) + " fields, found " +
                                                std::to_string(fields.size()));
        for (std::size_t i = 0; i < fields.size(); ++i) {
            const std::optional<double> v = sss::detail::parse_finite(fields[i].text);
            if (!v)
                throw sss::detail::error_at(name, line_no, fields[i].column,
                                            "column '" + std::string(d::column_name(columns[i].which)) + "': '" +
                                                std::string(fields[i].text) + "' is not a finite number");
            // As the samples will hold it: finite in T (1e39 is not a float), and an angle within 10^6 degrees
            // (beyond, wrapping it to a turn keeps none of its digits).
            const bool is_angle = columns[i].which == d::column::roll || columns[i].which == d::column::pitch ||
                                  columns[i].which == d::column::yaw;
            const bool in_rad = radians[static_cast<std::size_t>(columns[i].which)];
            const double as_held = is_angle && !in_rad ? deg_to_rad(*v) : *v;
            const bool in_t = columns[i].which != d::column::time && columns[i].which != d::column::ping; // time, ping: double
            if ((in_t && !std::isfinite(static_cast<T>(as_held))) ||
                (is_angle && !(std::abs(in_rad ? *v * 180.0 / pi_v<double> : *v) <= 1e6)))
                throw sss::detail::error_at(name, line_no, fields[i].column,
                                            "column '" + std::string(d::column_name(columns[i].which)) + "': '" +
                                                std::string(fields[i].text) + "' is out of range (" +
                                                (is_angle ? std::string("angles lie within 10^6 degrees")
                                                          : std::string("beyond the scalar type's range")) +
                                                ")");
            // Positions a float holds to a centimetre: within 2^17 m (131 km) of the world origin, where its spacing
            // is 1.6 cm (at a UTM northing of 6.5e6 m it is 0.5 m, and a towfish would move in half-metre steps).
            if constexpr (std::is_same_v<T, float>) {
                if ((columns[i].which == d::column::x || columns[i].which == d::column::y) && !(std::abs(*v) < 131072.0))
                    throw sss::detail::error_at(name, line_no, fields[i].column,
                                                "column '" + std::string(d::column_name(columns[i].which)) + "': '" +
                                                    std::string(fields[i].text) +
                                                    "' lies 131 km or more from the world origin, where float holds "
                                                    "positions to no better than 1.6 cm: read the trajectory in double, or "
                                                    "give it from an origin near the survey");
            }
            // Roll and pitch within 90 degrees of level once wrapped to (-180, 180] (a roll of 359 is -1): past that
            // the towfish would fly on its side or nose down, and its heading would lose its meaning.
            if (columns[i].which == d::column::roll || columns[i].which == d::column::pitch) {
                const double deg = radians[static_cast<std::size_t>(columns[i].which)] ? *v * 180.0 / pi_v<double> : *v;
                const double wrapped = deg - 360.0 * std::ceil((deg - 180.0) / 360.0);
                if (!(std::abs(wrapped) < 90.0))
                    throw sss::detail::error_at(name, line_no, fields[i].column,
                                                "column '" + std::string(d::column_name(columns[i].which)) + "': '" +
                                                    std::string(fields[i].text) +
                                                    "' is 90 deg or more from level (roll and pitch must lie within 90 "
                                                    "deg of it, wrapped to (-180, 180] deg)");
            }
            data[static_cast<std::size_t>(columns[i].which)].push_back(*v);
        }
        for (std::size_t c : {key, time}) {
            const std::vector<double>& v = data[c];
            if (present[c] && rows > 0 && !(v[rows] > v[rows - 1]))
                throw file_error(name, line_no, std::string(d::column_name(static_cast<d::column>(c))) +
                                                    " must strictly increase: " + std::to_string(v[rows]) +
                                                    " follows " + std::to_string(v[rows - 1]));
        }
        ++rows;
    }
    if (!header_seen) throw file_error(name, 0, "no header row");
    if (rows < 2) throw file_error(name, 0, "needs at least 2 samples, found " + std::to_string(rows));

    motion::trajectory_samples<T> s;
    const auto column_data = [&](d::column c) -> std::vector<double>& { return data[static_cast<std::size_t>(c)]; };
    s.time_s = std::move(column_data(d::column::time));
    s.ping = std::move(column_data(d::column::ping));
    s.position_m.resize(rows);
    for (std::size_t i = 0; i < rows; ++i)
        s.position_m[i] = vec3<T>{static_cast<T>(column_data(d::column::x)[i]), static_cast<T>(column_data(d::column::y)[i]),
                                  static_cast<T>(column_data(d::column::z)[i])};
    const auto copy = [&](d::column c, std::vector<T>& out) {
        const std::vector<double>& v = column_data(c);
        const bool angle = c == d::column::roll || c == d::column::pitch || c == d::column::yaw;
        const bool deg = angle && !radians[static_cast<std::size_t>(c)];
        out.reserve(v.size());
        for (double x : v) out.push_back(static_cast<T>(deg ? deg_to_rad(x) : x));
    };
    copy(d::column::roll, s.roll_rad);
    copy(d::column::pitch, s.pitch_rad);
    copy(d::column::yaw, s.yaw_rad);
    copy(d::column::heave, s.heave_m);
    copy(d::column::sway, s.sway_m);
    return s;
}

/// Reads trajectory samples from a CSV file. Throws sss::file_error when it cannot be opened or is malformed.
template <Real T> [[nodiscard]] motion::trajectory_samples<T> read_trajectory_csv(const std::filesystem::path& file) {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) throw file_error(file.string(), 0, "is a directory, not a file");
    std::ifstream in(file);
    if (!in) throw file_error(file.string(), 0, "cannot open for reading");
    return read_trajectory_csv<T>(in, file.string());
}

/// A trajectory from a CSV file (see read_trajectory_csv) with the given interpolation parameters.
template <Real T>
[[nodiscard]] motion::trajectory<T> load_trajectory_csv(const std::filesystem::path& file,
                                                        const motion::trajectory_params<T>& params = {}) {
    return motion::trajectory<T>(read_trajectory_csv<T>(file), params);
}

} // namespace sss::io
