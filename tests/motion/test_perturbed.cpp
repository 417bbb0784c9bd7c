// The perturbed path: a straight line or constant-rate turn with sinusoidal yaw, sway, pitch, heave and roll.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/motion/perturbed.hpp"
#include "sss/motion/straight_line.hpp"

namespace {

using sss::motion::constant_turn;
using sss::motion::oscillation;
using sss::motion::perturbed;
using sss::motion::perturbed_params;

constexpr double pi = sss::pi_v<double>;

double angle_diff(double a, double b) { return std::remainder(a - b, 2.0 * pi); }

/// Amplitude (half the peak-to-peak), period (mean spacing of upward zero crossings) and value at t = 0 of
/// a sampled zero-mean signal.
struct fit {
    double amplitude, period, first;
};
fit measure(const std::vector<double>& x, double dt) {
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    std::vector<double> ups;
    for (std::size_t i = 1; i < x.size(); ++i)
        if (x[i - 1] < 0.0 && x[i] >= 0.0) ups.push_back(dt * (static_cast<double>(i - 1) + x[i - 1] / (x[i - 1] - x[i])));
    const double period = ups.size() >= 2 ? (ups.back() - ups.front()) / static_cast<double>(ups.size() - 1) : 0.0;
    return fit{0.5 * (*hi - *lo), period, x.front()};
}

perturbed_params<double> all_oscillations() {
    perturbed_params<double> p;
    p.heading_deg = 30.0;
    p.speed_mps = 2.5;
    p.altitude_m = 12.0;
    p.ping_interval_s = 0.01;
    p.yaw_deg = {3.0, 7.0, 30.0};
    p.sway_m = {1.5, 11.0, -45.0};
    p.pitch_deg = {2.0, 5.0, 90.0};
    p.heave_m = {0.5, 4.0, 0.0};
    p.roll_deg = {4.0, 3.0, 10.0};
    return p;
}

} // namespace

TEST_CASE("Without a turn or oscillations the perturbed path is the straight line") {
    perturbed_params<double> p;
    p.start_m = {5.0, -3.0};
    p.heading_deg = 123.0;
    p.speed_mps = 1.7;
    p.altitude_m = 8.0;
    const perturbed<double> path(p);
    const sss::motion::straight_line<double> line({.start_m = {5.0, -3.0}, .heading_deg = 123.0, .speed_mps = 1.7, .altitude_m = 8.0, .ping_interval_s = 0.1});
    for (std::size_t ping : {0u, 1u, 17u, 1000u}) {
        const auto a = path.pose_at(ping), b = line.pose_at(ping);
        CHECK(a.position.x == doctest::Approx(b.position.x).epsilon(1e-12));
        CHECK(a.position.y == doctest::Approx(b.position.y).epsilon(1e-12));
        CHECK(a.position.z == b.position.z);
        CHECK(a.yaw_rad == doctest::Approx(b.yaw_rad).epsilon(1e-14));
        CHECK(a.time_s == doctest::Approx(b.time_s));
    }
    CHECK(std::isinf(path.turn_radius_m()));
}

