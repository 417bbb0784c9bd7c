#pragma once
/// \file
/// Tracing a vertical fan of rays in one sweep: rays that share their origin and their horizontal heading
/// (one along-track angle of a sidescan fan: the same azimuth, many depression angles) all lie in one
/// vertical plane, so they cross the same cells, and the surface under them is one profile z_p(rho),
/// rho the horizontal distance from the origin (m). With tau = tan(depression) a ray's height above the
/// surface is f(rho) = g(rho) - tau rho, g(rho) = z0 - z_p(rho), the same g for every ray of the fan.
///
/// Sweep: walk the profile's breakpoints once (the cell walk of height_field_tracer.hpp, applied to the
/// horizontal ray), and at each breakpoint resolve rays in order of decreasing tau. A steeper ray lies
/// below a shallower one at every rho > 0, so it hits first; the rays' hits come in the same order as the
/// breakpoints and the sweep costs O(breakpoints + rays). Each ray's hit is the linear root on the segment
/// where its f first goes from > 0 to <= 0, the same rule, the same breakpoints and the same watertightness
/// argument as the single-ray tracer; only the rounding differs. The computed f is exactly monotone in tau
/// (rounding is monotone), so the order argument holds in floating point too.
///
/// A ray's distance is s = rho / cos(depression). Rays count as one fan when their horizontal directions
/// agree to within 8 ulps of T per metre of travel: treating them as one plane then moves a hit sideways by
/// at most 8 ulps of its distance.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "sss/core/ray.hpp"
#include "sss/scene/height_field_tracer.hpp"

namespace sss::scene {

namespace detail {

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

/// The longest run of rays from rays[first] on that share the origin (exactly) and the horizontal heading
/// (to 8 ulps), are not within 0.06 deg of vertical, and are ordered by tau one way or the other; the
/// slopes of its rays go to slopes[0 ... count - 1] (slopes.size() >= rays.size() - first).
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
    if (!std::isfinite(tau_prev)) return run;
    slopes[0] = fan_slope<T>{tau_prev, inv_h0};
    run.count = 1;
    for (std::size_t j = first + 1; j < rays.size(); ++j) {
        const ray<T>& r = rays[j];
        if (!(r.origin == r0.origin)) break;
        const T inv_h = T(1) / std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
        if (!(inv_h <= T(1e3))) break;
        if (!(std::abs(hx * r.direction.y - hy * r.direction.x) <= tol)) break; // sideways drift per metre
        if (!(hx * r.direction.x + hy * r.direction.y > T(0))) break;
        const T tau = -r.direction.z * inv_h;
        if (!std::isfinite(tau)) break;
        const int step = tau < tau_prev ? 1 : (tau > tau_prev ? -1 : 0);
        if (step != 0) {
            if (order == 0)
                order = step;
            else if (step != order)
                break;
        }
        tau_prev = tau;
        slopes[run.count] = fan_slope<T>{tau, inv_h};
        ++run.count;
    }
    run.steep_first = order >= 0;
    return run;
}

} // namespace detail

