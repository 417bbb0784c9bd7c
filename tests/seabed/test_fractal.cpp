// Fractal surfaces: variance, units, periodicity and reproducibility of spectral synthesis.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/fractal.hpp"

namespace {

using namespace sss::seabed;

double mean_square(const raster<double>& h) {
    double s = 0;
    for (double v : h.values) s += v * v;
    return s / static_cast<double>(h.size());
}

fractal_params<double> sand(double gamma) {
    fractal_params<double> p;
    p.spectrum = jackson_spectrum(0.004446, gamma); // medium sand strength, TR 9407 Table 2
    return p;
}

} // namespace

TEST_CASE("w2 converts from the cm^4 of the APL-UW tables to SI as w2 * 10^(2 gamma - 8)") {
    // Medium sand, TR 9407 Table 2: w2 = 0.004446 cm^4, gamma = 3.25 -> 0.004446 * 10^-1.5 m^0.75.
    CHECK(w2_si_from_cm4(0.004446, 3.25) == doctest::Approx(1.4059487e-4).epsilon(1e-6).scale(0));
    // Same W at the same physical wavenumber: K = 10 rad/m = 0.1 rad/cm, W in cm^4 = 1e8 W in m^4.
    const double w_cm4 = 0.004446 / std::pow(0.1, 3.25);
    CHECK(1e8 * spectral_density_m4(jackson_spectrum(0.004446, 3.25), 10.0) ==
          doctest::Approx(w_cm4).epsilon(1e-12).scale(0));
    CHECK(w2_si_from_cm4(1.0f, 4.0f) == doctest::Approx(1.0f)); // gamma = 4: W and K^-4 scale alike
}

TEST_CASE("mean-square height equals the integral of W over the grid's band") {
    const std::size_t n = 64;
    const double dx = 0.1;
    for (double gamma : {3.25, 2.5}) {
        CAPTURE(gamma);
        auto p = sand(gamma);
        const double band = band_variance_m2(p, n, n, dx);
        // Gaussian coefficients: every realisation's variance is random (the few lowest modes dominate),
        // the ensemble mean is the band integral. 400 realisations: standard error about 1.5%.
        double mean = 0;
        const int m = 400;
        for (int s = 0; s < m; ++s)
            mean += mean_square(fractal_surface<double>(n, n, dx, p, static_cast<std::uint64_t>(s)));
        mean /= m;
        CHECK(std::sqrt(mean / band) == doctest::Approx(1.0).epsilon(0.05).scale(0));
        // Fixed moduli: Parseval makes every realisation's variance the band integral to rounding.
        p.amplitudes = spectral_amplitudes::fixed;
        for (std::uint64_t s : {1u, 2u})
            CHECK(mean_square(fractal_surface<double>(n, n + 6, dx, p, s)) ==
                  doctest::Approx(band_variance_m2(p, n, n + 6, dx)).epsilon(1e-10).scale(0));
    }
}

TEST_CASE("band variance of a von Karman spectrum approaches the closed form 2 pi w2 K0^(2 - gamma) / (gamma - 2)") {
    // With dK << K0 << K_Nyquist the lattice sum is the whole-plane integral, less the part beyond the
    // band, about (K0 / K_Nyquist)^(gamma - 2) = 0.75% (less the corners of the square band), and the K = 0
    // cell, (dK / K0)^2 (gamma - 2) / (2 pi) = 0.2%
    // (measured: 0.85% short).
    fractal_params<double> p = sand(3.25);
    p.spectrum.outer_scale_m = 2.0;
    const double k0 = sss::two_pi_v<double> / 2.0;
    const double closed = sss::two_pi_v<double> * p.spectrum.w2_si * std::pow(k0, 2.0 - 3.25) / (3.25 - 2.0);
    CHECK(band_variance_m2(p, 1024, 1024, 0.02) == doctest::Approx(closed).epsilon(0.015).scale(0));
}

