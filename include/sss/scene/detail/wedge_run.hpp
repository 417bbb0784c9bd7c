#pragma once
/// \file
/// Internal to scene/height_field_wedge.hpp: the run of rays that share an origin, with headings within a narrow
/// wedge and monotonic slopes, which the wedge tracer marches together. Not part of the API.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/height_field_tracer.hpp"

namespace sss::scene::detail {

/// A wedge ray's slope numbers: tau = tan(depression) = -dz / |(dx, dy)| and inv_h = 1 / |(dx, dy)|, the distance
/// along the ray per metre of horizontal travel; sin_turn, the sine of the angle from the run's first ray's heading
/// to this ray's (counter-clockwise positive, 0 for the first ray).
template <Real T> struct wedge_slope {
    T tau;
    T inv_h;
    T sin_turn{};
};

/// A wedge run: `count` consecutive rays from the first that share their origin exactly, have headings within
/// `max_spread_rad` of each other, are not within 0.06 deg of vertical, and are ordered by tau one way or the
/// other (`steep_first`: tau does not increase along the run). Their headings lie between the first ray's turned by
/// asin(sin_lo) and by asin(sin_hi) (counter-clockwise positive).
template <Real T> struct wedge_run {
    std::size_t count = 0;
    bool steep_first = true;
    T sin_lo{};
    T sin_hi{};
};

/// Largest spread of headings (rad) in one wedge run: at 400 cells from the origin the wedge is then 4 cells wide.
inline constexpr double wedge_max_spread_rad = 0.01;

/// The longest wedge run from rays[first] of at most slopes.size() rays (at least 1); the slopes of its rays go to
/// slopes[0 ... count - 1].
template <Real T>
[[nodiscard]] inline wedge_run<T> find_wedge_run(std::span<const ray<T>> rays, std::size_t first,
                                                 std::span<wedge_slope<T>> slopes) noexcept {
    wedge_run<T> run;
    const ray<T>& r0 = rays[first];
    const T inv_h0 = T(1) / std::sqrt(r0.direction.x * r0.direction.x + r0.direction.y * r0.direction.y);
    if (!(inv_h0 <= T(1e3)) || !std::isfinite(r0.direction.z)) return run;
    const T hx = r0.direction.x * inv_h0, hy = r0.direction.y * inv_h0;
    const T max_spread = static_cast<T>(wedge_max_spread_rad);
    int order = 0;
    T tau_prev = -r0.direction.z * inv_h0;
    slopes[0] = wedge_slope<T>{tau_prev, inv_h0, T(0)};
    run.count = 1;
    for (std::size_t j = first + 1; j < rays.size() && run.count < slopes.size(); ++j) {
        const ray<T>& r = rays[j];
        if (!(r.origin == r0.origin)) break;
        const T inv_h = T(1) / std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
        if (!(inv_h <= T(1e3))) break;
        if (!(hx * r.direction.x + hy * r.direction.y > T(0))) break;
        const T c = (hx * r.direction.y - hy * r.direction.x) * inv_h; // sin of the heading from the first ray's
        const T lo = std::min(run.sin_lo, c), hi = std::max(run.sin_hi, c);
        if (!(hi - lo <= max_spread)) break;
        const T tau = -r.direction.z * inv_h;
        if (!std::isfinite(tau)) break;
        if (!keeps_order(tau, tau_prev, order)) break;
        run.sin_lo = lo;
        run.sin_hi = hi;
        tau_prev = tau;
        slopes[run.count] = wedge_slope<T>{tau, inv_h, c};
        ++run.count;
    }
    run.steep_first = order >= 0;
    return run;
}

} // namespace sss::scene::detail
