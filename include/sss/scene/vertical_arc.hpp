#pragma once
/// \file
/// A circular arc in a vertical plane, and where it meets a scene: what layered water (propagation/layered.hpp) hands
/// a scene that meets its rays' arcs itself (`ArcScene`, scene/concept.hpp) instead of straight chords.
///
/// In a layer of water whose sound speed changes linearly with depth a ray is a circular arc in the vertical plane of
/// its launch; by Snell's law sin(phi), phi its inclination below the horizontal, falls linearly with horizontal
/// distance x:
///     sin phi(x) = sin phi0 - kappa x,
/// kappa (1/m) the signed curvature (positive where the ray bends up). Its depth below its start is then
///     d(x) = (cos phi(x) - cos phi0) / kappa = x (2 sin phi0 - kappa x) / (cos phi0 + cos phi(x)),
/// the second form free of cancellation as kappa goes to 0 (a straight ray, d = x tan phi0).

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"

namespace sss::scene {

/// A circular arc in a vertical plane, by horizontal distance x (m) from its start (file comment). Plain data.
template <Real T> struct vertical_arc {
    vec3<T> start{};   ///< world point at x = 0 (m)
    vec2<T> heading{}; ///< unit horizontal direction of travel (world x, y)
    T sin_phi0{};      ///< sine of the inclination below the horizontal at the start (+ down)
    T cos_phi0{1};     ///< its cosine (> 0)
    T kappa_per_m{};   ///< signed curvature (1/m): sin phi falls by kappa per metre of x (+: bends up)

    /// sin phi at horizontal distance x_m.
    [[nodiscard]] T sin_at(T x_m) const noexcept { return sin_phi0 - kappa_per_m * x_m; }
    /// cos phi at horizontal distance x_m (0 where the arc would be past vertical): cos^2 phi = cos^2 phi0 +
    /// kappa x (sin phi0 + sin phi), exact at the start and free of cancellation near vertical (1 - sin^2 is not).
    [[nodiscard]] T cos_at(T x_m) const noexcept {
        return std::sqrt(std::max(T(0), cos_phi0 * cos_phi0 + kappa_per_m * x_m * (sin_phi0 + sin_at(x_m))));
    }
    /// Depth below the start (m, + down) at horizontal distance x_m:
    /// x (2 sin phi0 - kappa x) / (cos phi0 + cos phi(x)).
    [[nodiscard]] T depth_m(T x_m) const noexcept {
        return x_m * (T(2) * sin_phi0 - kappa_per_m * x_m) / (cos_phi0 + cos_at(x_m));
    }
    /// World point at horizontal distance x_m.
    [[nodiscard]] vec3<T> at(T x_m) const noexcept {
        return vec3<T>{start.x + heading.x * x_m, start.y + heading.y * x_m, start.z - depth_m(x_m)};
    }
};

/// Where an arc meets a scene: the hit (its point on the arc; distance_m is x_m) and the horizontal distance x_m (m)
/// from the arc's start. Plain data.
template <Real T> struct arc_surface_hit {
    hit<T> surface{};
    T x_m{};
};

/// A Scene with nothing in it: what is left of a scene that meets arcs itself in all of its geometry (ArcScene's
/// arc_others, scene/concept.hpp).
template <Real T> struct no_geometry {
    using value_type = T;
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>&, T) const noexcept { return std::nullopt; }
    [[nodiscard]] T seabed_height_m(T, T) const noexcept { return -std::numeric_limits<T>::infinity(); }
    [[nodiscard]] T top_m() const noexcept { return -std::numeric_limits<T>::infinity(); }
};

} // namespace sss::scene
