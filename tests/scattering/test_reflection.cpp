// Plane-wave reflection at a fluid sediment: the Rayleigh coefficient and its coherent reduction by roughness.

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <string>

#include <sss/scattering/reflection.hpp>

using namespace sss::scattering;
using sss::deg_to_rad;

TEST_CASE("the reflection coefficient never exceeds 1 in magnitude (energy is not created)") {
    double worst = 0.0;
    float worst_f = 0.0f;
    for (double rho : {0.5, 1.0, 1.145, 1.845, 2.5, 4.0})
        for (double nu : {0.8, 0.98, 0.9999, 1.0, 1.0001, 1.1782, 2.5})
            for (double delta : {0.0, 1e-4, 0.01624, 0.2, 1.0})
                for (int i = 0; i <= 900; ++i) {
                    const double g = deg_to_rad(0.1 * i);
                    worst = std::max(worst, std::abs(rayleigh_reflection(rho, nu, delta, g)));
                    worst_f = std::max(worst_f, std::abs(rayleigh_reflection(float(rho), float(nu), float(delta), float(g))));
                }
    CHECK(worst <= 1.0);
    CHECK(worst_f <= 1.0f);
    CHECK(worst > 0.999); // total reflection does occur (grazing incidence, lossless fast beds)
}

TEST_CASE("at grazing incidence the reflection coefficient is -1") {
    for (const auto& row : sediment_table) {
        CAPTURE(row.name);
        const auto r = rayleigh_reflection(sediment_preset<double>(row.id), 0.0);
        CHECK(r.real() == doctest::Approx(-1.0).epsilon(1e-12));
        CHECK(std::abs(r.imag()) < 1e-12);
    }
}

TEST_CASE("at normal incidence the reflection coefficient is the impedance contrast (rho nu - 1 - i delta)/(rho nu + 1 + i delta)") {
    for (const auto& row : sediment_table) {
        CAPTURE(row.name);
        const std::complex<double> z(row.rho * row.nu, 0.0);
        const std::complex<double> expected = (z - std::complex<double>(1.0, row.delta)) / (z + std::complex<double>(1.0, row.delta));
        const auto r = rayleigh_reflection(sediment_preset<double>(row.id), sss::half_pi_v<double>);
        CHECK(r.real() == doctest::Approx(expected.real()).epsilon(1e-12));
        CHECK(r.imag() == doctest::Approx(expected.imag()).epsilon(1e-12));
    }
    // Medium sand: rho nu = 2.1738 -> R = 0.3701 (lossless value), |R|^2 = -8.63 dB.
    CHECK(std::abs(rayleigh_reflection(1.845, 1.1782, 0.0, sss::half_pi_v<double>)) == doctest::Approx(1.17378 / 3.17378).epsilon(1e-5));
}

TEST_CASE("a lossless fast bed reflects totally below the critical angle and conserves energy above it") {
    const double rho = 1.8, nu = 1.2;
    const double critical = std::acos(1.0 / nu); // 33.557 deg
    for (int i = 1; i < 900; ++i) {
        const double g = deg_to_rad(0.1 * i);
        CAPTURE(0.1 * i);
        const auto r = rayleigh_reflection(rho, nu, 0.0, g);
        if (g < critical - 1e-9) {
            CHECK(std::abs(r) == doctest::Approx(1.0).epsilon(1e-12));
        } else if (g > critical + 1e-9) {
            // Transmitted energy flux: 1 - |R|^2 = 4 rho sin(theta) P / (rho sin(theta) + P)^2, P real.
            const double p = std::sqrt(1.0 / (nu * nu) - std::cos(g) * std::cos(g));
            const double rs = rho * std::sin(g);
            CHECK(1.0 - std::norm(r) == doctest::Approx(4.0 * rs * p / ((rs + p) * (rs + p))).epsilon(1e-10));
        }
    }
}

TEST_CASE("a lossy bed always absorbs: |R| < 1 at every grazing angle above zero") {
    const auto p = sediment_preset<double>(sediment::rock); // nu = 2.5: critical angle 66.4 deg
    for (int i = 1; i <= 900; ++i) CHECK(std::abs(rayleigh_reflection(p, deg_to_rad(0.1 * i))) < 1.0);
}

