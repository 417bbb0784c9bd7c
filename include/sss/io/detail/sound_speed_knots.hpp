#pragma once
/// \file
/// Internal to io/sound_speed_profile.hpp: the knots of a sound-speed file gathered line by line and checked as
/// they arrive (lines, fields, numbers and errors from the readers' shared text core, io/detail/text.hpp).

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/io/detail/text.hpp"
#include "sss/propagation/profile.hpp"

namespace sss::io {

namespace detail::svp {

using sss::detail::iequals_prefix;
using sss::detail::quote;
using sss::detail::shortest;
using sss::detail::split_fields;
using sss::detail::text_line;
using sss::detail::trim;

/// The non-blank lines of `text`, comments stripped.
[[nodiscard]] inline std::vector<text_line> read_lines(std::string_view text) { return sss::detail::content_lines(text); }

/// Knots accumulated from data lines, checked as they arrive.
template <Real T> struct knot_list {
    std::vector<T> depth;
    std::vector<T> speed;
    std::size_t first_line = 0;

    void add(const text_line& line, std::string_view name) {
        const auto fields = split_fields(line);
        if (fields.size() != 2) {
            throw sss::detail::error_at(name, line.number, fields.size() > 2 ? fields[2].column : 0,
                                        "expected 2 columns (depth m, speed m/s), found " +
                                            std::to_string(fields.size()) + " in " + quote(line.text));
        }
        const auto d = sss::detail::parse_finite(fields[0].text);
        if (!d)
            throw sss::detail::error_at(name, line.number, fields[0].column,
                                        "depth " + quote(fields[0].text) + " is not a finite number");
        const auto c = sss::detail::parse_finite(fields[1].text);
        if (!c)
            throw sss::detail::error_at(name, line.number, fields[1].column,
                                        "speed " + quote(fields[1].text) + " is not a finite number");
        constexpr double largest = static_cast<double>(std::numeric_limits<T>::max());
        if (std::abs(*d) > largest)
            throw sss::detail::error_at(name, line.number, fields[0].column,
                                        "depth " + quote(fields[0].text) + " is out of range");
        if (!(*c > 0.0) || *c > largest)
            throw sss::detail::error_at(name, line.number, fields[1].column,
                                        "speed " + quote(fields[1].text) + " must be a positive number of m/s");
        const T depth_m = static_cast<T>(*d);
        const T speed_mps = static_cast<T>(*c);
        if (!(speed_mps > T(0))) // a positive double that underflows T
            throw sss::detail::error_at(name, line.number, fields[1].column,
                                        "speed " + quote(fields[1].text) + " must be a positive number of m/s");
        // Sound in water travels at 1400 to 1600 m/s; outside 1000 to 2500 the column is in other units (km/s, ft/s).
        if (!(*c >= 1000.0 && *c <= 2500.0))
            throw sss::detail::error_at(name, line.number, fields[1].column,
                                        "speed " + quote(fields[1].text) +
                                            " m/s is not a sound speed in water (1000 to 2500 m/s): is the column in m/s?");
        if (!depth.empty() && !(depth_m > depth.back())) {
            throw sss::detail::error_at(name, line.number, fields[0].column,
                             "depth " + quote(fields[0].text) + " does not increase: the previous depth is " +
                                 shortest(depth.back()) + " m (depths must increase strictly)");
        }
        // The gradient to the previous knot must be finite in T (knots a float's step apart overflow it).
        if (!depth.empty() && !std::isfinite((speed_mps - speed.back()) / (depth_m - depth.back())))
            throw sss::detail::error_at(name, line.number, fields[0].column,
                                        "depth " + quote(fields[0].text) + " lies too close to the previous depth (" +
                                            shortest(depth.back()) + " m): the speed gradient between them overflows");
        if (depth.empty()) first_line = line.number;
        depth.push_back(depth_m);
        speed.push_back(speed_mps);
    }

    [[nodiscard]] propagation::sound_speed_profile<T> build() && {
        return propagation::sound_speed_profile<T>(std::move(depth), std::move(speed));
    }
};

[[nodiscard]] inline bool looks_like_data(const text_line& line) {
    const auto fields = split_fields(line);
    return fields.size() == 2 && sss::detail::parse_finite(fields[0].text) && sss::detail::parse_finite(fields[1].text);
}

[[nodiscard]] inline std::ifstream open_for_reading(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw file_error(path.string(), 0, "is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw file_error(path.string(), 0, "cannot open for reading");
    return in;
}

} // namespace detail::svp

} // namespace sss::io
