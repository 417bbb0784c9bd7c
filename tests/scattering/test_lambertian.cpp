// Lambert's law (Mackenzie 1961): published backscattering strengths, the bistatic form, energy conservation at
// mu = 1/pi, and the policy's validation.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <sss/scattering/lambertian.hpp>

using namespace sss::scattering;
using sss::deg_to_rad;

static_assert(sss::Scattering<lambertian<float>>);
static_assert(sss::Scattering<lambertian<double>>);

TEST_CASE("Lambert's law with Mackenzie's -27 dB gives -27.00, -33.02 and -42.21 dB at 90, 30 and 10 deg") {
    const lambertian<double> d;
    const lambertian<float> f;
    const double angles[3] = {90.0, 30.0, 10.0};
    const double published[3] = {-27.00, -33.02, -42.21};
    for (int j = 0; j < 3; ++j) {
        CAPTURE(angles[j]);
        const double g = deg_to_rad(angles[j]);
        CHECK(std::abs(10.0 * std::log10(d.backscatter(g, 0)) - published[j]) <= 0.005);
        CHECK(std::abs(10.0 * std::log10(double(f.backscatter(float(g), 0))) - published[j]) <= 0.005);
    }
}

TEST_CASE("Lambert's bistatic form is mu sin(theta_i) sin(theta_s): reciprocal, azimuth-free, backscatter at equal angles") {
    const lambertian<double> s(-20.0);
    const double mu = std::pow(10.0, -2.0);
    for (double gi : {0.0, 0.2, 0.9, sss::half_pi_v<double>})
        for (double gs : {0.0, 0.4, 1.3})
            for (double phi : {0.0, 1.0, sss::pi_v<double>}) {
                // Relative to mu, the value at normal incidence both ways (at grazing incidence it is exactly 0).
                CHECK(s.bistatic(gi, gs, phi, 0) == doctest::Approx(mu * std::sin(gi) * std::sin(gs)).scale(mu));
                CHECK(s.bistatic(gi, gs, phi, 0) == doctest::Approx(s.bistatic(gs, gi, phi, 0)).epsilon(1e-15));
            }
    CHECK(s.bistatic(0.7, 0.7, sss::pi_v<double>, 0) == doctest::Approx(s.backscatter(0.7, 0)).epsilon(1e-15));
    CHECK(lambert_sigma(0.1, 0.5, 0.25) == doctest::Approx(0.1 * std::sin(0.5) * std::sin(0.25)).scale(0));
}

TEST_CASE("Lambert's law reads grazing angles as the Scattering concept does: NaN as 0, outside [0, pi/2] clamped") {
    const lambertian<double> s(-20.0);
    const lambertian<float> f(-20.0f);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(s.backscatter(nan, 0) == 0.0);
    CHECK(s.bistatic(nan, 0.5, nan, 0) == 0.0);
    CHECK(s.bistatic(0.5, nan, 1.0, 0) == 0.0);
    CHECK(f.backscatter(std::numeric_limits<float>::quiet_NaN(), 0) == 0.0f);
    // A negative grazing angle would make sigma negative, one beyond pi/2 would lower it: both read as the end.
    CHECK(s.backscatter(-0.3, 0) == 0.0);
    CHECK(s.bistatic(-0.3, 0.5, sss::pi_v<double>, 0) == 0.0);
    CHECK(s.backscatter(2.5, 0) == s.backscatter(sss::half_pi_v<double>, 0));
    CHECK(s.bistatic(0.4, 3.0, 0.0, 0) == s.bistatic(0.4, sss::half_pi_v<double>, 0.0, 0));
}

TEST_CASE("a Lambertian surface with mu = 1/pi scatters exactly the power it receives") {
    // Scattered power per unit area over incident intensity: integral over the upper hemisphere of sigma dOmega,
    // dOmega = cos(graze) d(graze) d(phi); incident power per unit area: sin(graze_i). Their ratio is mu pi.
    const lambertian<double> s(10.0 * std::log10(1.0 / sss::pi_v<double>));
    for (double gi : {0.1, 0.6, 1.4}) {
        const int n = 2000;
        double sum = 0.0;
        for (int a = 0; a < n; ++a) {
            const double gs = (a + 0.5) * sss::half_pi_v<double> / n;
            for (int b = 0; b < 16; ++b) {
                const double phi = (b + 0.5) * 2.0 * sss::pi_v<double> / 16;
                sum += s.bistatic(gi, gs, phi, 0) * std::cos(gs) * (sss::half_pi_v<double> / n) * (2.0 * sss::pi_v<double> / 16);
            }
        }
        CAPTURE(gi);
        CHECK(sum / std::sin(gi) == doctest::Approx(1.0).epsilon(1e-6));
    }
}

TEST_CASE("the Lambertian policy keeps one parameter per material and rejects energy-creating ones") {
    const lambertian<float> s({.mu_db = {-27.0f, -10.0f}});
    CHECK(s.material_count() == 2);
    CHECK(s.mu(0) == doctest::Approx(std::pow(10.0, -2.7)).scale(0));
    CHECK(s.mu(1) == doctest::Approx(0.1));
    CHECK(s.mu(99) == s.mu(1));
    CHECK(s.backscatter(1.0f, std::numeric_limits<std::uint32_t>::max()) == s.backscatter(1.0f, 1));
    // mu = 1/pi, 10 log10(1/pi) = -4.97150 dB, is the bound: -4.9715 is within it, -4.971 (mu pi = 1.0001) beyond.
    CHECK_NOTHROW(lambertian<double>{-4.9715});
    CHECK_NOTHROW(lambertian<double>{sss::scattering::lambert_max_db});
    CHECK_THROWS_AS(lambertian<double>{-4.971}, sss::invalid_parameter);
    CHECK_THROWS_AS(lambertian<float>{-4.971f}, sss::invalid_parameter);
    CHECK(std::pow(10.0, sss::scattering::lambert_max_db / 10.0) * 3.141592653589793 == doctest::Approx(1.0).epsilon(1e-15));
    try {
        const lambertian<double> bad({.mu_db = {-27.0, -3.0}});
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "lambertian.mu_db[1]");
    }
    try {
        const lambertian<float> bad(std::numeric_limits<float>::quiet_NaN());
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "lambertian.mu_db[0]");
    }
}
