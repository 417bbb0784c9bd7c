// Directivity of line apertures, pistons and linear arrays against closed forms and published values
// (Kinsler, Frey, Coppens & Sanders, 2000, "Fundamentals of Acoustics", 4th ed., ch. 8).
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "sss/beam/directivity.hpp"
#include "sss/core/constants.hpp"

namespace {

using sss::beam::array_factor;
using sss::beam::line_aperture;

constexpr double pi = sss::pi_v<double>;
constexpr double L = 0.5;        // aperture length (m)
constexpr double lambda = 0.015; // wavelength (m): 100 kHz at 1500 m/s

double one_way_db(double u) {
    const double b = line_aperture(L, lambda, u);
    return 10.0 * std::log10(b * b);
}

/// Angle (rad) in [lo, hi] where a decreasing function crosses `level`, by bisection.
template <class F> double bisect_down(F f, double level, double lo, double hi) {
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) > level ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// sin(N a) / (N sin a), evaluated directly in long double (valid away from a = m pi).
long double direct_af(std::size_t n, long double a) {
    return std::sin(static_cast<long double>(n) * a) / (static_cast<long double>(n) * std::sin(a));
}

} // namespace

TEST_CASE("A 0.5 m line aperture at 15 mm has the published half-power width 1.5228 deg and first null 1.7191 deg") {
    // Found from the pattern itself, then compared with the reference values and with the helpers.
    const double half_power = bisect_down([](double th) { return one_way_db(std::sin(th)); }, 10.0 * std::log10(0.5),
                                          0.0, 0.02);
    const double width_deg = sss::rad_to_deg(2.0 * half_power);
    CHECK(width_deg == doctest::Approx(1.5228).epsilon(1e-3));
    CHECK(sss::rad_to_deg(sss::beam::line_aperture_half_power_width_rad(L, lambda)) ==
          doctest::Approx(width_deg).epsilon(1e-9));
    // The half-power width is 0.885893 lambda / L to first order.
    CHECK(2.0 * half_power == doctest::Approx(0.885893 * lambda / L).epsilon(1e-3).scale(0));

    const double null = bisect_down([](double th) { return line_aperture(L, lambda, std::sin(th)); }, 0.0, 0.02, 0.04);
    CHECK(sss::rad_to_deg(null) == doctest::Approx(1.7191).epsilon(1e-3));
    CHECK(sss::beam::line_aperture_first_null_rad(L, lambda) == doctest::Approx(null).epsilon(1e-9));
    CHECK(std::abs(line_aperture(L, lambda, lambda / L)) < 1e-15);
}

TEST_CASE("The first sidelobe of a uniform line aperture is 13.26 dB down, at sin theta = 4.4934 lambda / (pi L)") {
    // Scan between the first and second nulls (sin theta = lambda/L and 2 lambda/L) for the peak.
    const double u1 = lambda / L, u2 = 2.0 * lambda / L;
    double best_u = u1, best_db = -1e9;
    const int n = 20000;
    for (int i = 0; i <= n; ++i) {
        const double u = u1 + (u2 - u1) * i / n;
        const double db = one_way_db(u);
        if (db > best_db) best_db = db, best_u = u;
    }
    CHECK(best_db == doctest::Approx(-13.26).epsilon(0.05 / 13.26));
    CHECK(sss::beam::line_aperture_first_sidelobe_db<double>() == doctest::Approx(best_db).epsilon(1e-6));
    // The scan finds the peak to within a grid step (u2 - u1) / n; allow two.
    CHECK(std::abs(std::sin(sss::beam::line_aperture_first_sidelobe_rad(L, lambda)) - best_u) <= 2.0 * (u2 - u1) / n);
    CHECK(sss::beam::line_aperture_first_sidelobe_db<float>() == doctest::Approx(-13.2614).epsilon(1e-4));
}

TEST_CASE_TEMPLATE("sin x / x is exact at 0 and accurate close to it", T, float, double) {
    CHECK(sss::beam::sinc(T(0)) == T(1));
    const double tol = std::is_same_v<T, float> ? 2e-7 : 4e-16;
    for (double x = 1e-12; x < 2.0; x *= 1.7) {
        const long double ref = std::sin(static_cast<long double>(x)) / static_cast<long double>(x);
        const double got = static_cast<double>(sss::beam::sinc(static_cast<T>(x)));
        CHECK(std::abs(got - static_cast<double>(ref)) <= tol);
        CHECK(sss::beam::sinc(static_cast<T>(-x)) == sss::beam::sinc(static_cast<T>(x)));
    }
}

