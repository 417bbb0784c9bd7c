#pragma once
/// \file
/// Fractional Brownian seabed surfaces by spectral synthesis, isotropic or directional.
///
/// Method: random Fourier coefficients c_mn on the N_x x N_y grid of wave vectors
/// K_mn = (m dKx, n dKy), dKx = 2 pi / (N_x dx), dKy = 2 pi / (N_y dx) (indices above N/2 wrap to negative),
/// with E|c_mn|^2 = W(K_mn) dKx dKy and c_{-m,-n} = conj(c_mn), then h(x) = sum_mn c_mn exp(i K_mn . x)
/// by one inverse 2D FFT (e.g. Thorsos, 1988, JASA 83(1) 78-92, for this
/// normalisation). Hence <h^2> = sum_{mn != 0} W(K_mn) dKx dKy: the integral of W over the grid's band
/// (`band_variance_m2`), and h is Gaussian with the requested spectrum at every grid wave vector.
/// The K = 0 coefficient is 0: the periodic surface has zero mean.
///
/// Directional surfaces. With u the unit vector at `direction_rad` (counter-clockwise from +x, east) and
/// v perpendicular to it, the spectrum is evaluated at the effective wavenumber
///   K_eff^2 = a K_u^2 + K_v^2 / a,   a = `anisotropy`,
/// i.e. h(u, v) = g(u / sqrt(a), v sqrt(a)) for an isotropic surface g of the same spectrum: the surface is
/// stretched by sqrt(a) along u and compressed by sqrt(a) across, the area (and so the variance of the
/// unbounded surface) unchanged. Meaning of the anisotropy ratio a: the ratio of horizontal length scales
/// along and across u. Equivalent measurable forms: the spectrum's level contours are ellipses whose
/// semi-axes along K_v and K_u are in the ratio a, so W(K v) / W(K u) = a^gamma at equal |K|; and the
/// structure function reaches the same value at lag r along u and at lag r / a across (exactly for the
/// unbounded surface; the grid's band cuts the two directions at different K_eff, which biases such
/// space-domain measures by a few percent). a = 1 is isotropic; a > 1 gives ridges elongated along
/// `direction_rad`; a and 1/a at direction + 90 degrees give the same surface.
///
/// Periodicity: the synthesised surface is periodic over the grid (it tiles seamlessly). With
/// `oversample` = m > 1 it is synthesised on an (m nx) x (m ny) grid and the first nx x ny samples are
/// kept: no periodicity is visible, the band then starts at 2 pi / (m nx dx), and the variance of the
/// (larger) band is that of the stationary field; the cropped piece no longer has exactly zero mean.
///
/// Reproducibility: the coefficients are drawn from `rng(seed)` (random.hpp) in a fixed order, so one
/// seed gives the same surface on every run; across platforms the surfaces agree to rounding (the
/// random draws are bit-identical, the FFT's twiddles come from the platform's cos and sin).

#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/detail/unit_fractal.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/fractal_params.hpp"
#include "sss/seabed/fractal_surface.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"
