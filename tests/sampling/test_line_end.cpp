// The last samples of a line hold what a render at sixteen times the rays puts there: the far edge of coverage (the
// last ray that returns within the line beside one that returns after it) is located as any edge is, in refracting
// water, where the launch angles' spacing (made for straight rays) leaves the last rays short of the line's end, and
// in straight water alike.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include <sss/sss.hpp>

namespace {

using T = float;

// The last samples of the starboard line over a flat Lambertian seabed, 10 m below a towfish with an ideal fan,
// at the default density and at 16 rays per sample, in the water `w`.
template <class Water> void check_line_end(const Water& w, double max_range_m) {
    const sss::scattering::lambertian<T> lambert(T(-27));
    const sss::beam::ideal_fan<T> fan({.along_width_deg = T(0.5), .vertical_width_deg = T(60), .depression_deg = T(20)});
    const sss::motion::straight_line<T> tow({.altitude_m = T(10)});
    sss::receiver_params rx;
    rx.sample_rate_hz = 20000;
    rx.max_range_m = max_range_m;
    rx.pulse = {1e-4, sss::pulse_shape::rectangular};
    using sim_t = sss::simulator<sss::scattering::lambertian<T>, Water, sss::beam::ideal_fan<T>, sss::motion::straight_line<T>>;
    const sim_t plain(lambert, w, fan, tow, rx, sss::ray_density{});
    const sim_t dense(lambert, w, fan, tow, rx, sss::ray_density{.per_sample = 16});
    const sss::scene::flat_seabed<T> bed(T(0));
    const auto a = plain.ping(bed, 0), b = dense.ping(bed, 0);
    const std::size_t n = a.starboard.size();
    REQUIRE(n > 8);
    for (std::size_t k = n - 6; k < n; ++k) {
        CAPTURE(k);
        CAPTURE(n);
        REQUIRE(b.starboard[k] > 0.0f);
        CHECK(std::abs(double(a.starboard[k]) / double(b.starboard[k]) - 1.0) < 0.01);
    }
}

} // namespace

TEST_CASE("in a thermocline, a line's last samples are within 1 % of a render at sixteen times the rays") {
    // 1520 m/s down to 32 m, 1470 m/s from 33 m: the towfish at 30 m depth, the seabed at 40 m. Before the far edge
    // was located, the second-to-last sample of the 100 m line was 29 % high and the last 9 % low, the last of the
    // 57.3 m line 5 % high.
    sss::propagation::layered_params<T> p;
    p.surface_z_m = T(40);
    p.frequency_hz = T(100000);
    const sss::propagation::layered<T> water(
        sss::propagation::sound_speed_profile<T>({T(0), T(32), T(33), T(200)}, {T(1520), T(1520), T(1470), T(1472.6)}), p);
    for (const double range_m : {100.0, 80.0, 57.3, 45.1}) {
        CAPTURE(range_m);
        check_line_end(water, range_m);
    }
}

TEST_CASE("in straight water, a line's last samples are within 1 % of a render at sixteen times the rays") {
    const sss::propagation::straight<T> water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    for (const double range_m : {100.0, 57.3, 45.1}) {
        CAPTURE(range_m);
        check_line_end(water, range_m);
    }
}
