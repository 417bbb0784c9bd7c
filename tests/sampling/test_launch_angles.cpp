// Launch angles are spaced evenly in nominal slant range (hence return time) for any attitude, start exactly on the
// beam's edges, refine towards a range minimum, and cover only what can be reached within the maximum range.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <sss/beam/concept.hpp>
#include <sss/core/pose.hpp>
#include <sss/sampling/launch_angles.hpp>

namespace {
const double deg = 3.141592653589793 / 180.0;

// Nominal slant range to the plane H below for a launch (along, e) on side s under rotation R.
double nominal_range(const sss::mat3<double>& R, sss::side s, double along, double e, double H) {
    const auto d = R * sss::beam_direction(s, along, e);
    return H / -d.z;
}
} // namespace

TEST_CASE("level towfish: depression angles are spaced evenly in nominal slant range from the beam's upper edge") {
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.3);
    std::vector<double> e;
    sss::column_density d;
    d.rays_per_m = 10;
    sss::depression_angles(e, sss::side::starboard, 0.004, -5 * deg, 45 * deg, R, 10.0, 10.0, 50.0, d);
    REQUIRE(e.size() > 100);
    CHECK(e.front() == 45 * deg);
    CHECK(nominal_range(R, sss::side::starboard, 0.004, e.back(), 10.0) == doctest::Approx(50.0).epsilon(1e-9));
    const double step = nominal_range(R, sss::side::starboard, 0.004, e[1], 10.0) - nominal_range(R, sss::side::starboard, 0.004, e[0], 10.0);
    CHECK(step == doctest::Approx(0.1).epsilon(0.02));
    for (std::size_t i = 1; i < e.size(); ++i) {
        CHECK(e[i] < e[i - 1]);
        const double dr = nominal_range(R, sss::side::starboard, 0.004, e[i], 10.0) - nominal_range(R, sss::side::starboard, 0.004, e[i - 1], 10.0);
        CHECK(dr == doctest::Approx(step).epsilon(1e-6));
    }
}

TEST_CASE("rolled and pitched towfish: spacing stays even in range and both branches around nadir are covered") {
    const auto R = sss::body_to_world_rotation(12 * deg, -4 * deg, 1.0);
    for (sss::side s : {sss::side::port, sss::side::starboard}) {
        std::vector<double> e;
        sss::column_density d;
        d.rays_per_m = 20;
        sss::depression_angles(e, s, 0.0, 0.0, 90 * deg, R, 8.0, 8.0, 30.0, d);
        REQUIRE(e.size() > 100);
        std::size_t runs = 1;
        double r_min = 1e9;
        for (std::size_t i = 0; i < e.size(); ++i) {
            if (std::isnan(e[i])) { ++runs; continue; }
            r_min = std::min(r_min, nominal_range(R, s, 0.0, e[i], 8.0));
            CHECK(nominal_range(R, s, 0.0, e[i], 8.0) <= 30.0 * (1 + 1e-9));
        }
        CHECK(runs == 1); // the pieces either side of the range minimum join into one run
        // Rolled 12 degrees starboard down, the starboard column holds the direction closest to the vertical that
        // its plane allows: pitched 4 degrees, that is H / cos(4 deg) away.
        if (s == sss::side::starboard) CHECK(r_min == doctest::Approx(8.0 / std::cos(4 * deg)).epsilon(1e-9));
    }
}

TEST_CASE("the range minimum at nadir is refined geometrically: the first steps shrink by a factor of four") {
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    std::vector<double> e;
    sss::column_density d;
    d.rays_per_m = 10;
    sss::depression_angles(e, sss::side::port, 0.0, 0.0, 90 * deg, R, 10.0, 10.0, 40.0, d);
    const double r0 = nominal_range(R, sss::side::port, 0.0, e[0], 10.0);
    CHECK(r0 == doctest::Approx(10.0));
    const double d1 = nominal_range(R, sss::side::port, 0.0, e[1], 10.0) - r0;
    const double d2 = nominal_range(R, sss::side::port, 0.0, e[2], 10.0) - r0;
    CHECK(d2 / d1 == doctest::Approx(4.0).epsilon(1e-3));
}

TEST_CASE("nothing is launched where nothing can be reached, and a towfish not above the scene falls back to even angles") {
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    std::vector<double> e;
    sss::column_density d;
    d.rays = 50;
    sss::depression_angles(e, sss::side::starboard, 0.0, -40 * deg, -10 * deg, R, 10.0, 10.0, 100.0, d);
    CHECK(e.empty());
    sss::depression_angles(e, sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, 30.0, 30.0, 20.0, d);
    CHECK(e.empty()); // the altitude exceeds the range
    sss::depression_angles(e, sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, 10.0, -1.0, 50.0, d);
    REQUIRE(e.size() == 52);
    CHECK(e.front() == doctest::Approx(30 * deg));
    CHECK(e.back() == doctest::Approx(10 * deg));
}
