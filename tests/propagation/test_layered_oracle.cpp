// The flat-seabed oracle for layered water (tests/support/layered_oracle.hpp) checked on its own: its rays against the
// closed-form arcs and straight lines, its spreading against finite differences of its own ray map (the section 4
// formula), and its line against the straight-ray oracle in uniform water, where the two must agree.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sss/beam/ideal_fan.hpp"
#include "sss/scattering/lambertian.hpp"
#include "support/flat_seabed_oracle.hpp"
#include "support/layered_oracle.hpp"

namespace {

constexpr double deg = 3.14159265358979323846 / 180;
using ld = long double;

double rel(double got, ld want) { return static_cast<double>(std::abs((static_cast<ld>(got) - want) / want)); }

sss_test::layered_water uniform_water(double seabed_depth, double alpha_db_per_km) {
    sss_test::layered_water w;
    w.depth_m = {0, 30, 45};
    w.speed_mps = {1500, 1500, 1500};
    w.seabed_depth_m = seabed_depth;
    w.absorption_db_per_km = [alpha_db_per_km](double) { return alpha_db_per_km; };
    return w;
}

sss_test::layered_water thermocline_water() {
    sss_test::layered_water w;
    w.depth_m = {0, 44, 54, 200};
    w.speed_mps = {1500, 1499, 1479, 1481.409};
    w.seabed_depth_m = 60;
    w.absorption_db_per_km = [](double z) { return 70.0 + 0.01 * z; };
    return w;
}

} // namespace

TEST_CASE("the layered oracle's ray reproduces the constant-gradient reference example") {
    // c0 1500 m/s, g 0.1 1/s, 20 deg down to 100 m below the source (the physics reference's check values).
    sss_test::layered_water w;
    w.depth_m = {10, 1010};
    w.speed_mps = {1500, 1600};
    w.seabed_depth_m = 110;
    const auto r = sss_test::layered_ray_to_seabed(w, 10, 20 * deg);
    REQUIRE(r.reaches);
    CHECK(std::abs(r.range_m - 282.998) <= 5e-4);
    CHECK(std::abs(r.time_s - 0.1994308) <= 5e-8);
    CHECK(std::abs(r.graze_rad / deg - 18.922649) <= 5e-7);
    // Textbook closed forms in long double.
    const ld th0 = 20 * static_cast<ld>(deg), xi = std::cos(th0) / 1500, th1 = std::acos(xi * 1510);
    CHECK(rel(r.range_m, (std::sin(th0) - std::sin(th1)) / (xi * 0.1L)) < 1e-12);
    CHECK(rel(r.time_s, std::log(((1 + std::sin(th0)) / std::cos(th0)) / ((1 + std::sin(th1)) / std::cos(th1))) / 0.1L) < 1e-12);
    CHECK(rel(r.graze_rad, th1) < 1e-12);
    CHECK(r.c_source == 1500);
    CHECK(r.c_seabed == doctest::Approx(1510).epsilon(1e-14));
}

TEST_CASE("in uniform water the layered oracle's ray is a straight line with spherical spreading") {
    const auto w = uniform_water(70, 60);
    for (double graze : {1.0, 10.0, 45.0, 89.0, 90.0}) {
        const auto r = sss_test::layered_ray_to_seabed(w, 50, graze * deg);
        REQUIRE(r.reaches);
        const double R = 20 / std::sin(graze * deg);
        CHECK(std::abs(r.range_m - 20 / std::tan(graze * deg)) <= 1e-12 * R);
        CHECK(rel(r.time_s, R / 1500) < 1e-13);
        CHECK(rel(r.spreading, 1 / (R * R)) < 1e-12);
        CHECK(rel(r.graze_rad, graze * deg) < 1e-12);
        CHECK(rel(r.absorption, std::pow(10.0L, -60.0L * R / 1e4L)) < 1e-12);
    }
}

TEST_CASE("the layered oracle's spreading is cos(theta0) / (r sin(theta) |dr/dtheta0|) of its own ray map") {
    const auto w = thermocline_water();
    double worst = 0;
    for (double graze : {2.0, 8.0, 20.0, 45.0, 80.0}) {
        const double th = graze * deg, h = 1e-6;
        const auto r = sss_test::layered_ray_to_seabed(w, 50, th);
        const double drdth = (sss_test::layered_ray_to_seabed(w, 50, th + h).range_m -
                              sss_test::layered_ray_to_seabed(w, 50, th - h).range_m) / (2 * h);
        const double want = std::cos(th) / (r.range_m * std::sin(r.graze_rad) * std::abs(drdth));
        worst = std::max(worst, rel(r.spreading, want));
    }
    MESSAGE("worst relative difference from finite differences: " << worst);
    CHECK(worst < 1e-7);
}

TEST_CASE("in uniform water the layered oracle's line equals the straight-ray oracle's") {
    // Same beam, scattering, pose and water; the one integrates over slant range, the other over launch angle.
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 1.0, .vertical_width_deg = 50.0, .depression_deg = 25.0});
    const sss::scattering::lambertian<double> lambert(-27.0);
    sss_test::oracle_setup o;
    o.altitude_m = 10;
    o.roll_rad = 0.05;
    o.pitch_rad = -0.03;
    o.yaw_rad = 0.4;
    o.c_mps = 1500;
    o.absorption_db_per_km = 60;
    o.samples = 500; // 37.5 m of slant range
    for (sss::side sd : {sss::side::port, sss::side::starboard}) {
        const auto straight = sss_test::oracle_line(o, fan, lambert, sd);
        const auto layered = sss_test::oracle_line_layered(o, uniform_water(60, 60), fan, lambert, sd);
        double peak = 0, worst = 0;
        for (double v : straight) peak = std::max(peak, v);
        int compared = 0;
        for (std::size_t k = 0; k < straight.size(); ++k) {
            if (!(straight[k] > 1e-4 * peak)) continue;
            ++compared;
            worst = std::max(worst, std::abs(layered[k] / straight[k] - 1));
        }
        MESSAGE(std::string(sd == sss::side::port ? "port" : "starboard") << ": " << compared << " samples, worst relative difference " << worst);
        CHECK(compared > 100);
        CHECK(worst < 1e-5);
    }
}

TEST_CASE("the layered oracle refuses water outside its domain") {
    // Speed rising steeply with depth: shallow launches turn before the seabed, and the line reaches past them.
    sss_test::layered_water w;
    w.depth_m = {0, 100};
    w.speed_mps = {1450, 1550};
    w.seabed_depth_m = 60;
    sss_test::oracle_setup o;
    o.samples = 2000;
    const sss::beam::ideal_fan<double> fan;
    const sss::scattering::lambertian<double> lambert(-27.0);
    CHECK_THROWS_AS((void)sss_test::oracle_line_layered(o, w, fan, lambert, sss::side::starboard), std::runtime_error);
    CHECK_FALSE(sss_test::layered_ray_to_seabed(w, 50, 1 * deg).reaches);
}
