#pragma once
/// \file
/// Internal to seabed/stamps.hpp: the samples near a feature, their coverage by its footprint, and the
/// raster checks the stamps share. Not part of the API.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/raster.hpp"

namespace sss::seabed::detail {

/// Index range [lo, hi) of samples whose coordinate lies within [a, b] (m), clipped to [0, n).
inline void sample_range(double a, double b, double cell, std::size_t n, std::size_t& lo, std::size_t& hi) {
    const double first = std::ceil(a / cell), last = std::floor(b / cell);
    lo = first <= 0.0 ? 0 : static_cast<std::size_t>(std::min(first, static_cast<double>(n)));
    hi = last < 0.0 ? 0 : static_cast<std::size_t>(std::min(last + 1.0, static_cast<double>(n)));
    if (hi < lo) hi = lo;
}

/// Calls f(ix, iy, x, y) for every sample of an nx x ny grid of spacing `cell` (m) within the box
/// (cx +- reach_x, cy +- reach_y) (m).
template <class F> void for_samples_near(std::size_t nx, std::size_t ny, double cell, double cx, double cy,
                                         double reach_x, double reach_y, F&& f) {
    std::size_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    sample_range(cx - reach_x, cx + reach_x, cell, nx, x0, x1);
    sample_range(cy - reach_y, cy + reach_y, cell, ny, y0, y1);
    for (std::size_t iy = y0; iy < y1; ++iy)
        for (std::size_t ix = x0; ix < x1; ++ix)
            f(ix, iy, static_cast<double>(ix) * cell, static_cast<double>(iy) * cell);
}

/// Normalised elliptical radius of (x, y) for an ellipse of semi-axes a (along heading) and b.
struct ellipse_frame {
    double cx, cy, c, s, a, b;
    [[nodiscard]] double r(double x, double y) const noexcept {
        const double dx = x - cx, dy = y - cy;
        const double u = dx * c + dy * s, v = -dx * s + dy * c;
        return std::sqrt((u / a) * (u / a) + (v / b) * (v / b));
    }
};

/// The frame of an elliptical feature (mound or scour): centre, heading and semi-axes.
template <class Feature> [[nodiscard]] ellipse_frame frame_of(const Feature& s) noexcept {
    const double heading = heading_to_ccw_from_east_rad(static_cast<double>(s.heading_deg));
    return {static_cast<double>(s.center_x_m), static_cast<double>(s.center_y_m), std::cos(heading), std::sin(heading),
            static_cast<double>(s.radius_u_m), static_cast<double>(s.radius_v_m)};
}

/// Distance (m) from (x, y) to the segment p0-p1.
inline double segment_distance(double x, double y, double x0, double y0, double x1, double y1) noexcept {
    const double ex = x1 - x0, ey = y1 - y0;
    const double len2 = ex * ex + ey * ey;
    double t = len2 > 0.0 ? ((x - x0) * ex + (y - y0) * ey) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(x - (x0 + t * ex), y - (y0 + t * ey));
}

/// Fraction of the cell around sample (x, y) inside a footprint (`inside(x, y)`), from 4 x 4 sub-samples.
template <class Inside> double coverage(double x, double y, double cell, Inside&& inside) {
    int n = 0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            if (inside(x + (static_cast<double>(i) - 1.5) * cell / 4.0,
                       y + (static_cast<double>(j) - 1.5) * cell / 4.0))
                ++n;
    return static_cast<double>(n) / 16.0;
}

/// Throws unless h has a valid grid and nx * ny values.
template <Real T> void require_raster(const raster<T>& h, const std::string& who) {
    require_grid(h.nx, h.ny, h.cell_m, who);
    sss::require(h.values.size() == h.nx * h.ny, who + ".values", "size differs from nx * ny");
}

/// Writes `id` into the samples of `regions` near (cx, cy) whose cells a footprint (`inside(x, y)`) covers at
/// least half of.
template <Real T, class Inside> void label(region_raster<T>& regions, double cx, double cy, double reach_x,
                                           double reach_y, std::uint32_t id, Inside&& inside) {
    const double cell = static_cast<double>(regions.cell_m);
    for_samples_near(regions.nx, regions.ny, cell, cx, cy, reach_x, reach_y,
                     [&](std::size_t ix, std::size_t iy, double x, double y) {
                         if (coverage(x, y, cell, inside) >= 0.5) regions(ix, iy) = id;
                     });
}

template <Real T> void require_same_grid(const raster<T>& h, const region_raster<T>& r) {
    require_raster(h, "stamp.h");
    sss::require(h.nx == r.nx && h.ny == r.ny && h.cell_m == r.cell_m && r.values.size() == r.nx * r.ny,
                    "stamp.regions", "must have the height raster's grid");
}

} // namespace sss::seabed::detail