TEST_CASE("Amplitudes, periods and phases of every oscillation are recovered from the sampled poses") {
    for (bool together : {true, false}) {
        const perturbed_params<double> all = all_oscillations();
        struct channel {
            const char* name;
            oscillation<double> perturbed_params<double>::*member;
        };
        for (const channel c : {channel{"yaw", &perturbed_params<double>::yaw_deg}, channel{"sway", &perturbed_params<double>::sway_m},
                                channel{"pitch", &perturbed_params<double>::pitch_deg},
                                channel{"heave", &perturbed_params<double>::heave_m},
                                channel{"roll", &perturbed_params<double>::roll_deg}}) {
            // Together: all five at once. Separately: only this one, the others must stay at zero.
            perturbed_params<double> p = all;
            if (!together) {
                p.yaw_deg = p.sway_m = p.pitch_deg = p.heave_m = p.roll_deg = {};
                p.*c.member = all.*c.member;
            }
            const perturbed<double> path(p);
            const std::size_t n = 6000; // 60 s
            std::vector<double> yaw, sway, pitch, heave, roll;
            for (std::size_t i = 0; i < n; ++i) {
                const auto q = path.pose_at(i), nominal = path.nominal_pose_at(i);
                const double psi = nominal.yaw_rad;
                yaw.push_back(sss::rad_to_deg(angle_diff(q.yaw_rad, psi)));
                sway.push_back((q.position.x - nominal.position.x) * std::cos(psi) - (q.position.y - nominal.position.y) * std::sin(psi));
                CHECK(std::abs((q.position.x - nominal.position.x) * std::sin(psi) +
                               (q.position.y - nominal.position.y) * std::cos(psi)) < 1e-9); // no surge
                pitch.push_back(sss::rad_to_deg(q.pitch_rad));
                heave.push_back(q.position.z - p.altitude_m);
                roll.push_back(sss::rad_to_deg(q.roll_rad));
            }
            const std::vector<double>* signals[] = {&yaw, &sway, &pitch, &heave, &roll};
            const oscillation<double> perturbed_params<double>::*members[] = {
                &perturbed_params<double>::yaw_deg, &perturbed_params<double>::sway_m, &perturbed_params<double>::pitch_deg,
                &perturbed_params<double>::heave_m, &perturbed_params<double>::roll_deg};
            for (int k = 0; k < 5; ++k) {
                const oscillation<double>& o = p.*members[k];
                const fit f = measure(*signals[k], p.ping_interval_s);
                CAPTURE(c.name);
                CAPTURE(k);
                if (o.amplitude == 0.0) {
                    CHECK(f.amplitude < 1e-12);
                    continue;
                }
                CHECK(f.amplitude == doctest::Approx(o.amplitude).epsilon(1e-4));
                CHECK(f.period == doctest::Approx(o.period_s).epsilon(1e-5));
                CHECK(f.first == doctest::Approx(o.amplitude * std::sin(sss::deg_to_rad(o.phase_deg))).scale(1.0).epsilon(1e-12));
            }
            if (together) break; // one pass covers all five channels
        }
    }
}

TEST_CASE("On a turn of radius R a point at across-track offset y moves (R - y)/R of the towfish's distance on "
          "the inner side and (R + y)/R on the outer side") {
    const double r = 80.0, v = 2.0, dt = 0.2, y = 30.0;
    for (sss::side toward : {sss::side::starboard, sss::side::port}) {
        perturbed_params<double> p;
        p.heading_deg = 250.0;
        p.speed_mps = v;
        p.ping_interval_s = dt;
        p.turn = constant_turn<double>{toward, r, 0.0};
        const perturbed<double> path(p);
        CHECK(path.turn_radius_m() == doctest::Approx(r));
        CHECK(path.turn_rate_rad_s() == doctest::Approx(sss::side_sign<double>(toward) * v / r));
        const double inner_sign = sss::side_sign<double>(toward); // body y of the inner side
        for (std::size_t i = 0; i < 2000; i += 37) {
            const auto a = path.pose_at(i), b = path.pose_at(i + 1);
            // The towfish's own distance per ping: the arc R dpsi is speed x interval, and the chord matches it.
            const double dpsi = angle_diff(b.yaw_rad, a.yaw_rad);
            CHECK(dpsi * inner_sign > 0.0); // turning towards the inner side
            CHECK(r * std::abs(dpsi) == doctest::Approx(v * dt).epsilon(1e-12));
            const double chord = glm::length(b.position - a.position);
            CHECK(chord == doctest::Approx(2.0 * r * std::sin(v * dt / (2.0 * r))).epsilon(1e-12));
            // Points across track, from the poses' own body frames.
            const auto at = [](const sss::pose<double>& q, double body_y) { return q.position + q.to_world({0.0, body_y, 0.0}); };
            const double inner = glm::length(at(b, inner_sign * y) - at(a, inner_sign * y));
            const double outer = glm::length(at(b, -inner_sign * y) - at(a, -inner_sign * y));
            CHECK(inner / chord == doctest::Approx((r - y) / r).epsilon(1e-10));
            CHECK(outer / chord == doctest::Approx((r + y) / r).epsilon(1e-10));
            // The centre of the turn, R to the inner side, stays put.
            const auto centre_a = at(a, inner_sign * r), centre_b = at(b, inner_sign * r);
            CHECK(glm::length(centre_b - centre_a) < 1e-9);
        }
    }
}