TEST_CASE("The rectangular piston pattern is the product of its two line apertures, and its directivity index "
          "matches 10 log10(4 pi Lx Ly / lambda^2)") {
    const double lx = 0.3, ly = 0.12;
    CHECK(sss::beam::rectangular_piston(lx, ly, lambda, 0.03, 0.05) ==
          doctest::Approx(line_aperture(lx, lambda, 0.03) * line_aperture(ly, lambda, 0.05)).epsilon(1e-14));
    // D = 4 pi / integral over the front hemisphere of |E|^2 dOmega (baffled piston).
    const int nt = 1200, np = 720;
    double integral = 0.0;
    for (int i = 0; i < nt; ++i) {
        const double th = (i + 0.5) * (0.5 * pi / nt);
        for (int j = 0; j < np; ++j) {
            const double ph = (j + 0.5) * (2.0 * pi / np);
            const double e = sss::beam::rectangular_piston(lx, ly, lambda, std::sin(th) * std::cos(ph),
                                                           std::sin(th) * std::sin(ph));
            integral += e * e * std::sin(th);
        }
    }
    integral *= (0.5 * pi / nt) * (2.0 * pi / np);
    const double di_numeric = 10.0 * std::log10(4.0 * pi / integral);
    MESSAGE("directivity index: numeric " << di_numeric << " dB, formula "
                                          << sss::beam::rectangular_piston_directivity_index_db(lx, ly, lambda) << " dB");
    // The formula holds for apertures large against lambda (here 20 and 8 wavelengths): 0.05 dB.
    CHECK(std::abs(di_numeric - sss::beam::rectangular_piston_directivity_index_db(lx, ly, lambda)) < 0.05);
}

TEST_CASE("The uniform array factor equals sin(N pi d u / lambda) / (N sin(pi d u / lambda))") {
    for (std::size_t n : {2u, 3u, 8u, 33u}) {
        const double d = 0.6 * lambda;
        for (double u = -0.999; u < 1.0; u += 0.00731) {
            const long double a = static_cast<long double>(pi * d * u / lambda);
            if (std::abs(std::sin(a)) < 1e-3L) continue;
            CHECK(array_factor(n, d, lambda, u) == doctest::Approx(static_cast<double>(direct_af(n, a))).epsilon(1e-12));
        }
    }
}

TEST_CASE("The array factor is finite and exact at its removable singularities: the main lobe and grating lobes") {
    // Pitch of 2.5 wavelengths: grating lobes at u = +-0.4, +-0.8 in visible space.
    const double d = 2.5 * lambda;
    for (std::size_t n : {4u, 5u}) {
        for (int m = -2; m <= 2; ++m) {
            const double u = sss::beam::grating_lobe_u(m, d, lambda);
            const double expected = (m % 2 != 0 && n % 2 == 0) ? -1.0 : 1.0; // (-1)^(m (N - 1))
            CHECK(array_factor(n, d, lambda, u) == doctest::Approx(expected).epsilon(1e-12));
            // Just beside it the series 1 - (N^2 - 1) delta^2 / 6 holds (delta the phase offset).
            for (double offset : {1e-13, 1e-9, 1e-6}) {
                const double delta = pi * d * offset / lambda;
                const double series = expected * (1.0 - (static_cast<double>(n * n) - 1.0) * delta * delta / 6.0);
                CHECK(array_factor(n, d, lambda, u + offset) == doctest::Approx(series).epsilon(1e-9));
            }
            const std::vector<double> w(n, 1.0);
            CHECK(array_factor(std::span<const double>(w), d, lambda, u) == doctest::Approx(1.0).epsilon(1e-12));
        }
    }
    // Float keeps the grating lobe at 1 too.
    CHECK(array_factor(std::size_t{6}, 2.5f * 0.015f, 0.015f, 0.4f) == doctest::Approx(-1.0).epsilon(1e-5));
}

