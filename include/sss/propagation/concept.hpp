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
/// The return path is the outgoing one reversed (monostatic, reciprocal water), so the two-way loss is the square
/// of the one-way loss and the two-way time twice the one-way time.

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
    T spreading{};         ///< one-way spreading: intensity relative to that at 1 m (1/r^2 in isovelocity water)
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
