// The sampled trajectory: orientation derived from the path, interpolation, heave and sway, ping timing.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/motion/trajectory.hpp"

namespace {

using sss::motion::interpolation;
using sss::motion::trajectory;
using sss::motion::trajectory_params;
using sss::motion::trajectory_samples;

constexpr double pi = sss::pi_v<double>;

/// Angle difference wrapped to (-pi, pi].
double angle_diff(double a, double b) { return std::remainder(a - b, 2.0 * pi); }

/// Samples one per second on a circle of radius r around (cx, cy), traversed clockwise seen from above (a turn
/// to starboard) with heading psi_i = psi0 + i dpsi, climbing `climb_m` per sample.
template <class T>
trajectory_samples<T> circle(std::size_t n, double r, double dpsi, double climb_m = 0.0, double psi0 = 0.3) {
    trajectory_samples<T> s;
    for (std::size_t i = 0; i < n; ++i) {
        const double psi = psi0 + static_cast<double>(i) * dpsi;
        s.time_s.push_back(static_cast<double>(i));
        // Clockwise: position = centre - r (cos psi, -sin psi), the starboard unit vector pointing at the centre.
        s.position_m.push_back(sss::vec3<T>{static_cast<T>(40.0 - r * std::cos(psi)), static_cast<T>(-20.0 + r * std::sin(psi)),
                                            static_cast<T>(30.0 + climb_m * static_cast<double>(i))});
    }
    return s;
}

} // namespace

TEST_CASE_TEMPLATE("On a circle turned to starboard the derived yaw follows the tangent and the starboard axis "
                   "points at the centre", T, float, double) {
    const double r = 50.0, dpsi = sss::deg_to_rad(2.0);
    const std::size_t n = 40;
    for (interpolation method : {interpolation::cubic, interpolation::linear}) {
        trajectory_params<T> p;
        p.ping_interval_s = T(0.25); // four pings per sample
        p.method = method;
        const trajectory<T> traj(circle<T>(n, r, dpsi), p);
        REQUIRE(traj.ping_count() == 4 * (n - 1) + 1);
        const double tol_sample = std::is_same_v<T, float> ? 2e-5 : 1e-9;
        double prev_yaw = -1.0;
        // The end samples use one-sided slopes, and the cubic's slopes at samples 1 and n - 2 see them: skip
        // the two end segments.
        for (std::size_t ping = 8; ping + 8 < traj.ping_count(); ++ping) {
            const sss::pose<T> q = traj.pose_at(ping);
            const double t = static_cast<double>(q.time_s);
            const double psi = 0.3 + t * dpsi;
            // At samples the three-point slope of a uniformly sampled circle is exactly tangent; between them
            // the yaw samples (linear in time) are interpolated exactly by both methods.
            CHECK(std::abs(angle_diff(static_cast<double>(q.yaw_rad), psi)) < tol_sample);
            if (prev_yaw >= 0.0) CHECK(angle_diff(static_cast<double>(q.yaw_rad), prev_yaw) > 0.0); // turning right
            prev_yaw = static_cast<double>(q.yaw_rad);
            const sss::vec3<T> starboard = q.to_world(sss::vec3<T>{T(0), T(1), T(0)});
            const double to_cx = (40.0 - static_cast<double>(q.position.x)) / r, to_cy = (-20.0 - static_cast<double>(q.position.y)) / r;
            CHECK(static_cast<double>(starboard.x) == doctest::Approx(to_cx).epsilon(1e-3).scale(1.0));
            CHECK(static_cast<double>(starboard.y) == doctest::Approx(to_cy).epsilon(1e-3).scale(1.0));
            CHECK(static_cast<double>(q.pitch_rad) == doctest::Approx(0.0).scale(1.0).epsilon(1e-6));
            CHECK(static_cast<double>(q.roll_rad) == 0.0);
        }
        // Near the ends the one-sided parabola is second order: the yaw error stays below dpsi^2.
        for (std::size_t ping : {std::size_t{0}, traj.ping_count() - 1}) {
            const sss::pose<T> q = traj.pose_at(ping);
            CHECK(std::abs(angle_diff(static_cast<double>(q.yaw_rad), 0.3 + static_cast<double>(q.time_s) * dpsi)) < dpsi * dpsi);
        }
    }
}

