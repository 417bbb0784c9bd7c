#pragma once
/// \file
/// How far a ray surely stays above a height field, from what a steeper neighbour found: the wedge sweep's chain
/// (height_field_wedge.hpp) for one ray at a time, as the simulator's refinement traces a ray between two it has
/// traced already (sampling/detail/tube_refinement.hpp).
///
/// Rays a and r leave one origin; a descends faster, tau_a > tau_r (tau = tan(depression), height lost per metre
/// of horizontal travel), and its heading is turned from r's by an angle theta. a is known above the surface out to
/// horizontal distance rho_a (its first hit: before it, the surface lies below it). At horizontal distance rho <=
/// rho_a, r lies (tau_a - tau_r) rho above a, and the points under the two rays are at most rho theta apart, so the
/// surface under r is at most L rho theta higher than under a, L = sqrt(2) max_step / cell the triangulated surface's
/// largest slope (max_pyramid::max_step_m). Hence r stays above the surface out to rho_a wherever
///     (tau_a - tau_r - L theta) rho > rounding,
/// that is, beyond rho_min = rounding / (tau_a - tau_r - L theta). Nearer the origin, r must lie above the highest
/// vertex within rho_min of it (from the maximum pyramid, over a square at least that wide): then the origin lies
/// clearly above the surface, so a cannot have started inside the sediment either. One more condition
/// keeps the argument exact: a's path up to rho_a lies over the grid's footprint (the surface under it is defined
/// there; a path that leaves the footprint is not covered).
///
/// Bent rays (layered water) keep the argument with a lower bound in place of (tau_a - tau_r) rho and a margin for the
/// chords they are traced along (beside_rays.hpp; propagation/layered.hpp derives both): clear_range_beside_m takes
/// the general form, clear_beside_m the straight one.
///
/// trace_accelerated then starts r's walk at the entry crossing of the cell holding that distance: the same hit to
/// the last bit, in a few cells instead of a walk from the top down, with one exception. The walk reads the surface
/// at a grid position rounded by about eps |u| cells (u the position in cells from the grid's corner), so where the
/// surface is steep it may read a height off by that times the steepest step between vertices: up to a millimetre
/// for a float ray 4000 cells from the corner passing a step of 2 m. A plain walk that stops before the guide's hit
/// because of that alone (the ray truly above the surface there) is not repeated: the guided walk passes the point,
/// as the exact geometry does. Bounding that rounding with the grid's steepest step would refuse most guides on a
/// large float grid with one steep feature (on the survey of bench/bench_survey.cpp, 86 % of them).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "sss/core/ray.hpp"
#include "sss/scene/beside_rays.hpp"
#include "sss/scene/grid_hit.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_grid.hpp"