TEST_CASE("A turn given by its rate equals the turn given by the radius V / rate") {
    perturbed_params<double> by_radius;
    by_radius.speed_mps = 3.0;
    by_radius.ping_interval_s = 2.0 * pi * 120.0 / 3.0 / 2000.0; // 2000 pings per full circle
    by_radius.turn = constant_turn<double>{sss::side::port, 120.0, 0.0};
    perturbed_params<double> by_rate = by_radius;
    by_rate.turn = constant_turn<double>{sss::side::port, 0.0, sss::rad_to_deg(3.0 / 120.0)};
    const perturbed<double> a(by_radius), b(by_rate);
    for (std::size_t ping : {1u, 500u, 12345u}) {
        CHECK(a.pose_at(ping).position.x == doctest::Approx(b.pose_at(ping).position.x).epsilon(1e-12));
        CHECK(a.pose_at(ping).position.y == doctest::Approx(b.pose_at(ping).position.y).epsilon(1e-12));
        CHECK(a.pose_at(ping).yaw_rad == doctest::Approx(b.pose_at(ping).yaw_rad).epsilon(1e-12));
    }
    // After a full circle (2 pi R / V seconds) the towfish is back at the start, heading as it began.
    CHECK(std::abs(a.pose_at(2000).position.x) < 1e-9);
    CHECK(std::abs(a.pose_at(2000).position.y) < 1e-9);
    CHECK(std::abs(angle_diff(a.pose_at(2000).yaw_rad, 0.0)) < 1e-12);
    CHECK(std::hypot(a.pose_at(1000).position.x, a.pose_at(1000).position.y) == doctest::Approx(240.0)); // a diameter away
}

TEST_CASE("With yaw following sway and pitch following heave the towfish points along its own track") {
    perturbed_params<double> p = all_oscillations();
    p.yaw_deg = {};
    p.pitch_deg = {};
    p.sway_m = {2.0, 6.0, 0.0};
    p.heave_m = {1.0, 5.0, 20.0};
    p.yaw_follows_sway = true;
    p.pitch_follows_heave = true;
    p.ping_interval_s = 0.001;
    for (bool turning : {false, true}) {
        if (turning) p.turn = constant_turn<double>{sss::side::starboard, 25.0, 0.0};
        const perturbed<double> path(p);
        double worst_yaw = 0.0, worst_pitch = 0.0, largest_yaw = 0.0;
        for (std::size_t i = 1; i < 20000; i += 13) {
            // Central difference of the positions: the direction of travel at ping i.
            const auto d = path.pose_at(i + 1).position - path.pose_at(i - 1).position;
            const auto q = path.pose_at(i);
            const double track = std::atan2(d.x, d.y), climb = std::atan2(d.z, std::hypot(d.x, d.y));
            worst_yaw = std::max(worst_yaw, std::abs(angle_diff(q.yaw_rad, track)));
            worst_pitch = std::max(worst_pitch, std::abs(q.pitch_rad - climb));
            largest_yaw = std::max(largest_yaw, std::abs(angle_diff(q.yaw_rad, path.nominal_pose_at(i).yaw_rad)));
        }
        CAPTURE(turning);
        CHECK(worst_yaw < 1e-5);
        CHECK(worst_pitch < 1e-5);
        CHECK(largest_yaw > 0.1); // the sway does swing the heading
    }
}

