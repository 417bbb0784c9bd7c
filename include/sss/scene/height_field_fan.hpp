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
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sss/core/detail/prefetch.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/detail/fan_run.hpp"
#include "sss/scene/detail/fan_segment.hpp"
#include "sss/scene/height_field_tracer.hpp"

namespace sss::scene {

/// The sweep of the vertical fan `rays` with slopes `slopes` (as found by detail::find_fan_run;
/// `steep_first` says whether tau does not increase along the span) limited to distance t_max_m: for every
/// ray k, segment_of[k] is the index in `segments` of the piece of the profile on which the ray comes down
/// (its hit, if detail::fan_distance finds one within t_max_m), or detail::no_fan_segment when it stays
/// above the surface to t_max_m; both spans hold rays.size() entries. As the sweep goes it calls
/// resolved(k_begin, k_end) for the rays it has settled since the last call, k in [k_begin, k_end), at
/// least `batch` of them each time but the last, so the caller can turn them into hits while the heights
/// under them are still in cache; every ray comes in exactly one call, and the segments of all rays of a
/// call stay valid until the sweep returns. Returns false, having settled nothing, when the sweep does not
/// apply (the origin is not above the surface where the sweep starts, or the fan is too sparse for its
/// length to pay off): the caller then traces the rays one by one.
template <Real T, class Resolved>
[[nodiscard]] bool sweep_fan(const height_grid_view<T>& g, height_bounds<T> hb, std::span<const ray<T>> rays,
                             std::span<const detail::fan_slope<T>> slopes, bool steep_first, T t_max_m,
                             std::span<std::uint32_t> segment_of, std::span<detail::fan_segment<T>> segments,
                             std::size_t batch, Resolved&& resolved) {
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
        std::fill_n(segment_of.begin(), n, detail::no_fan_segment);
        resolved(std::size_t(0), n);
        return true;
    }
    if ((std::abs(q.du) + std::abs(q.dv)) * (rho_end - rho_start) > T(32) * static_cast<T>(n)) return false;
    q.s_lo = rho_start;
    q.s_hi = rho_end;
    detail::walk_state<T> w = detail::start_at(g, q, rho_start);
    w.f = detail::f_at(g, q, rho_start);
    if (!(w.f - tau_max * rho_start > T(0))) return false; // the steepest ray starts on or below the surface

    // At each breakpoint (rho, g_rho), with [w.s, rho] the segment behind it: every ray not yet settled
    // whose f is <= 0 there comes down on that segment; the first one that is still above stops the visit,
    // unless it is above out to t_max_m (then it misses, and so on). Rays are settled in order of
    // decreasing tau: i counts them, k is the index of the next one.
    struct sweep {
        const detail::fan_slope<T>* slopes;
        std::uint32_t* segment_of;
        detail::fan_segment<T>* segments;
        const detail::grid_ray<T>& q;
        Resolved& resolved;
        T t_max_m;
        std::size_t n, batch;
        bool steep_first;
        std::size_t i = 0, reported = 0, count = 0;
        std::ptrdiff_t k = 0;

