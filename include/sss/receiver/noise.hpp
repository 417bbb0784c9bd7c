#pragma once
/// \file
/// Ambient and electronic noise at the receiver, as spectrum levels and as the mean power per sample that joins
/// the echo on the render's source level reference.
///
/// The received noise power in a band B (Hz), against the source level SL (dB re 1 uPa at 1 m), behind a
/// receiving directivity index DI (dB), is N = 10^((NL + 10 log10 B - DI - SL) / 10) (the passive sonar
/// equation's noise term, Urick, "Principles of Underwater Sound", 3rd ed., 1983, ch. 2 and 7). NL sums:
/// - sea-state (wind) noise after Knudsen, Alford & Emling (J. Mar. Res. 7, 1948), as tabulated by Urick ch. 7:
///   NL = NL_1kHz(sea state) - 17 log10(f / 1 kHz), NL_1kHz = 44.5, 50, 55, 61.5, 64.5, 66.5, 68.5, 70 dB re
///   1 uPa^2/Hz for sea states 0, 0.5, 1, 2, 3, 4, 5, 6 (linear in between);
/// - thermal noise of the water (Mellen, J. Acoust. Soc. Am. 24, 1952): NL = -15 + 20 log10(f / 1 kHz); it
///   dominates above about 100-200 kHz.
/// An electronic floor, a spectrum level referred to the receiver input, adds without the directivity gain.
/// The noise is a circular complex Gaussian field, independent from sample to sample (bandwidth 1/dt).
///
/// Under a compressed chirp the line is the matched filter's output scaled so that an echo's peak is its power
/// before compression (receiver/pulse.hpp); that filter, h(t) = s*(-t) / E_s for a chirp s of energy E_s = T,
/// passes white noise of spectral level N0 as N0 int |h|^2 dt = N0 / T, whatever the band before it: B = 1/T, the
/// compression gain B_rx T over the receiver's band B_rx (Cook & Bernfeld, "Radar Signals", 1967). The
/// compressed noise is correlated over 1/B; it is kept independent from sample to sample.

#include <array>
#include <cmath>
#include <limits>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss {

/// Knudsen sea-state noise spectrum level at frequency f_hz for a sea state 0-6 (dB re 1 uPa^2/Hz).
[[nodiscard]] inline double knudsen_noise_level_db(double f_hz, double sea_state) {
    sss::require_positive(f_hz, "knudsen_noise_level_db.f_hz");
    sss::require_in_range(sea_state, 0.0, 6.0, "knudsen_noise_level_db.sea_state");
    static constexpr std::array<double, 8> ss{0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
    static constexpr std::array<double, 8> nl{44.5, 50.0, 55.0, 61.5, 64.5, 66.5, 68.5, 70.0};
    std::size_t i = 0;
    while (i + 2 < ss.size() && sea_state > ss[i + 1]) ++i;
    const double f = (sea_state - ss[i]) / (ss[i + 1] - ss[i]);
    return nl[i] + f * (nl[i + 1] - nl[i]) - 17.0 * std::log10(f_hz / 1000.0);
}

/// Mellen's thermal noise spectrum level at f_hz (dB re 1 uPa^2/Hz).
[[nodiscard]] inline double thermal_noise_level_db(double f_hz) {
    sss::require_positive(f_hz, "thermal_noise_level_db.f_hz");
    return -15.0 + 20.0 * std::log10(f_hz / 1000.0);
}

/// Directivity index of a rectangular piston Lx x Ly (m) at wavelength lambda (m): 10 log10(4 pi Lx Ly / lambda^2)
/// (Urick 1983, ch. 3; valid for sides of several wavelengths).
[[nodiscard]] inline double piston_directivity_index_db(double lx_m, double ly_m, double wavelength_m) {
    sss::require_positive(lx_m, "piston_directivity_index_db.lx_m");
    sss::require_positive(ly_m, "piston_directivity_index_db.ly_m");
    sss::require_positive(wavelength_m, "piston_directivity_index_db.wavelength_m");
    return 10.0 * std::log10(4.0 * pi_v<double> * lx_m * ly_m / (wavelength_m * wavelength_m));
}

struct noise_params {
    double frequency_hz = 100e3;          ///< centre frequency (Hz), 1 Hz to 10 MHz
    double sea_state = 2.0;               ///< Knudsen sea state, 0-6
    bool thermal = true;                  ///< add Mellen's thermal noise
    double band_hz = 0.0;                 ///< receiver band (Hz), at most 10^9; 0: the sample rate 1/dt
    double directivity_index_db = 20.0;   ///< receiving directivity index DI (dB), 0 to 300
    double source_level_db = 210.0;       ///< absolute source level SL (dB re 1 uPa at 1 m), -300 to 300
    double electronic_floor_db = -std::numeric_limits<double>::infinity(); ///< input-referred electronic noise spectrum level (dB re 1 uPa^2/Hz), -300 to 300; -inf: none

    void validate() const {
        // Knudsen's curves and the thermal floor are for sonar frequencies; levels in dB within +-300 dB (their
        // powers of ten stay in range, in float too).
        sss::require_in_range(frequency_hz, 1.0, 1e7, "noise.frequency_hz");
        sss::require_in_range(sea_state, 0.0, 6.0, "noise.sea_state");
        sss::require_in_range(band_hz, 0.0, 1e9, "noise.band_hz");
        sss::require_in_range(directivity_index_db, 0.0, 300.0, "noise.directivity_index_db");
        sss::require_in_range(source_level_db, -300.0, 300.0, "noise.source_level_db");
        sss::require(electronic_floor_db == -std::numeric_limits<double>::infinity() ||
                         (electronic_floor_db >= -300.0 && electronic_floor_db <= 300.0),
                     "noise.electronic_floor_db", "must lie in [-300, 300] dB, or be -infinity (none)");
    }
};

/// Mean noise power per sample relative to the source level, N = 10^((NL + 10 log10 B - DI - SL)/10) plus the
/// electronic floor 10^((NL_e + 10 log10 B - SL)/10), for a sample interval dt_s (B = 1/dt unless given).
[[nodiscard]] inline double noise_power(const noise_params& p, double dt_s) {
    p.validate();
    sss::require_positive(dt_s, "noise_power.dt_s");
    const double band = p.band_hz > 0.0 ? p.band_hz : 1.0 / dt_s;
    double ambient = std::pow(10.0, knudsen_noise_level_db(p.frequency_hz, p.sea_state) / 10.0);
    if (p.thermal) ambient += std::pow(10.0, thermal_noise_level_db(p.frequency_hz) / 10.0);
    const double in_band = 10.0 * std::log10(band) - p.source_level_db;
    double n = ambient * std::pow(10.0, (in_band - p.directivity_index_db) / 10.0);
    if (std::isfinite(p.electronic_floor_db)) n += std::pow(10.0, (p.electronic_floor_db + in_band) / 10.0);
    return n;
}

/// The same in a line received with `pulse`: for a compressed chirp in the matched filter's band, B = 1/T (see the
/// file comment); for a burst as noise_power(p, dt_s).
[[nodiscard]] inline double noise_power(const noise_params& p, double dt_s, const pulse& received) {
    if (received.shape != pulse_shape::lfm) return noise_power(p, dt_s);
    received.validate();
    noise_params compressed = p;
    compressed.band_hz = 1.0 / received.length_s;
    return noise_power(compressed, dt_s);
}

} // namespace sss
