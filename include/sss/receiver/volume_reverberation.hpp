#pragma once
/// \file
/// Volume reverberation: the water column's own echo (particles, plankton, bubbles) before and beside the
/// seabed's.
///
/// Mean power per sample at slant range r (Urick, "Principles of Underwater Sound", 3rd ed., 1983, ch. 8):
///
///     RL = SL - 40 log10 r - 2 alpha r + S_v + 10 log10 V,   V = r^2 Psi c tau / 2   (m^3),
///
/// S_v the volume scattering strength (dB re 1 m^-1; typically -90 to -70 dB at 100 kHz in coastal water),
/// Psi the equivalent two-way beam solid angle (sr), alpha the absorption (dB/m), c tau / 2 the pulse's
/// range extent (for a shaped or compressed pulse, tau is its envelope's energy int p dt with p's peak 1, as the
/// time sampler convolves it). Relative to the source level it is S_v Psi (c tau / 2) 10^(-2 alpha r / 10) / r^2.
///
/// Beyond the seabed's range the shell is cut by the seabed: with the simulator's beam (`elevation_share`, the
/// line's altitude H and the towfish's roll), Psi at range r is the share of the beam at depressions shallower
/// than asin(H / r), so that the water's echo fades as the beam's lower part meets the seabed. Psi itself is
/// `psi_sr`, or with `psi_sr = 0` the beam's own int w dOmega.

#include <algorithm>
#include <cmath>

#include "sss/beam/elevation_share.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/types.hpp"

namespace sss {

struct volume_params {
    double sv_db = -80.0;                  ///< volume scattering strength S_v (dB re 1 m^-1), -300 to 300
    double psi_sr = 0.05;                  ///< equivalent two-way beam solid angle Psi (sr), in [0, 4 pi]; 0: the
                                           ///< simulator's beam's own (elevation_share::psi_sr)
    double absorption_db_per_m = 0.03;     ///< absorption alpha (dB/m), >= 0
    double min_range_m = 1.0;              ///< ranges below this are taken as this (the far-field form diverges at 0)

    void validate() const {
        sss::require_in_range(sv_db, -300.0, 300.0, "volume.sv_db"); // real water: -100 to -50 dB
        sss::require_non_negative(psi_sr, "volume.psi_sr");
        sss::require(psi_sr <= 4.0 * pi_v<double>, "volume.psi_sr", "must be at most 4 pi sr (the whole sphere)");
        sss::require_non_negative(absorption_db_per_m, "volume.absorption_db_per_m");
        sss::require_positive(min_range_m, "volume.min_range_m");
    }
};

/// Volume reverberation level relative to the source level at slant range r (m), for sound speed c (m/s), a pulse
/// of duration tau (s) and an equivalent beam solid angle psi_sr (sr): a power ratio (see the file comment).
[[nodiscard]] inline double volume_reverberation(const volume_params& p, double range_m, double c_mps, double tau_s,
                                                 double psi_sr) noexcept {
    const double r = std::max(range_m, p.min_range_m);
    return std::pow(10.0, (p.sv_db - 2.0 * p.absorption_db_per_m * r) / 10.0) * psi_sr * 0.5 * c_mps * tau_s / (r * r);
}

/// The same with the whole of `p.psi_sr`: the water column before the seabed's range, or without a seabed.
[[nodiscard]] inline double volume_reverberation(const volume_params& p, double range_m, double c_mps, double tau_s) noexcept {
    return volume_reverberation(p, range_m, c_mps, tau_s, p.psi_sr);
}

/// The share of the beam's Psi in water at slant range r (m) over a flat seabed at altitude H (m): its share at body
/// depressions shallower than asin(H / r) less the roll (starboard down positive) on starboard, plus it on port; 1
/// before the seabed's range (r <= H). The pitch, which turns the beam along track, is left out.
[[nodiscard]] inline double water_share(const elevation_share& beam, side s, double range_m, double altitude_m,
                                        double roll_rad) noexcept {
    if (!(range_m > altitude_m)) return 1.0;
    const double seabed_depression = std::asin(std::clamp(altitude_m / range_m, -1.0, 1.0));
    return beam.at(seabed_depression - (s == side::starboard ? roll_rad : -roll_rad));
}

} // namespace sss
