// The receiver chain after detection: time-varied gain, slant-to-ground-range correction and digitisation.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include <sss/receiver/echo_statistics.hpp>
#include <sss/receiver/ground_range.hpp>
#include <sss/receiver/quantise.hpp>
#include <sss/receiver/tvg.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/scene.hpp>
#include <sss/scene/sphere.hpp>
#include <sss/simulator.hpp>

namespace {

using straight = sss::propagation::straight<double>;
using fan = sss::beam::ideal_fan<double>;
using line_motion = sss::motion::straight_line<double>;
using lambert = sss::scattering::lambertian<double>;

// A seabed whose backscattering cross section is the same at every angle: what N = 30 is designed for.
struct constant_sigma {
    using value_type = double;
    double sigma = 1e-3;
    [[nodiscard]] double backscatter(double, std::uint32_t) const noexcept { return sigma; }
    [[nodiscard]] double bistatic(double, double, double, std::uint32_t) const noexcept { return sigma; }
    [[nodiscard]] std::size_t material_count() const noexcept { return 1; }
};

line_motion motion_at(double altitude_m) {
    return line_motion(sss::motion::straight_line_params<double>{.altitude_m = altitude_m});
}

// dB spread (max - min) of a line between 20% and 90% of its samples.
double spread_db(const std::vector<double>& line) {
    double lo = 1e300, hi = 0.0;
    for (std::size_t k = line.size() / 5; k < line.size() * 9 / 10; ++k) {
        lo = std::min(lo, line[k]);
        hi = std::max(hi, line[k]);
    }
    return 10.0 * std::log10(hi / lo);
}

} // namespace

TEST_CASE("TVG with N = 30 and the absorption flattens a constant-sigma flat seabed within 1 dB from 20% to 90% of range") {
    const sss::tvg gain(sss::tvg_params{.spreading_n = 30.0, .absorption_db_per_km = 60.0});
    const sss::simulator<constant_sigma, straight, fan, line_motion, sss::tvg> sim(
        constant_sigma{}, straight{}, fan{}, motion_at(5.0), sss::receiver_params{}, sss::ray_density{}, gain);
    const auto line = sim.ping(sss::scene::flat_seabed<double>{}, 0).starboard;
    MESSAGE("spread after TVG: " << spread_db(line) << " dB");
    CHECK(spread_db(line) < 2.0); // every sample within +-1 dB of the span's middle
    CHECK(sss::tvg_gain_db(sss::tvg_params{.spreading_n = 30.0, .absorption_db_per_km = 60.0, .gain_db = 3.0}, 100.0) ==
          doctest::Approx(60.0 + 12.0 + 3.0));
}

TEST_CASE_TEMPLATE("TVG beyond the number type's range holds a sample at its largest value, and zero stays zero", T, float, double) {
    // 1000 dB/km both ways over 1.5 km, N = 60 and G0 = 300 dB: about 3500 dB. 0 x infinity made NaN of every empty
    // far sample, and a lit one became infinity (shown black by a display that drops what is not finite).
    const sss::tvg gain(sss::tvg_params{.spreading_n = 60.0, .absorption_db_per_km = 1000.0, .gain_db = 300.0});
    sss::line_context<T> ctx;
    ctx.dt_s = 1e-3;
    std::vector<T> line(2000, T(0));
    for (std::size_t k = 0; k < line.size(); k += 2) line[k] = T(1e-30);
    gain.process(line, ctx);
    std::size_t held = 0;
    for (std::size_t k = 0; k < line.size(); ++k) {
        CAPTURE(k);
        REQUIRE(std::isfinite(line[k]));
        if (k % 2 == 1) CHECK(line[k] == T(0));
        held += line[k] == std::numeric_limits<T>::max();
    }
    CHECK(held > 0);
    // Near range the gain is exact: 1e-30 x 10^(G/10) at 0.75 m (the minimum range's 1 m).
    CHECK(double(line[0]) == doctest::Approx(1e-30 * std::pow(10.0, sss::tvg_gain_db(gain.params(), 0.75) / 10.0)).scale(0).epsilon(1e-6));
    // Where the gain alone passes double's range (3276 dB at 1425 m) a small sample still comes out finite and exact.
    if constexpr (std::is_same_v<T, double>) {
        const sss::tvg steep(sss::tvg_params{.spreading_n = 40.0, .absorption_db_per_km = 1000.0, .gain_db = 300.0});
        sss::line_context<T> far;
        far.dt_s = 1.9e-3; // sample 1000's centre at 1425.7 m
        std::vector<T> one(1001, T(0));
        one[1000] = T(1e-300);
        steep.process(one, far);
        const double g_db = sss::tvg_gain_db(steep.params(), 0.5 * 1500.0 * 1000.5 * 1.9e-3);
        REQUIRE(g_db > 3083.0);
        CHECK(std::log10(double(one[1000])) == doctest::Approx(-300.0 + g_db / 10.0).scale(0).epsilon(1e-9));
    }
    // A column whose mean is not finite is left as it is by the per-range normalisation.
    sss::waterfall<T> w;
    w.pings = 2;
    w.samples = 1;
    w.values = {std::numeric_limits<T>::infinity(), T(2), T(1), T(2)};
    sss::normalise_range_mean(w);
    CHECK(std::isinf(w.values[0]));
    CHECK(w.values[2] == T(1));
    CHECK(w.values[1] == T(1));
}

