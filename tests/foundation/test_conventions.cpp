// The conventions of docs/conventions.md, one test case each: world and body frames, the heading (degrees
// clockwise from north) shared by the towfish and every plan direction a user sets, pitch and roll signs,
// depression, sides of the waterfall, sample count and timing.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include <sss/sss.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/ripples.hpp>
#include <sss/seabed/stamps.hpp>
#include <sss/seabed/targets.hpp>

namespace {

using T = double;
using P = sss::policies<T>;

sss::vec3<T> unit(T x, T y, T z) { return sss::vec3<T>{x, y, z}; }

/// The world (x, y) unit vector of a heading (deg clockwise from north): (sin h, cos h).
sss::vec2<T> heading_vector(T heading_deg) {
    const T h = sss::deg_to_rad(heading_deg);
    return {std::sin(h), std::cos(h)};
}

P::straight_line track(T heading_deg, T speed_mps = 1, T interval_s = 0.5) {
    return P::straight_line({.start_m = {T(0), T(0)},
                             .heading_deg = heading_deg,
                             .speed_mps = speed_mps,
                             .altitude_m = T(10),
                             .ping_interval_s = interval_s});
}

/// The first sample of `line` where `with` exceeds `without` clearly (a target's echo), if any.
std::optional<std::size_t> first_extra(const std::vector<T>& with, const std::vector<T>& without) {
    for (std::size_t k = 0; k < with.size(); ++k)
        if (with[k] > 2 * without[k] + 1e-12) return k;
    return std::nullopt;
}

} // namespace

TEST_CASE("world x is east and y is north: a towfish heading 90 deg moves along +x, heading 0 along +y") {
    const auto east = track(90).pose_at(10), north = track(0).pose_at(10);
    CHECK(east.position.x == doctest::Approx(5.0));
    CHECK(std::abs(east.position.y) < 1e-12);
    CHECK(north.position.y == doctest::Approx(5.0));
    CHECK(std::abs(north.position.x) < 1e-12);
    CHECK(east.position.z == doctest::Approx(10.0)); // z up: altitude is +z
}

TEST_CASE("body axes: forward is the heading, starboard is to the right of it and down is -z at zero attitude") {
    for (T h : {0.0, 30.0, 90.0, 200.0, -45.0}) {
        const auto p = track(h).pose_at(0);
        const auto fwd = p.to_world(unit(1, 0, 0)), stbd = p.to_world(unit(0, 1, 0)), down = p.to_world(unit(0, 0, 1));
        const auto hv = heading_vector(h), rv = heading_vector(h + 90);
        CHECK(fwd.x == doctest::Approx(hv.x));
        CHECK(fwd.y == doctest::Approx(hv.y));
        CHECK(stbd.x == doctest::Approx(rv.x)); // starboard: the heading turned 90 deg clockwise
        CHECK(stbd.y == doctest::Approx(rv.y));
        CHECK(down.z == doctest::Approx(-1.0));
    }
}

TEST_CASE("positive pitch raises the bow and positive roll lowers the starboard side") {
    const auto pitched = sss::make_pose<T>(0, {}, 0, sss::deg_to_rad(10.0), sss::deg_to_rad(30.0));
    CHECK(pitched.to_world(unit(1, 0, 0)).z == doctest::Approx(std::sin(sss::deg_to_rad(10.0))));
    const auto rolled = sss::make_pose<T>(0, {}, sss::deg_to_rad(10.0), 0, sss::deg_to_rad(30.0));
    CHECK(rolled.to_world(unit(0, 1, 0)).z == doctest::Approx(-std::sin(sss::deg_to_rad(10.0))));
    // The motion policies use the same signs: a perturbed towfish pitched up at its oscillation's peak.
    sss::motion::perturbed_params<T> tp;
    tp.pitch_deg = {.amplitude = 5, .period_s = 4, .phase_deg = 90};
    tp.roll_deg = {.amplitude = 5, .period_s = 4, .phase_deg = 90};
    const auto pose = P::perturbed(tp).pose_at(0);
    CHECK(pose.to_world(unit(1, 0, 0)).z > 0.05);
    CHECK(pose.to_world(unit(0, 1, 0)).z < -0.05);
}

