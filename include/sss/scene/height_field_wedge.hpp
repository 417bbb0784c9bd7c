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
/// for this ray, it jumps to the first ring that is not, as the accelerated tracer skips pyramid blocks. A walk
/// starts (or resumes after a jump) at the entry crossing of the cell that holds the ring's start: a breakpoint of
/// the single-ray walk, in a clear ring (a cell spans less than two rings of rho; a jump passes two or more, and
/// before the pointer's ring every ring is clear or above top_m), so the ray is above the surface there and no hit
/// is skipped, and f there is evaluated by the same formula, so the walk sees the same numbers from there on and the
/// hit is the single-ray tracer's to the last bit, in float and in double. Where that cell is the one in which the
/// ray comes over the grid, the walk starts where it does, as the single-ray walk.
///
/// Chain. Neighbouring rays of a column differ much more in slope than in heading (a cone column turns its heading
/// by about tan(along) sin(e) de per de of depression e), so the previous, steeper ray's knowledge carries over: if
/// it stayed above the surface out to horizontal distance rho_a, a ray shallower by d_tau and turned by d_theta
/// from it is above the surface there too wherever d_tau rho > L d_theta rho + rounding, L the surface's Lipschitz
/// bound sqrt(2) max_step / cell (max_pyramid::max_step_m; the chord between the two rays at rho is at most
/// rho d_theta). Such a ray starts its exact walk at the entry crossing of the cell that holds rho_a (a breakpoint
/// of the single-ray walk, evaluated by the same formula), usually one or two cells before its own hit. It leaves
/// the ring pointer where it is: the pointer moves on only for rays the chain does not cover, so most rays of a
/// column test no ring at all (bench_height_field's cone columns: 0.1 ring tests per ray in float; 1.2 if the
/// pointer moved for every ray).
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

#include "sss/core/detail/force_inline.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/detail/wedge_rings.hpp"
#include "sss/scene/detail/wedge_run.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_field_tracer.hpp"

namespace sss::scene {

/// Traces the wedge run `rays` (as found by detail::find_wedge_run: `run` and the rays' `slopes`) limited to
/// distance t_max_m, calling emit(k, const grid_hit<T>* h) once for every ray k (h null for a miss). Always inlined
/// into its caller: out of line (as GCC 12 leaves it at -O3), cone columns take 15 to 18 % longer in double.
template <Real T, class Emit>
SSS_FORCE_INLINE void trace_wedge(const height_grid_view<T>& g, const max_pyramid<T>& p, height_bounds<T> hb,
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

    const detail::grid_origin<T> origin = detail::origin_in_grid(g, hb, r0.origin);
    const T u0 = origin.u0, v0 = origin.v0;
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
        if (!detail::setup_ray(g, hb, origin, r.direction, t_max_m, q)) {
            emit(k, static_cast<const grid_hit<T>*>(nullptr));
            chained = false;
            continue;
        }
        const T to_s = cell * slopes[k].inv_h;  // distance per cell of rho
        const T to_rho = T(1) / to_s;           // cells of rho per metre of distance
        const T rho_hi = std::min(q.s_hi * to_rho, ring_end);

        // Where the chain puts this ray's start: it is above the surface out to the previous ray's last point
        // above it when it is shallower by more than the sideways slope bound allows, with margin for rounding
        // (rings before `shared` are clear for it, the chain covers the rest). The shared pointer moves on only
        // where the chain does not hold: left behind, it still marks rings clear for this ray, and the chain then
        // asks for more gain, so the test is only stricter. Where the test fails, the pointer moves on for this ray
        // and the chain is tried once more from there.
        auto chain_holds = [&] {
            const T turned = T(1.001) * std::abs(slopes[k].sin_turn - chain_sin) + T(8) * eps;
            const T gain = (chain_tau - tau) - lipschitz * turned; // f gained over the previous ray per m of rho
            const T rho_lo_m = static_cast<T>(shared) * cell;
            return gain * rho_lo_m > chain_err * (T(1) + std::abs(chain_tau) * chain_rho_m);
        };
        bool from_chain = chained && chain_holds();
        if (!from_chain) {
            while (static_cast<T>(shared) < rho_hi && clear(shared, tau)) ++shared;
            if (!(static_cast<T>(shared) < rho_hi)) {
                emit(k, static_cast<const grid_hit<T>*>(nullptr));
                chained = false;
                continue;
            }
            from_chain = chained && chain_holds();
        }
        T s_chain = T(0);
        if (from_chain) {
            s_chain = chain_rho_m * slopes[k].inv_h;
            if (!(s_chain < q.s_hi)) { // above the surface all along its path: the chain goes on from here
                emit(k, static_cast<const grid_hit<T>*>(nullptr));
                chain_tau = tau;
                chain_sin = slopes[k].sin_turn;
                continue;
            }
        }
        chained = false;

        // The exact walk from ring `shared` (or the chain's start) on, jumping over rings that are clear for it.
        grid_hit<T> out;
        bool found = false;
        bool clean = true; // above the surface at every breakpoint so far (the chain needs it)
        std::int32_t ring = shared;
        detail::walk_state<T> w{};
        bool walking = false;
        int grace = 0; // cells to walk before looking for jumps
        // Resuming at the entry crossing of the cell that holds distance s, known above the surface before s: a
        // breakpoint of the single-ray walk, f there by the same formula, so the walk sees the same numbers from
        // there on. False when that cell is where the ray comes over the grid.
        auto resume_at_entry = [&](T s) {
            const auto e = detail::entry_of_cell_at(g, q, s);
            if (!e) return false;
            w = detail::walk_state<T>{.s = e->s, .f = detail::f_on_entry(g, q, *e), .ix = e->ix, .iy = e->iy, .above = false};
            if (!(w.f > T(0))) {
                // Above just before: only rounding puts f <= 0 here, and then this is the hit.
                found = detail::segment_root(q, w.s, T(1), w.s, w.f, w.ix, w.iy, out);
                clean = false;
            }
            w.above = w.f > T(0);
            return true;
        };
        if (s_chain > static_cast<T>(shared) * to_s && resume_at_entry(s_chain)) {
            ring = static_cast<std::int32_t>(w.s * to_rho);
            walking = true;
            grace = 3;
        }
        while (!found) {
            if (!walking) {
                const T s_ring = static_cast<T>(ring) * to_s;
                if (s_ring > q.s_lo && !(s_ring < q.s_hi)) break;
                if (!(s_ring > q.s_lo && resume_at_entry(s_ring))) {
                    // From where the ray comes over the grid (through its side, or from an origin over it), as the
                    // single-ray walk does. The chain needs the ray to have been over the grid, and above the
                    // envelope, before its walk, so it ends here.
                    w = detail::start_at(g, q, q.s_lo);
                    w.f = detail::f_at(g, q, q.s_lo);
                    w.above = w.f > T(0);
                    clean = false;
                } else if (found) {
                    break;
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