namespace sss::scene {

/// The highest vertex (m) within radius_cells of grid point (u, v) (a point of the footprint), or higher: the
/// maximum pyramid's blocks, at most two per axis, over the cells of the square around it; the top where that
/// square is too large or the grid has no pyramid.
template <Real T>
[[nodiscard]] T highest_near(const height_grid_view<T>& g, const max_pyramid<T>& p, height_bounds<T> hb, T u, T v,
                             T radius_cells) noexcept {
    const T reach = radius_cells + T(1);
    if (!(reach < T(1 << 20)) || p.levels() < 1) return hb.top_m;
    const auto cell = [](T x, std::int32_t last) {
        return static_cast<std::int32_t>(std::clamp(std::floor(x), T(0), static_cast<T>(last)));
    };
    const std::int32_t x0 = cell(u - reach, g.nx - 2), x1 = cell(u + reach, g.nx - 2);
    const std::int32_t y0 = cell(v - reach, g.ny - 2), y1 = cell(v + reach, g.ny - 2);
    const std::int32_t span = std::max(x1 - x0, y1 - y0);
    const auto width_level = static_cast<std::int32_t>(std::bit_width(static_cast<std::uint32_t>(span)));
    const std::int32_t level = std::min(p.levels(), std::max<std::int32_t>(1, width_level));
    T top = -std::numeric_limits<T>::infinity();
    for (std::int32_t by = y0 >> level; by <= (y1 >> level); ++by)
        for (std::int32_t bx = x0 >> level; bx <= (x1 >> level); ++bx) top = std::max(top, p.max_m(level, bx, by));
    return top;
}

/// Horizontal distance (m) from b.origin within which ray r surely stays above the height field (g, its pyramid p and
/// bounds hb), given what b says of r and its neighbour a (beside_rays.hpp): the file comment's chain with b.gain in
/// place of tau_a - tau_r, b.slope_r bounding how fast r comes down near the origin, and b.margin_m added to the
/// rounding. 0 where it does not apply (headings more than 2.5 degrees apart, a gain the turn eats, an origin not
/// clearly above the surface around it, a's path off the footprint, non-finite or negative inputs).
template <Real T>
[[nodiscard]] T clear_range_beside_m(const height_grid_view<T>& g, const max_pyramid<T>& p, height_bounds<T> hb,
                                     const beside_rays<T>& b) noexcept {
    const T rho_a = b.rho_a_m;
    if (!(rho_a > T(0)) || !std::isfinite(rho_a) || !(b.gain > T(0)) || !std::isfinite(b.gain) ||
        !(b.slope_r >= T(0)) || !std::isfinite(b.slope_r) || !(b.drop_a_m >= T(0)) || !std::isfinite(b.drop_a_m) ||
        !(b.margin_m >= T(0)) || !std::isfinite(b.margin_m))
        return T(0);
    const T z0 = b.origin.z;
    // a's path out to its clear point over the footprint (a segment between two points of a rectangle).
    const T u0 = (b.origin.x - g.origin_m.x) * g.inv_cell_m, v0 = (b.origin.y - g.origin_m.y) * g.inv_cell_m;
    const T ua = u0 + b.heading_a.x * rho_a * g.inv_cell_m, va = v0 + b.heading_a.y * rho_a * g.inv_cell_m;
    const T nu = static_cast<T>(g.nx - 1), nv = static_cast<T>(g.ny - 1);
    if (!(u0 >= T(0) && v0 >= T(0) && u0 <= nu && v0 <= nv && ua >= T(0) && va >= T(0) && ua <= nu && va <= nv))
        return T(0);
    // The turn between the headings, theta, as its sine: the points under the two rays at rho are 2 rho sin(theta/2)
    // apart, at most 1.001 rho sin(theta) while cos(theta) > 0.999 (theta below 2.5 degrees; neighbours in a
    // refinement turn far less), plus rounding.
    const T eps = std::numeric_limits<T>::epsilon();
    const vec2<T> hr = b.heading_r, ha = b.heading_a;
    if (!(hr.x * ha.x + hr.y * ha.y > T(0.999))) return T(0);
    const T turn = T(1.001) * std::abs(ha.x * hr.y - ha.y * hr.x) + T(8) * eps;
    const T lipschitz = p.max_step_m() * T(1.41421357) * g.inv_cell_m;
    const T gain = b.gain - lipschitz * turn; // height r gains over a per metre of horizontal travel
    // Rounding of f = z - h, at a's points (its first hit) and at r's: a few roundings of the terms' magnitudes. (Not
    // the rounding of the grid position the surface is read at: see the file comment.)
    const T err = T(16) * eps * (T(1) + std::abs(z0) + std::abs(hb.top_m) + std::abs(hb.bottom_m) + b.drop_a_m) +
                  b.margin_m;
    if (!(gain > T(0))) return T(0);
    const T rho_min = err / gain; // beyond it r is above a by more than rounding
    if (!(z0 - b.slope_r * rho_min > highest_near(g, p, hb, u0, v0, rho_min * g.inv_cell_m) + err)) return T(0);
    return rho_a;
}

/// Distance (m) along r below which r surely stays above the height field (g, its pyramid p and bounds hb), given
/// that straight ray `a` from the same origin met nothing of it for distances below a_clear_m (m): the file comment's
/// chain (clear_range_beside_m, with gain tau_a - tau_r). 0 where it does not apply (different origins, a not
/// steeper by enough, headings more than 2.5 degrees apart, an origin not clearly above the surface around it, a's
/// path off the footprint, near-vertical or non-finite rays).
template <Real T>
[[nodiscard]] T clear_beside_m(const height_grid_view<T>& g, const max_pyramid<T>& p, height_bounds<T> hb,
                               const ray<T>& r, const ray<T>& a, T a_clear_m) noexcept {
    if (!(r.origin == a.origin) || !(a_clear_m > T(0)) || !std::isfinite(a_clear_m)) return T(0);
    const T hr = std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
    const T ha = std::sqrt(a.direction.x * a.direction.x + a.direction.y * a.direction.y);
    // Within 0.06 degrees of vertical headings mean little (the wedge sweep's limit).
    if (!(hr >= T(1e-3)) || !(ha >= T(1e-3))) return T(0);
    const T tau_r = -r.direction.z / hr, tau_a = -a.direction.z / ha;
    if (!std::isfinite(tau_r) || !std::isfinite(tau_a) || !(tau_r > T(0)) || !(tau_a > tau_r)) return T(0);
    const T rho_a = a_clear_m * ha; // horizontal distance (m)
    const beside_rays<T> b{.origin = r.origin,
                           .heading_r = {r.direction.x / hr, r.direction.y / hr},
                           .heading_a = {a.direction.x / ha, a.direction.y / ha},
                           .rho_a_m = rho_a,
                           .gain = tau_a - tau_r,
                           .slope_r = tau_r,
                           .drop_a_m = tau_a * rho_a,
                           .margin_m = T(0)};
    return clear_range_beside_m(g, p, hb, b) > T(0) ? rho_a / hr : T(0);
}

} // namespace sss::scene
