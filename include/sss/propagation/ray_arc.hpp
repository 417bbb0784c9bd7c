#pragma once
/// \file
/// Exact ray paths through one layer of constant sound-speed gradient.
///
/// In a layer where c(z) = c0 + g (z - z0) (z positive down, g in 1/s), Snell's law keeps
/// xi = cos(phi)/c(z) constant along a ray, and the path is a circular arc of radius
/// R = 1/(xi |g|) = c0/(|g| cos phi0) (see for example Jensen, Kuperman, Porter & Schmidt,
/// "Computational Ocean Acoustics", 2nd ed. 2011, section 3.2, or Medwin & Clay, "Fundamentals of
/// Acoustical Oceanography", 1998, section 2.6). Here phi is the signed inclination of the ray below the
/// horizontal (rad): positive going down, negative going up; the grazing angle is |phi|.
/// Along the arc, phi falls linearly with arc length s, phi(s) = phi0 - kappa s with kappa = xi g, and
///
///     x(s)   = (sin phi0 - sin phi)/kappa                      horizontal range (m)
///     z(s)   = z0 + (cos phi - cos phi0)/kappa                 depth (m)
///     t(s)   = (1/g) [atanh(sin phi0) - atanh(sin phi)]        travel time (s)
///
/// which are the textbook forms x = R (sin theta0 - sin theta1), s = R |theta0 - theta1|,
/// t = (1/g) ln[((1 + sin theta0)/cos theta0)/((1 + sin theta1)/cos theta1)] written for signed angles.
/// As g -> 0 those forms divide a vanishing difference by a vanishing gradient. This header evaluates
/// them through identities that cancel nothing, with Dphi = phi0 - phi:
///
///     chord = s sinc(Dphi/2), along the mean inclination phi0 - Dphi/2;
///     tan(Dphi/2) = kappa dz/(sin phi0 + sin phi) = kappa x/(cos phi0 + cos phi);
///     x = dz (cos phi0 + cos phi)/(sin phi0 + sin phi)   (no turn);
///     sin^2 phi = sin^2 phi0 - cos^2 phi0 e (2 + e),  e = g dz / c0;
///     t = (xi x / D) atanh(u)/u,  D = 1 - sin phi0 sin phi = 2 sin^2(Dphi/2) + cos phi0 cos phi,  u = kappa x / D.
///
/// Measured against long double numerical integration the results agree to ~1e-15 relative in double
/// for g from 1e-1 down to 1e-12 1/s and at g = 0 (tests/propagation/test_ray_arc.cpp).
///
/// Conventions at the hard cases:
/// - A horizontal ray (phi0 = 0) moves the way the gradient bends it: up when g > 0 (speed rising
///   with depth), down when g < 0; in a zero-gradient layer it never leaves (layer_exit::none).
///   The requested vertical_direction is ignored for a horizontal ray.
/// - A ray whose turning depth is within rounding of a layer boundary reaches that boundary exactly
///   horizontal (exit grazing angle 0, turned = false); the next layer's gradient then decides where it
///   goes, which is the physically right continuation.
/// - A vertical ray (cos phi0 = 0) is a straight vertical line.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sss/core/constants.hpp"
#include "sss/core/types.hpp"
#include "sss/propagation/detail/arc_formulas.hpp"
#include "sss/propagation/layer_step.hpp"
#include "sss/propagation/profile.hpp"