TEST_CASE("Cubic interpolation stays on the circle between samples; linear cuts the chords") {
    const double r = 50.0, dpsi = sss::deg_to_rad(5.0);
    trajectory_params<double> p;
    p.ping_interval_s = 0.1;
    const trajectory<double> cubic(circle<double>(30, r, dpsi), p);
    p.method = interpolation::linear;
    const trajectory<double> linear(circle<double>(30, r, dpsi), p);
    double cubic_err = 0.0, linear_err = 0.0;
    for (std::size_t ping = 10; ping + 10 < cubic.ping_count(); ++ping) {
        const auto radius = [](const sss::pose<double>& q) { return std::hypot(q.position.x - 40.0, q.position.y + 20.0); };
        cubic_err = std::max(cubic_err, std::abs(radius(cubic.pose_at(ping)) - r));
        linear_err = std::max(linear_err, std::abs(radius(linear.pose_at(ping)) - r));
    }
    // Chord sagitta r (1 - cos(dpsi / 2)) = 4.8 cm for linear; the Hermite cubic is far closer.
    CHECK(linear_err == doctest::Approx(r * (1.0 - std::cos(dpsi / 2.0))).epsilon(1e-6));
    CHECK(cubic_err < 0.01 * linear_err);
    MESSAGE("largest radius error: cubic " << cubic_err << " m, linear " << linear_err << " m");
}

TEST_CASE("On a helix the derived pitch is the climb angle") {
    const double r = 40.0, dpsi = sss::deg_to_rad(2.0), climb = 0.3; // metres per sample (per second)
    trajectory_params<double> p;
    p.ping_interval_s = 0.5;
    const trajectory<double> traj(circle<double>(50, r, dpsi, climb), p);
    const double expected = std::atan2(climb, r * dpsi); // rise over horizontal arc per second
    for (std::size_t ping = 2; ping + 2 < traj.ping_count(); ++ping) {
        const double pitch = traj.pose_at(ping).pitch_rad;
        // The three-point slope sees the chord, r sin(dpsi) / dpsi of the arc: relative error dpsi^2 / 6.
        CHECK(pitch == doctest::Approx(expected).epsilon(dpsi * dpsi / 6.0 * 1.1));
    }
    CHECK(expected > 0.1); // a real climb, bow up
}

TEST_CASE("A coordinated-turn roll banks starboard down in a starboard turn by atan(V r / g)") {
    const double r = 30.0, dpsi = sss::deg_to_rad(4.0);
    trajectory_params<double> p;
    p.ping_interval_s = 1.0;
    p.roll_from_turn = true;
    const trajectory<double> traj(circle<double>(20, r, dpsi), p);
    const double speed = r * std::sin(dpsi) / 1.0; // the three-point slope's speed: chord over two seconds
    const double expected = std::atan(speed * dpsi / 9.80665);
    for (std::size_t ping = 2; ping + 2 < traj.ping_count(); ++ping)
        CHECK(traj.pose_at(ping).roll_rad == doctest::Approx(expected).epsilon(1e-9));
    // Mirror the circle (a port turn): the roll changes sign.
    trajectory_samples<double> s = circle<double>(20, r, dpsi);
    for (auto& q : s.position_m) q.x = -q.x;
    const trajectory<double> port(s, p);
    CHECK(port.pose_at(8).roll_rad == doctest::Approx(-expected).epsilon(1e-9));
}

TEST_CASE("Interpolation reproduces the samples, per-ping keys included") {
    trajectory_samples<double> s;
    s.ping = {0, 3, 4, 9, 10, 15};
    s.position_m = {{0, 0, 5}, {1, 2, 5.5}, {1.5, 2.5, 5.2}, {4, 6, 6}, {4.2, 7, 6.1}, {8, 9, 5}};
    s.yaw_rad = {0.1, 0.2, 6.2, 0.05, 3.0, -3.0};
    s.pitch_rad = {0.01, -0.02, 0.03, 0.0, 0.1, -0.1};
    s.roll_rad = {0.0, 0.05, -0.05, 0.2, -0.2, 0.3};
    s.heave_m = {0.0, 0.1, -0.1, 0.2, 0.0, 0.3};
    s.sway_m = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (interpolation method : {interpolation::cubic, interpolation::linear}) {
        trajectory_params<double> p;
        p.method = method;
        p.ping_interval_s = 0.2;
        const trajectory<double> traj(s, p);
        CHECK(traj.keyed_by_ping());
        CHECK(traj.ping_count() == 16);
        for (std::size_t i = 0; i < s.ping.size(); ++i) {
            const auto q = traj.pose_at(static_cast<std::size_t>(s.ping[i]));
            CHECK(q.position.x == doctest::Approx(s.position_m[i].x).epsilon(1e-13));
            CHECK(q.position.y == doctest::Approx(s.position_m[i].y).epsilon(1e-13));
            CHECK(q.position.z == doctest::Approx(s.position_m[i].z + s.heave_m[i]).epsilon(1e-13));
            CHECK(std::abs(angle_diff(q.yaw_rad, s.yaw_rad[i])) < 1e-13);
            CHECK(q.pitch_rad == doctest::Approx(s.pitch_rad[i]).epsilon(1e-13));
            CHECK(q.roll_rad == doctest::Approx(s.roll_rad[i]).epsilon(1e-13));
            CHECK(q.time_s == doctest::Approx(s.ping[i] * 0.2));
            CHECK(q.yaw_rad >= 0.0);
            CHECK(q.yaw_rad < 2.0 * pi);
        }
    }
}