TEST_CASE("the same seed gives the identical surface, a different seed a different one") {
    for (auto amp : {spectral_amplitudes::gaussian, spectral_amplitudes::fixed}) {
        auto p = sand(3.25);
        p.amplitudes = amp;
        p.anisotropy = 2.0;
        p.direction_rad = 0.3;
        const auto a = fractal_surface<double>(96, 80, 0.05, p, 42);
        const auto b = fractal_surface<double>(96, 80, 0.05, p, 42);
        const auto c = fractal_surface<double>(96, 80, 0.05, p, 43);
        CHECK(a.values == b.values);
        double diff = 0;
        for (std::size_t i = 0; i < a.size(); ++i) diff += (a.values[i] - c.values[i]) * (a.values[i] - c.values[i]);
        CHECK(diff / static_cast<double>(a.size()) > 0.5 * mean_square(a));
        // float output is the double synthesis rounded
        const auto f = fractal_surface<float>(
            96, 80, 0.05f,
            fractal_params<float>{{static_cast<float>(p.spectrum.w2_si), 3.25f, 0.0f}, 2.0f, 0.3f, amp, 1}, 42);
        double worst = 0;
        for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(f.values[i] - a.values[i]));
        CHECK(worst < 1e-5 * std::sqrt(mean_square(a)));
    }
}

TEST_CASE("synthesised surfaces are periodic; oversampling and cropping removes the periodicity") {
    auto p = sand(3.25);
    const std::size_t n = 128;
    // A periodic surface continues smoothly across its edge: the jump from the last column to the first is
    // a one-cell difference like any other. Cropped from a 4x larger grid it is a difference of n - 1 cells.
    auto edge_to_step = [&](const raster<double>& h) {
        double edge = 0, step = 0;
        for (std::size_t j = 0; j < n; ++j) {
            edge += std::pow(h(n - 1, j) - h(0, j), 2);
            step += std::pow(h(1, j) - h(0, j), 2);
        }
        return edge / step;
    };
    double periodic = 0, cropped = 0;
    for (std::uint64_t s = 1; s <= 4; ++s) {
        periodic += edge_to_step(fractal_surface<double>(n, n, 0.05, p, s));
        p.oversample = 4;
        cropped += edge_to_step(fractal_surface<double>(n, n, 0.05, p, s));
        p.oversample = 1;
    }
    CHECK(periodic / 4 < 2.0);
    // Expected ratio for a cropped fBm: (n - 1)^(2 alpha) = 127^1.25 ~ 425 (less the low-K band limit).
    CHECK(cropped / 4 > 50.0);
    // band_variance_m2 accounts for the larger synthesis grid.
    p.oversample = 4;
    auto q = p;
    q.oversample = 1;
    CHECK(band_variance_m2(p, n, n, 0.05) ==
          doctest::Approx(band_variance_m2(q, 4 * n, 4 * n, 0.05)).epsilon(1e-12).scale(0));
}

TEST_CASE("fractal synthesis rejects out-of-range parameters, naming them") {
    auto expect = [](auto&& f, const char* name) {
        try {
            f();
            FAIL("no exception for " << name);
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == name);
        }
    };
    auto p = sand(3.25);
    expect([&] { (void)fractal_surface<double>(0, 8, 0.1, p, 1); }, "fractal_surface.nx");
    expect([&] { (void)fractal_surface<double>(8, 8, -0.1, p, 1); }, "fractal_surface.cell_m");
    p.spectrum.gamma = 4.0;
    expect([&] { (void)fractal_surface<double>(8, 8, 0.1, p, 1); }, "fractal_surface.params.spectrum.gamma");
    p = sand(3.25);
    p.spectrum.w2_si = -1;
    expect([&] { (void)fractal_surface<double>(8, 8, 0.1, p, 1); }, "fractal_surface.params.spectrum.w2_si");
    p = sand(3.25);
    p.anisotropy = 0;
    expect([&] { (void)fractal_surface<double>(8, 8, 0.1, p, 1); }, "fractal_surface.params.anisotropy");
    p = sand(3.25);
    p.oversample = 0;
    expect([&] { (void)band_variance_m2(p, 8, 8, 0.1); }, "band_variance_m2.params.oversample");
}