TEST_CASE("Lambert's sin^2 law leaves 20 log r after N = 30; per-range mean normalisation flattens it within 1 dB") {
    const sss::tvg gain(sss::tvg_params{.spreading_n = 30.0, .absorption_db_per_km = 60.0});
    using chain = sss::line_chain<sss::echo_statistics, sss::tvg>;
    const sss::echo_statistics stats(sss::echo_statistics_params{.seed = 4, .speckle = sss::speckle_params{}});
    const sss::simulator<lambert, straight, fan, line_motion, chain> sim(
        lambert{}, straight{}, fan{}, motion_at(5.0), sss::receiver_params{}, sss::ray_density{},
        chain(stats, gain));
    const sss::simulator<lambert, straight, fan, line_motion, sss::tvg> mean_sim(
        lambert{}, straight{}, fan{}, motion_at(5.0), sss::receiver_params{}, sss::ray_density{}, gain);
    const auto mean_line = mean_sim.ping(sss::scene::flat_seabed<double>{}, 0).starboard;
    // sin^2 of the grazing angle on a flat seabed is H^2 / r^2: 20 log10 of the range ratio, less the footprint's
    // 1/cos(graze) growth towards nadir.
    const std::size_t k1 = mean_line.size() / 5, k2 = mean_line.size() * 4 / 5;
    const double drop_db = 10.0 * std::log10(mean_line[k1] / mean_line[k2]);
    const double r1 = 750.0 * (double(k1) + 0.5) * sim.dt_s(), r2 = 750.0 * (double(k2) + 0.5) * sim.dt_s();
    const double cos1 = std::sqrt(1.0 - 25.0 / (r1 * r1)), cos2 = std::sqrt(1.0 - 25.0 / (r2 * r2));
    const double expected_db = 20.0 * std::log10(r2 / r1) + 10.0 * std::log10(cos2 / cos1);
    MESSAGE("Lambert after N = 30 falls " << drop_db << " dB from 20% to 80% of range; 20 log(r2/r1) with the footprint: " << expected_db);
    CHECK(std::abs(drop_db - expected_db) < 0.3);
    auto w = sim.render(sss::scene::flat_seabed<double>{}, 0, 64, 1);
    sss::normalise_range_mean(w);
    // Mean over pings of the normalised record: 1 by construction; what matters is that one line is flat in
    // the mean, i.e. every range bin's mean over 16 adjacent samples and 64 pings is within 1 dB of the others.
    std::vector<double> smooth;
    for (std::size_t k0 = w.samples / 5; k0 + 16 <= w.samples * 9 / 10; k0 += 16) {
        double s = 0;
        for (std::size_t i = 0; i < 16; ++i) s += w.at(7, w.samples + k0 + i) + w.at(40, w.samples + k0 + i);
        smooth.push_back(s / 32.0);
    }
    const auto [lo, hi] = std::minmax_element(smooth.begin(), smooth.end());
    CHECK(10.0 * std::log10(*hi) < 3.0); // two pings' speckle, averaged over 32 samples: a few dB at most
    CHECK(10.0 * std::log10(*lo) > -3.0);
}