TEST_CASE("Cubic interpolation is exact on a quadratic path; linear on a straight one") {
    const auto f = [](double t) { return sss::vec3<double>{1.0 + 2.0 * t - 0.3 * t * t, -4.0 + 0.5 * t * t, 10.0 - 0.1 * t}; };
    trajectory_samples<double> s;
    for (double t : {0.0, 0.7, 1.0, 2.5, 2.6, 4.0, 5.9}) {
        s.time_s.push_back(t);
        s.position_m.push_back(f(t));
    }
    trajectory_params<double> p;
    p.ping_interval_s = 0.05;
    const trajectory<double> traj(s, p);
    for (std::size_t ping = 0; ping < traj.ping_count(); ++ping) {
        const auto q = traj.pose_at(ping);
        const auto e = f(0.05 * static_cast<double>(ping));
        CHECK(q.position.x == doctest::Approx(e.x).epsilon(1e-12));
        CHECK(q.position.y == doctest::Approx(e.y).epsilon(1e-12));
        CHECK(q.position.z == doctest::Approx(e.z).epsilon(1e-12));
    }
    // Linear: on the chord between the samples at 1.0 s and 2.5 s, in proportion to time.
    p.method = sss::motion::interpolation::linear;
    const trajectory<double> lin(s, p);
    const auto mid = lin.pose_at(33); // t = 1.65 s
    const double w = (1.65 - 1.0) / 1.5;
    CHECK(mid.position.x == doctest::Approx(f(1.0).x + w * (f(2.5).x - f(1.0).x)).epsilon(1e-12));
}

TEST_CASE("Angles are interpolated along the shortest arc") {
    trajectory_samples<double> s;
    s.time_s = {0.0, 1.0, 2.0};
    s.position_m = {{0, 0, 5}, {0, 1, 5}, {0, 2, 5}};
    s.yaw_rad = {sss::deg_to_rad(350.0), sss::deg_to_rad(10.0), sss::deg_to_rad(30.0)};
    s.roll_rad = {sss::deg_to_rad(359.0), sss::deg_to_rad(1.0), sss::deg_to_rad(3.0)}; // a recorder's 0..360 roll
    trajectory_params<double> p;
    p.method = interpolation::linear;
    p.ping_interval_s = 0.5;
    const trajectory<double> traj(s, p);
    const auto q = traj.pose_at(1); // t = 0.5
    CHECK(std::abs(angle_diff(q.yaw_rad, 0.0)) < 1e-12);
    CHECK(std::abs(angle_diff(q.roll_rad, 0.0)) < 1e-12);
    p.method = interpolation::cubic;
    const trajectory<double> cubic(s, p);
    CHECK(std::abs(angle_diff(cubic.pose_at(1).yaw_rad, 0.0)) < sss::deg_to_rad(1.0));
}

