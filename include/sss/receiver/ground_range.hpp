#pragma once
/// \file
/// Slant-range correction: a line resampled on a uniform ground-range grid with the water column removed.
///
/// Under the flat-bottom assumption a return from slant range r at altitude H lies at ground range
/// y = sqrt(r^2 - H^2) (Blondel, "The Handbook of Sidescan Sonar", 2009, ch. 4): ground pixel i (centre
/// y_i = (i + 1/2) dy) takes the slant line at two-way time 2 sqrt(y_i^2 + H^2) / c, linearly interpolated
/// between sample centres. Ranges shorter than H (the water column) have no ground range and are dropped.
/// H comes from navigation (the pose: line_context::altitude_m) or from the line itself: the first bottom
/// return, the first sample whose power reaches a fraction of the line's peak.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/receiver/image.hpp"

namespace sss {

/// Altitude (m) from the first bottom return: the start of the first sample whose power reaches
/// `fraction` of the line's peak, as range c k dt / 2; none for an empty or all-zero line.
template <Real T>
[[nodiscard]] std::optional<double> first_return_altitude(const std::vector<T>& line, double dt_s, double c_mps,
                                                          double fraction = 0.1) {
    sss::require_positive(dt_s, "first_return_altitude.dt_s");
    sss::require_positive(c_mps, "first_return_altitude.c_mps");
    sss::require_in_range(fraction, 0.0, 1.0, "first_return_altitude.fraction");
    if (line.empty()) return std::nullopt;
    const double peak = double(*std::max_element(line.begin(), line.end()));
    if (!(peak > 0.0)) return std::nullopt;
    for (std::size_t k = 0; k < line.size(); ++k)
        if (double(line[k]) >= fraction * peak) return 0.5 * c_mps * double(k) * dt_s;
    return std::nullopt;
}

/// The line on `pixels` ground-range pixels of `spacing_m` from nadir out (see the file comment); pixels beyond
/// the slant line's last sample are 0.
template <Real T>
[[nodiscard]] std::vector<T> to_ground_range(const std::vector<T>& slant, double dt_s, double c_mps, double altitude_m,
                                             double spacing_m, std::size_t pixels) {
    sss::require_positive(dt_s, "to_ground_range.dt_s");
    sss::require_positive(c_mps, "to_ground_range.c_mps");
    sss::require_non_negative(altitude_m, "to_ground_range.altitude_m");
    sss::require_positive(spacing_m, "to_ground_range.spacing_m");
    std::vector<T> out(pixels, T(0));
    if (slant.empty()) return out;
    const double last = double(slant.size() - 1);
    for (std::size_t i = 0; i < pixels; ++i) {
        const double y = (double(i) + 0.5) * spacing_m;
        const double t = 2.0 * std::sqrt(y * y + altitude_m * altitude_m) / c_mps;
        const double x = std::max(0.0, t / dt_s - 0.5); // fractional index between sample centres
        if (x > last) break;
        const auto k = static_cast<std::size_t>(x);
        const double f = x - double(k);
        const double a = double(slant[k]), b = k + 1 < slant.size() ? double(slant[k + 1]) : a;
        out[i] = static_cast<T>(a + f * (b - a));
    }
    return out;
}

/// A waterfall on ground range: each ping's lines resampled with its own altitude (one per ping, m), `pixels`
/// per side of `spacing_m`; the result's dt_s is 0 (its columns are ground ranges, not times).
template <Real T>
[[nodiscard]] waterfall<T> to_ground_range(const waterfall<T>& w, const std::vector<double>& altitudes_m, double c_mps,
                                           double spacing_m, std::size_t pixels) {
    sss::require(altitudes_m.size() == w.pings, "to_ground_range.altitudes_m", "must hold one altitude per ping");
    sss::require(pixels <= std::numeric_limits<std::size_t>::max() / 2, "to_ground_range.pixels", "overflows the size type");
    waterfall<T> g;
    g.pings = w.pings;
    g.samples = pixels;
    g.values.assign(checked_elements(w.pings, g.width(), "to_ground_range.pixels"), T(0));
    std::vector<T> port(w.samples), starboard(w.samples);
    for (std::size_t i = 0; i < w.pings; ++i) {
        for (std::size_t k = 0; k < w.samples; ++k) {
            port[k] = w.at(i, w.samples - 1 - k);
            starboard[k] = w.at(i, w.samples + k);
        }
        ping_lines<T> lines;
        lines.port = to_ground_range(port, w.dt_s, c_mps, altitudes_m[i], spacing_m, pixels);
        lines.starboard = to_ground_range(starboard, w.dt_s, c_mps, altitudes_m[i], spacing_m, pixels);
        g.set_row(i, lines);
    }
    return g;
}

} // namespace sss
