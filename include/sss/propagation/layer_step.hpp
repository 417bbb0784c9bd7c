#pragma once
/// \file
/// The plain results of stepping a ray through one constant-gradient layer: the arc it follows, a point on
/// that arc, and the step (arc, exit point, boundary left through). propagation/ray_arc.hpp computes them
/// (and includes this header).

#include <cmath>

#include "sss/core/types.hpp"

namespace sss::propagation {

/// Which boundary of its layer a ray leaves through.
enum class layer_exit : unsigned char { top, bottom, none };

/// A piece of ray path inside one constant-gradient layer: a circular arc (or a straight line when
/// g = 0), fixed by where it starts and how long it is. Plain data.
template <Real T> struct ray_arc {
    T start_depth_m{};     ///< z0 (m, positive down)
    T start_speed_mps{};   ///< c(z0) (m/s)
    T start_incline_rad{}; ///< phi0: signed inclination below horizontal (rad), + down, |phi0| <= pi/2
    T gradient_per_s{};    ///< g = dc/dz of the layer (1/s)
    T length_m{};          ///< arc length to the layer exit (m); +infinity when the ray never leaves
};

/// A point on a ray arc, measured from the arc's start. Plain data.
template <Real T> struct arc_sample {
    T depth_m{};     ///< z (m, positive down)
    T range_m{};     ///< horizontal distance travelled since the arc start (m)
    T time_s{};      ///< travel time since the arc start (s)
    T arc_m{};       ///< path length since the arc start (m)
    T incline_rad{}; ///< signed inclination below horizontal (rad), + down

    [[nodiscard]] T graze_rad() const noexcept { return std::abs(incline_rad); }
};

/// The result of stepping a ray through a layer. When boundary == layer_exit::none the ray never
/// leaves the layer: `exit` then holds the limit (depth the ray tends to, +infinity elsewhere).
template <Real T> struct layer_step {
    ray_arc<T> arc{};
    arc_sample<T> exit{};
    layer_exit boundary{layer_exit::none};
    bool turned{false}; ///< the ray passed through horizontal strictly inside the layer
};

} // namespace sss::propagation
