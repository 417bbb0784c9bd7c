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
#include "sss/scene/detail/grid_walk.hpp"
#include "sss/scene/grid_hit.hpp"
#include "sss/scene/height_field_surface.hpp"

namespace sss::scene {

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
/// formulas, in the cell the reference walk is in there (on the axis not crossed, the cell is found by comparing
/// the lines' crossings, as the walk does: the exit point's coordinate alone can round into the next cell, and the
/// walk would then miss that line's breakpoint; at a vertex, where a u and a v line are crossed at the same distance,
/// by the u line's formula, as the walk), so both traversals return the same hit to the last bit, in float and in
/// double (they could differ only for a ray passing within rounding of a skipped block's highest vertex, or entering
/// the grid's footprint within rounding of a block's edge).
///
/// A caller that knows the ray stays above the surface for every distance below `s_clear_m` (m; see
/// clear_beside_m, and its file comment for the one way rounding can still differ) lets the walk resume at the
/// entry crossing of the cell holding that distance, as it does where the ray comes down to top_m: the hit is the
/// same to the last bit, since the walk evaluates f at the same breakpoints from there on and the reference walk
/// finds no sign change before. With the guarantee broken, a hit before s_clear_m is missed.
template <Real T>
[[nodiscard]] std::optional<grid_hit<T>> trace_accelerated(const height_grid_view<T>& g, const max_pyramid<T>& p,
                                                           height_bounds<T> hb, const ray<T>& r, T t_max_m,
                                                           T s_clear_m = T(0)) noexcept {
    detail::grid_ray<T> q;
    if (!detail::setup_ray(g, hb, r, t_max_m, q)) return std::nullopt;
    constexpr T inf = std::numeric_limits<T>::infinity();

    detail::walk_state<T> w = detail::start_at(g, q, q.s_lo);
    // Where f was last evaluated: a plain point (the start) or a crossing of line u = line / v = line.
    enum class at_kind : unsigned char { point, u_line, v_line } kind = at_kind::point;
    std::int32_t line = 0;
    bool f_known = false; // w.f holds f at w.s

    // Nothing lies above top_m: a ray that does not come down to it misses, and one that does skips to
    // the cell where it does (or to where the caller knows it clear, if that is further), resuming at that
    // cell's entry crossing (a breakpoint of the reference walk too, so both walks evaluate f at the same places).
    const T z_top = hb.top_m + q.z_margin;
    T s_skip = T(0);
    if (q.z0 + q.dz * q.s_lo > z_top) {
        if (!(q.z0 + q.dz * q.s_hi <= z_top)) return std::nullopt;
        s_skip = (q.z0 - z_top) / -q.dz;
    }
    bool guided = false; // resuming where the caller's knowledge ends: the hit is usually a cell or two on
    if (s_clear_m > s_skip) {
        if (!(s_clear_m < q.s_hi)) return std::nullopt; // above the surface all along what is left of it
        s_skip = s_clear_m;
        guided = true;
    }
    if (s_skip > q.s_lo) {
        if (const auto e = detail::entry_of_cell_at(g, q, s_skip)) {
            w.ix = e->ix;
            w.iy = e->iy;
            w.s = e->s;
            w.above = true;
            kind = e->on_u ? at_kind::u_line : at_kind::v_line;
            line = e->line;
        }
    }
    const std::int32_t top_level = p.levels();
    // Start at the level whose blocks match the length of the ray's path over the grid (in cells).
    const T path_cells = (std::abs(q.du) + std::abs(q.dv)) * (q.s_hi - w.s);
    // Where the caller's knowledge ends the ray is usually about to meet the surface: start at the lowest level,
    // and climb as blocks are skipped.
    std::int32_t level = top_level;
    if (path_cells < static_cast<T>(std::int32_t(1) << std::min<std::int32_t>(top_level, 30)))
        level = static_cast<std::int32_t>(std::bit_width(static_cast<std::uint32_t>(path_cells)));
    if (guided) level = std::min(level, std::int32_t(1));
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
            // and never moved backwards (where the exact walk resumes, that cell is made the reference walk's).
            // A block whose exit line the ray crossed before where the walk already is (the cell on the other axis
            // was one short, by rounding) moves the cell but leaves the walk at the crossing it was at; at an exact
            // tie the u line's crossing counts, as in the reference walk.
            if (!(se < q.s_hi)) return std::nullopt;
            const std::int32_t old_ix = w.ix, old_iy = w.iy;
            const bool cross_x = sx <= sy, cross_y = sy <= sx;
            const T s_exit = std::min(sx, sy);
            const bool moved = kind == at_kind::point || s_exit > w.s || (s_exit == w.s && cross_x);
            if (cross_x) {
                w.ix = ux - 1 + pu;
                if (moved) {
                    kind = at_kind::u_line;
                    line = ux;
                }
            } else if (q.su != 0) {
                w.ix = detail::exit_cell_in_block(q.u0 + q.du * se, g.nx - 2, bx, level, q.su, w.ix);
            }
            if (cross_y) {
                w.iy = vy - 1 + pv;
                if (moved && !cross_x) {
                    kind = at_kind::v_line;
                    line = vy;
                }
            } else if (q.sv != 0) {
                w.iy = detail::exit_cell_in_block(q.v0 + q.dv * se, g.ny - 2, by, level, q.sv, w.iy);
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
            // At a line crossing, the cell on the other axis is made the one the reference walk is in there.
            switch (kind) {
            case at_kind::point:
                w.f = detail::f_at(g, q, w.s);
                break;
            case at_kind::u_line:
                w.iy = detail::walk_cell(q.v0, q.dv, q.inv_dv, q.sv, g.ny - 2, w.s);
                w.f = detail::f_on_u_line(g, q, line, w.s);
                break;
            case at_kind::v_line: {
                w.ix = detail::walk_cell(q.u0, q.du, q.inv_du, q.su, g.nx - 2, w.s);
                // At a vertex (the cell's u line crossed at the same distance) the reference walk takes the u line.
                const std::int32_t u_line = q.su > 0 ? w.ix : w.ix + 1;
                w.f = q.su != 0 && detail::cross_u(q, u_line) == w.s ? detail::f_on_u_line(g, q, u_line, w.s)
                                                                      : detail::f_on_v_line(g, q, line, w.s);
                break;
            }
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
