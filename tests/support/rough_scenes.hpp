#pragma once
// Small rough scenes for judging a rendered line against the converged reference: a ridge with a self-shadow, a
// power-law relief with two sets of ripples, an oblique trench, and targets on and above rough relief (a lying
// cylinder, a tethered mine, a pipeline spanning a hollow). All lie around a towfish at (0, 0) heading north
// (+y), 10 m above the mean seabed z = 0, with 30 m of slant range per side; height fields of 0.05 m cells over
// x in [-32, 32] m and y in [-4, 4] m cover both sides' footprints, rolled or pitched by a few degrees included.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include <sss/core/pose.hpp>
#include <sss/propagation/layered.hpp>
#include <sss/propagation/straight.hpp>
#include <sss/receiver/receiver.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/targets.hpp>

#include "grid_relief.hpp"

namespace sss_test {

inline constexpr double rough_altitude_m = 10.0; // towfish height above z = 0 (m)
inline constexpr double rough_range_m = 30.0;    // slant range per side (m)

/// A height field over the common footprint with z(x, y) (m, world coordinates).
template <class T, class Height> sss::scene::height_field<T> footprint_field(Height&& z, double cell_m = 0.05) {
    const double x0 = -32.0, y0 = -4.0;
    const auto nx = static_cast<std::size_t>(std::lround(64.0 / cell_m)) + 1;
    const auto ny = static_cast<std::size_t>(std::lround(8.0 / cell_m)) + 1;
    auto h = sample_heights<T>(nx, ny, cell_m, [&](double x, double y) { return z(x + x0, y + y0); });
    return sss::scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = T(cell_m), .origin_m = {T(x0), T(y0)}, .heights_m = std::move(h)});
}

/// The ridge: Gaussian, 1.5 m high, 0.3 m wide (standard deviation), running north-south 20 m to starboard.
/// Its crest (20, 1.5) shadows the seabed from slant range 21.6 m (the crest) to 25.5 m, where the ray grazing
/// the crest, at depression atan(8.5 / 20), meets z = 0 at ground range 20 x 10 / 8.5 = 23.53 m.
template <class T> sss::scene::height_field<T> ridge_field() {
    return footprint_field<T>([](double x, double) { return 1.5 * std::exp(-(x - 20.0) * (x - 20.0) / (2 * 0.09)); });
}

/// Power-law relief with two sets of ripples. With x, y (m): 24 plane waves of wavelengths 0.5 to 20 m
/// (geometric), amplitude 0.04 (lambda / 1 m)^1.25 m (a power-law spectrum), directions and phases drawn from
/// rng{seed}; plus ripples 0.08 m high (crest to trough) of wavelength 0.8 m with crests 30 deg off the track
/// and 0.04 m high of wavelength 0.5 m with crests 100 deg off it.
template <class T> sss::scene::height_field<T> ripple_field(std::uint64_t seed = 7) {
    rng r{seed};
    struct wave { double kx, ky, a, phase; };
    std::vector<wave> waves;
    for (int i = 0; i < 24; ++i) {
        const double lambda = 0.5 * std::pow(40.0, double(i) / 23.0);
        const double dir = r.uniform(0, 2 * std::numbers::pi), phase = r.uniform(0, 2 * std::numbers::pi);
        const double k = 2 * std::numbers::pi / lambda;
        waves.push_back({k * std::cos(dir), k * std::sin(dir), 0.04 * std::pow(lambda, 1.25) / 4.0, phase});
    }
    auto ripple = [](double x, double y, double crest_deg, double lambda, double height) {
        const double c = crest_deg * std::numbers::pi / 180.0; // crest direction from the track (+y)
        const double across = x * std::cos(c) - y * std::sin(c);
        return 0.5 * height * std::sin(2 * std::numbers::pi * across / lambda);
    };
    return footprint_field<T>([=](double x, double y) {
        double z = 0.0;
        for (const wave& w : waves) z += w.a * std::sin(w.kx * x + w.ky * y + w.phase);
        return z + ripple(x, y, 30.0, 0.8, 0.08) + ripple(x, y, 100.0, 0.5, 0.04);
    });
}

/// A trench 1.2 m deep, 1.5 m wide at its floor, walls at 60 deg, its axis at x = 16 + 0.2 y (crossing the beam
/// obliquely), in an otherwise flat seabed z = 0.
template <class T> sss::scene::height_field<T> trench_field() {
    return footprint_field<T>([](double x, double y) {
        const double d = std::abs(x - (16.0 + 0.2 * y)) * std::cos(std::atan(0.2)); // distance from the axis
        const double wall = std::tan(60.0 * std::numbers::pi / 180.0);
        return -std::clamp(1.2 - (d - 0.75) * wall, 0.0, 1.2);
    });
}

