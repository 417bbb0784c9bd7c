#pragma once
/// \file
/// Internal to propagation/ray_arc.hpp: the closed forms of a ray arc in a constant-gradient layer, written
/// through identities that cancel nothing as the gradient vanishes (see that header's file comment), and the
/// step through a layer built from them. Not part of the API.
///
/// The namespace is sss::propagation::detail. A nested namespace of that name hides sss::detail from
/// unqualified lookup in the rest of sss::propagation: code there names sss::detail in full.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sss/core/types.hpp"
#include "sss/propagation/layer_step.hpp"
#include "sss/propagation/profile.hpp"

namespace sss::propagation::detail {


/// sin(u)/u, exact at 0.
template <Real T> [[nodiscard]] inline T sinc(T u) noexcept {
    return std::abs(u) < T(1e-4) ? T(1) - u * u * T(1.0 / 6) : std::sin(u) / u;
}
/// sum_{n=0}^{7} (sign q)^n / (2n + 1): the series of atan(w)/w (sign -1) and atanh(u)/u (+1) in q = w^2 to the
/// q^7 term. For q <= 1/256 the first term left out, q^8 / 17, is below 3.2e-21: the sum is the function to rounding
/// in double.
template <Real T> [[nodiscard]] inline T odd_series(T q, T sign) noexcept {
    const T x = sign * q;
    return T(1) + x * (T(1.0 / 3) + x * (T(1.0 / 5) + x * (T(1.0 / 7) + x * (T(1.0 / 9) +
                                         x * (T(1.0 / 11) + x * (T(1.0 / 13) + x * T(1.0 / 15)))))));
}
/// atan(w)/w, exact at 0: its series where |w| <= 1/16 (to rounding; odd_series), the library's atan beyond.
template <Real T> [[nodiscard]] inline T atan_ratio(T w) noexcept {
    if (std::abs(w) < T(1e-4)) return T(1) - w * w * T(1.0 / 3);
    return std::abs(w) <= T(0.0625) ? odd_series(w * w, T(-1)) : std::atan(w) / w;
}
/// atanh(u)/u, exact at 0: its series where |u| <= 1/16 (to rounding; odd_series), the library's atanh beyond.
template <Real T> [[nodiscard]] inline T atanh_ratio(T u) noexcept {
    if (std::abs(u) < T(1e-4)) return T(1) + u * u * T(1.0 / 3);
    return std::abs(u) <= T(0.0625) ? odd_series(u * u, T(1)) : std::atanh(u) / u;
}
/// log(1 + e)/e, exact at 0: its series 1 - e/2 + e^2/3 - e^3/4 + e^4/5 where |e| < 1e-4 (the next term, e^5/6,
/// is below 2e-21), the library's log1p beyond.
template <Real T> [[nodiscard]] inline T log1p_ratio(T e) noexcept {
    return std::abs(e) < T(1e-4) ? T(1) + e * (T(-0.5) + e * (T(1.0 / 3) + e * (T(-0.25) + e * T(0.2))))
                                 : std::log1p(e) / e;
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


} // namespace sss::propagation::detail
