#pragma once
/// \file
/// Speed of sound in sea water from temperature, salinity and depth.
///
/// Mackenzie, K. V. (1981), "Nine-term equation for sound speed in the oceans",
/// J. Acoust. Soc. Am. 70(3), 807-812:
///
///     c = 1448.96 + 4.591 T - 5.304e-2 T^2 + 2.374e-4 T^3 + 1.340 (S - 35) + 1.630e-2 D + 1.675e-7 D^2
///         - 1.025e-2 T (S - 35) - 7.139e-13 T D^3
///
/// T temperature (degC), S salinity (ppt, practical salinity), D depth (m), c in m/s.
/// Published check value: c = 1550.744 m/s at T = 25 degC, S = 35 ppt, D = 1000 m.
/// Validity (as stated by Mackenzie): T from -2 to 30 degC, S from 25 to 40 ppt, D from 0 to 8000 m;
/// standard error 0.070 m/s against the Del Grosso-Mader data. Outside that range the polynomial is
/// still evaluated (no check is made) but it is an extrapolation.

#include "sss/core/types.hpp"

namespace sss::propagation {

/// Mackenzie (1981) nine-term sound speed (m/s).
/// \param temperature_c  in-situ temperature (degC)
/// \param salinity_ppt   salinity (ppt)
/// \param depth_m        depth below the surface (m, positive down)
template <Real T>
[[nodiscard]] constexpr T mackenzie_sound_speed_mps(T temperature_c, T salinity_ppt, T depth_m) noexcept {
    const T t = temperature_c;
    const T ds = salinity_ppt - T(35);
    const T d = depth_m;
    // Horner forms of the temperature and depth polynomials.
    const T temperature_part = T(1448.96) + t * (T(4.591) + t * (T(-5.304e-2) + t * T(2.374e-4)));
    const T depth_part = d * (T(1.630e-2) + d * T(1.675e-7));
    return temperature_part + T(1.340) * ds + depth_part - T(1.025e-2) * t * ds - T(7.139e-13) * t * d * d * d;
}

} // namespace sss::propagation
