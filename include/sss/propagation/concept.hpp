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

#include <concepts>
#include <optional>

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
};

template <class P>
concept Propagation = Real<typename P::value_type> &&
    requires(const P& p, const ray<typename P::value_type>& r,
             const scene::flat_seabed<typename P::value_type>& s, typename P::value_type t) {
        { p.reference_speed_mps() } -> std::same_as<typename P::value_type>;
        { p.trace(r, s, t) } -> std::same_as<std::optional<path<typename P::value_type>>>;
    };

} // namespace sss