TEST_CASE("Shaded array factors match their closed forms") {
    const double d = 0.5 * lambda;
    for (double u = -1.0; u <= 1.0; u += 0.0137) {
        const double psi = 2.0 * pi * d * u / lambda;
        // [1, 2, 1]: (2 + 2 cos psi) / 4 = cos^2(psi / 2).
        const std::vector<double> w121{1.0, 2.0, 1.0};
        CHECK(array_factor(std::span<const double>(w121), d, lambda, u) ==
              doctest::Approx(std::pow(std::cos(psi / 2.0), 2)).epsilon(1e-12));
        // [1, 0, 0, 1]: two elements 3 d apart, |cos(3 psi / 2)|.
        const std::vector<double> w1001{1.0, 0.0, 0.0, 1.0};
        CHECK(array_factor(std::span<const double>(w1001), d, lambda, u) ==
              doctest::Approx(std::abs(std::cos(1.5 * psi))).epsilon(1e-12).scale(1e-12));
        // Equal weights reduce to the uniform form.
        const std::vector<double> w7(7, 0.3);
        CHECK(array_factor(std::span<const double>(w7), d, lambda, u) ==
              doctest::Approx(std::abs(array_factor(std::size_t{7}, d, lambda, u))).epsilon(1e-12).scale(1e-12));
    }
}

TEST_CASE("Steering to u0 moves the main lobe and the first null by u0") {
    const std::size_t n = 16;
    const double d = 0.5 * lambda, u0 = std::sin(sss::deg_to_rad(20.0));
    CHECK(array_factor(n, d, lambda, u0, u0) == doctest::Approx(1.0));
    const double null_u = sss::beam::array_first_null_u(n, d, lambda);
    CHECK(null_u == doctest::Approx(lambda / (16.0 * d)));
    CHECK(std::abs(array_factor(n, d, lambda, u0 + null_u, u0)) < 1e-13);
    CHECK(std::abs(array_factor(n, d, lambda, u0 - null_u, u0)) < 1e-13);
    for (double u = -1.0; u <= 1.0; u += 0.05)
        CHECK(array_factor(n, d, lambda, u, u0) == doctest::Approx(array_factor(n, d, lambda, u - u0)).epsilon(1e-12));
    CHECK(line_aperture(L, lambda, u0, u0) == 1.0);
    CHECK(std::abs(line_aperture(L, lambda, u0 + lambda / L, u0)) < 1e-13);
    const std::vector<double> hann{0.25, 0.75, 1.0, 0.75, 0.25};
    CHECK(array_factor(std::span<const double>(hann), d, lambda, u0, u0) == doctest::Approx(1.0));
}

TEST_CASE("Array half-power widths: 2 asin(lambda / (4 d)) for two elements, 0.886 lambda / (N d) for many") {
    const double d = 0.5 * lambda;
    // N = 2: AF = cos(pi d u / lambda), half power where pi d u / lambda = pi / 4.
    CHECK(sss::beam::array_width_rad(std::size_t{2}, d, lambda, 0.5) ==
          doctest::Approx(2.0 * std::asin(lambda / (4.0 * d))).epsilon(1e-12));
    const std::size_t n = 64;
    const double w = sss::beam::array_width_rad(n, d, lambda, 0.5);
    CHECK(w == doctest::Approx(0.885893 * lambda / (static_cast<double>(n) * d)).epsilon(2e-3).scale(0));
    const double u_hp = std::sin(w / 2.0);
    CHECK(std::pow(array_factor(n, d, lambda, u_hp), 2) == doctest::Approx(0.5).epsilon(1e-9));
    // Line aperture at another level: -6 dB one way.
    const double w6 = sss::beam::line_aperture_width_rad(L, lambda, 0.25);
    CHECK(std::pow(line_aperture(L, lambda, std::sin(w6 / 2.0)), 2) == doctest::Approx(0.25).epsilon(1e-9));
    // An aperture shorter than the level needs covers the whole front half-space.
    CHECK(sss::beam::line_aperture_width_rad(0.005, lambda, 0.5) == doctest::Approx(pi));
    CHECK_THROWS_AS((void)sss::beam::line_aperture_first_null_rad(0.01, lambda), sss::invalid_parameter);
    CHECK_THROWS_AS((void)sss::beam::line_aperture_width_rad(L, lambda, 1.0), sss::invalid_parameter);
}
