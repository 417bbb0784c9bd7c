#pragma once
/// \file
/// Where a circular arc in a vertical plane first meets a height field: the path of a ray through one layer of
/// water whose sound speed changes linearly with depth (propagation/layered.hpp), met exactly rather than through
/// straight chords.
///
/// The arc (scene/vertical_arc.hpp) starts at world point P with inclination phi0 below the horizontal; sin(phi)
/// falls by kappa per metre of horizontal distance x, and its depth below P is d(x). Its horizontal projection is a
/// straight line along its heading, so the cells it passes over are a straight ray's.
///
/// The walk. Along that line the triangulated surface is linear between breakpoints: the crossings of the cells'
/// edges and of their diagonals. With f(x) = P.z - d(x) - surface(x), the arc meets the surface at the first x where
/// f goes from > 0 to <= 0. On one piece f'' = kappa / cos^3 phi: where the arc bends down f is concave and can only
/// change sign between the piece's ends; where it bends up f is convex and may dip below zero between two positive
/// ends, at the least value where the arc's slope tan phi equals the facet's descent along h, which the walk looks at
/// in closed form. The root is found by regula falsi from the piece's ends, to rounding (f is linear to within the
/// arc's sagitta over the piece, about kappa L^2 / (8 cos^3 phi) over a length L, so a few steps do).
///
/// Skipping. Blocks of the maximum pyramid (height_field_pyramid.hpp) are passed in one step where the arc stays above
/// the block's highest vertex by more than rounding over the block's stretch of the line, bounded below by its depth
/// where the stretch begins plus the stretch's length times the arc's steepest descent over the whole walk (tan phi is
/// monotonic in x, so that is at an end): one level up after a skip, one down after a refusal, as the maximum-mipmap
/// traversal goes. A guided walk tries no block before its first cell.
///
/// Starts. The walk starts at the arc's start (or where the line comes over the grid's footprint), or, given that
/// the arc meets nothing before x_clear_m (a neighbour's vouching), at the last breakpoint at or before x_clear_m;
/// skips end at a cell's entry crossing. Breakpoints and f there are computed by one formula whatever the start, so
/// every start that the arc is above sees the same pieces from there on, and the hit is the same to the last bit.
/// An arc that starts under the surface (inside the sediment, or coming over the footprint's side below it) is not
/// stopped while it rises out of it: its first crossing from above is the hit, as for a straight ray. An arc that turns
/// vertical is walked up to just before that point (where |sin phi| = 1 - 64 eps), whatever x_end_m.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "sss/core/detail/force_inline.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/detail/grid_cell.hpp"
#include "sss/scene/grid_hit.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_grid.hpp"
#include "sss/scene/vertical_arc.hpp"