TEST_CASE("with no contrast in wavenumber (nu = 1, delta = 0) R is the density contrast at every angle, zero included") {
    for (double g : {0.0, 1e-6, 0.3, 1.2, sss::half_pi_v<double>}) {
        CAPTURE(g);
        const auto r = rayleigh_reflection(1.5, 1.0, 0.0, g);
        CHECK(r.real() == doctest::Approx(0.5 / 2.5).epsilon(1e-12));
        CHECK(std::abs(r.imag()) < 1e-12);
    }
}

TEST_CASE("the RMS roughness height above a wavenumber equals the integral of the spectrum over that band") {
    // <h^2> = integral over K > K_min of W(K) d^2K = 2 pi integral K W(K) dK, W = w2 / K^gamma (cm units);
    // numerically with K = K_min e^u (trapezoid in u).
    for (double gamma : {2.5, 3.25, 3.8})
        for (double kmin_radpm : {0.5, 6.283185307179586, 100.0}) {
            CAPTURE(gamma);
            CAPTURE(kmin_radpm);
            const double w2 = 0.004446;
            const double kmin = kmin_radpm / 100.0;
            const int n = 200000;
            const double umax = 400.0 / (gamma - 2.0) / 10.0;
            const double du = umax / n;
            double sum = 0.0;
            for (int j = 0; j <= n; ++j) {
                const double k = kmin * std::exp(j * du);
                const double f = 2.0 * sss::pi_v<double> * k * k * w2 * std::pow(k, -gamma);
                sum += (j == 0 || j == n ? 0.5 : 1.0) * f * du;
            }
            const double h_m = std::sqrt(sum) / 100.0;
            CHECK(roughness_rms_height_m(w2, gamma, kmin_radpm) == doctest::Approx(h_m).epsilon(1e-5).scale(0));
        }
}

TEST_CASE("roughness reduces coherent reflection by exp(-2 k^2 h^2 sin^2 theta), never adding energy") {
    CHECK(coherent_roughness_factor(1.0, 1.0, sss::half_pi_v<double>) == doctest::Approx(std::exp(-2.0)));
    CHECK(coherent_roughness_factor(100.0, 0.01, deg_to_rad(30.0)) == doctest::Approx(std::exp(-0.5)));
    const auto sand = sediment_preset<double>(sediment::medium_sand);
    const double f = 100e3, c = 1500.0, patch = 0.5;
    const double k = 2.0 * sss::pi_v<double> * f / c;
    const double h = roughness_rms_height_m(sand.w2_cm4, sand.gamma, 2.0 * sss::pi_v<double> / patch);
    for (int i = 0; i <= 90; ++i) {
        const double g = deg_to_rad(double(i));
        const auto rc = coherent_reflection(sand, f, c, g, patch);
        const auto r = rayleigh_reflection(sand, g);
        const double expected = std::exp(-2.0 * k * k * h * h * std::sin(g) * std::sin(g));
        CHECK(std::abs(rc) == doctest::Approx(std::abs(r) * expected).epsilon(1e-12));
        CHECK(std::abs(rc) <= std::abs(r));
        const auto rcf = coherent_reflection(sediment_preset<float>(sediment::medium_sand), float(f), float(c), float(g), float(patch));
        CHECK(std::abs(rcf) <= 1.0f);
    }
    // A finer resolved scene leaves less unresolved roughness and more coherent reflection.
    CHECK(std::abs(coherent_reflection(sand, f, c, 0.3, 0.1)) > std::abs(coherent_reflection(sand, f, c, 0.3, 1.0)));
}

TEST_CASE("coherent reflection rejects invalid inputs, naming them") {
    const auto sand = sediment_preset<double>(sediment::medium_sand);
    auto name_of = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return "";
    };
    CHECK(name_of([&] { (void)coherent_reflection(sand, 0.0, 1500.0, 0.3, 1.0); }) == "f_hz");
    CHECK(name_of([&] { (void)coherent_reflection(sand, 1e5, -1.0, 0.3, 1.0); }) == "c_water_mps");
    CHECK(name_of([&] { (void)coherent_reflection(sand, 1e5, 1500.0, 0.3, 0.0); }) == "patch_size_m");
    auto bad = sand;
    bad.rho = -1.0;
    CHECK(name_of([&] { (void)coherent_reflection(bad, 1e5, 1500.0, 0.3, 1.0); }) == "sediment.rho");
}