TEST_CASE_TEMPLATE("The perturbed path is deterministic and agrees in float and double", T, float, double) {
    perturbed_params<T> p;
    p.turn = constant_turn<T>{sss::side::starboard, T(60), T(0)};
    p.yaw_deg = {T(2), T(9), T(0)};
    p.heave_m = {T(0.4), T(3), T(45)};
    const perturbed<T> path(p);
    perturbed_params<double> pd;
    pd.turn = constant_turn<double>{sss::side::starboard, 60.0, 0.0};
    pd.yaw_deg = {2.0, 9.0, 0.0};
    pd.heave_m = {0.4, 3.0, 45.0};
    const perturbed<double> ref(pd);
    for (std::size_t ping : {7u, 3000u, 2u, 7u}) {
        const auto a = path.pose_at(ping);
        const auto b = ref.pose_at(ping);
        CHECK(static_cast<double>(a.position.x) == doctest::Approx(b.position.x).epsilon(1e-5).scale(1.0));
        CHECK(static_cast<double>(a.position.z) == doctest::Approx(b.position.z).epsilon(1e-6));
        CHECK(static_cast<double>(a.yaw_rad) == doctest::Approx(b.yaw_rad).epsilon(1e-6));
    }
    // Another instance from the same parameters, asked in another order, gives the same bits.
    const perturbed<T> again(p);
    CHECK(again.pose_at(3000).position == path.pose_at(3000).position);
    CHECK(again.pose_at(3000).yaw_rad == path.pose_at(3000).yaw_rad);
}

TEST_CASE("Invalid perturbed-path parameters are rejected, naming the parameter") {
    const auto name_of = [](const perturbed_params<double>& p) {
        try {
            perturbed<double> m(p);
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(none)");
    };
    perturbed_params<double> p;
    p.sway_m.period_s = 0.0;
    CHECK(name_of(p) == "perturbed.sway_m.period_s");
    p = {};
    p.pitch_deg.amplitude = 95.0;
    CHECK(name_of(p) == "perturbed.pitch_deg.amplitude");
    p = {};
    p.turn = constant_turn<double>{};
    CHECK(name_of(p) == "perturbed.turn.rate_deg_s");
    p.turn = constant_turn<double>{sss::side::port, -5.0, 0.0};
    CHECK(name_of(p) == "perturbed.turn.radius_m");
    p.turn = constant_turn<double>{sss::side::port, 50.0, 3.0}; // both: the rate would be ignored
    CHECK(name_of(p) == "perturbed.turn.rate_deg_s");
    p = {};
    p.speed_mps = -1.0;
    CHECK(name_of(p) == "perturbed.speed_mps");
    p = {};
    p.heave_m.phase_deg = std::nan("");
    CHECK(name_of(p) == "perturbed.heave_m.phase_deg");
    // A heave that takes the towfish to z <= 0; a towfish that points along a track it does not have (at rest, or
    // swaying beyond its turn's radius, where the heading would turn round); a climb that pitches it past 90 deg.
    p = {};
    p.heave_m = {15.0, 4.0, 0.0};
    CHECK(name_of(p) == "perturbed.heave_m.amplitude");
    p = {};
    p.speed_mps = 0.0;
    p.yaw_follows_sway = true;
    CHECK(name_of(p) == "perturbed.yaw_follows_sway");
    p = {};
    p.turn = constant_turn<double>{sss::side::starboard, 5.0, 0.0};
    p.sway_m = {6.0, 20.0, 0.0};
    p.yaw_follows_sway = true;
    CHECK(name_of(p) == "perturbed.yaw_follows_sway");
    p = {};
    p.pitch_deg = {80.0, 10.0, 90.0};
    p.heave_m = {2.0, 4.0, 0.0};
    p.pitch_follows_heave = true;
    CHECK(name_of(p) == "perturbed.pitch_follows_heave");
    p.pitch_deg.amplitude = 10.0; // 10 deg and a climb of atan(3.14 / 2) = 57.5 deg: accepted
    CHECK(name_of(p) == "(none)");
}
