#pragma once
/// \file
/// The parameters of a fractal (power-law) seabed surface and their check. Part of seabed/fractal.hpp (see its
/// file comment for the model), which includes it.

#include <cstddef>
#include <string>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/seabed/power_law_spectrum.hpp"

namespace sss::seabed {

/// How the moduli of the Fourier coefficients are drawn.
enum class spectral_amplitudes : unsigned char {
    gaussian, ///< complex Gaussian coefficients: a Gaussian random field (the physical model)
    fixed     ///< |c_mn|^2 = W dKx dKy exactly, random phases only: every realisation has exactly the
              ///< requested periodogram and exactly the band variance (handy for calibration)
};

/// Parameters of a fractal (power-law) surface.
template <Real T> struct fractal_params {
    power_law_spectrum<T> spectrum{}; ///< W(K) (SI; see jackson_spectrum for the cm^4 tables)
    T anisotropy = T(1);              ///< a > 0: length-scale ratio along / across direction_rad (1 = isotropic)
    T direction_rad = T(0);           ///< direction of the long axis, counter-clockwise from +x (rad)
    spectral_amplitudes amplitudes = spectral_amplitudes::gaussian;
    std::size_t oversample = 1; ///< synthesise on a grid this many times larger per axis and crop (>= 1)
};

/// Throws invalid_parameter naming the offending field (prefixed by `who`).
template <Real T> void validate(const fractal_params<T>& p, const std::string& who) {
    validate(p.spectrum, who + ".spectrum");
    sss::require_positive(p.anisotropy, who + ".anisotropy");
    sss::require_finite(p.direction_rad, who + ".direction_rad");
    sss::require(p.oversample >= 1 && p.oversample <= 64, who + ".oversample", "must lie in [1, 64]");
}

} // namespace sss::seabed
