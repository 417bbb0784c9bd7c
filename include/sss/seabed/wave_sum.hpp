#pragma once
/// \file
/// Seabeds of any size, evaluated vertex by vertex: a sum of plane waves whose wave vectors sample a power-law
/// spectrum, the spectral representation method (Shinozuka & Deodatis, 1991, "Simulation of stochastic processes
/// by spectral representation", Applied Mechanics Reviews 44(4), 191-204):
///
///     h(x) = sum_i a_i cos(K_i . x + phi_i),   a_i = sqrt(2 sigma_i^2),
///     sigma_i^2 = integral over bin i of 2 pi K W(K) dK   (m^2; an isotropic W in m^4, K in rad/m),
///
/// with the band [2 pi / longest_m, pi / cell_m] cut into `waves` bins equally spaced in ln K, one wave per bin at
/// a log-uniform |K_i| within it, a uniform direction and a uniform phase phi_i (all drawn from rng(seed), in that
/// order). The expected mean square is the band's variance, sum_i sigma_i^2 (variance_m2()).
///
/// Unlike fractal.hpp's FFT synthesis, a height depends only on its own vertex, never on the grid it is computed
/// in: any tiling of a large seabed into bands of rows gives the same heights to the last bit (fill_rows), so a
/// seabed larger than memory is written band by band (io/mapped_height_field.hpp). The price: a finite sum of
/// waves is Gaussian only in the limit of many waves, and its spectrum is a line spectrum (one wave per bin).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/random.hpp"

namespace sss::seabed {

/// Parameters of a wave-sum surface.
template <Real T> struct wave_sum_params {
    power_law_spectrum<T> spectrum{}; ///< isotropic W(K) (SI)
    T longest_m = T(500);             ///< longest wavelength in the band (m), > 2 cells
    std::size_t waves = 64;           ///< plane waves, one per bin of ln K, in [1, 4096]
};

/// A seabed surface h(x, y) (m) as a sum of plane waves (see the file comment).
template <Real T> class wave_sum_surface {
public:
    /// The surface for vertex spacing cell_m (m; sets the band's upper end pi / cell_m) drawn from `seed`.
    wave_sum_surface(const wave_sum_params<T>& p, T cell_m, std::uint64_t seed) {
        validate(p.spectrum, "wave_sum_surface.params.spectrum");
        sss::require_positive(cell_m, "wave_sum_surface.cell_m");
        sss::require(p.waves >= 1 && p.waves <= 4096, "wave_sum_surface.params.waves", "must lie in [1, 4096]");
        sss::require(std::isfinite(p.longest_m) && p.longest_m > T(2) * cell_m, "wave_sum_surface.params.longest_m",
                             "must be finite and longer than 2 cells");
        const double k_lo = two_pi_v<double> / static_cast<double>(p.longest_m);
        const double k_hi = pi_v<double> / static_cast<double>(cell_m);
        const double step = std::log(k_hi / k_lo) / static_cast<double>(p.waves);
        const double w2 = static_cast<double>(p.spectrum.w2_si), gamma = static_cast<double>(p.spectrum.gamma);
        const double l0 = static_cast<double>(p.spectrum.outer_scale_m);
        const double k0sq = l0 > 0.0 ? (two_pi_v<double> / l0) * (two_pi_v<double> / l0) : 0.0;
        rng g(seed);
        waves_.resize(p.waves);
        for (std::size_t i = 0; i < p.waves; ++i) {
            const double ln_a = std::log(k_lo) + step * static_cast<double>(i);
            // sigma^2 of the bin by the midpoint rule in ln K: 2 pi K^2 W(K) d(ln K).
            const double km = std::exp(ln_a + 0.5 * step);
            const double var = two_pi_v<double> * km * km * w2 * std::pow(km * km + k0sq, -0.5 * gamma) * step;
            const double k = std::exp(ln_a + step * g.uniform());
            const double dir = two_pi_v<double> * g.uniform();
            wave& w = waves_[i];
            w.kx = k * std::cos(dir);
            w.ky = k * std::sin(dir);
            w.phase = two_pi_v<double> * g.uniform();
            w.amplitude = std::sqrt(2.0 * var);
            variance_ += var;
        }
    }

    /// Expected mean-square height (m^2): the band's variance.
    [[nodiscard]] double variance_m2() const noexcept { return variance_; }

    /// Height (m) at world (x_m, y_m).
    [[nodiscard]] double height_m(double x_m, double y_m) const noexcept {
        double h = 0.0;
        for (const wave& w : waves_) h += w.amplitude * std::cos(w.kx * x_m + w.ky * y_m + w.phase);
        return h;
    }

    /// Heights of rows [iy0, iy0 + rows) of a grid of nx vertices per row at spacing cell_m whose vertex (0, 0) lies
    /// at world (x0_m, y0_m), row-major into out (nx * rows values). Each value depends on its vertex (ix, iy) only:
    /// cos(a + b) = cos a cos b - sin a sin b with a = kx x and b = ky y + phi, each from its own index.
    void fill_rows(std::size_t nx, std::size_t iy0, std::size_t rows, double cell_m, double x0_m, double y0_m,
                   std::span<T> out) const {
        sss::require(out.size() == nx * rows, "wave_sum_surface.fill_rows.out", "must hold nx * rows values");
        const std::size_t n = waves_.size();
        // Columns a block at a time, so that the waves' x factors take 2 n block doubles (16 MiB at 1024 waves)
        // whatever the row's width; each vertex's sum runs over the waves in the same order, so the bits are the
        // same for any block.
        constexpr std::size_t block = 1024;
        const std::size_t width = std::min(nx, block);
        std::vector<double> cx(n * width), sx(n * width), cy(n), sy(n), row(width);
        for (std::size_t x0 = 0; x0 < nx; x0 += block) {
            const std::size_t w = std::min(block, nx - x0);
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t ix = 0; ix < w; ++ix) {
                    const double a = waves_[i].kx * (x0_m + static_cast<double>(x0 + ix) * cell_m);
                    cx[i * w + ix] = waves_[i].amplitude * std::cos(a);
                    sx[i * w + ix] = waves_[i].amplitude * std::sin(a);
                }
            for (std::size_t r = 0; r < rows; ++r) {
                const double y = y0_m + static_cast<double>(iy0 + r) * cell_m;
                for (std::size_t i = 0; i < n; ++i) {
                    const double b = waves_[i].ky * y + waves_[i].phase;
                    cy[i] = std::cos(b);
                    sy[i] = std::sin(b);
                }
                std::fill(row.begin(), row.begin() + static_cast<std::ptrdiff_t>(w), 0.0);
                for (std::size_t i = 0; i < n; ++i) {
                    const double* c = cx.data() + i * w;
                    const double* s = sx.data() + i * w;
                    const double ci = cy[i], si = sy[i];
                    for (std::size_t ix = 0; ix < w; ++ix) row[ix] += c[ix] * ci - s[ix] * si;
                }
                for (std::size_t ix = 0; ix < w; ++ix) out[r * nx + x0 + ix] = static_cast<T>(row[ix]);
            }
        }
    }

private:
    struct wave {
        double kx, ky, phase, amplitude;
    };
    std::vector<wave> waves_;
    double variance_ = 0.0;
};

} // namespace sss::seabed