TEST_CASE("beam angles: a positive along-track angle points forward and a positive depression down, starboard is body +y") {
    const auto d = sss::beam_direction<T>(sss::side::starboard, sss::deg_to_rad(5.0), sss::deg_to_rad(20.0));
    CHECK(d.x > 0); // forward (body x)
    CHECK(d.y > 0); // starboard (body y)
    CHECK(d.z > 0); // down (body z)
    const auto p = sss::beam_direction<T>(sss::side::port, sss::deg_to_rad(-5.0), sss::deg_to_rad(20.0));
    CHECK(p.x < 0);
    CHECK(p.y < 0);
    // In the world, a starboard ray of a level towfish heading north points east and down.
    const auto w = track(0).pose_at(0).to_world(d);
    CHECK(w.x > 0);
    CHECK(w.z < 0);
}

TEST_CASE("a cylinder laid with the towfish's heading number lies along the track: its echo stays at one range in every "
          "ping that sees it") {
    sss::receiver_params rx;
    rx.max_range_m = 30;
    const P::simulator<> sim(P::lambertian({.mu_db = {T(-30), T(-5)}}), {},
                             P::ideal_fan({.along_width_deg = 1, .vertical_width_deg = 60, .depression_deg = 30}),
                             P::straight_line{}, rx);
    const sss::scene::flat_seabed<T> flat(0.0);
    const auto ground = [](T, T) { return T(0); };
    for (T h : {0.0, 30.0, 135.0, -70.0}) {
        CAPTURE(h);
        const auto tow = track(h);
        // 10 m along the track, 15 m to starboard, axis along the same heading number, 12 m long.
        const sss::vec2<T> c = heading_vector(h) * T(10) + heading_vector(h + 90) * T(15);
        sss::seabed::lying_cylinder_params<T> cp;
        cp.center_m = c;
        cp.heading_deg = h;
        cp.length_m = 12;
        cp.radius_m = 0.3;
        std::vector<sss::scene::object<T>> objs{sss::seabed::lying_cylinder(cp, ground)};
        const sss::scene::scene world(flat, sss::scene::object_set<T>(std::move(objs)));
        std::size_t seen = 0, lo = 1u << 30, hi = 0;
        for (std::size_t k = 0; k < 40; ++k) { // 20 m of track
            const auto pose = tow.pose_at(k);
            const auto with = sim.ping_at(world, pose), without = sim.ping_at(flat, pose);
            CHECK(!first_extra(with.port, without.port)); // nothing on the port side
            if (const auto s = first_extra(with.starboard, without.starboard)) {
                ++seen;
                lo = std::min(lo, *s);
                hi = std::max(hi, *s);
            }
        }
        CHECK(seen >= 20); // abeam over most of its 12 m
        CHECK(hi - lo <= 1); // one range: straight along the track
    }
}

TEST_CASE("a target to the right of the heading shows on the starboard (right) half of the waterfall") {
    sss::receiver_params rx;
    rx.max_range_m = 30;
    const P::simulator<> sim(P::lambertian({.mu_db = {T(-30), T(-5)}}), {}, {}, track(90), rx);
    std::vector<sss::scene::object<T>> objs;
    objs.emplace_back(std::vector<sss::scene::sphere<T>>{sss::scene::sphere<T>(
                          unit(5, -15, 1), 1, sss::scene::surface_ids{.material = 1, .object = 1, .label = 1})},
                      std::vector<sss::scene::cylinder<T>>{});
    const sss::scene::flat_seabed<T> flat(0.0);
    const sss::scene::scene world(flat, sss::scene::object_set<T>(std::move(objs)));
    const auto with = sim.render(world, 0, 20, 1), without = sim.render(flat, 0, 20, 1);
    double left = 0, right = 0;
    for (std::size_t i = 0; i < with.pings; ++i)
        for (std::size_t j = 0; j < with.width(); ++j)
            (j < with.samples ? left : right) += std::max(0.0, with.at(i, j) - without.at(i, j));
    CHECK(right > 0);
    CHECK(left < 1e-6 * right); // heading east, south (-y) is starboard; port differs by rounding only
}

TEST_CASE("ripple crests and stamp axes with heading 0 run north-south") {
    sss::seabed::ripple_params<T> rp;
    rp.wavelength_m = 2;
    rp.height_m = 0.1;
    rp.crest_heading_deg = 0;
    const auto r = sss::seabed::ripple_field<T>(64, 64, 0.25, rp, 1);
    double along_y = 0, along_x = 0;
    for (std::size_t i = 0; i + 1 < 64; ++i) {
        along_y = std::max(along_y, std::abs(r(10, i + 1) - r(10, i)));
        along_x = std::max(along_x, std::abs(r(i + 1, 10) - r(i, 10)));
    }
    CHECK(along_y < 1e-9); // constant along a crest
    CHECK(along_x > 0.01);
    auto flat = sss::seabed::make_raster<T>(81, 81, 0.25, 0.0);
    sss::seabed::plate<T> pl;
    pl.center_x_m = 10;
    pl.center_y_m = 10;
    pl.length_m = 12;
    pl.width_m = 2;
    pl.heading_deg = 0;
    sss::seabed::stamp(flat, pl);
    std::size_t nx = 0, ny = 0; // raised samples along the row and the column through the centre
    for (std::size_t i = 0; i < 81; ++i) {
        nx += flat(i, 40) > 0.05 ? 1 : 0;
        ny += flat(40, i) > 0.05 ? 1 : 0;
    }
    CHECK(ny > 3 * nx); // its length runs north
}

