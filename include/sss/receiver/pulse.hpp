#pragma once
/// \file
/// The transmitted pulse's power envelope p(t), 0 <= t <= duration(), normalised to a peak of 1, as the receiver
/// sees it (after matched filtering for a chirp).
///
/// - rectangular: p = 1 (a CW burst; energy = length).
/// - hann: amplitude sin^2(pi t / length), so p = sin^4(pi t / length) (energy = 3/8 length): a tapered burst.
/// - lfm: a linear FM chirp of duration T = length and bandwidth B, compressed by its matched filter. The filter's
///   output is the chirp's autocorrelation, of amplitude (Cook & Bernfeld, "Radar Signals", 1967, ch. 6)
///       chi(s) = (1 - |s|/T) sinc(B s (1 - |s|/T)),  |s| <= T,  sinc(x) = sin(pi x) / (pi x),
///   so p(t) = chi(t - T)^2 over [0, 2T]: a main lobe 2/B wide at its -4 dB points 1/B apart, a range resolution
///   c / (2B) whatever T. Its peak comes T after the echo's arrival: the filter's delay, which a chirp sonar's
///   receiver takes out of its clock (`filter_delay_s`), so that an echo's compressed peak marks its range.
/// A point scatterer at two-way delay s returns power P p(t - s); the receiver sees the echo-power density
/// convolved with p. `amplitude` is the signed envelope (chi for a chirp) that speckle's correlation follows.

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "sss/core/detail/gauss_legendre.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"

namespace sss {

enum class pulse_shape : unsigned char { rectangular, hann, lfm };

struct pulse {
    double length_s = 100e-6;                     ///< duration (s), > 0
    pulse_shape shape = pulse_shape::rectangular; ///< power envelope
    double bandwidth_hz = 0.0;                    ///< chirp bandwidth B (Hz) for `lfm`, with 1 <= B length <= 10^4

    /// The largest time-bandwidth product B T of a chirp. Sidescan chirps have tens to a few thousand; the receiver
    /// tabulates the compressed chirp's energy 128 steps per 1/B over its 2T (1.3 million at 10^4).
    static constexpr double max_time_bandwidth = 1e4;

    void validate() const {
        sss::require_positive(length_s, "pulse.length_s");
        sss::require(length_s <= 1.0, "pulse.length_s", "must be <= 1 s");
        if (shape == pulse_shape::lfm) {
            sss::require_positive(bandwidth_hz, "pulse.bandwidth_hz");
            sss::require(bandwidth_hz * length_s >= 1.0 && bandwidth_hz * length_s <= max_time_bandwidth,
                         "pulse.bandwidth_hz",
                         "times pulse.length_s must lie in [1, 10^4] (a chirp's time-bandwidth product), got " +
                             std::to_string(bandwidth_hz * length_s));
        }
    }

    /// Support of the envelope the receiver sees (s): the length, twice it for a compressed chirp.
    [[nodiscard]] double duration_s() const noexcept { return shape == pulse_shape::lfm ? 2.0 * length_s : length_s; }

    /// The delay the receiver takes out of its clock (s): the matched filter's delay T for a chirp, 0 for a burst.
    /// Sample k of a line holds the envelope at k dt + filter_delay_s() after the transmission, so that a chirp's
    /// echo peaks at its arrival, and range c t / 2 holds at its peak.
    [[nodiscard]] double filter_delay_s() const noexcept { return shape == pulse_shape::lfm ? length_s : 0.0; }

    /// Delay from an echo's arrival to its peak in the line (s): 0 for a rectangular burst (flat from its arrival)
    /// and for a chirp (its filter's delay taken out), length/2 for a Hann burst.
    [[nodiscard]] double peak_delay_s() const noexcept { return shape == pulse_shape::hann ? 0.5 * length_s : 0.0; }

    /// Range resolution time (s): the length of a burst, 1/B for a compressed chirp.
    [[nodiscard]] double resolution_s() const noexcept { return shape == pulse_shape::lfm ? 1.0 / bandwidth_hz : length_s; }

    /// Signed amplitude envelope at time t after the echo's arrival: sqrt(p) for bursts, chi(t - T) for a chirp.
    [[nodiscard]] double amplitude(double t_s) const noexcept {
        if (t_s < 0.0 || t_s > duration_s()) return 0.0;
        if (shape == pulse_shape::rectangular) return 1.0;
        if (shape == pulse_shape::hann) {
            const double s = std::sin(pi_v<double> * t_s / length_s);
            return s * s;
        }
        const double s = t_s - length_s;
        const double taper = 1.0 - std::abs(s) / length_s;
        const double x = pi_v<double> * bandwidth_hz * s * taper;
        return std::abs(x) < 1e-9 ? taper : taper * std::sin(x) / x;
    }

    /// p(t): power envelope at time t after the start (s), 0 outside [0, duration].
    [[nodiscard]] double power(double t_s) const noexcept {
        if (t_s < 0.0 || t_s > duration_s()) return 0.0;
        if (shape == pulse_shape::rectangular) return 1.0;
        if (shape == pulse_shape::hann) {
            const double s = std::sin(pi_v<double> * t_s / length_s);
            return s * s * s * s;
        }
        const double a = amplitude(t_s);
        return a * a;
    }

    /// Integral of p from 0 to t (s): the envelope's cumulative energy, constant beyond the pulse end.
    [[nodiscard]] double cumulative(double t_s) const noexcept {
        const double t = std::clamp(t_s, 0.0, duration_s());
        if (shape == pulse_shape::rectangular) return t;
        if (shape == pulse_shape::hann) {
            // int_0^t sin^4(a x) dx = 3t/8 - sin(2 a t)/(4 a) + sin(4 a t)/(32 a), a = pi/length.
            const double a = pi_v<double> / length_s;
            return 3.0 * t / 8.0 - std::sin(2.0 * a * t) / (4.0 * a) + std::sin(4.0 * a * t) / (32.0 * a);
        }
        // The compressed chirp: 8-point Gauss-Legendre over pieces a quarter of a sidelobe (1/(4B)) long.
        const auto& gx = sss::detail::gauss_legendre8_x;
        const auto& gw = sss::detail::gauss_legendre8_w;
        const double piece = 0.25 / bandwidth_hz;
        double sum = 0.0;
        for (double lo = 0.0; lo < t; lo += piece) {
            const double hi = std::min(t, lo + piece);
            for (std::size_t g = 0; g < gx.size(); ++g) sum += (hi - lo) * gw[g] * power(lo + (hi - lo) * gx[g]);
        }
        return sum;
    }

    /// Total envelope energy, int p dt (s).
    [[nodiscard]] double energy_s() const noexcept { return cumulative(duration_s()); }
};

} // namespace sss
