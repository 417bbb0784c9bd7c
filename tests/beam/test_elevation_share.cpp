// A beam's equivalent two-way solid angle Psi = int w dOmega and its share in depression: an ideal fan's box
// integrated exactly, a rectangular piston against Urick's rule, and the share cut by a flat seabed.
#include <doctest/doctest.h>

#include <cmath>

#include "sss/beam/elevation_share.hpp"
#include "sss/beam/ideal_fan.hpp"
#include "sss/beam/planar_array.hpp"
#include "sss/core/constants.hpp"
#include "sss/receiver/volume_reverberation.hpp"

namespace {
constexpr double pi = sss::pi_v<double>;
double rad(double deg) { return deg * pi / 180.0; }
} // namespace

TEST_CASE("an ideal fan's Psi is its box's solid angle, 2 sin(along / 2) x vertical, shared evenly in depression") {
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 2.0, .vertical_width_deg = 40.0, .depression_deg = 20.0});
    for (auto s : {sss::side::port, sss::side::starboard}) {
        const auto e = sss::elevation_share_of(fan, s);
        CHECK(e.psi_sr == doctest::Approx(2.0 * std::sin(rad(1.0)) * rad(40.0)).epsilon(1e-6));
        CHECK(e.at(rad(-5.0)) == 0.0);
        CHECK(e.at(rad(0.0)) == doctest::Approx(0.0));
        CHECK(e.at(rad(10.0)) == doctest::Approx(0.25).epsilon(1e-9));
        CHECK(e.at(rad(20.0)) == doctest::Approx(0.5).epsilon(1e-9));
        CHECK(e.at(rad(40.0)) == doctest::Approx(1.0));
        CHECK(e.at(rad(60.0)) == 1.0);
    }
}

TEST_CASE("a rectangular piston's Psi is Urick's 10 log10(lambda^2 / (4 pi L W)) + 7.4 dB within 0.15 dB") {
    // Urick (1983), table 8.1; the small-angle integral of sinc^4 x sinc^4 gives 4 lambda^2 / (9 L W), 0.07 dB above.
    for (double w_m : {0.05, 0.1}) {
        const double lambda = 1500.0 / 100e3, l_m = 0.5;
        const sss::beam::planar_array<double> piston({.depression_deg = 20.0,
                                                      .transmit = {.along = {.count = 1, .element_m = l_m},
                                                                   .vertical = {.count = 1, .element_m = w_m}},
                                                      .threshold_db = -40.0});
        const double psi = sss::elevation_share_of(piston, sss::side::starboard).psi_sr;
        const double urick_db = 10.0 * std::log10(lambda * lambda / (4.0 * pi * l_m * w_m)) + 7.4;
        MESSAGE("W = " << w_m << " m: Psi " << 10.0 * std::log10(psi) << " dB, Urick " << urick_db << " dB");
        CHECK(std::abs(10.0 * std::log10(psi) - urick_db) < 0.15);
        // Half of the symmetric pattern lies above its axis.
        CHECK(sss::elevation_share_of(piston, sss::side::starboard).at(rad(20.0)) == doctest::Approx(0.5).epsilon(0.005));
    }
}

TEST_CASE("over a flat seabed the water holds the whole beam before the seabed's range, then what lies above asin(H / r)") {
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 2.0, .vertical_width_deg = 40.0, .depression_deg = 20.0});
    const auto e = sss::elevation_share_of(fan, sss::side::starboard);
    CHECK(sss::water_share(e, sss::side::starboard, 9.0, 10.0, 0.0) == 1.0);
    // 10 m up, 20 m out: the seabed at 30 deg, 3/4 of the fan above it; 10/sin(40 deg) out, the fan's lower edge.
    CHECK(sss::water_share(e, sss::side::starboard, 20.0, 10.0, 0.0) == doctest::Approx(0.75).epsilon(1e-9));
    CHECK(sss::water_share(e, sss::side::starboard, 10.0 / std::sin(rad(40.0)), 10.0, 0.0) == doctest::Approx(1.0));
    // Rolled 5 deg starboard down: the starboard fan looks deeper and meets the seabed sooner; the port fan later.
    CHECK(sss::water_share(e, sss::side::starboard, 20.0, 10.0, rad(5.0)) == doctest::Approx(0.625).epsilon(1e-9));
    CHECK(sss::water_share(e, sss::side::port, 20.0, 10.0, rad(5.0)) == doctest::Approx(0.875).epsilon(1e-9));
}
