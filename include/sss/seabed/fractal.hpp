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
#include "sss/seabed/fft.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"

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

namespace detail {

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

} // namespace detail

/// Directional spectral density W(K_eff) (m^4) at wave vector (kx, ky) (rad/m); see the file comment.
template <Real T>
[[nodiscard]] inline double directional_density_m4(const fractal_params<T>& p, double kx, double ky) noexcept {
    return detail::make_density(p)(kx, ky);
}

/// The integral of W over the band of an nx x ny grid of spacing cell_m, as the discrete sum
/// sum_{mn != 0} W(K_mn) dKx dKy (m^2): the expected mean-square height of `fractal_surface` (with
/// oversample m the band is that of the (m nx) x (m ny) synthesis grid, which this accounts for).
template <Real T>
[[nodiscard]] double band_variance_m2(const fractal_params<T>& p, std::size_t nx, std::size_t ny, T cell_m) {
    require_grid(nx, ny, cell_m, "band_variance_m2");
    validate(p, "band_variance_m2.params");
    const std::size_t sx = checked_mul(nx, p.oversample, "band_variance_m2.params.oversample");
    const std::size_t sy = checked_mul(ny, p.oversample, "band_variance_m2.params.oversample");
    (void)checked_elements(sx, sy, "band_variance_m2.params.oversample");
    const double dx = static_cast<double>(cell_m);
    const double dkx = two_pi_v<double> / (static_cast<double>(sx) * dx);
    const double dky = two_pi_v<double> / (static_cast<double>(sy) * dx);
    const detail::directional_density w = detail::make_density(p);
    double sum = 0.0;
    for (std::size_t j = 0; j < sy; ++j)
        for (std::size_t i = 0; i < sx; ++i) sum += detail::mode_variance(w, i, j, sx, sy, dkx, dky);
    return sum;
}

/// A fractal surface of nx x ny samples of spacing cell_m (m), heights in m (see the file comment).
/// Any nx, ny >= 1 (powers of two are fastest). Same (arguments, seed), same surface.
template <Real T> [[nodiscard]] raster<T> fractal_surface(std::size_t nx, std::size_t ny, T cell_m,
                                                          const fractal_params<T>& p, std::uint64_t seed) {
    require_grid(nx, ny, cell_m, "fractal_surface");
    validate(p, "fractal_surface.params");
    const std::size_t sx = checked_mul(nx, p.oversample, "fractal_surface.params.oversample");
    const std::size_t sy = checked_mul(ny, p.oversample, "fractal_surface.params.oversample");
    (void)checked_elements(sx, sy, "fractal_surface.params.oversample");
    rng g(seed);
    std::vector<std::complex<double>> c;
    detail::fill_coefficients(c, sx, sy, static_cast<double>(cell_m), p, g);
    fft_2d(c, sx, sy, fft_direction::backward);
    raster<T> out{nx, ny, cell_m, std::vector<T>(nx * ny)};
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) out.values[iy * nx + ix] = static_cast<T>(c[iy * sx + ix].real());
    return out;
}

namespace detail {

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

} // namespace detail

} // namespace sss::seabed
