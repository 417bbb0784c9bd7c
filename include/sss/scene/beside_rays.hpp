#pragma once
/// \file
/// Two rays from one origin, and what the first is known to keep over the second: the question a GuidedScene answers
/// with `clear_range_beside_m` (scene/concept.hpp), for straight rays and rays bent by refraction alike.
///
/// Ray a has met nothing of the scene within horizontal distance rho_a_m of the origin. Ray r leaves the same origin
/// in a vertical plane turned from a's by a small angle, and at every horizontal distance rho <= rho_a_m it lies at
/// least gain * rho above a, less margin_m: straight rays with tan(depression) tau_a > tau_r have
/// gain = tau_a - tau_r and no margin; bent rays have a lower bound from their ray parameters and margin_m for the
/// chords they are traced along (propagation/layered.hpp derives both).

#include "sss/core/types.hpp"

namespace sss::scene {

/// Plain data. Headings are unit horizontal directions (world x, y).
template <Real T> struct beside_rays {
    vec3<T> origin{};    ///< where both rays leave (world, m)
    vec2<T> heading_r{}; ///< r's horizontal direction of travel (unit)
    vec2<T> heading_a{}; ///< a's (unit)
    T rho_a_m{};         ///< a met nothing within this horizontal distance of the origin (m)
    T gain{};            ///< r lies at least gain * rho above a at horizontal distance rho <= rho_a_m (m per m)
    T slope_r{};         ///< r descends at most this much per metre of horizontal travel (m per m)
    T drop_a_m{};        ///< a lies at most this far below the origin within rho_a_m (m)
    T margin_m{};        ///< the paths traced lie within this vertical distance of what gain and slope_r bound (m)
};

} // namespace sss::scene