TEST_CASE_TEMPLATE("Interpolated roll and pitch stay within 90 degrees of level where a cubic overshoots samples near it",
                   T, float, double) {
    // Roll 0, 89, 89, 0 degrees: the cubic between the two 89s reaches about 100 degrees; pitch likewise, negative.
    trajectory_samples<T> s;
    s.time_s = {0.0, 1.0, 2.0, 3.0};
    s.position_m = {{0, 0, 10}, {0, 2, 10}, {0, 4, 10}, {0, 6, 10}};
    const T r = T(sss::deg_to_rad(89.0));
    s.roll_rad = {T(0), r, r, T(0)};
    s.pitch_rad = {T(0), -r, -r, T(0)};
    const trajectory<T> traj(s, {.ping_interval_s = T(0.05)});
    const double right = 0.5 * sss::pi_v<double>;
    double most_roll = 0, most_pitch = 0;
    for (std::size_t i = 0; i < traj.ping_count(); ++i) {
        const auto q = traj.pose_at(i);
        CHECK(std::abs(double(q.roll_rad)) < right);
        CHECK(std::abs(double(q.pitch_rad)) < right);
        most_roll = std::max(most_roll, double(q.roll_rad));
        most_pitch = std::min(most_pitch, double(q.pitch_rad));
    }
    CHECK(most_roll > sss::deg_to_rad(89.9)); // held at the limit, not bent back below the samples
    CHECK(most_pitch < -sss::deg_to_rad(89.9));
    // Samples within the limit come back as they are.
    CHECK(double(traj.pose_at(20).roll_rad) == doctest::Approx(double(r)));
}

TEST_CASE("Heave raises z and sway moves along the horizontal starboard direction") {
    trajectory_samples<double> s;
    s.time_s = {0.0, 10.0};
    s.position_m = {{0, 0, 8}, {20, 0, 8}}; // due east: starboard is south
    s.heave_m = {1.5, 1.5};
    s.sway_m = {2.0, 2.0};
    s.pitch_rad = {0.3, 0.3}; // bow up: sway stays horizontal all the same
    s.roll_rad = {0.2, 0.2};
    const trajectory<double> traj(s);
    const auto q = traj.pose_at(50); // t = 5 s
    CHECK(q.yaw_rad == doctest::Approx(pi / 2.0));
    CHECK(q.position.x == doctest::Approx(10.0));
    CHECK(q.position.y == doctest::Approx(-2.0));
    CHECK(q.position.z == doctest::Approx(9.5));
}

TEST_CASE("Pings map to time through the ping interval, from the first sample or a chosen origin") {
    trajectory_samples<double> s;
    s.time_s = {1.7e9, 1.7e9 + 4.0, 1.7e9 + 10.0}; // absolute times keep their resolution
    s.position_m = {{0, 0, 5}, {0, 4, 5}, {0, 10, 5}};
    trajectory_params<double> p;
    p.ping_interval_s = 0.1;
    const trajectory<double> traj(s, p);
    CHECK(traj.ping_count() == 101);
    CHECK(traj.start_time_s() == 1.7e9);
    const auto q = traj.pose_at(55);
    CHECK(q.time_s == doctest::Approx(5.5));
    CHECK(q.position.y == doctest::Approx(5.5).epsilon(1e-9));
    CHECK(q.yaw_rad == doctest::Approx(0.0).scale(1.0));
    CHECK_THROWS_AS((void)traj.pose_at(101), sss::invalid_parameter);
    p.ping_zero_at = 1.7e9 + 2.0;
    const trajectory<double> later(s, p);
    CHECK(later.ping_count() == 81);
    CHECK(later.pose_at(0).position.y == doctest::Approx(2.0).epsilon(1e-9));
    // A float ping interval (0.1f is not 0.1) still reaches the last sample.
    trajectory_samples<float> sf;
    sf.time_s = {0.0, 10.0};
    sf.position_m = {{0, 0, 5}, {0, 10, 5}};
    const trajectory<float> tf(sf, trajectory_params<float>{});
    CHECK(tf.ping_count() == 101);
    CHECK(static_cast<double>(tf.pose_at(100).position.y) == doctest::Approx(10.0));
}

TEST_CASE("Keyed by ping, the interpolated time increases across a gap in the record as at the samples") {
    // Samples every 10 pings, 0.1 s per ping, then a 98 s gap: the parabola's slope at ping 20 (4.95 s per ping)
    // made the cubic run back to -5.4 s between pings 10 and 20.
    trajectory_samples<double> s;
    s.ping = {0.0, 10.0, 20.0, 30.0};
    s.time_s = {0.0, 1.0, 2.0, 100.0};
    s.position_m = {{0, 0, 5}, {0, 1, 5}, {0, 2, 5}, {0, 100, 5}};
    const trajectory<double> traj(s, trajectory_params<double>{});
    REQUIRE(traj.ping_count() == 31);
    double worst_step = 1e300;
    for (std::size_t i = 1; i < traj.ping_count(); ++i)
        worst_step = std::min(worst_step, traj.time_since_ping0_s(i) - traj.time_since_ping0_s(i - 1));
    CHECK(worst_step > 0.0);
    CHECK(traj.time_since_ping0_s(20) == 2.0);
    CHECK(traj.time_since_ping0_s(30) == 100.0);
    for (std::size_t i = 10; i <= 20; ++i) { // between the samples' times, as the samples are
        CHECK(traj.time_since_ping0_s(i) >= 1.0);
        CHECK(traj.time_since_ping0_s(i) <= 2.0);
    }
}

