// Directional fractal surfaces: the anisotropy ratio a (length scales along / across the direction)
// measured in the wavenumber domain and in the space domain.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/fractal.hpp"

namespace {

using cd = std::complex<double>;
using namespace sss::seabed;

fractal_params<double> directional(double a, double direction_deg) {
    fractal_params<double> p;
    p.spectrum = jackson_spectrum(0.004446, 3.25);
    p.anisotropy = a;
    p.direction_rad = sss::deg_to_rad(direction_deg);
    return p;
}

/// Axis ratio of the spectrum's level contours, from the periodogram of `seeds` surfaces. On the along
/// axis u, W = w2 (a K^2)^(-gamma/2); on the across axis v, W = w2 (K^2 / a)^(-gamma/2): the mean of
/// P |K|^gamma over wave vectors within 2 degrees of v, over the same within 2 degrees of u
/// (|K| from 8 dK to N/2 dK), is a^gamma. Returns the a it implies.
double spectral_axis_ratio(const fractal_params<double>& p, std::size_t n, int seeds, std::uint64_t first_seed = 500) {
    const double gamma = p.spectrum.gamma;
    const double cu = std::cos(p.direction_rad), su = std::sin(p.direction_rad);
    const double tol = std::sin(sss::deg_to_rad(2.0));
    double along = 0, across = 0, n_along = 0, n_across = 0;
    for (int s = 0; s < seeds; ++s) {
        const auto h = fractal_surface<double>(n, n, 0.1, p, first_seed + static_cast<std::uint64_t>(s));
        std::vector<cd> c(h.values.begin(), h.values.end());
        fft_2d(c, n, n, fft_direction::forward);
        for (std::size_t j = 0; j < n; ++j)
            for (std::size_t i = 0; i < n; ++i) {
                const double kx = i <= n / 2 ? static_cast<double>(i) : -static_cast<double>(n - i);
                const double ky = j <= n / 2 ? static_cast<double>(j) : -static_cast<double>(n - j);
                const double k = std::hypot(kx, ky);
                if (k < 8.0 || k >= static_cast<double>(n / 2)) continue;
                const double cos_u = (kx * cu + ky * su) / k; // cosine of the angle between K and u
                const double cos_v = (-kx * su + ky * cu) / k;
                const double v = std::norm(c[j * n + i]) * std::pow(k, gamma);
                if (std::abs(cos_v) < tol) { // K along u
                    along += v;
                    n_along += 1;
                }
                if (std::abs(cos_u) < tol) { // K along v
                    across += v;
                    n_across += 1;
                }
            }
    }
    return std::pow((across / n_across) / (along / n_along), 1.0 / gamma);
}

/// Periodic sample structure function of h along the lattice step (sx, sy) cells, at k steps.
double structure_function(const raster<double>& h, long sx, long sy, long k) {
    const long nx = static_cast<long>(h.nx), ny = static_cast<long>(h.ny);
    double d = 0;
    for (long j = 0; j < ny; ++j)
        for (long i = 0; i < nx; ++i) {
            const long i2 = ((i + sx * k) % nx + nx) % nx;
            const long j2 = ((j + sy * k) % ny + ny) % ny;
            const double a = h(static_cast<std::size_t>(i2), static_cast<std::size_t>(j2)) -
                             h(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
            d += a * a;
        }
    return d / static_cast<double>(h.size());
}

/// The lag along u (in steps (ux, uy)) at which the structure function equals its value at `rv` steps
/// along v (steps (vx, vy), of the same length), divided by rv: log-log interpolation between lags.
double equal_variogram_lag_ratio(const raster<double>& h, long ux, long uy, long vx, long vy, long rv) {
    const double target = structure_function(h, vx, vy, rv);
    double prev = structure_function(h, ux, uy, 1);
    if (target <= prev) return 0.0;
    for (long k = 2; k <= 64; ++k) {
        const double cur = structure_function(h, ux, uy, k);
        if (cur >= target) {
            const double t = std::log(target / prev) / std::log(cur / prev);
            const double lk = std::log(static_cast<double>(k - 1)) +
                              t * (std::log(static_cast<double>(k)) - std::log(static_cast<double>(k - 1)));
            return std::exp(lk) / static_cast<double>(rv);
        }
        prev = cur;
    }
    return 0.0;
}

} // namespace

TEST_CASE("directional surface: spectrum contours are ellipses with the requested axis ratio") {
    struct config {
        double a, direction_deg;
    };
    for (config c : {config{2.0, 0.0}, config{4.0, 30.0}, config{2.5, 45.0}, config{1.0, 20.0}, config{0.5, 120.0}}) {
        CAPTURE(c.a);
        CAPTURE(c.direction_deg);
        const double a = spectral_axis_ratio(directional(c.a, c.direction_deg), 256, 4);
        CHECK(a == doctest::Approx(c.a).epsilon(0.10).scale(0));
    }
}

TEST_CASE("directional surface: the structure function reaches equal values at lags in the ratio a") {
    // Along u (the long axis) the surface takes a times the lag to vary as much as across it.
    // Fixed moduli make the periodic sample structure function its band expectation; the band's
    // limits bias the ratio by a few percent (less at small lags).
    for (double a : {2.0, 3.0}) {
        for (double direction : {0.0, 45.0, 90.0}) {
            CAPTURE(a);
            CAPTURE(direction);
            auto p = directional(a, direction);
            p.amplitudes = spectral_amplitudes::fixed;
            const auto h = fractal_surface<double>(512, 512, 0.05, p, 3);
            // Lattice steps of equal length along u and v.
            long ux = 1, uy = 0, vx = 0, vy = 1;
            if (direction == 45.0) {
                ux = 1, uy = 1, vx = -1, vy = 1;
            } else if (direction == 90.0) {
                ux = 0, uy = 1, vx = -1, vy = 0;
            }
            CHECK(equal_variogram_lag_ratio(h, ux, uy, vx, vy, 4) == doctest::Approx(a).epsilon(0.10).scale(0));
            // And the isotropic surface of the same seed: ratio 1 whatever the axes.
            p.anisotropy = 1.0;
            const auto iso = fractal_surface<double>(512, 512, 0.05, p, 3);
            CHECK(equal_variogram_lag_ratio(iso, ux, uy, vx, vy, 4) == doctest::Approx(1.0).epsilon(0.03).scale(0));
        }
    }
}

TEST_CASE("anisotropy a at direction theta equals anisotropy 1/a at theta + 90 degrees") {
    const auto a = fractal_surface<double>(64, 48, 0.1, directional(3.0, 10.0), 11);
    const auto b = fractal_surface<double>(64, 48, 0.1, directional(1.0 / 3.0, 100.0), 11);
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        worst = std::max(worst, std::abs(a.values[i] - b.values[i]));
        scale = std::max(scale, std::abs(a.values[i]));
    }
    CHECK(worst < 1e-12 * scale);
}
