// Bad parameters raise sss::invalid_parameter naming the parameter, before anything is rendered.

#include <doctest/doctest.h>

#include <limits>
#include <string>

#include <sss/sss.hpp>

namespace {

// Runs f and returns the name of the parameter its invalid_parameter names ("" if it did not throw one).
template <class F> std::string named(F&& f) {
    try {
        f();
    } catch (const sss::invalid_parameter& e) {
        CHECK(std::string(e.what()).find(e.parameter()) != std::string::npos);
        return e.parameter();
    }
    return {};
}

constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();
constexpr double inf_v = std::numeric_limits<double>::infinity();

} // namespace

TEST_CASE("a negative, zero or NaN altitude is rejected by name") {
    for (double a : {-10.0, 0.0, nan_v}) {
        sss::motion::straight_line_params<double> p;
        p.altitude_m = a;
        CHECK(named([&] { sss::motion::straight_line<double>{p}; }) == "straight_line.altitude_m");
    }
}

TEST_CASE("a zero, negative or NaN sample rate is rejected by name") {
    for (double fs : {0.0, -1.0, nan_v, inf_v}) {
        sss::receiver_params rx;
        rx.sample_rate_hz = fs;
        CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "receiver.sample_rate_hz");
    }
}

TEST_CASE("receiver range and pulse out of range are rejected by name") {
    sss::receiver_params rx;
    rx.max_range_m = -5;
    CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "receiver.max_range_m");
    rx = {};
    rx.pulse.length_s = 0;
    CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "pulse.length_s");
    rx = {};
    rx.pulse.length_s = nan_v;
    CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "pulse.length_s");
    rx = {};
    rx.max_range_m = 1e9; // more samples than a line may hold
    CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "receiver.max_range_m");
}

TEST_CASE("beam widths and depression outside their ranges are rejected by name") {
    using P = sss::beam::ideal_fan_params<double>;
    CHECK(named([] { sss::beam::ideal_fan<double>{P{0.0, 50, 20}}; }) == "ideal_fan.along_width_deg");
    CHECK(named([] { sss::beam::ideal_fan<double>{P{180.0, 50, 20}}; }) == "ideal_fan.along_width_deg");
    CHECK(named([] { sss::beam::ideal_fan<double>{P{nan_v, 50, 20}}; }) == "ideal_fan.along_width_deg");
    CHECK(named([] { sss::beam::ideal_fan<double>{P{1, -3, 20}}; }) == "ideal_fan.vertical_width_deg");
    CHECK(named([] { sss::beam::ideal_fan<double>{P{1, 200, 20}}; }) == "ideal_fan.vertical_width_deg");
    CHECK(named([] { sss::beam::ideal_fan<double>{P{1, 50, 95}}; }) == "ideal_fan.depression_deg");
    CHECK(named([] { sss::beam::ideal_fan<double>{P{1, 50, nan_v}}; }) == "ideal_fan.depression_deg");
}

TEST_CASE("propagation, scattering, motion and ray density parameters are rejected by name") {
    CHECK(named([] { sss::propagation::straight<double>{{nan_v, 60}}; }) == "straight.sound_speed_mps");
    CHECK(named([] { sss::propagation::straight<double>{{1500, -1}}; }) == "straight.absorption_db_per_km");
    CHECK(named([] { sss::scattering::lambertian<double>{-3.0}; }) == "lambertian.mu_db[0]");
    CHECK(named([] { sss::scattering::lambertian<double>({.mu_db = {-27.0, nan_v}}); }) == "lambertian.mu_db[1]");
    sss::motion::straight_line_params<double> m;
    m.ping_interval_s = 0;
    CHECK(named([&] { sss::motion::straight_line<double>{m}; }) == "straight_line.ping_interval_s");
    m = {};
    m.speed_mps = -1;
    CHECK(named([&] { sss::motion::straight_line<double>{m}; }) == "straight_line.speed_mps");
    m = {};
    m.heading_deg = inf_v;
    CHECK(named([&] { sss::motion::straight_line<double>{m}; }) == "straight_line.heading_deg");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {0, 0, 1.0}); }) == "ray_density.along");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {8, 1, 1.0}); }) == "ray_density.across");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {8, 0, nan_v}); }) == "ray_density.per_sample");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.along_split = 6562}); }) == "ray_density.along_split");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.along_split_echo = -0.1}); }) ==
          "ray_density.along_split_echo");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.along_split_echo = nan_v}); }) ==
          "ray_density.along_split_echo");
    CHECK(named([] { sss::scene::flat_seabed<double>{nan_v}; }) == "flat_seabed.height_m");
}