TEST_CASE("A long float trajectory holds exactly the pings its samples span, none beyond their end") {
    // A tolerance relative to the span added a ping past 2^20 pings (9.7 hours at 30 pings per second).
    trajectory_samples<float> by_ping;
    by_ping.ping = {0.0, 1048575.0};
    by_ping.position_m = {{0, 0, 5}, {0, 1000, 5}};
    CHECK(trajectory<float>(by_ping, trajectory_params<float>{}).ping_count() == 1048576);
    trajectory_samples<float> by_time;
    by_time.time_s = {0.0, 250000.0};
    by_time.position_m = {{0, 0, 5}, {0, 1000, 5}};
    trajectory_params<float> p;
    p.ping_interval_s = 0.125f;
    CHECK(trajectory<float>(by_time, p).ping_count() == 2000001);
}

TEST_CASE("A float heading just short of 2 pi stays within [0, 2 pi) in float") {
    trajectory_samples<float> s;
    s.time_s = {0.0, 1.0, 2.0};
    s.position_m = {{0, 0, 5}, {0, 1, 5}, {0, 2, 5}};
    s.yaw_rad = {-1e-8f, -1e-8f, -1e-8f};
    const trajectory<float> traj(s, trajectory_params<float>{});
    for (std::size_t i = 0; i < traj.ping_count(); i += 5) {
        const float yaw = traj.pose_at(i).yaw_rad;
        CHECK(yaw >= 0.0f);
        CHECK(yaw < static_cast<float>(2.0 * pi));
    }
}

TEST_CASE("Malformed samples are rejected, naming the field") {
    const auto name_of = [](const trajectory_samples<double>& s, trajectory_params<double> p = {}) {
        try {
            trajectory<double> t(s, p);
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(none)");
    };
    trajectory_samples<double> s;
    s.time_s = {0.0, 1.0, 1.0};
    s.position_m = {{0, 0, 5}, {0, 1, 5}, {0, 2, 5}};
    CHECK(name_of(s) == "trajectory.time_s");
    s.time_s = {0.0, 1.0, 2.0};
    CHECK(name_of(s) == "(none)");
    s.yaw_rad = {0.0, 1.0};
    CHECK(name_of(s) == "trajectory.yaw_rad");
    s.yaw_rad.clear();
    s.heave_m = {0.0, std::nan(""), 0.0};
    CHECK(name_of(s) == "trajectory.heave_m");
    s.heave_m.clear();
    // Roll and pitch within 90 deg of level, modulo a turn: on its side or nose down is refused, 359 deg is -1 deg.
    s.roll_rad = {0.0, sss::deg_to_rad(95.0), 0.0};
    CHECK(name_of(s) == "trajectory.roll_rad");
    s.roll_rad = {sss::deg_to_rad(359.0), sss::deg_to_rad(-271.0), 0.0};
    CHECK(name_of(s) == "(none)");
    s.roll_rad.clear();
    s.pitch_rad = {0.0, 0.0, -0.5 * pi};
    CHECK(name_of(s) == "trajectory.pitch_rad");
    s.pitch_rad.clear();
    s.position_m.pop_back();
    CHECK(name_of(s) == "trajectory.position_m");
    s.position_m.push_back({0, 2, 5});
    trajectory_params<double> p;
    p.ping_interval_s = 0.0;
    CHECK(name_of(s, p) == "trajectory.ping_interval_s");
    p = {};
    p.ping_zero_at = 5.0;
    CHECK(name_of(s, p) == "trajectory.ping_zero_at");
    trajectory_samples<double> one;
    one.time_s = {0.0};
    one.position_m = {{0, 0, 5}};
    CHECK(name_of(one) == "trajectory.time_s");
}
