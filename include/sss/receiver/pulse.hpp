#pragma once
/// \file
/// The transmitted pulse's power envelope p(t), 0 <= t <= length, normalised to a peak of 1.
///
/// - rectangular: p = 1 (a CW burst; energy = length).
/// - hann: amplitude sin^2(pi t / length), so p = sin^4(pi t / length) (energy = 3/8 length): a tapered burst.
/// A point scatterer at two-way delay s returns power P p(t - s); the receiver sees the echo-power density
/// convolved with p.

#include <algorithm>
#include <cmath>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"

namespace sss {

enum class pulse_shape : unsigned char { rectangular, hann };

struct pulse {
    double length_s = 100e-6;                     ///< duration (s), > 0
    pulse_shape shape = pulse_shape::rectangular; ///< power envelope

    void validate() const {
        sss::require_positive(length_s, "pulse.length_s");
        sss::require(length_s <= 1.0, "pulse.length_s", "must be <= 1 s");
    }

    /// p(t): power envelope at time t after the start (s), 0 outside [0, length].
    [[nodiscard]] double power(double t_s) const noexcept {
        if (t_s < 0.0 || t_s > length_s) return 0.0;
        if (shape == pulse_shape::rectangular) return 1.0;
        const double s = std::sin(pi_v<double> * t_s / length_s);
        return s * s * s * s;
    }

    /// Integral of p from 0 to t (s): the envelope's cumulative energy, constant beyond the pulse end.
    [[nodiscard]] double cumulative(double t_s) const noexcept {
        const double t = std::clamp(t_s, 0.0, length_s);
        if (shape == pulse_shape::rectangular) return t;
        // int_0^t sin^4(a x) dx = 3t/8 - sin(2 a t)/(4 a) + sin(4 a t)/(32 a), a = pi/length.
        const double a = pi_v<double> / length_s;
        return 3.0 * t / 8.0 - std::sin(2.0 * a * t) / (4.0 * a) + std::sin(4.0 * a * t) / (32.0 * a);
    }

    /// Total envelope energy, int p dt (s).
    [[nodiscard]] double energy_s() const noexcept { return cumulative(length_s); }
};

} // namespace sss