/// Traces the vertical fan `rays` with slopes `slopes` (as found by detail::find_fan_run; `steep_first`
/// says whether tau does not increase along the span) limited to distance t_max_m, calling
/// emit(k, const grid_hit<T>* h) once for every ray k (h null for a miss). Returns false, having emitted nothing, when the sweep does not apply
/// (the origin is not above the surface where the sweep starts, or the fan is too sparse for its length to
/// pay off): the caller then traces the rays one by one.
template <Real T, class Emit>
[[nodiscard]] bool trace_fan(const height_grid_view<T>& g, height_bounds<T> hb, std::span<const ray<T>> rays,
                             std::span<const detail::fan_slope<T>> slopes, bool steep_first, T t_max_m, Emit&& emit) {
    const std::size_t n = rays.size();
    if (n == 0) return true;
    auto index = [&](std::size_t i) { return steep_first ? i : n - 1 - i; };
    const T tau_max = slopes[index(0)].tau, tau_min = slopes[index(n - 1)].tau;
    const ray<T>& r0 = rays[0];
    const T inv_h0 = slopes[0].inv_h;
    const ray<T> profile{r0.origin, vec3<T>{r0.direction.x * inv_h0, r0.direction.y * inv_h0, T(0)}};

    // The profile walk covers rho in [start, end]: a unit ray's rho never exceeds its distance.
    detail::grid_ray<T> q;
    bool any = detail::setup_ray(g, hb, profile, t_max_m, q);
    T rho_end = q.s_hi;
    if (any && tau_min > T(0)) rho_end = std::min(rho_end, (q.z0 - (hb.bottom_m - q.z_margin)) / tau_min);
    T rho_start = any ? q.s_lo : T(0);
    const T z_top = hb.top_m + q.z_margin;
    if (any && q.z0 > z_top) {
        // Nothing lies above top_m: no ray hits before the steepest one comes down to it.
        if (tau_max > T(0))
            rho_start = std::max(rho_start, (q.z0 - z_top) / tau_max);
        else
            any = false;
    }
    if (!any || !(rho_start <= rho_end)) {
        for (std::size_t i = 0; i < n; ++i) emit(index(i), static_cast<const grid_hit<T>*>(nullptr));
        return true;
    }
    if ((std::abs(q.du) + std::abs(q.dv)) * (rho_end - rho_start) > T(32) * static_cast<T>(n)) return false;
    q.s_lo = rho_start;
    q.s_hi = rho_end;
    detail::walk_state<T> w = detail::start_at(g, q, rho_start);
    w.f = detail::f_at(g, q, rho_start);
    if (!(w.f - tau_max * rho_start > T(0))) return false; // the steepest ray starts on or below the surface

    struct sweep {
        std::span<const detail::fan_slope<T>> slopes;
        const detail::grid_ray<T>& q;
        T t_max_m;
        Emit& emit;
        bool steep_first;
        std::size_t i = 0, n = 0;
        T tau{}, inv_h{};

        [[nodiscard]] std::size_t index(std::size_t k) const noexcept { return steep_first ? k : n - 1 - k; }
        void load() {
            if (i >= n) return;
            tau = slopes[index(i)].tau;
            inv_h = slopes[index(i)].inv_h;
        }
        bool operator()(detail::walk_state<T>& w, T rho, T g_rho) {
            while (i < n) {
                const T fb = g_rho - tau * rho;
                if (!(fb > T(0))) {
                    const T fa = w.f - tau * w.s; // > 0: this ray, or a steeper one, was above at w.s
                    const T r_hit = std::clamp(w.s + (rho - w.s) * (fa / (fa - fb)), w.s, rho);
                    const T s = r_hit * inv_h;
                    if (s > T(0) && s <= t_max_m) {
                        const T mid = T(0.5) * (w.s + rho);
                        grid_hit<T> h;
                        h.distance_m = s;
                        h.ix = w.ix;
                        h.iy = w.iy;
                        h.triangle = triangle_of((q.u0 + q.du * mid) - static_cast<T>(w.ix),
                                                 (q.v0 + q.dv * mid) - static_cast<T>(w.iy));
                        emit(index(i), &h);
                    } else {
                        emit(index(i), static_cast<const grid_hit<T>*>(nullptr));
                    }
                } else if (rho * inv_h > t_max_m) {
                    emit(index(i), static_cast<const grid_hit<T>*>(nullptr)); // above the surface all the way to t_max
                } else {
                    return false;
                }
                ++i;
                load();
            }
            return true;
        }
    } visit{slopes, q, t_max_m, emit, steep_first, 0, n, T(0), T(0)};
    visit.load();

    for (;;) {
        const detail::step_outcome o = detail::cell_step(g, q, w, visit);
        if (o != detail::step_outcome::next) break;
    }
    for (; visit.i < n; ++visit.i) emit(index(visit.i), static_cast<const grid_hit<T>*>(nullptr));
    return true;
}

} // namespace sss::scene
