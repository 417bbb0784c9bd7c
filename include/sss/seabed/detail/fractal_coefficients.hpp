#pragma once
/// \file
/// Internal to the fractal surfaces (seabed/fractal.hpp): the directional spectral density, the variance of each
/// grid mode and the draw of Hermitian-symmetric random Fourier coefficients. Not part of the API.

#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/types.hpp"
#include "sss/seabed/fractal_params.hpp"
#include "sss/seabed/random.hpp"

namespace sss::seabed::detail {

/// W(K_eff) with the direction's cosine and sine and the outer scale evaluated once.
struct directional_density {
    double c, s, a, k0sq, w2, half_gamma;
    [[nodiscard]] double operator()(double kx, double ky) const noexcept {
        const double ku = kx * c + ky * s;
        const double kv = -kx * s + ky * c;
        return w2 * std::pow(a * ku * ku + kv * kv / a + k0sq, -half_gamma);
    }
};

template <Real T> [[nodiscard]] directional_density make_density(const fractal_params<T>& p) noexcept {
    const double l0 = static_cast<double>(p.spectrum.outer_scale_m);
    const double k0 = l0 > 0.0 ? two_pi_v<double> / l0 : 0.0;
    return {std::cos(static_cast<double>(p.direction_rad)),
            std::sin(static_cast<double>(p.direction_rad)),
            static_cast<double>(p.anisotropy),
            k0 * k0,
            static_cast<double>(p.spectrum.w2_si),
            0.5 * static_cast<double>(p.spectrum.gamma)};
}

/// Signed wavenumber (rad/m) of FFT index i on an n-point axis of spacing dk.
[[nodiscard]] inline double wavenumber(std::size_t i, std::size_t n, double dk) noexcept {
    return i <= n / 2 ? static_cast<double>(i) * dk : -static_cast<double>(n - i) * dk;
}

/// W dKx dKy for grid mode (i, j) of an nx x ny grid. Modes on a Nyquist line (index n/2 of an even
/// axis) alias +K and -K; they take the mean of W at both, which makes the value symmetric under
/// (i, j) -> (-i, -j) as Hermitian symmetry needs. 0 at K = 0.
[[nodiscard]] inline double mode_variance(const directional_density& w, std::size_t i, std::size_t j, std::size_t nx,
                                          std::size_t ny, double dkx, double dky) noexcept {
    if (i == 0 && j == 0) return 0.0;
    const double kx = wavenumber(i, nx, dkx);
    const double ky = wavenumber(j, ny, dky);
    const bool nyq_x = nx % 2 == 0 && i == nx / 2;
    const bool nyq_y = ny % 2 == 0 && j == ny / 2;
    double d = 0.0;
    if (nyq_x && nyq_y)
        d = w(kx, ky); // self-conjugate: any alias will do
    else if (nyq_x)
        d = 0.5 * (w(kx, ky) + w(-kx, ky));
    else if (nyq_y)
        d = 0.5 * (w(kx, ky) + w(kx, -ky));
    else
        d = w(kx, ky);
    return d * dkx * dky;
}

/// One mode's random coefficient of variance `var` from `g`: real for a self-conjugate mode.
template <Real T>
[[nodiscard]] inline std::complex<double> draw_mode(double var, bool self_conjugate, const fractal_params<T>& p, rng& g) {
    if (self_conjugate) {
        const double x = p.amplitudes == spectral_amplitudes::gaussian ? g.normal() : (g.uniform() < 0.5 ? -1.0 : 1.0);
        return {std::sqrt(var) * x, 0.0};
    }
    if (p.amplitudes == spectral_amplitudes::gaussian) {
        const double sd = std::sqrt(0.5 * var);
        const double re = g.normal();
        const double im = g.normal();
        return {sd * re, sd * im};
    }
    const double phase = two_pi_v<double> * g.uniform();
    return std::polar(std::sqrt(var), phase);
}

/// Draws Hermitian-symmetric random coefficients of the spectrum for an nx x ny grid in the fixed order (rows of
/// modes, each mode with its partner), from every generator of `gens` in step (each generator draws the same
/// sequence as alone), calling store(own, partner, v) with v[k] from gens[k] for each pair (partner == own for
/// a self-conjugate mode, v then real): the caller sets c[own] = v and c[partner] = conj(v), or combines them.
/// Returns the sum of the modes' variances, the band variance of the grid.
template <Real T, std::size_t N, class Store>
double draw_coefficients(std::size_t nx, std::size_t ny, double cell_m, const fractal_params<T>& p,
                         std::array<rng*, N> gens, Store&& store) {
    const double dkx = two_pi_v<double> / (static_cast<double>(nx) * cell_m);
    const double dky = two_pi_v<double> / (static_cast<double>(ny) * cell_m);
    const directional_density w = make_density(p);
    double band = 0.0;
    std::array<std::complex<double>, N> v;
    for (std::size_t j = 0; j < ny; ++j) {
        const std::size_t pj = (ny - j) % ny;
        for (std::size_t i = 0; i < nx; ++i) {
            const std::size_t pi_ = (nx - i) % nx;
            const std::size_t own = j * nx + i;
            const std::size_t partner = pj * nx + pi_;
            if (partner < own) continue; // set together with its partner
            const double var = mode_variance(w, i, j, nx, ny, dkx, dky);
            band += partner == own ? var : 2.0 * var;
            for (std::size_t k = 0; k < N; ++k) v[k] = draw_mode(var, partner == own, p, *gens[k]);
            store(own, partner, v);
        }
    }
    return band;
}

/// Fills `c` (nx * ny, row-major) with Hermitian-symmetric random coefficients of the spectrum.
template <Real T> void fill_coefficients(std::vector<std::complex<double>>& c, std::size_t nx, std::size_t ny,
                                         double cell_m, const fractal_params<T>& p, rng& g) {
    c.assign(nx * ny, std::complex<double>(0.0, 0.0));
    (void)draw_coefficients(nx, ny, cell_m, p, std::array<rng*, 1>{&g},
                            [&](std::size_t own, std::size_t partner, const std::array<std::complex<double>, 1>& v) {
                                c[own] = v[0];
                                c[partner] = std::conj(v[0]);
                            });
}

} // namespace sss::seabed::detail
