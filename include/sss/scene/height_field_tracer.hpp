#pragma once
/// \file
/// Exact, watertight ray tracing of a triangulated height field (see height_field_surface.hpp), two ways:
/// `trace_reference`, a plain 2D DDA over every cell the ray's xy projection crosses (the reference,
/// kept simple on purpose), and `trace_accelerated`, the same exact cell test behind a maximum pyramid
/// (height_field_pyramid.hpp) that skips blocks the ray passes above.
///
/// How a hit is found. Along the ray, with s the distance (m), let f(s) = z_ray(s) - h(x(s), y(s)): the
/// ray's height above the surface. Inside one triangle h is linear in x and y, hence f is linear in s; f
/// changes slope only where the ray's projection crosses a line u = i, v = j or u - v = k (grid units).
/// The tracer walks those crossings ("breakpoints") in order, evaluates f once at each, and reports the
/// first segment where f goes from > 0 to <= 0; the hit is that segment's linear root,
///     s = s_a + (s_b - s_a) f_a / (f_a - f_b),
/// exact up to rounding because f is linear on the segment.
///
/// Why it is watertight. Every breakpoint's f is computed once and shared by the two segments that meet
/// there, so the walk sees one sequence of numbers and a sign change in it cannot fall between two
/// segments, whatever the rounding: a ray aimed at an edge or a vertex gets f ~ 0 there, and either that
/// value or its neighbour closes the sign change. Rounding can move a hit by a few ulps; it cannot lose
/// one. (The only rays that may pass are those that touch the surface tangentially, within rounding, and
/// leave it again: f never becomes clearly negative.) No per-triangle test is needed at all.
///
/// Which side counts. The seabed is the top of a solid: only a crossing from above (f > 0) to on/below
/// (f <= 0) is a hit, the same rule as flat_seabed. A ray that starts below the surface, or enters the
/// grid's footprint through its side below the surface, is inside the sediment: it is not stopped while
/// it rises out of the surface, and it hits the surface further on only if it comes down onto it again.
/// A ray whose origin lies on the surface (within rounding) does not hit that point (hits need
/// distance > 0). Outside the grid's footprint there is no surface for rays (seabed_height_m clamps, the
/// tracer does not).
///
/// The hit's triangle is the one holding the midpoint of the segment that holds the root.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "sss/core/ray.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_field_surface.hpp"

