#pragma once
/// \file
/// Internal to the seabed generators: fractal fields of unit expected RMS, one at a time or two from one FFT,
/// the shapes of perturbation, warp and partition fields. Not part of the API.

#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sss/core/types.hpp"
#include "sss/seabed/detail/fractal_coefficients.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/fractal_params.hpp"
#include "sss/seabed/fractal_surface.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"

namespace sss::seabed::detail {

/// A fractal field of unit expected RMS (power law of exponent gamma, outer scale l0_m; w2 scaled so
/// that the band variance is 1), in double: the shape of perturbation, warp and partition fields.
template <Real T> [[nodiscard]] raster<double> unit_fractal_field(std::size_t nx, std::size_t ny, T cell_m, T gamma,
                                                                  T l0_m, std::uint64_t seed) {
    fractal_params<double> f;
    f.spectrum = power_law_spectrum<double>{1.0, static_cast<double>(gamma), static_cast<double>(l0_m)};
    raster<double> g = fractal_surface<double>(nx, ny, static_cast<double>(cell_m), f, seed);
    const double scale = 1.0 / std::sqrt(band_variance_m2(f, nx, ny, static_cast<double>(cell_m)));
    for (double& v : g.values) v *= scale;
    return g;
}

/// Two independent unit fractal fields of one spectrum (as unit_fractal_field with seeds seed_a and seed_b, equal
/// to rounding) from one complex inverse FFT: the real part of element iy * nx + ix holds field a, the imaginary
/// part field b. The transform of a Hermitian spectrum is real, so the transform of C = c_a + i c_b is
/// h_a + i h_b: one FFT and one complex array serve both fields (Press et al., 2007, Numerical Recipes, 3rd ed.,
/// section 12.3.2, "two real FFTs for the price of one"). With `with_b` false the imaginary parts are 0.
template <Real T>
[[nodiscard]] std::vector<std::complex<double>> unit_fractal_pair(std::size_t nx, std::size_t ny, T cell_m, T gamma, T l0_m,
                                                                  std::uint64_t seed_a, std::uint64_t seed_b, bool with_b) {
    fractal_params<double> f;
    f.spectrum = power_law_spectrum<double>{1.0, static_cast<double>(gamma), static_cast<double>(l0_m)};
    const double dx = static_cast<double>(cell_m);
    std::vector<std::complex<double>> c(nx * ny, std::complex<double>(0.0, 0.0));
    rng ga(seed_a), gb(seed_b);
    double band = 0.0;
    if (with_b) {
        // C[own] = a + i b, C[partner] = conj(a) + i conj(b) (for own == partner, a and b are real).
        band = draw_coefficients(nx, ny, dx, f, std::array<rng*, 2>{&ga, &gb},
                                 [&](std::size_t own, std::size_t partner, const std::array<std::complex<double>, 2>& v) {
                                     const std::complex<double> a = v[0], b = v[1];
                                     c[own] = {a.real() - b.imag(), a.imag() + b.real()};
                                     c[partner] = {a.real() + b.imag(), b.real() - a.imag()};
                                 });
    } else {
        band = draw_coefficients(nx, ny, dx, f, std::array<rng*, 1>{&ga},
                                 [&](std::size_t own, std::size_t partner, const std::array<std::complex<double>, 1>& v) {
                                     c[own] = v[0];
                                     c[partner] = std::conj(v[0]);
                                 });
    }
    fft_2d(c, nx, ny, fft_direction::backward);
    const double scale = 1.0 / std::sqrt(band);
    for (auto& v : c) v *= scale;
    return c;
}

} // namespace sss::seabed::detail
