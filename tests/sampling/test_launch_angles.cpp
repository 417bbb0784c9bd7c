// Launch angles are spaced evenly in nominal slant range (hence return time) for any attitude, start exactly on the
// beam's edges, refine towards a range minimum, and cover only what can be reached within the maximum range.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/matrix.hpp>

#include <sss/beam/concept.hpp>
#include <sss/core/pose.hpp>
#include <sss/sampling/launch_angles.hpp>
#include <sss/scene/sloping_plane.hpp>

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
    CHECK(step == doctest::Approx(0.1).epsilon(0.02).scale(0));
    for (std::size_t i = 1; i < e.size(); ++i) {
        CHECK(e[i] < e[i - 1]);
        const double dr = nominal_range(R, sss::side::starboard, 0.004, e[i], 10.0) - nominal_range(R, sss::side::starboard, 0.004, e[i - 1], 10.0);
        CHECK(dr == doctest::Approx(step).epsilon(1e-6).scale(0));
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

TEST_CASE("with no seabed under the towfish (an infinite altitude) or an endless range, the angles are even and as many "
          "as the budget allows") {
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> e;
    sss::column_density d;
    d.rays_per_m = 2.0;
    d.max_rays = 300;
    // Objects 30 m below, nothing else: 2 rays per metre of the 100 m range, evenly over the column.
    sss::depression_angles(e, sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, inf, 30.0, 100.0, d);
    REQUIRE(e.size() == 202);
    CHECK(e.front() == doctest::Approx(30 * deg));
    CHECK(e.back() == doctest::Approx(10 * deg));
    CHECK(sss::launch_span_m(sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, sss::nominal_seabed{.altitude_m = inf,
                                                                                                    .clearance_m = 30.0},
                             100.0) == 100.0);
    // An endless range: the budget, not an overflow.
    sss::depression_angles(e, sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, inf, 30.0, inf, d);
    CHECK(e.size() == 300);
    sss::depression_angles(e, sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, 10.0, 10.0, inf, d);
    CHECK(e.size() == 300);
    CHECK(std::all_of(e.begin(), e.end(), [](double x) { return std::isfinite(x); }));
}

TEST_CASE("a column's pieces share its ray budget: a column across nadir, with its steps capped, launches max_rays") {
    std::vector<double> e;
    sss::column_density d;
    d.rays_per_m = 1000;
    d.max_rays = 1000;
    for (const double roll_deg : {0.0, 15.0})
        for (const double altitude_m : {10.0, 0.05})
            for (const double step_deg : {0.0, 0.5}) {
                CAPTURE(roll_deg);
                CAPTURE(altitude_m);
                CAPTURE(step_deg);
                d.max_step_rad = step_deg * deg;
                const auto R = sss::body_to_world_rotation(roll_deg * deg, 0.0, 0.0);
                sss::depression_angles(e, sss::side::starboard, 0.0, 0.0, 120 * deg, R, altitude_m, altitude_m, 50.0, d);
                CHECK(e.size() >= 100);
                CHECK(e.size() <= 1000);
            }
}

TEST_CASE("close to the seabed no step between launch angles exceeds the cap, and every angle spaced in range is kept") {
    // 1 mm above a level seabed, a 20 to 60 degree fan returns within 2 mm of range: spaced evenly in range, its
    // rays are the fan's two edges.
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    sss::column_density d;
    d.rays_per_m = 27.3; // one ray per 0.0366 m: 2048 samples over 75 m
    d.max_range_step = 0.0; // the angle's cap alone
    std::vector<double> plain, capped;
    sss::depression_angles(plain, sss::side::starboard, 0.0, 20 * deg, 60 * deg, R, 0.001, 0.001, 75.0, d);
    REQUIRE(plain.size() >= 2);
    double widest = 0.0;
    for (std::size_t i = 1; i < plain.size(); ++i) widest = std::max(widest, plain[i - 1] - plain[i]);
    CHECK(widest > 30 * deg);
    d.max_step_rad = 1 * deg;
    sss::depression_angles(capped, sss::side::starboard, 0.0, 20 * deg, 60 * deg, R, 0.001, 0.001, 75.0, d);
    CHECK(capped.size() >= plain.size() + 38); // the fan's 40 degrees in steps of at most 1
    CHECK(capped.size() <= plain.size() + 40);
    for (std::size_t i = 1; i < capped.size(); ++i) {
        CHECK(capped[i] < capped[i - 1]);
        CHECK(capped[i - 1] - capped[i] <= 1 * deg * (1 + 1e-12));
    }
    std::size_t kept = 0;
    for (double e : plain) kept += std::count(capped.begin(), capped.end(), e) == 1 ? 1 : 0;
    CHECK(kept == plain.size());
    // A cap wider than every step changes nothing, bit for bit.
    std::vector<double> wide;
    d.max_step_rad = 50 * deg;
    sss::depression_angles(wide, sss::side::starboard, 0.0, 20 * deg, 60 * deg, R, 10.0, 10.0, 75.0, d);
    d.max_step_rad = 0.0;
    sss::depression_angles(plain, sss::side::starboard, 0.0, 20 * deg, 60 * deg, R, 10.0, 10.0, 75.0, d);
    CHECK(wide == plain);
    // A cap finer than the column's ray budget allows is widened to fit it.
    d.max_step_rad = 1e-9;
    d.max_rays = 4096;
    sss::depression_angles(capped, sss::side::starboard, 0.0, 20 * deg, 60 * deg, R, 0.001, 0.001, 75.0, d);
    CHECK(capped.size() <= 4096);
    CHECK(capped.size() > 2048); // widened by factors of 2 from 1e-9: more than half the budget used
}

TEST_CASE("the step cap holds across nadir under a rolled towfish, and for the even angles of a towfish not above the scene") {
    // 5 cm up, rolled 10 degrees: the column passes the vertical, its two pieces either side of the range minimum join
    // into one run, and each piece's steps are capped.
    const auto R = sss::body_to_world_rotation(10 * deg, 0.0, 0.0);
    sss::column_density d;
    d.rays_per_m = 27.3;
    d.max_step_rad = 1 * deg;
    for (sss::side s : {sss::side::port, sss::side::starboard}) {
        std::vector<double> e;
        sss::depression_angles(e, s, 0.0, 0.0, 90 * deg, R, 0.05, 0.05, 75.0, d);
        REQUIRE(e.size() > 100);
        CHECK(std::count_if(e.begin(), e.end(), [](double x) { return std::isnan(x); }) == 0);
        for (std::size_t i = 1; i < e.size(); ++i) {
            CHECK(e[i] < e[i - 1]);
            CHECK(e[i - 1] - e[i] <= 1 * deg * (1 + 1e-12));
        }
    }
    // Not above the scene: 11 even angles asked over 20 degrees, 21 given.
    std::vector<double> e;
    sss::column_density few;
    few.rays = 9;
    few.max_step_rad = 1 * deg;
    sss::depression_angles(e, sss::side::starboard, 0.0, 10 * deg, 30 * deg, R, 10.0, -1.0, 50.0, few);
    REQUIRE(e.size() == 21);
    for (std::size_t i = 1; i < e.size(); ++i) CHECK(e[i - 1] - e[i] <= 1 * deg * (1 + 1e-12));
}

TEST_CASE("close to the seabed no step in nominal range exceeds a twentieth of the range, and the even ranges are kept") {
    // 1 cm up, 0.0366 m steps: near nadir one step is several times the range.
    const auto R = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    sss::column_density d;
    d.rays_per_m = 27.3;
    std::vector<double> e, plain;
    sss::depression_angles(e, sss::side::starboard, 0.0, 0.0, 90 * deg, R, 0.01, 0.01, 75.0, d);
    d.max_range_step = 0.0;
    sss::depression_angles(plain, sss::side::starboard, 0.0, 0.0, 90 * deg, R, 0.01, 0.01, 75.0, d);
    REQUIRE(e.size() > plain.size());
    CHECK(e.size() < plain.size() + 200);
    for (std::size_t i = 1; i < e.size(); ++i) {
        REQUIRE(e[i] < e[i - 1]);
        const double r0 = nominal_range(R, sss::side::starboard, 0.0, e[i - 1], 0.01);
        const double r1 = nominal_range(R, sss::side::starboard, 0.0, e[i], 0.01);
        CHECK(r1 - r0 <= 0.05 * r0 * (1 + 1e-6));
    }
    std::size_t kept = 0;
    for (double a : plain) kept += std::count(e.begin(), e.end(), a) == 1 ? 1 : 0;
    CHECK(kept == plain.size());
    // 10 m up nothing changes.
    std::vector<double> high, high_plain;
    sss::depression_angles(high_plain, sss::side::starboard, 0.0, 0.0, 90 * deg, R, 10.0, 10.0, 75.0, d);
    d.max_range_step = 0.05;
    sss::depression_angles(high, sss::side::starboard, 0.0, 0.0, 90 * deg, R, 10.0, 10.0, 75.0, d);
    CHECK(high == high_plain);
}

namespace {
// Nominal slant range to the plane of unit upward normal n at distance H from the towfish.
double range_to_plane(const sss::mat3<double>& R, sss::side s, double along, double e, const sss::vec3<double>& n, double H) {
    const auto d = R * sss::beam_direction(s, along, e);
    return H / -(d.x * n.x + d.y * n.y + d.z * n.z);
}
} // namespace

TEST_CASE("over a sloping plane the depression angles are spaced evenly in slant range to that plane, out to where a ray "
          "comes within the clearance of it at the longest range") {
    const auto R = sss::body_to_world_rotation(6 * deg, 4 * deg, 0.7);
    const sss::scene::sloping_plane plane{.gradient = {0.15, -0.075}};
    const sss::vec3<double> n = plane.up();
    for (sss::side s : {sss::side::port, sss::side::starboard}) {
        CAPTURE(s == sss::side::port ? "port" : "starboard");
        const sss::nominal_seabed nominal{.up = n, .altitude_m = 10.0, .clearance_m = 9.0};
        std::vector<double> e;
        sss::column_density d;
        d.rays_per_m = 10;
        d.max_range_step = 0.0;
        // Up to 60 degrees of depression: the plane's nearest point, some 8 degrees from the vertical, is not in it.
        sss::depression_angles(e, s, 0.01, 0.0, 60 * deg, R, nominal, 30.0, d);
        REQUIRE(e.size() > 50);
        CHECK(std::count_if(e.begin(), e.end(), [](double x) { return std::isnan(x); }) == 0);
        CHECK(e.front() == 60 * deg);
        std::vector<double> r(e.size());
        for (std::size_t i = 0; i < e.size(); ++i) r[i] = range_to_plane(R, s, 0.01, e[i], n, 10.0);
        const double step = r[1] - r[0];
        CHECK(step == doctest::Approx(0.1).epsilon(0.05).scale(0));
        for (std::size_t i = 1; i < r.size(); ++i) CHECK(r[i] - r[i - 1] == doctest::Approx(step).epsilon(1e-6).scale(0));
        // The last ray's straight line comes down to the clearance (1 m above the plane) at the longest range, 30 m.
        CHECK(r.back() * 9.0 / 10.0 == doctest::Approx(30.0).epsilon(1e-9));
        // What it spans is what launch_span_m says: the rays launched over it are rays_per_m to the metre.
        const double span = sss::launch_span_m(s, 0.01, 0.0, 60 * deg, R, nominal, 30.0);
        CHECK(span == doctest::Approx(r.back() - r.front()).epsilon(1e-9));
        CHECK(double(e.size()) == doctest::Approx(10 * span).epsilon(0.02));
    }
}

TEST_CASE("launching for a tilted plane is launching for the level seabed with the world tilted to put that plane level, "
          "and a towfish not above the scene spans the longest range") {
    // The plane of normal n = W^T z under the body rotation R is the level plane under W R, W a rotation of the world:
    // the same angles to rounding.
    const auto R = sss::body_to_world_rotation(12 * deg, -4 * deg, 1.0);
    const sss::mat3<double> W = sss::body_to_world_rotation(-5 * deg, 8 * deg, 0.3) *
                                glm::transpose(sss::body_to_world_rotation(0.0, 0.0, 0.0));
    const sss::vec3<double> n = glm::transpose(W) * sss::vec3<double>{0.0, 0.0, 1.0};
    REQUIRE(n.z == doctest::Approx(std::cos(5 * deg) * std::cos(8 * deg)));
    sss::column_density d;
    d.rays_per_m = 20;
    for (sss::side s : {sss::side::port, sss::side::starboard}) {
        CAPTURE(s == sss::side::port ? "port" : "starboard");
        std::vector<double> level, plane;
        sss::depression_angles(level, s, 0.003, 0.0, 90 * deg, sss::mat3<double>(W * R), 8.0, 7.5, 30.0, d);
        sss::depression_angles(plane, s, 0.003, 0.0, 90 * deg, R,
                               sss::nominal_seabed{.up = n, .altitude_m = 8.0, .clearance_m = 7.5}, 30.0, d);
        REQUIRE(level.size() > 100);
        REQUIRE(plane.size() == level.size());
        for (std::size_t i = 0; i < level.size(); ++i) {
            if (std::isnan(level[i])) {
                CHECK(std::isnan(plane[i]));
                continue;
            }
            CHECK(plane[i] == doctest::Approx(level[i]).epsilon(1e-10));
        }
    }
    CHECK(sss::launch_span_m(sss::side::starboard, 0.0, 10 * deg, 30 * deg, R,
                             sss::nominal_seabed{.altitude_m = 10.0, .clearance_m = -1.0}, 50.0) == 50.0);
}
