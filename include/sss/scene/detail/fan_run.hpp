#pragma once
/// \file
/// Internal to scene/height_field_fan.hpp: the run of rays that share an origin and a heading with monotonic
/// slopes, which the fan tracer marches together. Not part of the API.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "sss/core/detail/prefetch.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/height_field_tracer.hpp"

namespace sss::scene::detail {

/// A fan ray's slope numbers: tau = tan(depression) = -dz / |(dx, dy)|, and inv_h = 1 / |(dx, dy)|, the
/// distance along the ray per metre of horizontal travel.
template <Real T> struct fan_slope {
    T tau;
    T inv_h;
};

/// A run of consecutive rays that forms a vertical fan; `steep_first`: tau does not increase along it.
struct fan_run {
    std::size_t count = 0;
    bool steep_first = true;
};

/// The most rays height_field::intersect_many sweeps as one fan (a longer run is swept in pieces): this
/// bounds its working memory, and a piece this long already spreads the sweep's fixed cost thin.
inline constexpr std::size_t max_fan_rays = 4096;

/// The longest run of at most slopes.size() rays from rays[first] on that share the origin (exactly) and
/// the horizontal heading (to 8 ulps), are not within 0.06 deg of vertical, and are ordered by tau one way
/// or the other; the slopes of its rays go to slopes[0 ... count - 1].
template <Real T> [[nodiscard]] inline fan_run find_fan_run(std::span<const ray<T>> rays, std::size_t first,
                                                            std::span<fan_slope<T>> slopes) noexcept {
    fan_run run;
    const ray<T>& r0 = rays[first];
    const T inv_h0 = T(1) / std::sqrt(r0.direction.x * r0.direction.x + r0.direction.y * r0.direction.y);
    if (!(inv_h0 <= T(1e3))) return run; // near-vertical (or not finite): no heading to share
    const T hx = r0.direction.x * inv_h0, hy = r0.direction.y * inv_h0;
    const T tol = T(8) * std::numeric_limits<T>::epsilon();
    int order = 0; // 0 unknown, +1 tau non-increasing, -1 tau non-decreasing
    T tau_prev = -r0.direction.z * inv_h0;
    if (!std::isfinite(tau_prev) || slopes.empty()) return run;
    slopes[0] = fan_slope<T>{tau_prev, inv_h0};
    run.count = 1;
    const std::size_t end = first + std::min(rays.size() - first, slopes.size());
    for (std::size_t j = first + 1; j < end; ++j) {
        const ray<T>& r = rays[j];
        if (j + 32 < rays.size()) sss::detail::prefetch(&rays[j + 32]); // rays arrive from memory: ask ahead
        if (!(r.origin == r0.origin)) break;
        const T inv_h = T(1) / std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
        if (!(inv_h <= T(1e3))) break;
        if (!(std::abs(hx * r.direction.y - hy * r.direction.x) <= tol)) break; // sideways drift per metre
        if (!(hx * r.direction.x + hy * r.direction.y > T(0))) break;
        const T tau = -r.direction.z * inv_h;
        if (!std::isfinite(tau)) break;
        if (!keeps_order(tau, tau_prev, order)) break;
        tau_prev = tau;
        slopes[run.count] = fan_slope<T>{tau, inv_h};
        ++run.count;
    }
    run.steep_first = order >= 0;
    return run;
}

} // namespace sss::scene::detail