TEST_CASE("a fan tilted down by its depression sees the seabed first at the range its steepest edge predicts") {
    sss::receiver_params rx;
    rx.max_range_m = 40;
    rx.pulse = {20e-6, sss::pulse_shape::rectangular};
    // Axis 30 deg down, 20 deg wide: the steepest ray is 40 deg down and meets z = 0 from 10 m at 10 / sin 40.
    const P::simulator<> sim({}, {}, P::ideal_fan({.along_width_deg = 1, .vertical_width_deg = 20, .depression_deg = 30}),
                             track(0), rx);
    const auto l = sim.ping(sss::scene::flat_seabed<T>(0.0), 0);
    std::size_t first = 0;
    while (first < l.starboard.size() && l.starboard[first] == 0) ++first;
    const double expected = 2 * (10 / std::sin(sss::deg_to_rad(40.0))) / 1500 / l.dt_s;
    CHECK(double(first) == doctest::Approx(std::floor(expected)).epsilon(0.02));
}

TEST_CASE("an echo from slant range R lands in sample floor(2 R / c / dt)") {
    // A 2 cm sphere in the water column to starboard, its nearest point at R = (j + f) c dt / 2 for a few whole j and
    // fractions f of a sample; a 10 us burst (a fifth of a sample) starts at the echo's arrival.
    sss::receiver_params rx;
    rx.sample_rate_hz = 20000;
    rx.max_range_m = 30;
    rx.pulse = {10e-6, sss::pulse_shape::rectangular};
    const P::simulator<> sim(P::lambertian({.mu_db = {T(-30), T(-5)}}), {},
                             P::ideal_fan({.along_width_deg = 1, .vertical_width_deg = 90, .depression_deg = 45}), track(0), rx);
    const sss::scene::flat_seabed<T> flat(0.0);
    const auto without = sim.ping(flat, 0).starboard;
    const T a = 0.02, half_sample_m = 0.5 * 1500.0 / 20000.0;
    for (const std::size_t j : {150u, 201u, 247u})
        for (const T f : {T(0.1), T(0.5), T(0.9)}) {
            CAPTURE(j);
            CAPTURE(f);
            const T R = (T(j) + f) * half_sample_m;
            // Heading north, starboard is +x: the centre 3 m below the towfish, R + a from it.
            const T x = std::sqrt((R + a) * (R + a) - T(9));
            std::vector<sss::scene::object<T>> objs;
            objs.emplace_back(std::vector<sss::scene::sphere<T>>{sss::scene::sphere<T>(
                                  unit(x, 0, 7), a, sss::scene::surface_ids{.material = 1, .object = 1, .label = 1})},
                              std::vector<sss::scene::cylinder<T>>{});
            const sss::scene::scene world(flat, sss::scene::object_set<T>(std::move(objs)));
            const auto first = first_extra(sim.ping(world, 0).starboard, without);
            REQUIRE(first.has_value());
            CHECK(*first == j);
        }
}

TEST_CASE("a 20 kHz receiver over 75 m gives ceil(2 x 75 / 1500 x 20000) samples per side") {
    sss::receiver_params rx;
    rx.sample_rate_hz = 20000;
    rx.max_range_m = 75;
    CHECK(rx.samples(1500.0) == 2000u);
    const P::simulator<> sim({}, {}, {}, {}, rx);
    CHECK(sim.ping(sss::scene::flat_seabed<T>(0.0), 0).starboard.size() == 2000u);
    CHECK(sim.dt_s() == doctest::Approx(1.0 / 20000).scale(0));
}

TEST_CASE("ping k is transmitted at k ping intervals") {
    for (std::size_t k : {0u, 1u, 17u}) {
        CHECK(track(0, 1, 0.25).pose_at(k).time_s == doctest::Approx(0.25 * double(k)));
        sss::motion::perturbed_params<T> tp;
        tp.ping_interval_s = 0.2;
        CHECK(P::perturbed(tp).pose_at(k).time_s == doctest::Approx(0.2 * double(k)));
    }
}
