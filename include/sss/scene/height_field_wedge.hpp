#pragma once
/// \file
/// Tracing a column of rays that share their origin but not their vertical plane: the rays of one along-track
/// column of a sidescan beam (a cone about the array axis, tilted by roll and pitch), whose horizontal headings
/// differ a little from ray to ray. Such rays cannot share one surface profile (height_field_fan.hpp needs a
/// single vertical plane), but they share a thin wedge of the grid around the origin, and their heights along the
/// horizontal distance rho are all z0 - tau rho, tau = tan(depression), whatever their heading.
///
/// Envelope. The wedge (every heading of the run, widened by rounding) is cut into rings of one cell in rho. Ring
/// i holds the part of the wedge with rho in [i, i + 1] cells; its envelope G_i is the highest vertex of the
/// cells under that part (directly for small rings, from the maximum pyramid for wide ones), so G_i bounds the
/// surface under every ray of the run there. A ray whose lowest point over ring i stays above G_i (with a margin
/// well above rounding) cannot hit in ring i: ring i is "clear" for it.
///
/// Sweep. A steeper ray is lower at every rho > 0, so a ring clear for a steeper ray is clear for every shallower
/// one. Taking the rays steep first, one pointer runs over the rings: it moves on while the ring is clear for the
/// current ray, and where it stops the ray may meet the surface. Rings are evaluated on demand, once per run, so
/// the sweep costs O(rings + rays).
///
/// Exact part. From where the pointer stopped, each ray is walked exactly, cell by cell, with the same breakpoints
/// and the same rule as the single-ray tracer (height_field_tracer.hpp): a hit where f = z_ray - h goes from > 0 to
/// <= 0, the linear root on that segment. Whenever the walk enters a ring and finds it and the following rings clear
/// for this ray, it jumps to the first ring that is not, as the accelerated tracer skips pyramid blocks. Jumps
/// land only on points where the ray is above the envelope, hence above the surface, so no hit is skipped; f is
/// evaluated afresh at such a point (a plain point, as at a ray's start), which can move a hit by rounding only.
///
/// Chain. Neighbouring rays of a column differ much more in slope than in heading (a cone column turns its heading
/// by about tan(along) sin(e) de per de of depression e), so the previous, steeper ray's knowledge carries over: if
/// it stayed above the surface out to horizontal distance rho_a, a ray shallower by d_tau and turned by d_theta
/// from it is above the surface there too wherever d_tau rho > L d_theta rho + rounding, L the surface's Lipschitz
/// bound sqrt(2) max_step / cell (max_pyramid::max_step_m; the chord between the two rays at rho is at most
/// rho d_theta). Such a ray starts its exact walk at the entry crossing of the cell that holds rho_a (a breakpoint
/// of the single-ray walk, evaluated by the same formula), usually one or two cells before its own hit.
///
/// Rays that start inside the sediment, or enter the grid's footprint through its side below the surface, follow
/// the single-ray rule: they are not stopped while they rise out of the surface.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sss/core/ray.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_field_tracer.hpp"

