#pragma once
/// \file
/// Mathematical constants as variable templates, so float and double code both get exact literals.

#include "sss/core/types.hpp"

namespace sss {

template <Real T> inline constexpr T pi_v = T(3.141592653589793238462643383279502884L);
template <Real T> inline constexpr T two_pi_v = T(6.283185307179586476925286766559005768L);
template <Real T> inline constexpr T half_pi_v = T(1.570796326794896619231321691639751442L);
template <Real T> inline constexpr T ln10_v = T(2.302585092994045684017991454684364208L);

/// Degrees to radians.
template <Real T> [[nodiscard]] constexpr T deg_to_rad(T deg) noexcept { return deg * (pi_v<T> / T(180)); }
/// A heading or direction as users give it (deg, clockwise from north: docs/conventions.md) as the angle
/// counter-clockwise from east (rad) that the trigonometry of plan geometry uses: 90 deg - heading. The unit
/// vector of the heading, world (x east, y north), is (cos, sin) of the result.
template <Real T> [[nodiscard]] constexpr T heading_to_ccw_from_east_rad(T heading_deg) noexcept {
    return deg_to_rad(T(90) - heading_deg);
}
/// Radians to degrees.
template <Real T> [[nodiscard]] constexpr T rad_to_deg(T rad) noexcept { return rad * (T(180) / pi_v<T>); }

} // namespace sss
