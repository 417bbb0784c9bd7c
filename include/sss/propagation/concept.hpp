#pragma once
/// \file
/// The Propagation concept: how sound travels from the towfish to the scene and back.
///
/// | expression                       | type                      | meaning                                                 |
/// |----------------------------------|---------------------------|---------------------------------------------------------|
/// | `P::value_type`                  | T                         | float or double                                         |
/// | `p.reference_speed_mps()`        | T                         | a representative sound speed (m/s): converts the        |
/// |                                  |                           | receiver's range to time and steers ray sampling        |
/// | `p.trace(r, scene, t_max_s)`     | `std::optional<path<T>>`  | the launched ray `r` followed through the water until   |
/// |                                  |                           | it meets the scene within one-way time `t_max_s` (s)    |
///
/// `trace` is a member template over any `Scene`; the concept is checked with the flat seabed. Propagation knows
/// the water, the scene knows the geometry: a curved-ray propagation hands the scene pieces of its path.
/// The return path is the outgoing one reversed (monostatic, reciprocal water): the two-way time is twice the
/// one-way time and the two-way absorption the square of the one-way absorption. `spreading` is the return leg's:
/// the intensity arriving back at the transducer relative to that 1 m from the hit. The simulator multiplies it by
/// the footprint per steradian, 1/(spreading_out sin theta), and by the outgoing spreading; by energy conservation
/// in the ray tube those two outgoing factors cancel, so the echo power is SL b sigma spreading absorption^2
/// dOmega / sin theta exactly, in refracting water too. In isovelocity water spreading = 1/r^2 both ways.
///
/// Optional (`BatchPropagation`): a policy that can share work among the rays of one column (same origin, ordered
/// by depression) also offers
///
/// | `p.trace_many(rays, scene, t_max_s, paths)` | `void` | paths[k] = p.trace(rays[k], scene, t_max_s), up to rounding |
///
/// with `rays` a `std::span<const ray<T>>` and `paths` a `std::span<std::optional<path<T>>>` of the same size.
/// `sss::trace_all` calls it where it exists and falls back to one `trace` per ray.
///
/// Optional (`ReachBoundedPropagation`): a policy whose rays keep their horizontal heading also offers
///
/// | `p.reach_speed_mps(z)` | T | k (m/s): a ray launched from world z with unit direction d stays, for one-way |
/// |                        |   | time t, within horizontal distance k t sqrt(d.x^2 + d.y^2) of its origin along |
/// |                        |   | d's heading, and its path is at most k t long                                  |
///
/// The simulator then knows the rectangle a side's rays can reach (sampling/reach.hpp) and shows the scene's
/// geometry over it only (scene/area_view.hpp).
///
/// Optional (`RangeHeightPropagation`): a policy whose rays stay in the vertical plane of their launch also offers
///
/// | `p.height_at_range_m(r, range_m, t_max_s)` | `std::optional<T>` | the world height (m) of the ray launched along r |
/// |                                            |                    | where it has gone range_m horizontally from its  |
/// |                                            |                    | origin along its heading; none where it does not |
/// |                                            |                    | get there within one-way time t_max_s            |
///
/// with no scene. The simulator asks it for the launch angles that meet a small target (sampling/target_spans.hpp);
/// without it, the same answer comes from a trace to a vertical wall at that range.
///
/// Optional (`GuidedPropagation`): a policy that can use what a neighbouring ray found also offers
///
/// | `p.trace_beside(r, scene, t_max_s, a_launch, a_clear_range_m)` | `std::optional<path<T>>` | p.trace(r, scene, t_max_s), bit for bit |
///
/// given that the ray launched from r's origin along the unit direction `a_launch` (a `vec3<T>`) met nothing of the
/// scene within horizontal distance a_clear_range_m (m) of the origin (its path's `clear_range_m`), save what the
/// scene's guided query leaves out (scene/concept.hpp). The simulator's refinement passes the steeper of the two rays
/// it traces a new one between (straight rays hand it to a GuidedScene's intersect_beside; bent rays ask a
/// GuidedScene's clear_range_beside_m how many chords they may skip, and hand a ResumableScene the chord that reaches
/// past them with its part within that distance known clear). A policy may also take a second guide, asked
/// where the first gives nothing: `p.trace_beside(r, scene, t_max_s, a_launch, a_clear_range_m, b_launch,
/// b_clear_range_m)`, p.trace(r, scene, t_max_s) bit for bit. The simulator then passes the steeper ray of the first
/// interval it refines as b (layered water: a very close neighbour gains too little over its chords' tolerance).

