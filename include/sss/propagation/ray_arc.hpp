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

// Not `detail`: a nested namespace of that name would hide sss::detail from the rest of sss::propagation.
namespace detail {

/// sin(u)/u, exact at 0.
template <Real T> [[nodiscard]] inline T sinc(T u) noexcept {
    return std::abs(u) < T(1e-4) ? T(1) - u * u * T(1.0 / 6) : std::sin(u) / u;
}
/// atan(w)/w, exact at 0.
template <Real T> [[nodiscard]] inline T atan_ratio(T w) noexcept {
    return std::abs(w) < T(1e-4) ? T(1) - w * w * T(1.0 / 3) : std::atan(w) / w;
}
/// atanh(u)/u, exact at 0.
template <Real T> [[nodiscard]] inline T atanh_ratio(T u) noexcept {
    return std::abs(u) < T(1e-4) ? T(1) + u * u * T(1.0 / 3) : std::atanh(u) / u;
}
/// log(1 + e)/e, exact at 0.
template <Real T> [[nodiscard]] inline T log1p_ratio(T e) noexcept {
    return std::abs(e) < T(1e-4) ? T(1) - e * T(0.5) + e * e * T(1.0 / 3) : std::log1p(e) / e;
}

/// Start of an arc in the form the formulas want.
template <Real T> struct arc_start {
    T z0, c0, phi0, sin0, cos0, g, xi, kappa;
};

template <Real T> [[nodiscard]] inline arc_start<T> make_start(T z0, T c0, T phi0, T g) noexcept {
    const T cos0 = std::max(std::cos(phi0), T(0));
    const T xi = cos0 / c0;
    return {z0, c0, phi0, std::sin(phi0), cos0, g, xi, xi * g};
}

/// Travel time from the start to a point with range x and inclination (sin1, cos1) given
/// s2 = sin^2(Dphi/2): t = (xi x / D) atanh(u)/u, D = 2 s2 + cos0 cos1, u = kappa x / D.
template <Real T> [[nodiscard]] inline T arc_time(const arc_start<T>& a, T x, T cos1, T s2) noexcept {
    const T d = T(2) * s2 + a.cos0 * cos1;
    return a.xi * x / d * atanh_ratio(a.kappa * x / d);
}

/// Rounding-level negative sin^2 at a boundary means "reaches it horizontally".
template <Real T> [[nodiscard]] inline T snap_sin2(T s1sq, T sin2_0, T bend) noexcept {
    const T tol = T(8) * std::numeric_limits<T>::epsilon() * std::max(sin2_0, std::abs(bend));
    return std::abs(s1sq) <= tol ? T(0) : s1sq;
}

/// The first point at depth zt reached by the arc. `after_turn` selects the branch: false for a depth
/// ahead of the ray before any turn, true for one reached after the ray has turned. nullopt when the
/// branch never reaches zt.
template <Real T>
[[nodiscard]] inline std::optional<arc_sample<T>> reach_depth(const arc_start<T>& a, T zt, bool after_turn) noexcept {
    const T dz = zt - a.z0;
    if (dz == T(0) && !after_turn) return arc_sample<T>{zt, T(0), T(0), T(0), a.phi0};
    const T e = a.g * dz / a.c0;
    const T bend = a.cos0 * a.cos0 * e * (T(2) + e);
    const T sin2_0 = a.sin0 * a.sin0;
    const T s1sq = snap_sin2(sin2_0 - bend, sin2_0, bend);
    if (s1sq < T(0)) return std::nullopt;
    const T cos1 = std::clamp(a.cos0 * (T(1) + e), T(0), T(1));
    if (!after_turn) {
        const T sin1 = std::copysign(std::sqrt(s1sq), dz);
        const T sum = a.sin0 + sin1; // same sign as dz, never zero for dz != 0
        if (sum == T(0)) return std::nullopt;
        const T w = a.kappa * dz / sum; // tan(Dphi/2)
        const T x = dz * (a.cos0 + cos1) / sum;
        const T s = T(2) * dz / sum * atan_ratio(w);
        const T t = arc_time(a, x, cos1, w * w / (T(1) + w * w));
        return arc_sample<T>{zt, x, t, s, std::atan2(sin1, cos1)};
    }
    if (a.kappa == T(0) || a.sin0 == T(0)) return std::nullopt;
    const T sin1 = -std::copysign(std::sqrt(s1sq), a.sin0);
    const T phi1 = std::atan2(sin1, cos1);
    const T dphi = a.phi0 - phi1; // the two angles have opposite signs: no cancellation
    const T s = dphi / a.kappa;
    const T x = (a.sin0 - sin1) / a.kappa;
    const T sh = std::sin(dphi / T(2));
    const T t = arc_time(a, x, cos1, sh * sh);
    return arc_sample<T>{zt, x, t, s, phi1};
}

/// +1 when the arc starts moving down, -1 up, 0 when it is horizontal in a zero-gradient layer.
template <Real T> [[nodiscard]] inline int start_motion(const arc_start<T>& a) noexcept {
    if (a.sin0 > T(0)) return 1;
    if (a.sin0 < T(0)) return -1;
    if (a.kappa > T(0)) return -1; // horizontal: phi decreases, the ray rises
    if (a.kappa < T(0)) return 1;
    return 0;
}

/// Can the arc turn (pass through horizontal) after its start?
template <Real T> [[nodiscard]] inline bool can_turn(const arc_start<T>& a) noexcept {
    return (a.sin0 > T(0) && a.kappa > T(0)) || (a.sin0 < T(0) && a.kappa < T(0));
}

template <Real T>
[[nodiscard]] inline layer_step<T> step_from(const gradient_layer<T>& layer, T z0, T phi0) noexcept {
    constexpr T inf = std::numeric_limits<T>::infinity();
    z0 = std::clamp(z0, layer.z_top_m, layer.z_bottom_m);
    const arc_start<T> a = make_start(z0, layer.speed_mps(z0), phi0, layer.gradient_per_s);
    layer_step<T> out;
    out.arc = {z0, a.c0, phi0, a.g, inf};
    out.exit = {z0, inf, inf, inf, phi0};

    if (a.cos0 == T(0)) { // vertical: a straight line
        const bool down = a.sin0 > T(0);
        const T zt = down ? layer.z_bottom_m : layer.z_top_m;
        if (!std::isfinite(zt)) {
            out.exit.depth_m = zt;
            return out;
        }
        const T dz = zt - z0;
        const T s = std::abs(dz);
        const T t = s / a.c0 * log1p_ratio(a.g * dz / a.c0);
        out.arc.length_m = s;
        out.exit = {zt, T(0), t, s, phi0};
        out.boundary = down ? layer_exit::bottom : layer_exit::top;
        return out;
    }

    const int motion = start_motion(a);
    if (motion == 0) return out; // horizontal in a uniform layer: stays at z0 for ever
    const T ahead = motion > 0 ? layer.z_bottom_m : layer.z_top_m;
    const T behind = motion > 0 ? layer.z_top_m : layer.z_bottom_m;
    if (std::isfinite(ahead)) {
        if (auto hit = reach_depth(a, ahead, false)) {
            out.arc.length_m = hit->arc_m;
            out.exit = *hit;
            out.boundary = motion > 0 ? layer_exit::bottom : layer_exit::top;
            return out;
        }
    }
    if (!can_turn(a)) { // runs off to an infinite bound without turning
        out.exit.depth_m = ahead;
        return out;
    }
    out.turned = true;
    if (!std::isfinite(behind)) {
        out.exit.depth_m = behind;
        return out;
    }
    if (auto hit = reach_depth(a, behind, true)) {
        out.arc.length_m = hit->arc_m;
        out.exit = *hit;
        out.boundary = motion > 0 ? layer_exit::top : layer_exit::bottom;
    }
    return out;
}

} // namespace detail

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
