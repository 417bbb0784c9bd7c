#pragma once
/// \file
/// Far-field directivity of apertures and arrays: the uniform line aperture, the rectangular piston and the
/// linear array factor (uniform, or with shading weights), with steering, and helpers for the half-power
/// width, first null and first sidelobe.
///
/// All patterns are amplitude (pressure) patterns, 1 on their axis; square them for intensity (one way) and
/// multiply transmit and receive intensities for the two-way response. The angle argument is the direction
/// cosine `u = sin(theta)` measured from the aperture normal in the plane of the aperture's length, because
/// that is what separates in 3D: a direction with cosines (u, v) against the two axes of a planar aperture has
/// the product pattern f(u) g(v). Steering to `u0` replaces u by u - u0 (Kinsler et al., 2000, "Fundamentals
/// of Acoustics", 4th ed., Wiley, ch. 8; Urick, 1983, "Principles of Underwater Sound", 3rd ed., ch. 3).
///
/// Units: lengths and wavelengths in metres, angles in radians, direction cosines dimensionless.

#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "sss/beam/detail/lobe_inverse.hpp"
#include "sss/beam/sinc.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/types.hpp"

namespace sss::beam {

/// Uniform line aperture of length `length_m`: b = sin x / x, x = pi L (u - u0) / lambda (amplitude, 1 on
/// the steered axis). `u` = sin(theta) from the aperture normal; `u0` the steering direction cosine.
template <Real T>
[[nodiscard]] inline T line_aperture(T length_m, T wavelength_m, T u, T u0 = T(0)) noexcept {
    return sinc(pi_v<T> * length_m * (u - u0) / wavelength_m);
}

/// Rectangular piston `length_x_m` by `length_y_m` in a rigid baffle:
/// sinc(pi Lx u / lambda) sinc(pi Ly v / lambda), u and v the direction cosines against the x and y edges
/// (u = sin th cos ph, v = sin th sin ph).
template <Real T>
[[nodiscard]] inline T rectangular_piston(T length_x_m, T length_y_m, T wavelength_m, T u, T v) noexcept {
    return line_aperture(length_x_m, wavelength_m, u) * line_aperture(length_y_m, wavelength_m, v);
}

/// Directivity index of a rectangular piston large against the wavelength: 10 log10(4 pi Lx Ly / lambda^2) (dB).
template <Real T>
[[nodiscard]] inline T rectangular_piston_directivity_index_db(T length_x_m, T length_y_m, T wavelength_m) noexcept {
    return T(10) * std::log10(T(4) * pi_v<T> * length_x_m * length_y_m / (wavelength_m * wavelength_m));
}

/// Array factor of `count` equal, equally weighted elements at pitch `pitch_m`:
/// sin(N a) / (N sin a), a = pi d (u - u0) / lambda (signed amplitude, 1 on the steered axis).
/// Evaluated without loss at its removable singularities a = m pi (the main lobe and the grating lobes
/// u = u0 + m lambda / d, where it equals (-1)^(m (N - 1))): a is reduced to m pi + delta, |delta| <= pi/2,
/// and the ratio is written sinc(N delta) / sinc(delta).
template <Real T>
[[nodiscard]] inline T array_factor(std::size_t count, T pitch_m, T wavelength_m, T u, T u0 = T(0)) noexcept {
    if (count <= 1) return T(1);
    const T a = pi_v<T> * pitch_m * (u - u0) / wavelength_m;
    const T m = std::nearbyint(a / pi_v<T>);
    const T delta = a - m * pi_v<T>;
    const T n = static_cast<T>(count);
    const T ratio = sinc(n * delta) / sinc(delta);
    // (-1)^(m (N - 1)): negative only for odd m and even N.
    const bool odd_m = std::fmod(std::abs(m), T(2)) == T(1);
    return (odd_m && count % 2 == 0) ? -ratio : ratio;
}

/// Magnitude of the shaded array factor |sum_n w_n exp(i 2 pi x_n (u - u0) / lambda)| / |sum_n w_n| of
/// elements at x_n = (n - (N - 1)/2) d (centred on the array), amplitude weights `weights` (N of them).
/// With all weights equal it is |array_factor(N, d, lambda, u, u0)|. For non-negative weights it lies in
/// [0, 1] with 1 on the steered axis and at the grating lobes. Returns 1 for an empty span or a zero sum.
template <Real T>
[[nodiscard]] inline T array_factor(std::span<const T> weights, T pitch_m, T wavelength_m, T u, T u0 = T(0)) noexcept {
    const std::size_t n = weights.size();
    if (n <= 1) return T(1);
    const T k = two_pi_v<T> * pitch_m * (u - u0) / wavelength_m;
    const T centre = static_cast<T>(n - 1) / T(2);
    T re = 0, im = 0, sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const T phase = k * (static_cast<T>(i) - centre);
        re += weights[i] * std::cos(phase);
        im += weights[i] * std::sin(phase);
        sum += weights[i];
    }
    if (sum == T(0)) return T(1);
    return std::sqrt(re * re + im * im) / std::abs(sum);
}