#include <concepts>
#include <cstddef>
#include <optional>
#include <span>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/flat_seabed.hpp"

namespace sss {

/// A traced one-way path from the transducer to a surface.
template <Real T> struct path {
    hit<T> surface{};      ///< where the path ends
    T time_s{};            ///< one-way travel time (s)
    T spreading{};         ///< return-leg spreading: intensity at the transducer relative to 1 m from the hit (1/r^2 isovelocity)
    T absorption{};        ///< one-way absorption: intensity ratio in (0, 1]
    vec3<T> arrival{};     ///< unit direction of travel where the path meets the surface (world)
    /// Horizontal distance from the source within which the path surely met nothing (m): no further than the hit, and
    /// short of it by what the propagation cannot vouch for (a neighbour's trace builds on it, GuidedPropagation); 0
    /// claims nothing.
    T clear_range_m{};
};

template <class P>
concept Propagation = Real<typename P::value_type> &&
    requires(const P& p, const ray<typename P::value_type>& r,
             const scene::flat_seabed<typename P::value_type>& s, typename P::value_type t) {
        { p.reference_speed_mps() } -> std::same_as<typename P::value_type>;
        { p.trace(r, s, t) } -> std::same_as<std::optional<path<typename P::value_type>>>;
    };

/// A Propagation policy that traces many rays at once over scene type `Sc` (see the table above).
template <class P, class Sc>
concept BatchPropagation = Propagation<P> && Scene<Sc> &&
    requires(const P& p, std::span<const ray<typename P::value_type>> rays, const Sc& s, typename P::value_type t,
             std::span<std::optional<path<typename P::value_type>>> out) {
        { p.trace_many(rays, s, t, out) };
    };

/// A Propagation policy that bounds how far its rays reach (see the table above).
template <class P>
concept ReachBoundedPropagation = Propagation<P> && requires(const P& p, typename P::value_type z) {
    { p.reach_speed_mps(z) } -> std::same_as<typename P::value_type>;
};

/// A Propagation policy that says where its rays pass a horizontal range, with no scene (see the table above).
template <class P>
concept RangeHeightPropagation = Propagation<P> &&
    requires(const P& p, const ray<typename P::value_type>& r, typename P::value_type t) {
        { p.height_at_range_m(r, t, t) } -> std::same_as<std::optional<typename P::value_type>>;
    };

/// A Propagation policy that takes a neighbouring ray's clear time as a guide over scene type `Sc` (see the table
/// above).
template <class P, class Sc>
concept GuidedPropagation = Propagation<P> && Scene<Sc> &&
    requires(const P& p, const ray<typename P::value_type>& r, const Sc& s, typename P::value_type t,
             const vec3<typename P::value_type>& d) {
        { p.trace_beside(r, s, t, d, t) } -> std::same_as<std::optional<path<typename P::value_type>>>;
    };

/// paths[k] = p.trace(rays[k], scene, t_max_s) for every k, through the policy's batch method when it has one.
/// `paths` must hold at least rays.size() slots.
template <Propagation P, Scene Sc>
void trace_all(const P& p, std::span<const ray<typename P::value_type>> rays, const Sc& scene,
               typename P::value_type t_max_s, std::span<std::optional<path<typename P::value_type>>> paths) {
    if constexpr (BatchPropagation<P, Sc>) {
        p.trace_many(rays, scene, t_max_s, paths.first(rays.size()));
    } else {
        for (std::size_t k = 0; k < rays.size(); ++k) paths[k] = p.trace(rays[k], scene, t_max_s);
    }
}

} // namespace sss