        // The heights the walk and the hits will want a few cells further on, asked for now: along the
        // profile every cell is a new row or column, which would otherwise come from memory on demand.
        const height_grid_view<T>& g;
        T lookahead; // rho per 8 cells (m)
        std::int32_t ahead_ix = -1, ahead_iy = -1;
        void fetch_ahead(T rho) noexcept {
            const T r = rho + lookahead;
            const std::int32_t ix = detail::cell_of(q.u0 + q.du * r, g.nx - 2), iy = detail::cell_of(q.v0 + q.dv * r, g.ny - 2);
            if (ix == ahead_ix && iy == ahead_iy) return;
            ahead_ix = ix;
            ahead_iy = iy;
            const std::int32_t x0 = std::max(ix - 1, 0), x1 = std::min(ix + 2, g.nx - 1);
            for (std::int32_t y = std::max(iy - 1, 0); y <= std::min(iy + 2, g.ny - 1); ++y) {
                sss::detail::prefetch(&g.heights[static_cast<std::size_t>(y) * static_cast<std::size_t>(g.nx) + static_cast<std::size_t>(x0)]);
                sss::detail::prefetch(&g.heights[static_cast<std::size_t>(y) * static_cast<std::size_t>(g.nx) + static_cast<std::size_t>(x1)]);
            }
        }
        void report() {
            if (steep_first)
                resolved(reported, i);
            else
                resolved(n - i, n - reported);
            reported = i;
        }
        bool operator()(detail::walk_state<T>& w, T rho, T g_rho) {
            fetch_ahead(rho);
            const std::ptrdiff_t step = steep_first ? 1 : -1;
            std::uint32_t seg = detail::no_fan_segment;
            while (i < n) {
                const detail::fan_slope<T> sl = slopes[k];
                if (!(g_rho - sl.tau * rho > T(0))) {
                    if (seg == detail::no_fan_segment) {
                        const T mid = T(0.5) * (w.s + rho);
                        seg = static_cast<std::uint32_t>(count++);
                        segments[seg] = detail::fan_segment<T>{
                            w.s, w.f, rho, g_rho, w.ix, w.iy,
                            triangle_of((q.u0 + q.du * mid) - static_cast<T>(w.ix),
                                        (q.v0 + q.dv * mid) - static_cast<T>(w.iy))};
                    }
                    segment_of[k] = seg;
                } else if (rho * sl.inv_h > t_max_m) {
                    segment_of[k] = detail::no_fan_segment; // above the surface all the way to t_max
                } else {
                    break;
                }
                ++i;
                k += step;
            }
            if (i - reported >= batch || i == n) report();
            return i == n;
        }
    } visit{slopes.data(), segment_of.data(), segments.data(), q, resolved, t_max_m, n, std::max<std::size_t>(batch, 1),
            steep_first, 0, 0, 0, 0, g, T(8) / std::max(std::abs(q.du), std::abs(q.dv))};
    visit.k = steep_first ? 0 : static_cast<std::ptrdiff_t>(n) - 1;

    for (;;) {
        const detail::step_outcome o = detail::cell_step(g, q, w, visit);
        if (o != detail::step_outcome::next) break;
    }
    if (visit.i < n) {
        for (; visit.i < n; ++visit.i, visit.k += steep_first ? 1 : -1)
            segment_of[static_cast<std::size_t>(visit.k)] = detail::no_fan_segment;
        visit.report();
    }
    return true;
}

/// Traces the vertical fan `rays` with slopes `slopes` (as found by detail::find_fan_run; `steep_first`
/// says whether tau does not increase along the span) limited to distance t_max_m, calling
/// emit(k, const grid_hit<T>* h) once for every ray k (h null for a miss): sweep_fan, then each ray's root.
/// Returns false, having emitted nothing, when the sweep does not apply (see sweep_fan): the caller then
/// traces the rays one by one.
template <Real T, class Emit>
[[nodiscard]] bool trace_fan(const height_grid_view<T>& g, height_bounds<T> hb, std::span<const ray<T>> rays,
                             std::span<const detail::fan_slope<T>> slopes, bool steep_first, T t_max_m, Emit&& emit) {
    const std::size_t n = rays.size();
    std::vector<std::uint32_t> segment_of(n);
    std::vector<detail::fan_segment<T>> segments(n);
    return sweep_fan(g, hb, rays, slopes, steep_first, t_max_m, std::span(segment_of), std::span(segments), 1,
                     [&](std::size_t k_begin, std::size_t k_end) {
                         for (std::size_t k = k_begin; k < k_end; ++k) {
                             const std::uint32_t c = segment_of[k];
                             const T s = c == detail::no_fan_segment
                                             ? T(0)
                                             : detail::fan_distance(segments[c], slopes[k], t_max_m);
                             if (s > T(0)) {
                                 const grid_hit<T> h{s, segments[c].ix, segments[c].iy, segments[c].triangle};
                                 emit(k, &h);
                             } else {
                                 emit(k, static_cast<const grid_hit<T>*>(nullptr));
                             }
                         }
                     });
}

} // namespace sss::scene
