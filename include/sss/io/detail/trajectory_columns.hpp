#pragma once
/// \file
/// Internal to io/trajectory_csv.hpp: the columns a trajectory CSV file may hold and the names it accepts for
/// them. Not part of the API.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "sss/io/detail/text.hpp"

namespace sss::io::detail::trajectory_csv {

enum class column : unsigned char { time, ping, x, y, z, roll, pitch, yaw, heave, sway, count };

struct column_spec {
    column which;
    bool radians; ///< for angle columns: values in radians
};

inline std::optional<column_spec> parse_column(std::string_view raw) {
    const std::string n = sss::detail::lower(raw);
    const auto is = [&](std::initializer_list<std::string_view> names) {
        for (std::string_view s : names)
            if (n == s) return true;
        return false;
    };
    if (is({"time", "time_s"})) return column_spec{column::time, false};
    if (is({"ping"})) return column_spec{column::ping, false};
    if (is({"x", "x_m"})) return column_spec{column::x, false};
    if (is({"y", "y_m"})) return column_spec{column::y, false};
    if (is({"z", "z_m"})) return column_spec{column::z, false};
    if (is({"heave", "heave_m"})) return column_spec{column::heave, false};
    if (is({"sway", "sway_m"})) return column_spec{column::sway, false};
    if (is({"roll", "roll_deg"})) return column_spec{column::roll, false};
    if (is({"roll_rad"})) return column_spec{column::roll, true};
    if (is({"pitch", "pitch_deg"})) return column_spec{column::pitch, false};
    if (is({"pitch_rad"})) return column_spec{column::pitch, true};
    if (is({"yaw", "yaw_deg", "heading", "heading_deg"})) return column_spec{column::yaw, false};
    if (is({"yaw_rad", "heading_rad"})) return column_spec{column::yaw, true};
    return std::nullopt;
}

inline const char* column_name(column c) noexcept {
    constexpr std::array<const char*, static_cast<std::size_t>(column::count)> names{
        "time", "ping", "x", "y", "z", "roll", "pitch", "yaw", "heave", "sway"};
    return names[static_cast<std::size_t>(c)];
}

} // namespace sss::io::detail::trajectory_csv
