#pragma once
/// \file
/// Plane-wave reflection at the seafloor: the Rayleigh coefficient of a flat interface between water and a
/// lossy fluid sediment, and the coherent (specular) coefficient of a rough one.
///
/// Notation of APL-UW TR 9407 (1994) Section IV: theta is the grazing angle (rad), rho the density ratio,
/// nu the sound-speed ratio, delta the loss parameter, kappa = (1 + i delta) / nu the complex wavenumber
/// ratio. Everything is evaluated in double whatever T is, then rounded to T.

#include <cmath>
#include <complex>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/scattering/sediments.hpp"

namespace sss::scattering {

/// kappa = (1 + i delta) / nu: sediment-to-water complex wavenumber ratio (dimensionless).
template <Real T> [[nodiscard]] inline std::complex<T> wavenumber_ratio(T nu, T delta) noexcept {
    return std::complex<T>(T(1), delta) / nu;
}

/// P(theta) = sqrt(kappa^2 - cos^2 theta): the sediment's vertical wavenumber over the water wavenumber,
/// principal root (TR 9407 Section IV). For delta >= 0, Im(kappa^2) >= 0, so the root has Re P >= 0 and
/// Im P >= 0: the transmitted wave carries energy down and decays with depth (evanescent below the
/// critical angle when nu > 1). graze_rad in [0, pi/2].
/// Evaluated as sqrt((kappa^2 - 1) + sin^2 theta), which keeps full precision at grazing incidence.
template <Real T> [[nodiscard]] inline std::complex<T> vertical_wavenumber_ratio(std::complex<T> kappa, T graze_rad) noexcept {
    const T s = std::sin(graze_rad);
    // Adding a real number keeps the +0 imaginary part of a lossless kappa, so the root lands on +i, never -i.
    return std::sqrt((kappa * kappa - T(1)) + s * s);
}

/// Rayleigh reflection coefficient of a flat water / fluid-sediment interface (pressure ratio, complex):
///   R(theta) = (rho sin theta - P) / (rho sin theta + P)        (TR 9407 Section IV; Brekhovskikh)
/// rho, nu (dimensionless ratios), delta >= 0 (dimensionless), graze_rad in [0, pi/2].
/// |R| <= 1 for every input (Re P >= 0); R(0) = -1, except for the degenerate kappa = 1 (nu = 1, delta = 0)
/// where P = sin theta and R = (rho - 1) / (rho + 1) at every angle, its value at 0 included.
template <Real T> [[nodiscard]] inline std::complex<T> rayleigh_reflection(T rho, T nu, T delta, T graze_rad) noexcept {
    const std::complex<double> kappa = wavenumber_ratio(double(nu), double(delta));
    const double g = double(graze_rad);
    const std::complex<double> p = vertical_wavenumber_ratio(kappa, g);
    const double rs = double(rho) * std::sin(g);
    const std::complex<double> den = rs + p;
    std::complex<double> r = std::abs(den) > 0.0 ? (rs - p) / den
                                                 : std::complex<double>((double(rho) - 1.0) / (double(rho) + 1.0), 0.0);
    const double mag = std::abs(r);
    if (mag > 1.0) r /= mag; // rounding only: energy is never created
    return {T(r.real()), T(r.imag())};
}

/// The Rayleigh coefficient of a sediment (see above); graze_rad in [0, pi/2].
template <Real T> [[nodiscard]] inline std::complex<T> rayleigh_reflection(const sediment_params<T>& s, T graze_rad) noexcept {
    return rayleigh_reflection(s.rho, s.nu, s.delta, graze_rad);
}

/// RMS height (m) of the roughness with wavenumbers above k_min (rad/m) for the APL-UW spectrum
/// W(K) = w2 / (h0 K)^gamma (h0 = 1 cm, K in rad/cm, W in cm^4), with <h^2> = integral of W over d^2K:
///   <h^2> = 2 pi w2 integral_{K_min}^{inf} K^(1 - gamma) dK = 2 pi w2 K_min^(2 - gamma) / (gamma - 2)  (cm^2).
/// The integral converges at high K for gamma > 2 and diverges as K_min -> 0, so a band must be stated:
/// the coherent field of a patch of size L is degraded only by relief finer than L, K > 2 pi / L; relief
/// coarser than that is deterministic geometry (a tilt of the patch), which the scene's height field
/// carries. w2_cm4 (cm^4), gamma in (2, 4), k_min_radpm > 0 (rad/m). Returns metres.
template <Real T> [[nodiscard]] inline T roughness_rms_height_m(T w2_cm4, T gamma, T k_min_radpm) noexcept {
    const double g = double(gamma);
    const double kmin_cm = double(k_min_radpm) / 100.0;
    const double h2_cm2 = two_pi_v<double> * double(w2_cm4) * std::pow(kmin_cm, 2.0 - g) / (g - 2.0);
    return T(std::sqrt(h2_cm2) / 100.0);
}

/// Kirchhoff (Eckart 1953, JASA 25, 566) reduction of the coherent reflected amplitude by Gaussian roughness
/// of RMS height h: exp(-2 k^2 h^2 sin^2 theta), the characteristic function of the height at the
/// two-way vertical wavenumber 2 k sin theta. k_radpm = 2 pi f / c (rad/m), h_m (m), graze_rad (rad).
/// Always in (0, 1].
template <Real T> [[nodiscard]] inline T coherent_roughness_factor(T k_radpm, T h_m, T graze_rad) noexcept {
    const double kh = double(k_radpm) * double(h_m) * std::sin(double(graze_rad));
    return T(std::exp(-2.0 * kh * kh));
}

/// Coherent reflection coefficient of a rough sediment surface (complex pressure ratio):
///   R_coh(theta) = R(theta) exp(-2 k^2 h^2 sin^2 theta),  h = roughness_rms_height_m(w2, gamma, 2 pi / L),
/// i.e. the Rayleigh coefficient reduced by the roughness the scene does not resolve, relief finer than
/// patch_size_m = L (m; e.g. the cell size of the scene's height field). f_hz (Hz) and c_water_mps (m/s)
/// give k = 2 pi f / c. |R_coh| <= |R| <= 1. Throws invalid_parameter for a non-positive f_hz,
/// c_water_mps or patch_size_m, or invalid sediment parameters ("sediment.*").
template <Real T>
[[nodiscard]] std::complex<T> coherent_reflection(const sediment_params<T>& s, T f_hz, T c_water_mps, T graze_rad,
                                                  T patch_size_m) {
    validate(s, "sediment");
    sss::require_positive(f_hz, "f_hz");
    sss::require_positive(c_water_mps, "c_water_mps");
    sss::require_positive(patch_size_m, "patch_size_m");
    const double k = two_pi_v<double> * double(f_hz) / double(c_water_mps);
    const double h = roughness_rms_height_m(double(s.w2_cm4), double(s.gamma), two_pi_v<double> / double(patch_size_m));
    const std::complex<T> r = rayleigh_reflection(s, graze_rad);
    return r * T(coherent_roughness_factor(k, h, double(graze_rad)));
}

} // namespace sss::scattering