namespace sss::scene {

namespace detail {

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

/// The rings of a wedge and their envelopes, evaluated on demand.
template <Real T> class wedge_rings {
public:
    /// The wedge from grid point (u0, v0) between unit headings e_lo and e_hi (grid axes; the angle from e_lo to
    /// e_hi at most wedge_max_spread_rad plus rounding), rings from `first_ring` on.
    wedge_rings(const height_grid_view<T>& g, const max_pyramid<T>& p, T u0, T v0, vec2<T> e_lo, vec2<T> e_hi,
                T spread_rad, std::int32_t first_ring)
        : g_(g), p_(p), u0_(u0), v0_(v0), e_lo_(e_lo), e_hi_(e_hi), first_(first_ring) {
        // The arc of a ring lies within its sagitta, r (1 - cos(spread / 2)) <= r spread^2 / 8, of the chord
        // between the corners; 1e-3 cells more covers rounding of the corners themselves.
        sagitta_per_cell_ = spread_rad * spread_rad / T(8) + T(1e-6);
        // Beyond the farthest corner of the grid's footprint no ring meets a cell (one cell more for rounding).
        const T nu = static_cast<T>(g.nx - 1), nv = static_cast<T>(g.ny - 1);
        const T du = std::max(std::abs(u0), std::abs(nu - u0)), dv = std::max(std::abs(v0), std::abs(nv - v0));
        end_ = std::floor(std::sqrt(du * du + dv * dv) + T(2));
    }

    /// Rho (cells) beyond which the wedge meets no cell of the grid.
    [[nodiscard]] T end_cells() const noexcept { return end_; }

    /// Envelope of ring i (m): the highest vertex under it, or -infinity where it lies outside the grid.
    [[nodiscard]] T envelope(std::int32_t i) {
        const std::size_t k = static_cast<std::size_t>(i - first_);
        while (values_.size() <= k) values_.push_back(compute(first_ + static_cast<std::int32_t>(values_.size())));
        return values_[k];
    }

private:
    [[nodiscard]] T compute(std::int32_t i) const noexcept {
        const T r0 = static_cast<T>(i), r1 = r0 + T(1);
        const T m = r1 * sagitta_per_cell_ + T(1e-3) + (std::abs(u0_) + std::abs(v0_) + r1) * T(1e-6);
        const T ua = u0_ + r0 * e_lo_.x, ub = u0_ + r0 * e_hi_.x, uc = u0_ + r1 * e_lo_.x, ud = u0_ + r1 * e_hi_.x;
        const T va = v0_ + r0 * e_lo_.y, vb = v0_ + r0 * e_hi_.y, vc = v0_ + r1 * e_lo_.y, vd = v0_ + r1 * e_hi_.y;
        const T u_min = std::min(std::min(ua, ub), std::min(uc, ud)) - m;
        const T u_max = std::max(std::max(ua, ub), std::max(uc, ud)) + m;
        const T v_min = std::min(std::min(va, vb), std::min(vc, vd)) - m;
        const T v_max = std::max(std::max(va, vb), std::max(vc, vd)) + m;
        constexpr T lowest = -std::numeric_limits<T>::infinity();
        const T nu = static_cast<T>(g_.nx - 1), nv = static_cast<T>(g_.ny - 1);
        if (!(u_max >= T(0) && v_max >= T(0) && u_min <= nu && v_min <= nv)) return lowest;
        const std::int32_t cx0 = cell_of(u_min, g_.nx - 2), cx1 = cell_of(u_max, g_.nx - 2);
        const std::int32_t cy0 = cell_of(v_min, g_.ny - 2), cy1 = cell_of(v_max, g_.ny - 2);
        const std::int32_t span = std::max(cx1 - cx0, cy1 - cy0);
        T top = lowest;
        if (span < 4) {
            for (std::int32_t y = cy0; y <= cy1 + 1; ++y)
                for (std::int32_t x = cx0; x <= cx1 + 1; ++x) top = std::max(top, g_.at(x, y));
            return top;
        }
        // A wide ring: blocks of the maximum pyramid at least as wide as the ring, two or three per axis.
        const std::int32_t level = std::min(p_.levels(), static_cast<std::int32_t>(std::bit_width(static_cast<std::uint32_t>(span))));
        for (std::int32_t by = cy0 >> level; by <= (cy1 >> level); ++by)
            for (std::int32_t bx = cx0 >> level; bx <= (cx1 >> level); ++bx) top = std::max(top, p_.max_m(level, bx, by));
        return top;
    }

    const height_grid_view<T>& g_;
    const max_pyramid<T>& p_;
    T u0_, v0_;
    vec2<T> e_lo_, e_hi_;
    std::int32_t first_;
    T sagitta_per_cell_{};
    T end_{};
    std::vector<T> values_;
};

} // namespace detail

/// Traces the wedge run `rays` (as found by detail::find_wedge_run: `run` and the rays' `slopes`) limited to
/// distance t_max_m, calling emit(k, const grid_hit<T>* h) once for every ray k (h null for a miss).
template <Real T, class Emit>
void trace_wedge(const height_grid_view<T>& g, const max_pyramid<T>& p, height_bounds<T> hb,
                 std::span<const ray<T>> rays, std::span<const detail::wedge_slope<T>> slopes,
                 const detail::wedge_run<T>& run, T t_max_m, Emit&& emit) {
    const std::size_t n = rays.size();
    if (n == 0) return;
    const bool steep_first = run.steep_first;
    auto index = [&](std::size_t i) { return steep_first ? i : n - 1 - i; };
    const ray<T>& r0 = rays[0];

    // The wedge: the first ray's heading turned by the run's extremes, widened by rounding.
    const vec2<T> m{r0.direction.x * slopes[0].inv_h, r0.direction.y * slopes[0].inv_h};
    const T widen = T(16) * std::numeric_limits<T>::epsilon();
    const T a_lo = std::asin(std::clamp(run.sin_lo, T(-1), T(1))) - widen,
            a_hi = std::asin(std::clamp(run.sin_hi, T(-1), T(1))) + widen;
    auto turn = [&](T a) { return vec2<T>{m.x * std::cos(a) - m.y * std::sin(a), m.x * std::sin(a) + m.y * std::cos(a)}; };

    const T u0 = (r0.origin.x - g.origin_m.x) * g.inv_cell_m, v0 = (r0.origin.y - g.origin_m.y) * g.inv_cell_m;
    const T z0 = r0.origin.z;
    const T cell = g.cell_m;
    // No geometry above top_m: nothing is hit before the steepest ray comes down to it.
    const T tau_max = slopes[index(0)].tau;
    const T z_top = hb.top_m + T(1e-4) * (T(1) + std::abs(z0) + std::abs(hb.top_m) + std::abs(hb.bottom_m));
    T rho_first = T(0); // cells
    if (z0 > z_top) {
        if (!(tau_max > T(0))) {
            for (std::size_t k = 0; k < n; ++k) emit(k, static_cast<const grid_hit<T>*>(nullptr));
            return;
        }
        rho_first = (z0 - z_top) / (tau_max * cell);
    }
    const std::int32_t ring0 =
        static_cast<std::int32_t>(std::min(std::floor(rho_first), static_cast<T>(std::numeric_limits<std::int32_t>::max() / 4)));
    detail::wedge_rings<T> rings(g, p, u0, v0, turn(a_lo), turn(a_hi), a_hi - a_lo, ring0);
    const T ring_end = rings.end_cells();
    const T tol = T(64) * std::numeric_limits<T>::epsilon();

    // Ring i is clear for a ray of slope tau when its lowest point over the ring stays above the envelope.
    auto clear = [&](std::int32_t i, T tau) {
        const T rho_low = static_cast<T>(tau > T(0) ? i + 1 : i) * cell;
        const T z = z0 - tau * rho_low;
        const T env = rings.envelope(i);
        return z > env + tol * (std::abs(z0) + std::abs(tau * rho_low) + std::abs(env) + T(1));
    };

    // The chain (see the file comment): the previous ray's slope, heading and the horizontal distance (m) up to
    // which it is known above the surface, and the surface's Lipschitz bound (m of height per m sideways).
    const T lipschitz = p.max_step_m() * T(1.41421357) * g.inv_cell_m;
    const T eps = std::numeric_limits<T>::epsilon();
    const T chain_err = tol * (T(1) + std::abs(z0) + std::abs(hb.top_m) + std::abs(hb.bottom_m));
    bool chained = false;
    T chain_rho_m{}, chain_tau{}, chain_sin{};

    std::int32_t shared = ring0; // first ring not known clear for every ray so far
    for (std::size_t step = 0; step < n; ++step) {
        const std::size_t k = index(step);
        const ray<T>& r = rays[k];
        const T tau = slopes[k].tau;
        detail::grid_ray<T> q;
        if (!detail::setup_ray(g, hb, r, t_max_m, q)) {
            emit(k, static_cast<const grid_hit<T>*>(nullptr));
            chained = false;
            continue;
        }
        const T to_s = cell * slopes[k].inv_h;  // distance per cell of rho
        const T to_rho = T(1) / to_s;           // cells of rho per metre of distance
        const T rho_hi = std::min(q.s_hi * to_rho, ring_end);

        // Where the chain puts this ray's start: it is above the surface out to the previous ray's last point
        // above it when it is shallower by more than the sideways slope bound allows, with margin for rounding
        // (rings before `shared` are clear for it, the chain covers the rest).
        T s_chain = T(0);
        if (chained) {
            const T turn = T(1.001) * std::abs(slopes[k].sin_turn - chain_sin) + T(8) * eps;
            const T gain = (chain_tau - tau) - lipschitz * turn; // f gained over the previous ray per m of rho
            const T rho_lo_m = static_cast<T>(shared) * cell;
            if (gain * rho_lo_m > chain_err * (T(1) + std::abs(chain_tau) * chain_rho_m)) {
                s_chain = chain_rho_m * slopes[k].inv_h;
                if (!(s_chain < q.s_hi)) { // above the surface all along its path
                    emit(k, static_cast<const grid_hit<T>*>(nullptr));
                    chain_tau = tau;
                    chain_sin = slopes[k].sin_turn;
                    continue;
                }
            }
        }
        chained = false;
        while (static_cast<T>(shared) < rho_hi && clear(shared, tau)) ++shared;
        if (!(static_cast<T>(shared) < rho_hi)) {
            emit(k, static_cast<const grid_hit<T>*>(nullptr));
            continue;
        }

        // The exact walk from ring `shared` (or the chain's start) on, jumping over rings that are clear for it.
        grid_hit<T> out;
        bool found = false;
        bool clean = true; // above the surface at every breakpoint so far (the chain needs it)
        std::int32_t ring = shared;
        detail::walk_state<T> w{};
        bool walking = false;
        int grace = 0; // cells to walk before looking for jumps
        if (s_chain > static_cast<T>(shared) * to_s) {
            // Resume at the entry crossing of the cell that holds the chain's point: a breakpoint of the
            // single-ray walk, evaluated by the same formula.
            const detail::walk_state<T> c = detail::start_at(g, q, s_chain);
            constexpr T inf = std::numeric_limits<T>::infinity();
            const T s_in_u = q.su > 0 ? detail::cross_u(q, c.ix) : (q.su < 0 ? detail::cross_u(q, c.ix + 1) : -inf);
            const T s_in_v = q.sv > 0 ? detail::cross_v(q, c.iy) : (q.sv < 0 ? detail::cross_v(q, c.iy + 1) : -inf);
            const T s_in = std::max(s_in_u, s_in_v);
            if (s_in > q.s_lo && s_in <= s_chain && s_in > T(0)) {
                w = c;
                w.s = s_in;
                w.f = s_in_u >= s_in_v ? detail::f_on_u_line(g, q, q.su > 0 ? c.ix : c.ix + 1, s_in)
                                       : detail::f_on_v_line(g, q, q.sv > 0 ? c.iy : c.iy + 1, s_in);
                if (!(w.f > T(0))) {
                    // Above just before: only rounding puts f <= 0 here, and then this is the hit.
                    found = detail::segment_root(q, s_in, T(1), s_in, w.f, w.ix, w.iy, out);
                    clean = false;
                }
                w.above = w.f > T(0);
                ring = static_cast<std::int32_t>(s_in * to_rho);
                walking = true;
                grace = 3;
            }
        }
        while (!found) {
            if (!walking) {
                const T s_ring = static_cast<T>(ring) * to_s;
                const bool at_entry = !(s_ring > q.s_lo);
                const T s = at_entry ? q.s_lo : s_ring;
                if (!(s < q.s_hi)) break;
                w = detail::start_at(g, q, s);
                w.f = detail::f_at(g, q, s);
                if (at_entry) {
                    w.above = w.f > T(0);
                    // Entering the grid here (through its side, or from an origin over it): the chain needs the
                    // ray to have been over the grid, and above the envelope, before its walk, so it ends here.
                    clean = false;
                } else {
                    // Above the envelope just before: only rounding can put f <= 0 here, and then this is the hit.
                    if (!(w.f > T(0)) && detail::segment_root(q, s, T(1), s, w.f, w.ix, w.iy, out)) {
                        found = true;
                        clean = false;
                        break;
                    }
                    w.above = w.f > T(0);
                    if (!w.above) clean = false;
                }
                walking = true;
            }
            const detail::step_outcome o = detail::cell_step(g, q, w, detail::first_crossing<T>{q, out});
            if (o == detail::step_outcome::found) {
                found = true;
                break;
            }
            if (o == detail::step_outcome::done) break;
            if (!w.above) clean = false;
            // A chained walk usually ends within a cell or two: look for jumps only after a few cells.
            if (grace > 0) {
                --grace;
                continue;
            }
            // Entering a new ring: jump when it and the next ones are clear for this ray.
            const T rho = w.s * to_rho;
            const std::int32_t now = static_cast<std::int32_t>(rho);
            if (now > ring) {
                ring = now;
                if (w.above && clear(ring, tau)) {
                    std::int32_t next = ring + 1;
                    while (static_cast<T>(next) < rho_hi && clear(next, tau)) ++next;
                    if (!(static_cast<T>(next) < rho_hi)) break; // clear to the end: a miss
                    if (next > ring + 1) {
                        ring = next;
                        walking = false;
                    }
                }
            }
        }
        if (found && clean) {
            // Above at every breakpoint up to w.s, the start of the segment that holds the hit.
            chained = true;
            chain_rho_m = w.s / slopes[k].inv_h;
            chain_tau = tau;
            chain_sin = slopes[k].sin_turn;
        }
        emit(k, found ? &out : static_cast<const grid_hit<T>*>(nullptr));
    }
}

} // namespace sss::scene