TEST_CASE("ground range: an echo from the seabed lands in the ground-range pixel of its flat-bottom position") {
    using sss::scene::flat_seabed;
    using sss::scene::object;
    using sss::scene::object_set;
    using sss::scene::sphere;
    // A bright 10 cm sphere resting on a dark seabed 30 m to starboard; towfish 10 m up.
    std::vector<object<double>> objs{object<double>({sphere<double>(sss::vec3<double>{30.0, 0.0, 0.1}, 0.1, {.material = 1, .object = 1})}, {})};
    const sss::scene::scene sc(flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
    const sss::simulator<lambert, straight, fan, line_motion> sim(lambert({.mu_db = {-60.0, -6.0}}), straight{}, fan{}, motion_at(10.0));
    // The straight line heads north: starboard is east (+x).
    const auto lines = sim.ping(sc, 0);
    const double spacing = 0.1;
    const auto ground = sss::to_ground_range(lines.starboard, sim.dt_s(), 1500.0, 10.0, spacing, 500);
    const auto peak = static_cast<std::size_t>(std::max_element(ground.begin(), ground.end()) - ground.begin());
    // The sphere's nearest point to the towfish, at slant range |C - S| - a, has flat-bottom ground range:
    const double slant = std::sqrt(30.0 * 30.0 + 9.9 * 9.9) - 0.1;
    const double expected = std::sqrt(slant * slant - 100.0) / spacing;
    MESSAGE("highlight in ground pixel " << peak << ", expected " << expected);
    CHECK(std::abs(double(peak) - std::floor(expected)) <= 1.0);
    // The water column is gone: pixel 0 is nadir, and the first bottom return gives the altitude.
    // (A fan that reaches nadir: 0 to 90 degrees of depression.)
    const sss::simulator<lambert, straight, fan, line_motion> down(
        lambert{}, straight{}, fan(sss::beam::ideal_fan_params<double>{.vertical_width_deg = 90.0, .depression_deg = 45.0}), motion_at(10.0));
    const auto altitude = sss::first_return_altitude(down.ping(flat_seabed<double>(0.0), 0).starboard, down.dt_s(), 1500.0);
    REQUIRE(altitude);
    CHECK(*altitude == doctest::Approx(10.0).epsilon(0.01));
}

TEST_CASE("a compressed chirp's echoes lie at their ranges: the matched filter's delay is out of the line") {
    using sss::scene::flat_seabed;
    using sss::scene::object;
    using sss::scene::object_set;
    using sss::scene::sphere;
    // The sphere of the test above, and the fan reaching nadir, under a 5 ms chirp of 20 kHz (c T / 2 = 3.75 m, the
    // offset its filter's delay would leave; c / (2B) = 3.75 cm) sampled at 40 kHz.
    sss::receiver_params rx;
    rx.sample_rate_hz = 40000.0;
    rx.pulse = sss::pulse{.length_s = 5e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 20e3};
    std::vector<object<double>> objs{object<double>({sphere<double>(sss::vec3<double>{30.0, 0.0, 0.1}, 0.1, {.material = 1, .object = 1})}, {})};
    const sss::scene::scene sc(flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
    const sss::simulator<lambert, straight, fan, line_motion> sim(lambert({.mu_db = {-60.0, -6.0}}), straight{}, fan{},
                                                                  motion_at(10.0), rx);
    const auto lines = sim.ping(sc, 0);
    const auto peak = static_cast<std::size_t>(std::max_element(lines.starboard.begin(), lines.starboard.end()) -
                                               lines.starboard.begin());
    // The sphere's nearest point at slant |C - S| - a: its compressed peak in the sample holding 2 r / c.
    const double slant = std::sqrt(30.0 * 30.0 + 9.9 * 9.9) - 0.1;
    const double expected = 2.0 * slant / 1500.0 / sim.dt_s();
    MESSAGE("chirp highlight in sample " << peak << ", expected " << expected);
    CHECK(std::abs(double(peak) - expected) <= 2.0);
    // The first bottom return gives the altitude, as under a burst.
    const sss::simulator<lambert, straight, fan, line_motion> down(
        lambert{}, straight{}, fan(sss::beam::ideal_fan_params<double>{.vertical_width_deg = 90.0, .depression_deg = 45.0}),
        motion_at(10.0), rx);
    const auto altitude = sss::first_return_altitude(down.ping(flat_seabed<double>(0.0), 0).starboard, down.dt_s(), 1500.0);
    REQUIRE(altitude);
    CHECK(*altitude == doctest::Approx(10.0).epsilon(0.01));
}

TEST_CASE("quantisation: 8, 16, 32 and 64 bits round gain x amplitude, clip at full scale, and keep order") {
    const std::vector<double> power{0.0, 1.0, 4.0, 100.0, 1e6, 2.25};
    const auto q8 = sss::quantise<std::uint8_t>(std::span<const double>(power), sss::quantise_params{.gain = 10.0});
    CHECK(q8 == std::vector<std::uint8_t>{0, 10, 20, 100, 255, 15});
    const auto q16 = sss::quantise<std::uint16_t>(std::span<const double>(power), sss::quantise_params{.gain = 10.0});
    CHECK(q16[4] == 10000);
    const auto qi = sss::quantise<std::uint16_t>(std::span<const double>(power), sss::quantise_params{.gain = 100.0, .amplitude = false});
    CHECK(qi[3] == 10000);
    CHECK(qi[4] == 65535);
    // A gain chosen for a reference power puts it at the chosen count.
    CHECK(sss::quantise<std::uint8_t>(std::span<const double>(power).subspan(3, 1),
                                      sss::quantise_params{.gain = sss::quantise_gain(100.0, 128.0)})[0] == 128);
    // 32 and 64 bits clip too: a 64-bit count saturates at the largest double below 2^64, which it can hold.
    const std::vector<double> huge{1e300};
    CHECK(sss::quantise<std::uint32_t>(std::span<const double>(huge), sss::quantise_params{})[0] == 4294967295u);
    CHECK(sss::quantise<std::uint64_t>(std::span<const double>(huge), sss::quantise_params{})[0] ==
          18446744073709549568ull);
}