namespace sss::scene {

/// Where an arc meets a height field: horizontal distance from the arc's start, cell and triangle. Plain data.
template <Real T> struct arc_grid_hit {
    T x_m{};
    std::int32_t ix = 0, iy = 0;
    cell_triangle triangle = cell_triangle::lower;
};

namespace detail {

/// The walk's position on the line of an arc over the grid: the line's crossings of grid lines, by one formula.
template <Real T> struct arc_line {
    T u0, v0, du, dv;       // grid position at x = 0 (cells) and its change per metre of x
    T inv_du, inv_dv, inv_dd; // 1 / du, 1 / dv, 1 / (du - dv) (0 where they divide by 0)
    std::int32_t su, sv;

    /// A component too small for its inverse to be finite is taken as 0 (the line runs along the other axis).
    arc_line(T u0_, T v0_, T du_, T dv_) noexcept
        : u0(u0_), v0(v0_), du(flush(du_)), dv(flush(dv_)), inv_du(du != T(0) ? T(1) / du : T(0)),
          inv_dv(dv != T(0) ? T(1) / dv : T(0)), inv_dd(du != dv ? T(1) / (du - dv) : T(0)),
          su(du > T(0) ? 1 : (du < T(0) ? -1 : 0)), sv(dv > T(0) ? 1 : (dv < T(0) ? -1 : 0)) {}
    [[nodiscard]] static T flush(T d) noexcept { return std::abs(d) < T(1) / std::numeric_limits<T>::max() ? T(0) : d; }

    [[nodiscard]] T cross_u(std::int32_t line) const noexcept { return (static_cast<T>(line) - u0) * inv_du; }
    [[nodiscard]] T cross_v(std::int32_t line) const noexcept { return (static_cast<T>(line) - v0) * inv_dv; }
    /// Where the line enters and leaves column ix (x, m); -inf / +inf along a line parallel to the columns.
    [[nodiscard]] T enter_u(std::int32_t ix) const noexcept {
        return su > 0 ? cross_u(ix) : (su < 0 ? cross_u(ix + 1) : -std::numeric_limits<T>::infinity());
    }
    [[nodiscard]] T leave_u(std::int32_t ix) const noexcept {
        return su > 0 ? cross_u(ix + 1) : (su < 0 ? cross_u(ix) : std::numeric_limits<T>::infinity());
    }
    [[nodiscard]] T enter_v(std::int32_t iy) const noexcept {
        return sv > 0 ? cross_v(iy) : (sv < 0 ? cross_v(iy + 1) : -std::numeric_limits<T>::infinity());
    }
    [[nodiscard]] T leave_v(std::int32_t iy) const noexcept {
        return sv > 0 ? cross_v(iy + 1) : (sv < 0 ? cross_v(iy) : std::numeric_limits<T>::infinity());
    }
    /// Where the line crosses the diagonal (a = b) of cell (ix, iy); +inf where it runs along it or never meets it.
    [[nodiscard]] T cross_diagonal(std::int32_t ix, std::int32_t iy) const noexcept {
        if (du == dv) return std::numeric_limits<T>::infinity();
        return ((v0 - static_cast<T>(iy)) - (u0 - static_cast<T>(ix))) * inv_dd;
    }
    /// The column (row) holding x as the walk goes: the one it has entered at or before x and not yet left
    /// (crossings compared, not the rounded position alone), within [0, last].
    [[nodiscard]] std::int32_t column_at(T x, std::int32_t last) const noexcept {
        return axis_cell(x, u0, du, inv_du, su, last);
    }
    [[nodiscard]] std::int32_t row_at(T x, std::int32_t last) const noexcept {
        return axis_cell(x, v0, dv, inv_dv, sv, last);
    }

private:
    /// column_at and row_at along one axis: position p0 + dp x (cells), crossings (line - p0) inv as cross_u/cross_v.
    [[nodiscard]] static std::int32_t axis_cell(T x, T p0, T dp, T inv, std::int32_t s, std::int32_t last) noexcept {
        std::int32_t c = cell_of(p0 + dp * x, last);
        if (s == 0) return c;
        const auto cross = [&](std::int32_t line) { return (static_cast<T>(line) - p0) * inv; };
        while ((s > 0 ? c < last : c > 0) && !(cross(s > 0 ? c + 1 : c) > x)) c += s; // already left c
        while ((s > 0 ? c > 0 : c < last) && cross(s > 0 ? c : c + 1) > x) c -= s;   // not yet entered c
        return c;
    }
};

/// f, the arc's height above the surface (m) at horizontal distance x (m) in cell (ix, iy), given the arc's depth
/// there (m below z0, its start's height).
template <Real T>
[[nodiscard]] SSS_FORCE_INLINE T arc_above(const height_grid_view<T>& g, const arc_line<T>& line, T z0, T x, T depth,
                                           std::int32_t ix, std::int32_t iy) noexcept {
    return z0 - depth - height_in_cell(g, ix, iy, line.u0 + line.du * x - static_cast<T>(ix),
                                       line.v0 + line.dv * x - static_cast<T>(iy));
}

} // namespace detail

/// The first crossing from above of the height field (grid g, its pyramid p and bounds hb) by the arc `a` for
/// horizontal distances up to x_end_m, given that the arc meets nothing before x_clear_m (0: nothing is known); none
/// where it stays above (or never comes over the grid's footprint) up to x_end_m. See the file comment.
template <Real T>
[[nodiscard]] std::optional<arc_grid_hit<T>> trace_arc(const height_grid_view<T>& g, const max_pyramid<T>& p,
                                                       height_bounds<T> hb, const vertical_arc<T>& a, T x_clear_m,
                                                       T x_end_m) noexcept {
    constexpr T inf = std::numeric_limits<T>::infinity();
    const T eps = std::numeric_limits<T>::epsilon();
    const bool finite = std::isfinite(a.start.x) && std::isfinite(a.start.y) && std::isfinite(a.start.z) &&
                        std::isfinite(a.heading.x) && std::isfinite(a.heading.y) && std::isfinite(a.sin_phi0) &&
                        std::isfinite(a.kappa_per_m) && !std::isnan(x_clear_m) && !std::isnan(x_end_m);
    // A unit heading and a unit inclination (sin^2 + cos^2 = 1), to well within float's rounding.
    const bool unit = std::abs(a.heading.x * a.heading.x + a.heading.y * a.heading.y - T(1)) <= T(1e-3) &&
                      std::abs(a.sin_phi0 * a.sin_phi0 + a.cos_phi0 * a.cos_phi0 - T(1)) <= T(1e-3);
    if (!finite || !unit || !(x_end_m > T(0)) || !(a.cos_phi0 > T(0))) return std::nullopt;
    const T ic = g.inv_cell_m;
    const detail::arc_line<T> line((a.start.x - g.origin_m.x) * ic, (a.start.y - g.origin_m.y) * ic, a.heading.x * ic,
                                   a.heading.y * ic);
    const std::int32_t last_x = g.nx - 2, last_y = g.ny - 2;

    // The stretch of x over the footprint [0, nx - 1] x [0, ny - 1] (in cells), by the crossings' formula.
    T x_lo = T(0), x_hi = x_end_m;
    const auto clip = [&](std::int32_t s, T p0, std::int32_t last_line, T lo_line_x, T hi_line_x) {
        if (s == 0) {
            if (!(p0 >= T(0) && p0 <= static_cast<T>(last_line))) x_hi = -inf;
            return;
        }
        x_lo = std::max(x_lo, s > 0 ? lo_line_x : hi_line_x);
        x_hi = std::min(x_hi, s > 0 ? hi_line_x : lo_line_x);
    };
    clip(line.su, line.u0, g.nx - 1, line.su != 0 ? line.cross_u(0) : T(0),
         line.su != 0 ? line.cross_u(g.nx - 1) : T(0));
    clip(line.sv, line.v0, g.ny - 1, line.sv != 0 ? line.cross_v(0) : T(0),
         line.sv != 0 ? line.cross_v(g.ny - 1) : T(0));
    // The arc is a function of x up to where it turns vertical (|sin phi| = 1, at (sin phi0 -+ 1) / kappa); beyond it
    // the arc curls back and is not traced. The stretch ends where |sin phi| = 1 - 64 eps, where cos phi (about
    // sqrt(128 eps)) still bounds the walk's slopes: short of the vertical point by cos phi / |kappa| of depth (4 cm in
    // float at kappa = 0.1 1/m, 2e-6 m in double).
    if (a.kappa_per_m != T(0)) {
        const T edge = (a.kappa_per_m < T(0) ? T(1) : T(-1)) * (T(1) - T(64) * eps);
        if (!(std::abs(a.sin_at(x_hi)) < std::abs(edge))) {
            x_hi = std::min(x_hi, (a.sin_phi0 - edge) / a.kappa_per_m);
            const auto short_of_edge = [&] { return std::abs(a.sin_at(x_hi)) < std::abs(edge); };
            for (T back = eps * std::abs(x_hi); x_hi > x_lo && !short_of_edge(); back *= T(2))
                x_hi = std::max(x_lo, x_hi - back);
        }
    }
    if (!(x_lo <= x_hi) || x_clear_m >= x_hi) return std::nullopt; // off the footprint, or all of it known clear
    if (!(std::abs(a.sin_at(x_lo)) < T(1)) || !(std::abs(a.sin_at(x_hi)) < T(1))) return std::nullopt;

    // f at x in cell (ix, iy) is detail::arc_above with the arc's depth there; on entering a cell at a crossing the
    // depth is the one the previous cell's last piece ended with (the same x, the same number), the surface the new
    // cell's.
    const T z0 = a.start.z;
    // The steepest descent of the arc over the stretch (tan phi is monotonic in x: an end), for the skips' bound, and
    // the largest f'' = kappa / cos^3 phi over it (cos phi is least at an end) where the arc bends up: worked out when
    // first needed (a guided walk often needs neither).
    T tan_hi = -T(1), curv_hi = -T(1);
    const auto steepest = [&] {
        if (tan_hi < T(0)) {
            const auto tan_at = [&](T x) { return a.sin_at(x) / std::max(a.cos_at(x), std::numeric_limits<T>::min()); };
            tan_hi = std::max({T(0), tan_at(x_lo), tan_at(x_hi)});
        }
        return tan_hi;
    };
    const auto most_convex = [&] {
        if (curv_hi < T(0)) {
            const T cos_lo = std::min(a.cos_at(x_lo), a.cos_at(x_hi));
            curv_hi = a.kappa_per_m > T(0)
                          ? a.kappa_per_m / std::max(cos_lo * cos_lo * cos_lo, std::numeric_limits<T>::min())
                          : T(0);
        }
        return curv_hi;
    };

    // Where the walk starts: its beginning, or the last breakpoint at or before x_clear_m past it.
    T x = x_lo;
    std::int32_t ix, iy;
    if (x_clear_m > x_lo && x_clear_m < x_hi) {
        ix = line.column_at(x_clear_m, last_x);
        iy = line.row_at(x_clear_m, last_y);
        const T entry = std::max(line.enter_u(ix), line.enter_v(iy));
        x = std::max(x_lo, entry);
        const T xd = line.cross_diagonal(ix, iy);
        if (xd > x && xd <= x_clear_m) x = xd;
    } else {
        ix = line.column_at(x_lo, last_x);
        iy = line.row_at(x_lo, last_y);
    }
    // Rounding of f: a few roundings of the magnitudes it is made of (world heights and the arc's depth).
    const T z_scale = std::abs(a.start.z) + std::max(std::abs(hb.top_m), std::abs(hb.bottom_m));
    const T f_rounding = T(16) * eps * (T(1) + z_scale);

    T d_x = a.depth_m(x); // the arc's depth at x
    T fx = detail::arc_above(g, line, z0, x, d_x, ix, iy);
    // The hit at a breakpoint where f is at or below 0 after the piece before it was above (rounding between the two
    // cells' surfaces there), as every walk that comes to it sees it.
    const auto at_entry = [&] {
        const T ae = line.u0 + line.du * x - static_cast<T>(ix), be = line.v0 + line.dv * x - static_cast<T>(iy);
        return arc_grid_hit<T>{x, ix, iy, triangle_of(ae, be)};
    };
    // Under the surface at its beginning: not stopped until it has come out. A start past the beginning is one the
    // caller knows the arc above: at or below there (rounding again), the start is the hit.
    if (x > x_lo && !(fx > T(0))) return at_entry();
    bool below = !(fx > T(0));
    const std::int32_t levels = p.levels();
    // A guided walk starts a cell or two before its hit: the first cell is walked before any block is tried.
    std::int32_t level = x_clear_m > T(0) ? 0 : levels;
    // Where f is stationary on triangle tri of cell (cx, cy): where the arc descends as fast as the facet does along
    // the line, tan phi = -(dh/dx along it); f's least value where the arc bends up (kappa > 0), its greatest where it
    // bends down. kappa must not be 0.
    const auto stationary = [&](std::int32_t cx, std::int32_t cy, cell_triangle tri) {
        const vec2<T> grad = triangle_gradient(g, cx, cy, tri);
        const T slope = grad.x * a.heading.x + grad.y * a.heading.y;
        return (a.sin_phi0 + slope / std::sqrt(T(1) + slope * slope)) / a.kappa_per_m;
    };
    // The first root of f in [xa, xb] (cell ix, iy, triangle tri), f(xa) > 0: where f ends <= 0 or dips below 0
    // (where the arc bends up; curv_hi is 0 where it does not, and the walk asks only where a dip is possible).
    const auto root = [&](T xa, T fa, T xb, T fb, std::int32_t cx, std::int32_t cy,
                          cell_triangle tri) -> std::optional<T> {
        if (fb > T(0)) {
            // Both ends above: a convex f (the arc bending up) may dip in between, at its least value.
            const T xs = stationary(cx, cy, tri);
            if (!(xs > xa && xs < xb)) return std::nullopt;
            const T fs = detail::arc_above(g, line, z0, xs, a.depth_m(xs), cx, cy);
            if (fs > T(0)) return std::nullopt;
            xb = xs;
            fb = fs;
        }
        // Regula falsi with the Illinois rule (an end kept twice in a row has its f halved: Dowell & Jarratt 1971,
        // BIT 11, 168-174), until f is within its own rounding or x stops moving: over a cell of 0.25 m the first
        // estimate is off by about kappa L^2 / (8 cos^3 phi) in f, below float's rounding of world heights, and in
        // double a few more steps settle it; over large cells or tight bends it converges superlinearly all the same.
        T lo = xa, flo = fa, hi = xb, fhi = fb;
        T xr = std::clamp(lo + (hi - lo) * (flo / (flo - fhi)), lo, hi);
        int kept = 0; // -1: lo was moved last, +1: hi was
        for (int it = 0; it < 64; ++it) {
            const T fr = detail::arc_above(g, line, z0, xr, a.depth_m(xr), cx, cy);
            if (std::abs(fr) <= f_rounding) break; // on the surface to f's own rounding
            if (fr > T(0)) {
                lo = xr;
                flo = fr;
                if (kept == -1) fhi *= T(0.5);
                kept = -1;
            } else {
                hi = xr;
                fhi = fr;
                if (kept == 1) flo *= T(0.5);
                kept = 1;
            }
            if (!(hi > lo) || !(flo - fhi > T(0))) break;
            const T next = std::clamp(lo + (hi - lo) * (flo / (flo - fhi)), lo, hi);
            const bool settled = std::abs(next - xr) <= T(4) * eps * std::max(std::abs(xr), T(1));
            xr = next;
            if (settled) break;
        }
        return xr;
    };

    for (std::size_t steps = 0; steps < (std::size_t(1) << 26); ++steps) {
        if (!(x < x_hi)) return std::nullopt;
        // Skip blocks of the pyramid the arc stays above.
        if (!below) {
            while (level >= 1) {
                const std::int32_t bx = ix >> level, by = iy >> level;
                const T xbu = line.su > 0 ? line.cross_u((bx + 1) << level)
                                          : (line.su < 0 ? line.cross_u(bx << level) : inf);
                const T xbv = line.sv > 0 ? line.cross_v((by + 1) << level)
                                          : (line.sv < 0 ? line.cross_v(by << level) : inf);
                const T xe = std::min(std::min(xbu, xbv), x_hi);
                // The arc comes down at most tan_hi per metre: its deepest over [x, xe] is no deeper than this.
                const T descent = (xe - x) * steepest();
                const T z_low = a.start.z - (d_x + descent);
                const T margin = T(16) * eps * (T(1) + z_scale + std::abs(z_low) + descent);
                if (z_low > p.max_m(level, bx, by) + margin) {
                    if (!(xe < x_hi)) return std::nullopt;
                    x = xe;
                    ix = xbu <= xbv ? (line.su > 0 ? (bx + 1) << level : (bx << level) - 1) : line.column_at(x, last_x);
                    iy = xbv <= xbu ? (line.sv > 0 ? (by + 1) << level : (by << level) - 1) : line.row_at(x, last_y);
                    if (ix < 0 || iy < 0 || ix > last_x || iy > last_y) return std::nullopt;
                    d_x = a.depth_m(x);
                    fx = detail::arc_above(g, line, z0, x, d_x, ix, iy);
                    level = std::min(level + 1, levels);
                    // The block's highest vertex bounds the surface at its edge too: f > 0 here but for rounding
                    // beyond the margin, which would make the entry itself the crossing.
                    if (!(fx > T(0))) return at_entry();
                } else {
                    --level;
                }
            }
            level = std::max<std::int32_t>(level, levels > 0 ? 1 : 0);
        }
        // The cell exactly: its pieces up to the diagonal and past it.
        const T xu = line.leave_u(ix), xv = line.leave_v(iy);
        const T x_leave = std::min(std::min(xu, xv), x_hi);
        const T xd = line.cross_diagonal(ix, iy);
        T ends[2];
        int pieces = 0;
        if (xd > x && xd < x_leave) ends[pieces++] = xd;
        ends[pieces++] = x_leave;
        for (int k = 0; k < pieces; ++k) {
            const T xb = ends[k];
            const T db = a.depth_m(xb);
            const T fb = detail::arc_above(g, line, z0, xb, db, ix, iy);
            if (below) {
                // Still under at the piece's end: bending down (f concave) the arc may have come out and gone back in
                // between, above the surface at f's greatest value.
                if (!(fb > T(0)) && a.kappa_per_m < T(0)) {
                    const T xm = T(0.5) * (x + xb);
                    const cell_triangle tri = triangle_of(line.u0 + line.du * xm - static_cast<T>(ix),
                                                          line.v0 + line.dv * xm - static_cast<T>(iy));
                    const T xs = stationary(ix, iy, tri);
                    if (xs > x && xs < xb) {
                        const T fs = detail::arc_above(g, line, z0, xs, a.depth_m(xs), ix, iy);
                        if (fs > T(0))
                            if (const auto r = root(xs, fs, xb, fb, ix, iy, tri))
                                return arc_grid_hit<T>{*r, ix, iy, tri};
                    }
                }
                below = !(fb > T(0));
            } else if (!(fb > T(0)) ||
                       // f'' <= curv_hi: f lies above the chord of its ends less curv_hi L^2 / 8, so only where the
                       // ends come that close to the surface can it dip in between.
                       (a.kappa_per_m > T(0) &&
                        std::min(fx, fb) <= most_convex() * (xb - x) * (xb - x) * T(0.125) + f_rounding)) {
                const T xm = T(0.5) * (x + xb);
                const T am = line.u0 + line.du * xm - static_cast<T>(ix);
                const T bm = line.v0 + line.dv * xm - static_cast<T>(iy);
                const cell_triangle tri = triangle_of(am, bm);
                if (const auto r = root(x, fx, xb, fb, ix, iy, tri)) return arc_grid_hit<T>{*r, ix, iy, tri};
            }
            x = xb;
            fx = fb;
            d_x = db;
        }
        if (!(x_leave < x_hi)) return std::nullopt;
        // Into the next cell (both ways at a vertex).
        if (xu <= xv) ix += line.su;
        if (xv <= xu) iy += line.sv;
        if (ix < 0 || iy < 0 || ix > last_x || iy > last_y) return std::nullopt;
        fx = detail::arc_above(g, line, z0, x, d_x, ix, iy);
        if (below) below = !(fx > T(0));
        else if (!(fx > T(0))) return at_entry();
    }
    return std::nullopt;
}

} // namespace sss::scene
