#pragma once
/// \file
/// Internal to the height-field tracers (height_field_tracer.hpp, height_field_fan.hpp, height_field_wedge.hpp):
/// a ray set up in grid units, its breakpoints (the grid lines and diagonals it crosses), the height of the ray
/// above the surface at them, and one step of the walk from cell to cell.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "sss/core/detail/force_inline.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/grid_hit.hpp"
#include "sss/scene/height_field_surface.hpp"

namespace sss::scene {

namespace detail {

/// Whether tau keeps a run of rays monotone: the first change fixes the run's order (`order` 0: not yet known,
/// 1: falling, -1: rising), a later change against it ends the run (false). Fan and wedge runs share it.
template <Real T> [[nodiscard]] inline bool keeps_order(T tau, T tau_prev, int& order) noexcept {
    const int step = tau < tau_prev ? 1 : (tau > tau_prev ? -1 : 0);
    if (step != 0) {
        if (order == 0)
            order = step;
        else if (step != order)
            return false;
    }
    return true;
}

/// A ray in grid units: u(s) = u0 + du s, v(s) = v0 + dv s, z(s) = z0 + dz s, s in metres.
template <Real T> struct grid_ray {
    T u0, v0, z0;
    T du, dv, dz;
    T inv_du, inv_dv;    // 1/du, 1/dv (unused when the step is 0)
    T w0, dw, inv_dw;    // w = u - v, the coordinate across the diagonals
    std::int32_t su, sv; // step of the cell index along u, v: -1, 0 or +1
    bool has_diag;       // the ray crosses diagonals (dw != 0)
    T s_lo, s_hi;        // the part of the ray over the grid, within [0, t_max] and the height slab
    T z_margin;          // a height well above rounding at this ray's scale (m)
};

/// 1/x, or 0 with step 0 when 1/x is not finite (a direction component too small to ever cross a line).
template <Real T> inline void inverse_and_step(T& x, T& inv, std::int32_t& step) noexcept {
    inv = T(1) / x;
    if (x == T(0) || !std::isfinite(inv)) {
        x = T(0);
        inv = T(0);
        step = 0;
    } else {
        step = x > T(0) ? 1 : -1;
    }
}

/// Clips [lo, hi] to the slab 0 <= x0 + dx s <= x_max; false when nothing is left. A ray that does not move along
/// this axis (dx = 0) is inside when x0 is, to within `slack` (grid units): a ray exactly on the footprint's edge, whose
/// grid coordinate rounding put a few ulps outside, still meets the edge.
template <Real T> inline bool clip_slab(T x0, T dx, T inv, T x_max, T& lo, T& hi, T slack) noexcept {
    if (dx == T(0)) return x0 >= -slack && x0 <= x_max + slack;
    T a = (T(0) - x0) * inv, b = (x_max - x0) * inv;
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
    return lo <= hi;
}

/// The part of a grid ray that depends on its origin alone, shared by rays from one point (the wedge sweep).
template <Real T> struct grid_origin {
    T u0, v0, z0, w0; // as in grid_ray
    T z_margin;       // as in grid_ray: it depends on the origin's height alone
    T u_slack, v_slack; // the rounding of u0 and of v0 (grid units): world x (y) rounded, less the origin, over the cell
    bool finite;        // u0, v0 and z0 are finite
};

/// The origin part of setup_ray for rays from `origin`.
template <Real T>
[[nodiscard]] inline grid_origin<T> origin_in_grid(const height_grid_view<T>& g, height_bounds<T> hb,
                                                   const vec3<T>& origin) noexcept {
    grid_origin<T> o;
    o.u0 = (origin.x - g.origin_m.x) * g.inv_cell_m;
    o.v0 = (origin.y - g.origin_m.y) * g.inv_cell_m;
    o.z0 = origin.z;
    o.w0 = o.u0 - o.v0;
    o.finite = std::isfinite(o.u0) && std::isfinite(o.v0) && std::isfinite(o.z0);
    // A world x on the grid rounds by at most eps/2 |x| <= eps/2 (|origin x| + |u0| cell), and u0's subtraction and
    // scaling add at most 1.5 eps |u0|.
    constexpr T eps = std::numeric_limits<T>::epsilon();
    o.u_slack = eps * (T(1) + T(2) * std::abs(o.u0) + T(0.5) * std::abs(g.origin_m.x) * g.inv_cell_m);
    o.v_slack = eps * (T(1) + T(2) * std::abs(o.v0) + T(0.5) * std::abs(g.origin_m.y) * g.inv_cell_m);
    // The margin, far above rounding, by which setup_ray widens the height slab: below bottom_m a ray that was above
    // the surface has hit it already, above top_m nothing can be hit. It also makes s_hi finite for every unit ray.
    o.z_margin = T(1e-4) * (T(1) + std::abs(o.z0) + std::abs(hb.top_m) + std::abs(hb.bottom_m)) +
                 T(1e-3) * (hb.top_m - hb.bottom_m);
    return o;
}

/// Prepares `q` for the ray from origin `o` (origin_in_grid) along `direction`, limited to distance t_max_m; false
/// when the ray cannot hit the grid at all. Always inlined: the wedge sweep sets up every ray of a column.
template <Real T>
SSS_FORCE_INLINE bool setup_ray(const height_grid_view<T>& g, height_bounds<T> hb, const grid_origin<T>& o,
                                const vec3<T>& direction, T t_max_m, grid_ray<T>& q) noexcept {
    if (!(t_max_m > T(0)) || !o.finite) return false;
    const T inv_c = g.inv_cell_m;
    q.u0 = o.u0;
    q.v0 = o.v0;
    q.z0 = o.z0;
    q.du = direction.x * inv_c;
    q.dv = direction.y * inv_c;
    q.dz = direction.z;
    if (!std::isfinite(q.du) || !std::isfinite(q.dv) || !std::isfinite(q.dz)) return false;
    inverse_and_step(q.du, q.inv_du, q.su);
    inverse_and_step(q.dv, q.inv_dv, q.sv);
    q.w0 = o.w0;
    q.dw = q.du - q.dv;
    std::int32_t sw = 0;
    inverse_and_step(q.dw, q.inv_dw, sw);
    q.has_diag = sw != 0;
    if (q.su == 0 && q.sv == 0 && q.dz == T(0)) return false; // not a direction

    T lo = T(0), hi = t_max_m;
    if (!clip_slab(q.u0, q.du, q.inv_du, static_cast<T>(g.nx - 1), lo, hi, o.u_slack)) return false;
    if (!clip_slab(q.v0, q.dv, q.inv_dv, static_cast<T>(g.ny - 1), lo, hi, o.v_slack)) return false;
    q.z_margin = o.z_margin;
    if (q.dz < T(0)) {
        hi = std::min(hi, (q.z0 - (hb.bottom_m - q.z_margin)) / -q.dz);
    } else if (q.dz > T(0)) {
        hi = std::min(hi, (q.z0 - (hb.top_m + q.z_margin)) / -q.dz);
    }
    if (!(lo <= hi) || !std::isfinite(hi)) return false;
    q.s_lo = lo;
    q.s_hi = hi;
    return true;
}

/// Prepares `q` for ray `r` limited to distance t_max_m; false when the ray cannot hit the grid at all.
template <Real T> inline bool setup_ray(const height_grid_view<T>& g, height_bounds<T> hb, const ray<T>& r, T t_max_m,
                                        grid_ray<T>& q) noexcept {
    return setup_ray(g, hb, origin_in_grid(g, hb, r.origin), r.direction, t_max_m, q);
}

/// Distance at which the ray crosses the line u = i, v = j, or u - v = k.
template <Real T> [[nodiscard]] inline T cross_u(const grid_ray<T>& q, std::int32_t i) noexcept {
    return (static_cast<T>(i) - q.u0) * q.inv_du;
}
template <Real T> [[nodiscard]] inline T cross_v(const grid_ray<T>& q, std::int32_t j) noexcept {
    return (static_cast<T>(j) - q.v0) * q.inv_dv;
}
template <Real T> [[nodiscard]] inline T cross_diag(const grid_ray<T>& q, std::int32_t k) noexcept {
    return (static_cast<T>(k) - q.w0) * q.inv_dw;
}

/// f = z_ray - h at distance s where the ray crosses the vertex column u = i (linear along that line).
template <Real T>
[[nodiscard]] inline T f_on_u_line(const height_grid_view<T>& g, const grid_ray<T>& q, std::int32_t i, T s) noexcept {
    const T v = q.v0 + q.dv * s;
    const std::int32_t j = cell_of(v, g.ny - 2);
    const T h0 = g.at(i, j);
    const T h = h0 + (v - static_cast<T>(j)) * (g.at(i, j + 1) - h0);
    return (q.z0 + q.dz * s) - h;
}
/// f where the ray crosses the vertex row v = j.
template <Real T>
[[nodiscard]] inline T f_on_v_line(const height_grid_view<T>& g, const grid_ray<T>& q, std::int32_t j, T s) noexcept {
    const T u = q.u0 + q.du * s;
    const std::int32_t i = cell_of(u, g.nx - 2);
    const T h0 = g.at(i, j);
    const T h = h0 + (u - static_cast<T>(i)) * (g.at(i + 1, j) - h0);
    return (q.z0 + q.dz * s) - h;
}
/// f where the ray crosses the diagonal of cell (ix, iy).
template <Real T> [[nodiscard]] inline T f_on_diagonal(const height_grid_view<T>& g, const grid_ray<T>& q,
                                                       std::int32_t ix, std::int32_t iy, T s) noexcept {
    const T a = (q.u0 + q.du * s) - static_cast<T>(ix);
    const T h0 = g.at(ix, iy);
    const T h = h0 + a * (g.at(ix + 1, iy + 1) - h0);
    return (q.z0 + q.dz * s) - h;
}
/// f at any distance s (the ray's start and end points).
template <Real T> [[nodiscard]] inline T f_at(const height_grid_view<T>& g, const grid_ray<T>& q, T s) noexcept {
    return (q.z0 + q.dz * s) - height_at_grid(g, q.u0 + q.du * s, q.v0 + q.dv * s);
}

/// The walk along one ray: the last breakpoint (distance s, value f), its cell, and whether f > 0 there.
template <Real T> struct walk_state {
    T s;
    T f;
    std::int32_t ix, iy;
    bool above;
};

/// The root of f on the segment [s_a, s_b] of cell (ix, iy), with f_a > 0 >= f_b. False when the root is
/// not at a positive distance (a ray starting on the surface).
template <Real T> inline bool segment_root(const grid_ray<T>& q, T s_a, T f_a, T s_b, T f_b, std::int32_t ix,
                                           std::int32_t iy, grid_hit<T>& out) noexcept {
    const T s = std::clamp(s_a + (s_b - s_a) * (f_a / (f_a - f_b)), s_a, s_b);
    if (!(s > T(0))) return false;
    const T s_mid = T(0.5) * (s_a + s_b);
    out.distance_m = s;
    out.ix = ix;
    out.iy = iy;
    out.triangle = triangle_of((q.u0 + q.du * s_mid) - static_cast<T>(ix), (q.v0 + q.dv * s_mid) - static_cast<T>(iy));
    return true;
}

enum class step_outcome : unsigned char { next, done, found };

/// Walks one cell: from the state's breakpoint through the cell's diagonal (when the ray crosses it) to
/// the cell's exit (or to s_hi), calling `visit(w, s, f)` at each new breakpoint while `w` still holds the
/// previous one (so [w.s, s] is a segment inside cell (w.ix, w.iy)); `visit` returns true to stop the walk.
/// Then moves the state into the next cell. Always inlined: it runs once or twice per ray in the sweeps, where the
/// call took about a sixth of the time.
template <Real T, class Visit>
SSS_FORCE_INLINE step_outcome cell_step(const height_grid_view<T>& g, const grid_ray<T>& q, walk_state<T>& w,
                                        Visit&& visit) noexcept {
    constexpr T inf = std::numeric_limits<T>::infinity();
    const T sx = q.su > 0 ? cross_u(q, w.ix + 1) : (q.su < 0 ? cross_u(q, w.ix) : inf);
    const T sy = q.sv > 0 ? cross_v(q, w.iy + 1) : (q.sv < 0 ? cross_v(q, w.iy) : inf);
    const T s_exit = std::min(sx, sy);
    const bool last = !(s_exit < q.s_hi);
    const T se = last ? q.s_hi : std::max(s_exit, w.s);
    if (q.has_diag) {
        const T sd = cross_diag(q, w.ix - w.iy);
        if (sd > w.s && sd < se) {
            const T fd = f_on_diagonal(g, q, w.ix, w.iy, sd);
            if (visit(w, sd, fd)) return step_outcome::found;
            w.s = sd;
            w.f = fd;
        }
    }
    T fe;
    if (last)
        fe = f_at(g, q, se);
    else if (sx <= sy)
        fe = f_on_u_line(g, q, q.su > 0 ? w.ix + 1 : w.ix, se);
    else
        fe = f_on_v_line(g, q, q.sv > 0 ? w.iy + 1 : w.iy, se);
    if (visit(w, se, fe)) return step_outcome::found;
    w.s = se;
    w.f = fe;
    if (last) return step_outcome::done;
    if (sx <= sy) w.ix += q.su;
    if (sy <= sx) w.iy += q.sv;
    if (w.ix < 0 || w.iy < 0 || w.ix > g.nx - 2 || w.iy > g.ny - 2) return step_outcome::done;
    return step_outcome::next;
}

/// The single-ray rule at a breakpoint: a hit when f goes from > 0 to <= 0; `above` remembers the sign.
template <Real T> struct first_crossing {
    const grid_ray<T>& q;
    grid_hit<T>& out;
    bool operator()(walk_state<T>& w, T s, T f) const noexcept {
        if (w.above && !(f > T(0)) && segment_root(q, w.s, w.f, s, f, w.ix, w.iy, out)) return true;
        w.above = f > T(0);
        return false;
    }
};

/// The walk's first state at distance s: its cell and f there.
template <Real T>
[[nodiscard]] inline walk_state<T> start_at(const height_grid_view<T>& g, const grid_ray<T>& q, T s) noexcept {
    walk_state<T> w;
    w.s = s;
    w.ix = cell_of(q.u0 + q.du * s, g.nx - 2);
    w.iy = cell_of(q.v0 + q.dv * s, g.ny - 2);
    w.f = T(0);
    w.above = false;
    return w;
}

/// The cell along one axis that the walk is in at distance s (m), the axis being c(s) = c0 + d s with 1/d = inv and
/// the walk's step `step` on it: the cell entered by the last line crossed at a distance <= s (by cross_u / cross_v's
/// formula, a tie crossed, as cell_step does). cell_of(c(s)) alone can put a point a rounding error from a line in
/// the cell beyond it while the walk, comparing the lines' crossings, is still before it; a walk resumed there would
/// miss that line's breakpoint.
template <Real T>
[[nodiscard]] inline std::int32_t walk_cell(T c0, T d, T inv, std::int32_t step, std::int32_t last_cell, T s) noexcept {
    std::int32_t i = cell_of(c0 + d * s, last_cell);
    auto crossed = [&](std::int32_t line) { return (static_cast<T>(line) - c0) * inv <= s; };
    if (step > 0) {
        if (i > 0 && !crossed(i))
            --i;
        else if (i < last_cell && crossed(i + 1))
            ++i;
    } else if (step < 0) {
        if (i < last_cell && !crossed(i + 1))
            ++i;
        else if (i > 0 && crossed(i))
            --i;
    }
    return i;
}

/// A breakpoint where the single-ray walk enters cell (ix, iy): across the line u = line (on_u) or v = line, at
/// distance s (m).
template <Real T> struct cell_entry {
    T s;
    std::int32_t ix, iy;
    std::int32_t line;
    bool on_u;
};

/// The crossing where the walk enters the cell that holds distance s (m). It is a breakpoint of the walk from the
/// ray's start, so a walk resumed there, with f by the line's formula (f_on_entry), sees the same numbers from
/// there on as the walk from the start: the hit is the same to the last bit. Empty when that cell is the one where
/// the ray comes over the grid (the crossing lies at or before s_lo); a walk then starts at s_lo, as that one does.
template <Real T>
[[nodiscard]] inline std::optional<cell_entry<T>> entry_of_cell_at(const height_grid_view<T>& g, const grid_ray<T>& q,
                                                                   T s) noexcept {
    constexpr T inf = std::numeric_limits<T>::infinity();
    const std::int32_t ix = walk_cell(q.u0, q.du, q.inv_du, q.su, g.nx - 2, s);
    const std::int32_t iy = walk_cell(q.v0, q.dv, q.inv_dv, q.sv, g.ny - 2, s);
    const T s_in_u = q.su > 0 ? cross_u(q, ix) : (q.su < 0 ? cross_u(q, ix + 1) : -inf);
    const T s_in_v = q.sv > 0 ? cross_v(q, iy) : (q.sv < 0 ? cross_v(q, iy + 1) : -inf);
    const T s_in = std::max(s_in_u, s_in_v);
    if (!(s_in > q.s_lo && s_in <= s)) return std::nullopt;
    const bool on_u = s_in_u >= s_in_v;
    return cell_entry<T>{s_in, ix, iy, on_u ? (q.su > 0 ? ix : ix + 1) : (q.sv > 0 ? iy : iy + 1), on_u};
}

/// f at a cell's entry crossing, by the formula the walk uses there.
template <Real T>
[[nodiscard]] inline T f_on_entry(const height_grid_view<T>& g, const grid_ray<T>& q, const cell_entry<T>& e) noexcept {
    return e.on_u ? f_on_u_line(g, q, e.line, e.s) : f_on_v_line(g, q, e.line, e.s);
}

/// The cell along one axis (0 to last_cell) that holds grid coordinate c, kept inside block b of 2^level cells
/// and never moved against the walk's step (step > 0: not below current; step < 0: not above it).
template <Real T>
[[nodiscard]] inline std::int32_t exit_cell_in_block(T c, std::int32_t last_cell, std::int32_t b, int level,
                                                     std::int32_t step, std::int32_t current) noexcept {
    const std::int32_t lo = b << level, hi = std::min(((b + 1) << level) - 1, last_cell);
    const std::int32_t i = std::clamp(cell_of(c, last_cell), lo, hi);
    return step > 0 ? std::max(i, current) : std::min(i, current);
}

} // namespace detail

} // namespace sss::scene