/// A lee slope seen at grazing incidence: a plateau 1 m high out to x = 18 m, then a slope down to z = 0 whose plane
/// passes `below_deg` below the towfish at (0, 0, rough_altitude_m). Every ray that meets the slope meets it within
/// below_deg of grazing incidence (those steeper than the slope's plane, shallower than the plateau's edge), so its
/// echo per radian, 1/sin of the angle to the facet, is tens to thousands of times its neighbours'.
template <class T> sss::scene::height_field<T> lee_slope_field(double below_deg) {
    const double e_edge = std::atan((rough_altitude_m - 1.0) / 18.0);
    const double slope = std::tan(e_edge - below_deg * std::numbers::pi / 180.0), x_foot = 18.0 + 1.0 / slope;
    return footprint_field<T>([=](double x, double) {
        return x < 18.0 ? 1.0 : (x < x_foot ? 1.0 - (x - 18.0) * slope : 0.0);
    });
}

/// Gentle rolling relief (0.3 m swell, 0.05 m ripples) with a hollow 0.8 m deep around x = 25 for the pipeline to
/// span.
inline double target_relief_m(double x, double y) {
    return 0.3 * std::sin(0.35 * x + 0.2 * y) + 0.025 * std::sin(2 * std::numbers::pi * (x + 0.3 * y) / 0.7) -
           0.8 * std::exp(-(x - 25.0) * (x - 25.0) / (2 * 0.8 * 0.8));
}

/// Targets on and above rough relief: a cylinder 2 m long and 0.25 m in radius lying along the track at
/// x = 12 m, a spherical mine (radius 0.5 m) moored 2.5 m above the seabed at x = 18 m, and a pipeline (radius
/// 0.3 m) running from (23, -4) to (27, 4), spanning the hollow at x = 25 m.
template <class T> auto target_scene() {
    auto field = footprint_field<T>(target_relief_m);
    auto h = [](T x, T y) { return T(target_relief_m(double(x), double(y))); };
    std::vector<sss::scene::object<T>> objs;
    objs.push_back(sss::seabed::lying_cylinder(
        sss::seabed::lying_cylinder_params<T>{.center_m = {T(12), T(0)}, .heading_deg = T(0),
                                              .ids = {.material = 2, .object = 1, .label = 3}},
        h));
    objs.push_back(sss::seabed::tethered_mine(
        sss::seabed::tethered_mine_params<T>{.anchor_m = {T(18), T(0.3)}, .case_height_m = T(2.5), .object_id = 2,
                                             .class_id = 4, .case_material = 2, .tether_material = 2,
                                             .anchor_material = 2},
        h));
    objs.push_back(sss::seabed::pipeline(
        sss::seabed::pipeline_params<T>{.route_m = {{T(23), T(-4)}, {T(27), T(4)}}, .ids = {.material = 2, .object = 3, .label = 5}}, h));
    return sss::scene::scene(std::move(field), sss::scene::object_set<T>(std::move(objs)));
}

/// The towfish: level, or rolled 6 deg (starboard down) and pitched 4 deg (nose up).
template <class T> sss::pose<T> rough_pose(bool tilted = false) {
    const T roll = tilted ? T(6 * std::numbers::pi / 180) : T(0), pitch = tilted ? T(4 * std::numbers::pi / 180) : T(0);
    return sss::make_pose<T>(T(0), sss::vec3<T>{T(0), T(0), T(rough_altitude_m)}, roll, pitch, T(0));
}

/// The receiver: 20 kHz, 100 us pulse, 30 m per side (800 samples).
inline sss::receiver_params rough_receiver() {
    sss::receiver_params rx;
    rx.max_range_m = rough_range_m;
    return rx;
}

/// Three-layer water over the scenes: the surface 40 m above z = 0; 1500 m/s down to 8 m depth, a thermocline
/// to 1488 m/s at 22 m (just above the towfish), 1486 m/s at the seabed; absorption at 100 kHz.
template <class T> sss::propagation::layered<T> three_layer_water() {
    sss::propagation::layered_params<T> p;
    p.surface_z_m = T(40);
    p.frequency_hz = T(100000);
    return sss::propagation::layered<T>(
        sss::propagation::sound_speed_profile<T>({T(0), T(8), T(22), T(40.5)}, {T(1500), T(1499), T(1488), T(1486)}), p);
}

} // namespace sss_test
