// The oracle itself against the closed form of the sonar equation on a flat seabed (the reverberation form of the sonar
// equation, Urick, 1983, "Principles of Underwater Sound", 3rd ed., McGraw-Hill, ch. 8):
// ideal fan of along-track width phi, isovelocity, no absorption, away from nadir, the echo density per unit delay
// is rho(s) = SL sigma(theta) phi c / (2 r^3 cos theta); a rectangular pulse of length tau records rho tau.

#include <doctest/doctest.h>

#include <cmath>

#include "../support/flat_seabed_oracle.hpp"
#include <sss/beam/ideal_fan.hpp>
#include <sss/scattering/lambertian.hpp>

namespace {
constexpr double pi = 3.141592653589793238;
}

TEST_CASE("oracle reproduces the closed-form sonar equation sigma phi c dt / (2 r^3 cos theta) away from nadir") {
    const double phi_deg = 0.5;
    const sss::beam::ideal_fan<double> fan({.along_width_deg = phi_deg, .vertical_width_deg = 60.0, .depression_deg = 25.0});
    const sss::scattering::lambertian<double> lambert(-27.0);
    sss_test::oracle_setup o;
    o.altitude_m = 10.0;
    o.dt_s = 1.0 / 10000.0;
    o.samples = 700;
    o.pulse_length_s = 2.0 / 10000.0;
    o.absorption_db_per_km = 0.0;
    o.rel_tol = 1e-9;
    const auto y = sss_test::oracle_line(o, fan, lambert, sss::side::starboard);
    const double phi = phi_deg * pi / 180.0;
    int checked = 0;
    for (std::size_t k = 400; k < 700; k += 50) {
        // Mid-sample delay minus half the pulse: where the window is centred.
        const double s = (double(k) + 0.5) * o.dt_s - 0.5 * o.pulse_length_s;
        const double r = 0.5 * o.c_mps * s;
        const double sin_t = o.altitude_m / r, cos_t = std::sqrt(1 - sin_t * sin_t);
        const double sigma = lambert.backscatter(std::asin(sin_t), 0);
        const double closed = sigma * phi * o.c_mps / (2 * r * r * r * cos_t) * o.pulse_length_s;
        INFO("sample " << k << " range " << r << " m: oracle " << y[k] << " closed form " << closed);
        // The closed form takes the fan's along-track extent as r phi (small angle) and rho constant over the window;
        // both approximations are below 0.1% here.
        CHECK(y[k] == doctest::Approx(closed).epsilon(1e-3).scale(0));
        ++checked;
    }
    CHECK(checked == 6);
}

TEST_CASE("oracle conserves the line's energy: sum of samples x dt equals the pulse energy x the echo power") {
    // The same seabed with two pulse lengths: total energy scales exactly with the pulse energy.
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 1.0, .vertical_width_deg = 50.0, .depression_deg = 20.0});
    const sss::scattering::lambertian<double> lambert(-27.0);
    sss_test::oracle_setup o;
    o.samples = 600;
    o.absorption_db_per_km = 60.0;
    auto total = [&](double tau) {
        o.pulse_length_s = tau;
        double e = 0;
        for (double v : sss_test::oracle_line(o, fan, lambert, sss::side::port)) e += v * o.dt_s;
        return e;
    };
    // Echoes start after 2H/(c sin 45 deg) and end well before the line does except for the last pulse length.
    const double e1 = total(50e-6), e2 = total(150e-6);
    CHECK(e2 / e1 == doctest::Approx(3.0).epsilon(2e-3).scale(0));
}
