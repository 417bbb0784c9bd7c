// Bad parameters raise sss::invalid_parameter naming the parameter, before anything is rendered.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
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
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.along_onset = -1.0}); }) == "ray_density.along_onset");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.along_onset = nan_v}); }) == "ray_density.along_onset");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.max_launch_step_deg = -1.0}); }) ==
          "ray_density.max_launch_step_deg");
    CHECK(named([] { sss::simulator<> sim({}, {}, {}, {}, {}, {.max_launch_step_deg = nan_v}); }) ==
          "ray_density.max_launch_step_deg");
    CHECK(named([] { sss::scene::flat_seabed<double>{nan_v}; }) == "flat_seabed.height_m");
}

TEST_CASE("receiver levels, chirps and speckle beyond what a sonar has are rejected by name, not overflowed") {
    // A chirp's time-bandwidth product beyond 10^4 (its energy table would need more than a million steps, and at
    // 10^300 the table's size was no number).
    for (const double b : {1.1e8, 1e300}) {
        sss::receiver_params rx;
        rx.pulse = {.length_s = 1e-4, .shape = sss::pulse_shape::lfm, .bandwidth_hz = b};
        CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "pulse.bandwidth_hz");
    }
    sss::receiver_params rx;
    rx.pulse = {.length_s = 1e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 1e7}; // B T = 10^4: fine
    CHECK_NOTHROW(sss::simulator<>({}, {}, {}, {}, rx));
    rx = {};
    rx.source_level_db = 1e6;
    CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "receiver.source_level_db");
    const auto tvg_named = [](sss::tvg_params p) { return named([&] { sss::tvg{p}; }); };
    CHECK(tvg_named({.gain_db = 1e6}) == "tvg.gain_db");
    CHECK(tvg_named({.spreading_n = 1e6}) == "tvg.spreading_n");
    CHECK(tvg_named({.absorption_db_per_km = 1e12}) == "tvg.absorption_db_per_km");
    const auto stats_named = [](sss::echo_statistics_params p) { return named([&] { sss::echo_statistics{p}; }); };
    for (const double f : {1e-300, 1e300})
        CHECK(stats_named({.noise = sss::noise_params{.frequency_hz = f}}) == "noise.frequency_hz");
    CHECK(stats_named({.noise = sss::noise_params{.source_level_db = -1e6}}) == "noise.source_level_db");
    CHECK(stats_named({.noise = sss::noise_params{.band_hz = 1e300}}) == "noise.band_hz");
    CHECK(stats_named({.noise = sss::noise_params{.electronic_floor_db = 1e6}}) == "noise.electronic_floor_db");
    CHECK(stats_named({.volume = sss::volume_params{.sv_db = 1e6}}) == "volume.sv_db");
    CHECK(stats_named({.volume = sss::volume_params{.psi_sr = 13.0}}) == "volume.psi_sr"); // more than the sphere
    // Speckle: a transducer so short that its lattice's indices run out of integers (the row loop never ended),
    // an epoch count beyond 64 bits, a density or beam width whose cell has no size.
    CHECK(stats_named({.speckle = sss::speckle_params{.transducer_length_m = 1e-300}}) == "speckle.transducer_length_m");
    CHECK(stats_named({.speckle = sss::speckle_params{.survey_time_s = 1e300, .decorrelation_time_s = 1e-300}}) ==
          "speckle.survey_time_s");
    CHECK(stats_named({.speckle = sss::speckle_params{.scatterer_density_per_m2 = 1e300, .along_beamwidth_rad = 0.01}}) ==
          "speckle.scatterer_density_per_m2");
    CHECK(stats_named({.speckle = sss::speckle_params{.scatterer_density_per_m2 = 10, .along_beamwidth_rad = 1e300}}) ==
          "speckle.along_beamwidth_rad");
    CHECK(stats_named({.speckle = sss::speckle_params{.transducer_length_m = 0.001}}).empty());
}

TEST_CASE("a height field whose cell has no finite inverse, and a towfish within 1 mm of the seabed, are rejected by name") {
    CHECK(named([] { sss::scene::height_field<double>({.nx = 2, .ny = 2, .cell_m = 1e-310}); }) == "height_field.cell_m");
    CHECK(named([] { sss::scene::height_field<float>({.nx = 2, .ny = 2, .cell_m = 1e-40f}); }) == "height_field.cell_m");
    // 1e-300 m above: the nearest echoes' spreading and footprint left double's range and the line held NaN.
    for (const double altitude : {1e-300, 9e-4}) {
        sss::motion::straight_line_params<double> m;
        m.altitude_m = altitude;
        const sss::simulator<> sim({}, {}, {}, sss::motion::straight_line<double>(m));
        CHECK(named([&] { (void)sim.ping(sss::scene::flat_seabed<double>(0.0), 0); }) == "ping[0]");
    }
    sss::motion::straight_line_params<double> m;
    m.altitude_m = 1e-3;
    const sss::simulator<> sim({}, {}, {}, sss::motion::straight_line<double>(m));
    const auto lines = sim.ping(sss::scene::flat_seabed<double>(0.0), 0);
    CHECK(std::all_of(lines.starboard.begin(), lines.starboard.end(), [](double v) { return std::isfinite(v); }));
}
