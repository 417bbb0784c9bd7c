#pragma once
/// \file
/// The power-law roughness spectrum of the seabed, in SI units, with the conversion from the cm-based
/// parameters of the APL-UW tables, so that one set of sediment parameters drives both the synthesised
/// geometry and the scattering model.
///
/// APL-UW High-Frequency Ocean Environmental Acoustic Models Handbook, TR 9407 (1994), Section IV:
///   W(K) = w2 / (h0 K)^gamma,  h0 = 1 cm, K in rad/cm, W in cm^4, w2 in cm^4 (Table 2: gamma = 3.25).
/// Convention: <h^2> = integral of W(K) over d^2K (two-sided, both signs of Kx and Ky).
/// In SI (K in rad/m, W in m^4) the same law reads W(K) = w2_si K^-gamma with
///   w2_si [m^(4 - gamma)] = w2 [cm^4] * 10^(2 gamma - 8),
/// since W_si = 1e-8 W_cm and K_cm = K_si / 100.
/// A finite outer scale L0 (optional) rolls the spectrum off below K0 = 2 pi / L0 (von Karman form):
///   W(K) = w2_si (K^2 + K0^2)^(-gamma/2),
/// which keeps the height variance finite however large the area; L0 = 0 is the pure power law.

#include <cmath>
#include <string>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"

namespace sss::seabed {

/// Isotropic power-law spectrum in SI units.
template <Real T> struct power_law_spectrum {
    T w2_si = T(0);         ///< spectral strength, m^(4 - gamma) (W in m^4 for K in rad/m); 0 = flat
    T gamma = T(3.25);      ///< spectral exponent, in (2, 4) (fractal dimension D = (8 - gamma)/2)
    T outer_scale_m = T(0); ///< outer scale L0 (m); 0 = none (pure power law)
};

/// w2 in SI, m^(4 - gamma), from the APL-UW table value in cm^4 (h0 = 1 cm):
/// w2_si = w2_cm4 * 10^(2 gamma - 8). Example: medium sand, w2 = 0.004446 cm^4, gamma = 3.25
/// gives 0.004446 * 10^(-1.5) = 1.40595e-4 m^0.75.
template <Real T> [[nodiscard]] inline T w2_si_from_cm4(T w2_cm4, T gamma) noexcept {
    return w2_cm4 * std::pow(T(10), T(2) * gamma - T(8));
}

/// The spectrum of an APL-UW sediment: w2 in cm^4 as printed in TR 9407 Table 2, gamma dimensionless.
template <Real T>
[[nodiscard]] inline power_law_spectrum<T> jackson_spectrum(T w2_cm4, T gamma, T outer_scale_m = T(0)) noexcept {
    return power_law_spectrum<T>{w2_si_from_cm4(w2_cm4, gamma), gamma, outer_scale_m};
}

/// W(K) in m^4 for K in rad/m: w2_si (K^2 + K0^2)^(-gamma/2), K0 = 2 pi / L0 (0 without outer scale).
/// Infinite at K = 0 without outer scale.
template <Real T> [[nodiscard]] inline T spectral_density_m4(const power_law_spectrum<T>& s, T k_radpm) noexcept {
    const T k0 = s.outer_scale_m > T(0) ? two_pi_v<T> / s.outer_scale_m : T(0);
    return s.w2_si * std::pow(k_radpm * k_radpm + k0 * k0, -s.gamma / T(2));
}

/// Throws invalid_parameter (named `who`.w2_si, .gamma, .outer_scale_m) unless w2_si >= 0,
/// 2 < gamma < 4 and outer_scale_m >= 0.
template <Real T> void validate(const power_law_spectrum<T>& s, const std::string& who) {
    sss::require_non_negative(s.w2_si, who + ".w2_si");
    sss::require_finite(s.gamma, who + ".gamma");
    sss::require(s.gamma > T(2) && s.gamma < T(4), who + ".gamma",
                    [&] { return "must lie in (2, 4) (fractional Brownian surface), got " + std::to_string(s.gamma); });
    sss::require_non_negative(s.outer_scale_m, who + ".outer_scale_m");
}

} // namespace sss::seabed