namespace sss::scene {

/// What a grid tracer found: the distance along the ray and the cell and triangle that hold the hit.
template <Real T> struct grid_hit {
    T distance_m{};                                ///< distance from the ray origin (m)
    std::int32_t ix = 0;                           ///< cell column
    std::int32_t iy = 0;                           ///< cell row
    cell_triangle triangle = cell_triangle::lower; ///< half of the cell
};

/// Height bounds of a grid: the tracers clip rays to the slab bottom_m <= z <= top_m.
template <Real T> struct height_bounds {
    T bottom_m{}; ///< lowest vertex (m)
    T top_m{};    ///< highest vertex (m)
};

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

/// Clips [lo, hi] to the slab 0 <= x0 + dx s <= x_max; false when nothing is left.
template <Real T> inline bool clip_slab(T x0, T dx, T inv, T x_max, T& lo, T& hi) noexcept {
    if (dx == T(0)) return x0 >= T(0) && x0 <= x_max;
    T a = (T(0) - x0) * inv, b = (x_max - x0) * inv;
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
    return lo <= hi;
}

/// Prepares `q` for ray `r` limited to distance t_max_m; false when the ray cannot hit the grid at all.
template <Real T> inline bool setup_ray(const height_grid_view<T>& g, height_bounds<T> hb, const ray<T>& r, T t_max_m,
                                        grid_ray<T>& q) noexcept {
    if (!(t_max_m > T(0))) return false;
    const T inv_c = g.inv_cell_m;
    q.u0 = (r.origin.x - g.origin_m.x) * inv_c;
    q.v0 = (r.origin.y - g.origin_m.y) * inv_c;
    q.z0 = r.origin.z;
    q.du = r.direction.x * inv_c;
    q.dv = r.direction.y * inv_c;
    q.dz = r.direction.z;
    if (!std::isfinite(q.u0) || !std::isfinite(q.v0) || !std::isfinite(q.z0) || !std::isfinite(q.du) ||
        !std::isfinite(q.dv) || !std::isfinite(q.dz))
        return false;
    inverse_and_step(q.du, q.inv_du, q.su);
    inverse_and_step(q.dv, q.inv_dv, q.sv);
    q.w0 = q.u0 - q.v0;
    q.dw = q.du - q.dv;
    std::int32_t sw = 0;
    inverse_and_step(q.dw, q.inv_dw, sw);
    q.has_diag = sw != 0;
    if (q.su == 0 && q.sv == 0 && q.dz == T(0)) return false; // not a direction

    T lo = T(0), hi = t_max_m;
    if (!clip_slab(q.u0, q.du, q.inv_du, static_cast<T>(g.nx - 1), lo, hi)) return false;
    if (!clip_slab(q.v0, q.dv, q.inv_dv, static_cast<T>(g.ny - 1), lo, hi)) return false;
    // Height slab, widened by a margin far above rounding: below bottom_m a ray that was above the surface
    // has hit it already, above top_m nothing can be hit. This also makes s_hi finite for every unit ray.
    q.z_margin = T(1e-4) * (T(1) + std::abs(q.z0) + std::abs(hb.top_m) + std::abs(hb.bottom_m)) +
                 T(1e-3) * (hb.top_m - hb.bottom_m);
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
/// Then moves the state into the next cell.
template <Real T, class Visit> inline step_outcome cell_step(const height_grid_view<T>& g, const grid_ray<T>& q,
                                                             walk_state<T>& w, Visit&& visit) noexcept {
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

} // namespace detail

/// The reference traversal: every cell along the ray's xy projection, clipped to the grid's footprint and
/// to [0, t_max_m], gets the exact cell test. Simple on purpose; it checks the accelerated one.
template <Real T> [[nodiscard]] std::optional<grid_hit<T>>
trace_reference(const height_grid_view<T>& g, height_bounds<T> hb, const ray<T>& r, T t_max_m) noexcept {
    detail::grid_ray<T> q;
    if (!detail::setup_ray(g, hb, r, t_max_m, q)) return std::nullopt;
    detail::walk_state<T> w = detail::start_at(g, q, q.s_lo);
    w.f = detail::f_at(g, q, w.s);
    w.above = w.f > T(0);
    grid_hit<T> out;
    const detail::first_crossing<T> visit{q, out};
    for (;;) {
        const detail::step_outcome o = detail::cell_step(g, q, w, visit);
        if (o == detail::step_outcome::found) return out;
        if (o == detail::step_outcome::done) return std::nullopt;
    }
}

/// The accelerated traversal over the maximum pyramid `p` of grid `g` (Tevs, Ihrke & Seidel 2008): a ray
/// first jumps to where it comes down to top_m; then, starting at the level whose blocks match the
/// length of its path, it skips every block whose maximum lies below the ray all across the block,
/// descends a level where it cannot skip, goes up a level after a skip or a cell only into a parent block
/// not tested yet, and gives the cells it cannot skip the same exact test as trace_reference. Skips and
/// jumps resume at crossings that are breakpoints of the reference walk too, evaluated by the same
/// formulas, so both traversals return the same hit to the last bit, in float and in double (they could
/// differ only for a ray passing within rounding of a skipped block's highest vertex).
template <Real T>
[[nodiscard]] std::optional<grid_hit<T>> trace_accelerated(const height_grid_view<T>& g, const max_pyramid<T>& p,
                                                           height_bounds<T> hb, const ray<T>& r, T t_max_m) noexcept {
    detail::grid_ray<T> q;
    if (!detail::setup_ray(g, hb, r, t_max_m, q)) return std::nullopt;
    constexpr T inf = std::numeric_limits<T>::infinity();

    detail::walk_state<T> w = detail::start_at(g, q, q.s_lo);
    // Where f was last evaluated: a plain point (the start) or a crossing of line u = line / v = line.
    enum class at_kind : unsigned char { point, u_line, v_line } kind = at_kind::point;
    std::int32_t line = 0;
    bool f_known = false; // w.f holds f at w.s

    // Nothing lies above top_m: a ray that does not come down to it misses, and one that does skips to
    // the cell where it does, resuming at that cell's entry crossing (a breakpoint of the reference walk
    // too, so both walks evaluate f at the same places).
    const T z_top = hb.top_m + q.z_margin;
    if (q.z0 + q.dz * q.s_lo > z_top) {
        if (!(q.z0 + q.dz * q.s_hi <= z_top)) return std::nullopt;
        const T s_top = (q.z0 - z_top) / -q.dz;
        const detail::walk_state<T> c = detail::start_at(g, q, s_top);
        const T s_in_u = q.su > 0 ? detail::cross_u(q, c.ix) : (q.su < 0 ? detail::cross_u(q, c.ix + 1) : -inf);
        const T s_in_v = q.sv > 0 ? detail::cross_v(q, c.iy) : (q.sv < 0 ? detail::cross_v(q, c.iy + 1) : -inf);
        const T s_in = std::max(s_in_u, s_in_v);
        if (s_in > q.s_lo && s_in <= s_top) {
            w.ix = c.ix;
            w.iy = c.iy;
            w.s = s_in;
            w.above = true;
            kind = s_in_u >= s_in_v ? at_kind::u_line : at_kind::v_line;
            line = s_in_u >= s_in_v ? (q.su > 0 ? c.ix : c.ix + 1) : (q.sv > 0 ? c.iy : c.iy + 1);
        }
    }
    const std::int32_t top_level = p.levels();
    // Start at the level whose blocks match the length of the ray's path over the grid (in cells).
    const T path_cells = (std::abs(q.du) + std::abs(q.dv)) * (q.s_hi - w.s);
    std::int32_t level = top_level;
    if (path_cells < static_cast<T>(std::int32_t(1) << std::min<std::int32_t>(top_level, 30)))
        level = static_cast<std::int32_t>(std::bit_width(static_cast<std::uint32_t>(path_cells)));
    grid_hit<T> out;

    const std::int32_t pu = q.su > 0 ? 1 : 0, pv = q.sv > 0 ? 1 : 0;
    for (;;) {
        if (level > 0) {
            // Block (bx, by) at `level` holds the current cell; the ray leaves it across line u = ux or
            // v = vy at distance se.
            const std::int32_t bx = w.ix >> level, by = w.iy >> level;
            const std::int32_t ux = (bx + pu) << level, vy = (by + pv) << level;
            const T sx = q.su != 0 ? detail::cross_u(q, ux) : inf;
            const T sy = q.sv != 0 ? detail::cross_v(q, vy) : inf;
            const T se = std::max(std::min(std::min(sx, sy), q.s_hi), w.s);
            const T z_low = q.z0 + q.dz * (q.dz < T(0) ? se : w.s);
            if (!(z_low > p.max_m(level, bx, by))) {
                --level;
                continue;
            }
            // The ray is above everything in this block: skip to its exit, across the exit line on the
            // crossed axis; on the other axis into the cell holding the exit point, kept inside the block
            // and never moved backwards.
            if (!(se < q.s_hi)) return std::nullopt;
            const std::int32_t old_ix = w.ix, old_iy = w.iy;
            const bool cross_x = sx <= sy, cross_y = sy <= sx;
            if (cross_x) {
                w.ix = ux - 1 + pu;
                kind = at_kind::u_line;
                line = ux;
            } else if (q.su != 0) {
                const std::int32_t lo = bx << level, hi = std::min(((bx + 1) << level) - 1, g.nx - 2);
                const std::int32_t i = std::clamp(detail::cell_of(q.u0 + q.du * se, g.nx - 2), lo, hi);
                w.ix = q.su > 0 ? std::max(i, w.ix) : std::min(i, w.ix);
            }
            if (cross_y) {
                w.iy = vy - 1 + pv;
                if (!cross_x) {
                    kind = at_kind::v_line;
                    line = vy;
                }
            } else if (q.sv != 0) {
                const std::int32_t lo = by << level, hi = std::min(((by + 1) << level) - 1, g.ny - 2);
                const std::int32_t j = std::clamp(detail::cell_of(q.v0 + q.dv * se, g.ny - 2), lo, hi);
                w.iy = q.sv > 0 ? std::max(j, w.iy) : std::min(j, w.iy);
            }
            if (w.ix < 0 || w.iy < 0 || w.ix > g.nx - 2 || w.iy > g.ny - 2) return std::nullopt;
            w.s = se;
            w.above = true; // f > 0 all through the skipped block
            f_known = false;
            // Go up only into a parent block not tested yet: the old parent failed with this same exit.
            if (level < top_level && (((w.ix ^ old_ix) | (w.iy ^ old_iy)) >> (level + 1)) != 0) ++level;
            continue;
        }

        if (!f_known) {
            switch (kind) {
            case at_kind::point:
                w.f = detail::f_at(g, q, w.s);
                break;
            case at_kind::u_line:
                w.f = detail::f_on_u_line(g, q, line, w.s);
                break;
            case at_kind::v_line:
                w.f = detail::f_on_v_line(g, q, line, w.s);
                break;
            }
            f_known = true;
            // After a skip f was > 0 just before; only rounding can make it <= 0 here: the hit is this point.
            if (w.above && !(w.f > T(0)) && detail::segment_root(q, w.s, T(1), w.s, w.f, w.ix, w.iy, out)) return out;
            w.above = w.f > T(0);
        }
        const std::int32_t old_ix = w.ix, old_iy = w.iy;
        const detail::step_outcome o = detail::cell_step(g, q, w, detail::first_crossing<T>{q, out});
        if (o == detail::step_outcome::found) return out;
        if (o == detail::step_outcome::done) return std::nullopt;
        if (top_level > 0 && (((w.ix ^ old_ix) | (w.iy ^ old_iy)) >> 1) != 0) level = 1;
    }
}

} // namespace sss::scene