/// Full width (rad) of a uniform line aperture's main lobe at the one-way intensity level `power_ratio`
/// (linear, in (0, 1); 0.5 is the half-power or "-3 dB" width): 2 asin(x lambda / (pi L)) with
/// sinc(x)^2 = power_ratio. For half power x = 1.391557 and the width is about 0.885893 lambda / L.
/// Returns pi when the level is not reached in the front half-space (aperture too short).
template <Real T> [[nodiscard]] inline T line_aperture_width_rad(T length_m, T wavelength_m, T power_ratio) {
    sss::require_positive(length_m, "length_m");
    sss::require_positive(wavelength_m, "wavelength_m");
    sss::require(power_ratio > T(0) && power_ratio < T(1), "power_ratio", "must lie in (0, 1)");
    const T x = detail::sinc_inverse(std::sqrt(power_ratio));
    return detail::full_width_from_sine(x * wavelength_m / (pi_v<T> * length_m));
}

/// Half-power (-3.01 dB one way) full width of a uniform line aperture (rad).
template <Real T> [[nodiscard]] inline T line_aperture_half_power_width_rad(T length_m, T wavelength_m) {
    return line_aperture_width_rad(length_m, wavelength_m, T(0.5));
}

/// Angle of the first null of a uniform line aperture from its axis (rad): sin theta = lambda / L.
/// Throws invalid_parameter("length_m") when L <= lambda (no null in the front half-space).
template <Real T> [[nodiscard]] inline T line_aperture_first_null_rad(T length_m, T wavelength_m) {
    sss::require_positive(length_m, "length_m");
    sss::require_positive(wavelength_m, "wavelength_m");
    sss::require(length_m > wavelength_m, "length_m", "must exceed the wavelength for a null to exist");
    return std::asin(wavelength_m / length_m);
}

/// Angle of the first sidelobe peak of a uniform line aperture (rad): sin theta = 4.4934 lambda / (pi L),
/// where the one-way level is sinc(4.4934)^2 = -13.26 dB. Throws invalid_parameter("length_m") when the
/// sidelobe lies beyond the front half-space.
template <Real T> [[nodiscard]] inline T line_aperture_first_sidelobe_rad(T length_m, T wavelength_m) {
    sss::require_positive(length_m, "length_m");
    sss::require_positive(wavelength_m, "wavelength_m");
    const T s = sinc_first_sidelobe_x_v<T> * wavelength_m / (pi_v<T> * length_m);
    sss::require(s < T(1), "length_m", "too short for a sidelobe in the front half-space");
    return std::asin(s);
}

/// One-way intensity level of the first sidelobe of a uniform line aperture (dB), about -13.26.
template <Real T> [[nodiscard]] inline T line_aperture_first_sidelobe_db() noexcept {
    const T b = sinc(sinc_first_sidelobe_x_v<T>);
    return T(10) * std::log10(b * b);
}

/// Full width (rad) at one-way intensity `power_ratio` (in (0, 1)) of the main lobe of a uniform array of
/// `count` elements at pitch `pitch_m`, broadside (unsteered), element pattern excluded. Returns pi when
/// the level is not reached in the front half-space.
template <Real T>
[[nodiscard]] inline T array_width_rad(std::size_t count, T pitch_m, T wavelength_m, T power_ratio) {
    sss::require(count >= 2, "count", "must be at least 2");
    sss::require_positive(pitch_m, "pitch_m");
    sss::require_positive(wavelength_m, "wavelength_m");
    sss::require(power_ratio > T(0) && power_ratio < T(1), "power_ratio", "must lie in (0, 1)");
    const T delta = detail::array_factor_inverse(count, std::sqrt(power_ratio));
    return detail::full_width_from_sine(delta * wavelength_m / (pi_v<T> * pitch_m));
}

/// Direction cosine of the first null of a uniform array from its steered axis: u - u0 = lambda / (N d).
template <Real T> [[nodiscard]] inline T array_first_null_u(std::size_t count, T pitch_m, T wavelength_m) noexcept {
    return wavelength_m / (static_cast<T>(count) * pitch_m);
}

/// Direction cosine of the grating lobe of order m (m = 0 is the main lobe): u = u0 + m lambda / d. It lies
/// in visible space only when |u| <= 1.
template <Real T> [[nodiscard]] inline T grating_lobe_u(int order, T pitch_m, T wavelength_m, T u0 = T(0)) noexcept {
    return u0 + static_cast<T>(order) * wavelength_m / pitch_m;
}

} // namespace sss::beam
