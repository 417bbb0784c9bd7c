#pragma once
/// \file
/// Internal to the seabed generators: fractal fields of unit expected RMS, one at a time or two drawn in step,
/// the shapes of perturbation, warp and partition fields. Not part of the API.

#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sss/core/types.hpp"
#include "sss/seabed/detail/fractal_coefficients.hpp"
#include "sss/seabed/detail/half_spectrum.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/fractal_params.hpp"
#include "sss/seabed/fractal_surface.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"

namespace sss::seabed::detail {

/// The factor that gives a field of band variance `band` unit RMS; 0 where the grid holds no mode but the mean (a
/// 1 x 1 grid: its band is empty, and the field is flat).
[[nodiscard]] inline double unit_scale(double band) noexcept { return band > 0.0 ? 1.0 / std::sqrt(band) : 0.0; }

/// A fractal field of unit expected RMS (power law of exponent gamma, outer scale l0_m; w2 scaled so
/// that the band variance is 1), in double: the shape of perturbation, warp and partition fields.
template <Real T> [[nodiscard]] raster<double> unit_fractal_field(std::size_t nx, std::size_t ny, T cell_m, T gamma,
                                                                  T l0_m, std::uint64_t seed) {
    fractal_params<double> f;
    f.spectrum = power_law_spectrum<double>{1.0, static_cast<double>(gamma), static_cast<double>(l0_m)};
    raster<double> g = fractal_surface<double>(nx, ny, static_cast<double>(cell_m), f, seed);
    const double scale = unit_scale(band_variance_m2(f, nx, ny, static_cast<double>(cell_m)));
    for (double& v : g.values) v *= scale;
    return g;
}

/// Two unit fractal fields of one spectrum, each nx * ny values row-major (element iy * nx + ix); `b` is empty
/// when only one was asked for.
template <Real S> struct fractal_pair {
    std::vector<S> a;
    std::vector<S> b;
};

/// Two independent unit fractal fields of one spectrum (as unit_fractal_field with seeds seed_a and seed_b, equal
/// to rounding), stored as S: the two generators draw in step (draw_coefficients) and each field's Hermitian half
/// spectrum is transformed in its own storage (half_spectrum.hpp), so the peak is the two fields plus a column
/// each. With `with_b` false only `a` is made.
template <Real S, Real T>
[[nodiscard]] fractal_pair<S> unit_fractal_pair(std::size_t nx, std::size_t ny, T cell_m, T gamma, T l0_m,
                                                std::uint64_t seed_a, std::uint64_t seed_b, bool with_b) {
    fractal_params<double> f;
    f.spectrum = power_law_spectrum<double>{1.0, static_cast<double>(gamma), static_cast<double>(l0_m)};
    const double dx = static_cast<double>(cell_m);
    fractal_pair<S> out;
    out.a.assign(nx * ny, S(0));
    std::vector<std::complex<S>> last_a(ny), last_b;
    const half_spectrum<S> sa{out.a.data(), last_a.data(), nx, ny};
    rng ga(seed_a), gb(seed_b);
    double band = 0.0;
    if (with_b) {
        out.b.assign(nx * ny, S(0));
        last_b.resize(ny);
        const half_spectrum<S> sb{out.b.data(), last_b.data(), nx, ny};
        band = draw_coefficients(nx, ny, dx, f, std::array<rng*, 2>{&ga, &gb},
                                 [&](const mode_pair& m, const std::array<std::complex<double>, 2>& v) {
                                     sa.set_pair(m.i, m.j, m.pi, m.pj, v[0]);
                                     sb.set_pair(m.i, m.j, m.pi, m.pj, v[1]);
                                 });
        inverse_half_spectrum(sb, unit_scale(band));
    } else {
        band = draw_coefficients(nx, ny, dx, f, std::array<rng*, 1>{&ga},
                                 [&](const mode_pair& m, const std::array<std::complex<double>, 1>& v) {
                                     sa.set_pair(m.i, m.j, m.pi, m.pj, v[0]);
                                 });
    }
    inverse_half_spectrum(sa, unit_scale(band));
    return out;
}

} // namespace sss::seabed::detail