namespace sss::propagation {

/// Snell invariant xi = cos(graze)/c (s/m) of a ray at grazing angle graze_rad (rad) where the sound
/// speed is c_mps (m/s).
template <Real T> [[nodiscard]] inline T snell_invariant(T graze_rad, T c_mps) noexcept {
    return std::cos(graze_rad) / c_mps;
}

/// Grazing angle (rad, in [0, pi/2]) of a ray with Snell invariant xi_s_per_m where the speed is c_mps;
/// 0 where the ray cannot exist (xi c > 1: beyond its turning depth).
template <Real T> [[nodiscard]] inline T graze_from_invariant(T xi_s_per_m, T c_mps) noexcept {
    const T cos_g = std::min(xi_s_per_m * c_mps, T(1));
    return std::atan2(std::sqrt((T(1) - cos_g) * (T(1) + cos_g)), cos_g);
}

/// Steps a ray through a constant-gradient layer from depth depth_m (clamped into the layer) at grazing
/// angle graze_rad (rad, 0..pi/2) heading `heading`: returns the arc and where and how it leaves
/// (depth, range, time, arc length, exit inclination, whether it turned inside). Closed forms, no
/// iteration; see the file comment for the formulas and the conventions at the hard cases.
template <Real T>
[[nodiscard]] inline layer_step<T> step_through_layer(const gradient_layer<T>& layer, T depth_m, T graze_rad,
                                                      vertical_direction heading) noexcept {
    const T graze = std::clamp(graze_rad, T(0), half_pi_v<T>);
    return detail::step_from(layer, depth_m, heading == vertical_direction::down ? graze : -graze);
}

/// As step_through_layer, with the ray given by its Snell invariant xi_s_per_m = cos(graze)/c (s/m).
/// Note that near horizontal the invariant fixes the angle only to about sqrt(2 eps) rad; carrying the
/// grazing angle from layer to layer (the other overload) keeps full precision.
template <Real T>
[[nodiscard]] inline layer_step<T> step_through_layer_invariant(const gradient_layer<T>& layer, T depth_m,
                                                                T xi_s_per_m, vertical_direction heading) noexcept {
    const T z0 = std::clamp(depth_m, layer.z_top_m, layer.z_bottom_m);
    return step_through_layer(layer, z0, graze_from_invariant(xi_s_per_m, layer.speed_mps(z0)), heading);
}

/// The point at arc length arc_m along the arc (clamped to [0, length_m]).
template <Real T> [[nodiscard]] inline arc_sample<T> arc_point(const ray_arc<T>& arc, T arc_m) noexcept {
    const auto a = detail::make_start(arc.start_depth_m, arc.start_speed_mps, arc.start_incline_rad, arc.gradient_per_s);
    const T s = std::clamp(arc_m, T(0), arc.length_m);
    if (a.cos0 == T(0)) {
        const T dz = std::copysign(s, a.sin0);
        return {a.z0 + dz, T(0), s / a.c0 * detail::log1p_ratio(a.g * dz / a.c0), s, a.phi0};
    }
    // The chord runs along the mean inclination phi0 - half. Its cosine is expanded so that it keeps
    // full relative precision near vertical, where cos(phi0 - half) itself would not.
    const T half = a.kappa * s / T(2);
    const T ch = std::cos(half);
    const T sh = std::sin(half);
    const T chord = s * detail::sinc(half);
    const T x = chord * (a.cos0 * ch + a.sin0 * sh);
    const T dz = chord * (a.sin0 * ch - a.cos0 * sh);
    const T cos1 = std::clamp(a.cos0 * (T(1) + a.g * dz / a.c0), T(0), T(1)); // Snell: cos(phi) = xi c(z)
    const T t = detail::arc_time(a, x, cos1, sh * sh);
    return {a.z0 + dz, x, t, s, a.phi0 - T(2) * half};
}

/// The point where the arc has advanced range_m horizontally; nullopt when range_m is negative or
/// beyond the arc's end. Range grows monotonically along an arc, so the point is unique.
template <Real T>
[[nodiscard]] inline std::optional<arc_sample<T>> arc_point_at_range(const ray_arc<T>& arc, T range_m) noexcept {
    if (!(range_m >= T(0))) return std::nullopt;
    const auto a = detail::make_start(arc.start_depth_m, arc.start_speed_mps, arc.start_incline_rad, arc.gradient_per_s);
    if (a.cos0 == T(0)) return range_m == T(0) ? std::optional(arc_point(arc, T(0))) : std::nullopt;
    const T sin1 = a.sin0 - a.kappa * range_m;
    if (!(std::abs(sin1) <= T(1))) return std::nullopt;
    const T cos_sum = a.cos0 + std::sqrt((T(1) - sin1) * (T(1) + sin1));
    const T s = T(2) * range_m / cos_sum * detail::atan_ratio(a.kappa * range_m / cos_sum);
    if (s > arc.length_m * (T(1) + T(4) * std::numeric_limits<T>::epsilon())) return std::nullopt;
    arc_sample<T> p = arc_point(arc, s);
    p.range_m = range_m;
    return p;
}

/// The first point at which the arc reaches depth_m; nullopt when it does not before its end.
template <Real T>
[[nodiscard]] inline std::optional<arc_sample<T>> arc_point_at_depth(const ray_arc<T>& arc, T depth_m) noexcept {
    const auto a = detail::make_start(arc.start_depth_m, arc.start_speed_mps, arc.start_incline_rad, arc.gradient_per_s);
    if (depth_m == a.z0) return arc_point(arc, T(0));
    std::optional<arc_sample<T>> hit;
    if (a.cos0 == T(0)) {
        if ((depth_m - a.z0) * a.sin0 > T(0)) hit = arc_point(arc, std::abs(depth_m - a.z0));
        if (hit && std::abs(depth_m - a.z0) > arc.length_m) hit.reset();
        if (hit) hit->depth_m = depth_m;
        return hit;
    }
    const int motion = detail::start_motion(a);
    if (motion == 0) return std::nullopt;
    if ((depth_m - a.z0) * T(motion) > T(0)) hit = detail::reach_depth(a, depth_m, false);
    if (!hit && detail::can_turn(a)) hit = detail::reach_depth(a, depth_m, true);
    if (hit && hit->arc_m > arc.length_m * (T(1) + T(4) * std::numeric_limits<T>::epsilon())) hit.reset();
    return hit;
}

/// The turning point (where the ray is horizontal) strictly inside the arc, if there is one.
template <Real T> [[nodiscard]] inline std::optional<arc_sample<T>> arc_turning_point(const ray_arc<T>& arc) noexcept {
    const auto a = detail::make_start(arc.start_depth_m, arc.start_speed_mps, arc.start_incline_rad, arc.gradient_per_s);
    if (!detail::can_turn(a)) return std::nullopt;
    const T s = a.phi0 / a.kappa;
    if (!(s < arc.length_m)) return std::nullopt;
    arc_sample<T> p = arc_point(arc, s);
    p.incline_rad = T(0);
    return p;
}

} // namespace sss::propagation
