#pragma once
/// \file
/// Fractal (power-law) seabed surfaces by spectral synthesis: the surface, its band variance and the directional
/// spectral density. Part of seabed/fractal.hpp (see its file comment for the model), which includes it.

#include <algorithm>
#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sss/core/checked_size.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/types.hpp"
#include "sss/seabed/detail/fractal_coefficients.hpp"
#include "sss/seabed/detail/half_spectrum.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/fractal_params.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"

namespace sss::seabed {

/// Directional spectral density W(K_eff) (m^4) at wave vector (kx, ky) (rad/m) (see seabed/fractal.hpp).
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

/// A fractal surface of nx x ny samples of spacing cell_m (m), heights in m (see seabed/fractal.hpp).
/// Any nx, ny >= 1 (powers of two are fastest). Same (arguments, seed), same surface.
/// Memory: the coefficients' Hermitian half is drawn into the surface's own storage and transformed there
/// (detail/half_spectrum.hpp), so the peak is the surface plus one column (with oversample m: the
/// (m nx) x (m ny) synthesis grid in T plus the surface). Each row and column is transformed in double; for
/// float the coefficients and the half-transformed columns are held in float, which differs from a synthesis
/// wholly in double by a few float roundings of the surface's RMS.
template <Real T> [[nodiscard]] raster<T> fractal_surface(std::size_t nx, std::size_t ny, T cell_m,
                                                          const fractal_params<T>& p, std::uint64_t seed) {
    require_grid(nx, ny, cell_m, "fractal_surface");
    validate(p, "fractal_surface.params");
    const std::size_t sx = checked_mul(nx, p.oversample, "fractal_surface.params.oversample");
    const std::size_t sy = checked_mul(ny, p.oversample, "fractal_surface.params.oversample");
    (void)checked_elements(sx, sy, "fractal_surface.params.oversample");
    rng g(seed);
    std::vector<T> work(sx * sy, T(0));
    std::vector<std::complex<T>> last(sy);
    const detail::half_spectrum<T> s{work.data(), last.data(), sx, sy};
    (void)detail::draw_coefficients(sx, sy, static_cast<double>(cell_m), p, std::array<rng*, 1>{&g},
                                    [&](const detail::mode_pair& m, const std::array<std::complex<double>, 1>& v) {
                                        s.set_pair(m.i, m.j, m.pi, m.pj, v[0]);
                                    });
    detail::inverse_half_spectrum(s, 1.0);
    last = {};
    if (sx == nx && sy == ny) return raster<T>{nx, ny, cell_m, std::move(work)};
    raster<T> out{nx, ny, cell_m, std::vector<T>(nx * ny)};
    for (std::size_t iy = 0; iy < ny; ++iy)
        std::copy_n(work.begin() + static_cast<std::ptrdiff_t>(iy * sx), nx,
                    out.values.begin() + static_cast<std::ptrdiff_t>(iy * nx));
    return out;
}

} // namespace sss::seabed
