#pragma once
// A realistic survey scene for benchmarks: a square fractal seabed with two sets of ripples and 20 targets (moored
// mines, lying cylinders, rocks and a pipeline), Jackson medium sand at 100 kHz, three-layer water, a 100 kHz
// planar array and a perturbed towfish, 100 m of slant range per side in 2048 samples. Build it with
// `make_survey(survey_params<T>{...})`; every size is a named parameter, so a smaller copy (for a quick run or a
// reference that must be rendered many times over) is the same scene scaled down.
//
// World: the seabed covers [-size/2, size/2]^2 around the origin, heights about z = 0; the towfish runs north
// along x = 0 from y = -track/2 at `altitude_m`. Targets lie within `target_band_m` of the track on either side,
// spread along the track's first `track_m`, drawn from rng{seed} (positions), and resting on the seabed.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include <sss/beam/planar_array.hpp>
#include <sss/motion/perturbed.hpp>
#include <sss/propagation/layered.hpp>
#include <sss/receiver/receiver.hpp>
#include <sss/receiver/time_sampler.hpp>
#include <sss/scattering/jackson.hpp>
#include <sss/scattering/sediments.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/power_law_spectrum.hpp>
#include <sss/seabed/ripples.hpp>
#include <sss/seabed/targets.hpp>
#include <sss/simulator.hpp>

namespace sss_bench {

template <class T> struct survey_params {
    double size_m = 1024.0;        ///< side of the square seabed (m)
    double cell_m = 0.25;          ///< height spacing (m): 1024 m at 0.25 m is 4096^2 heights
    double altitude_m = 10.0;      ///< towfish height above z = 0 (m)
    double range_m = 100.0;        ///< slant range per side (m)
    std::size_t samples = 2048;    ///< samples per side over range_m
    double track_m = 200.0;        ///< length of track the targets are spread along (m)
    double target_band_m = 90.0;   ///< targets lie between 5 m and this far from the track (m)
    double frequency_hz = 100e3;   ///< sonar frequency: array, absorption and Jackson scattering (Hz)
    double relief_strength = 400.0; ///< the fractal's spectral strength in units of medium sand's (w2 = 0.004446 cm^4)
    std::uint64_t seed = 11;       ///< seabed and target positions
};

/// The scene's pieces, each built from survey_params.
template <class T> struct survey {
    using seabed_type = sss::scene::scene<sss::scene::height_field<T>>;
    seabed_type scene;
    sss::scattering::jackson<T> scattering;
    sss::propagation::layered<T> water;
    sss::beam::planar_array<T> array;
    sss::motion::perturbed<T> motion;
    sss::receiver_params receiver;
};

/// Fractal relief (Jackson medium sand roughness spectrum, w2 = 0.004446 cm^4, gamma = 3.25, outer scale 50 m,
/// its strength scaled by relief_strength for visible relief) plus ripples of 0.8 m (0.1 m high, crests 30 deg from
/// east) and 0.6 m (0.04 m high, crests 110 deg from east).
template <class T> sss::scene::height_field<T> survey_seabed(const survey_params<T>& p) {
    const auto n = static_cast<std::size_t>(std::lround(p.size_m / p.cell_m));
    sss::seabed::fractal_params<T> f;
    f.spectrum = sss::seabed::jackson_spectrum<T>(T(0.004446 * p.relief_strength), T(3.25), T(50));
    auto h = sss::seabed::fractal_surface<T>(n, n, T(p.cell_m), f, p.seed);
    sss::seabed::add_ripples(h, sss::seabed::ripple_params<T>{.wavelength_m = T(0.8), .height_m = T(0.1),
                                                              .crest_heading_deg = T(60)},
                             p.seed + 1);
    sss::seabed::add_ripples(h, sss::seabed::ripple_params<T>{.wavelength_m = T(0.6), .height_m = T(0.04),
                                                              .crest_heading_deg = T(340)},
                             p.seed + 2);
    const T half = T(0.5 * p.size_m);
    return sss::scene::height_field<T>({.nx = n, .ny = n, .cell_m = T(p.cell_m), .origin_m = {-half, -half}, .heights_m = std::move(h.values)});
}

/// 20 targets on the seabed `field`: 8 moored mines (spherical and cylindrical cases, 2 to 5 m up), 8 cylinders
/// lying at random headings, 3 rocks (spheres half buried) and a pipeline crossing the track obliquely.
template <class T> std::vector<sss::scene::object<T>> survey_targets(const survey_params<T>& p,
                                                                     const sss::scene::height_field<T>& field) {
    std::uint64_t state = p.seed * 0x9E3779B97F4A7C15ull + 7;
    auto uniform = [&state](double a, double b) { // splitmix64
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return a + (b - a) * double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    };
    auto h = [&field](T x, T y) { return field.seabed_height_m(x, y); };
    auto place = [&](std::size_t i) {
        const double side = i % 2 ? 1.0 : -1.0;
        return sss::vec2<T>{T(side * uniform(5.0, p.target_band_m)), T(-0.5 * p.track_m + p.track_m * (double(i) + uniform(0, 1)) / 20.0)};
    };
    std::vector<sss::scene::object<T>> objs;
    std::uint32_t id = 0;
    for (std::size_t i = 0; i < 8; ++i, ++id)
        objs.push_back(sss::seabed::tethered_mine(
            sss::seabed::tethered_mine_params<T>{.anchor_m = place(id), .case_height_m = T(uniform(2, 5)),
                                                 .shape = i % 2 ? sss::seabed::mine_case::cylinder : sss::seabed::mine_case::sphere,
                                                 .object_id = id, .class_id = 1},
            h));
    for (std::size_t i = 0; i < 8; ++i, ++id)
        objs.push_back(sss::seabed::lying_cylinder(
            sss::seabed::lying_cylinder_params<T>{.center_m = place(id), .heading_deg = T(90 - uniform(0, 180)),
                                                  .length_m = T(uniform(1.5, 3)), .radius_m = T(uniform(0.2, 0.4)),
                                                  .ids = {.material = 1, .object = id, .label = 2}},
            h));
    for (std::size_t i = 0; i < 3; ++i, ++id) {
        const sss::vec2<T> c = place(id);
        const T r = T(uniform(0.3, 0.8));
        objs.push_back(sss::scene::object<T>({sss::scene::sphere<T>(sss::vec3<T>{c.x, c.y, h(c.x, c.y)}, r, {.material = 1, .object = id, .label = 3})}, {}));
    }
    const T y0 = T(-0.25 * p.track_m);
    objs.push_back(sss::seabed::pipeline(
        sss::seabed::pipeline_params<T>{.route_m = {{T(-p.target_band_m), y0}, {T(p.target_band_m), y0 + T(0.4 * p.target_band_m)}},
                                        .ids = {.material = 1, .object = id, .label = 4}},
        h));
    return objs;
}

/// The whole survey: scene, Jackson medium sand (material 0: seabed; 1: targets, rock), three-layer water (surface
/// 40 m above z = 0; 1500 m/s to 8 m, 1490 m/s at 20 m, 1484 m/s at the seabed), the default 100 kHz planar array,
/// and a towfish heading north at 2 m/s, 10 pings/s, with 1 deg roll, 0.5 deg pitch, 1 deg yaw and 0.2 m heave.
template <class T> survey<T> make_survey(const survey_params<T>& p = {}) {
    auto field = survey_seabed(p);
    auto objs = survey_targets(p, field);
    sss::scene::scene sc(std::move(field), sss::scene::object_set<T>(std::move(objs)));
    const auto sand = sss::scattering::sediment_preset<T>(sss::scattering::sediment::medium_sand);
    const auto rock = sss::scattering::sediment_preset<T>(sss::scattering::sediment::rock);
    sss::propagation::layered_params<T> wp;
    wp.surface_z_m = T(40);
    wp.frequency_hz = T(p.frequency_hz);
    sss::propagation::layered<T> water(
        sss::propagation::sound_speed_profile<T>({T(0), T(8), T(20), T(40.5)}, {T(1500), T(1499), T(1490), T(1484)}), wp);
    sss::beam::planar_array_params<T> ap;
    ap.frequency_hz = T(p.frequency_hz);
    sss::motion::perturbed_params<T> mp;
    mp.start_m = {T(0), T(-0.5 * p.track_m)};
    mp.altitude_m = T(p.altitude_m);
    mp.roll_deg = {T(1), T(6), T(0)};
    mp.pitch_deg = {T(0.5), T(8), T(40)};
    mp.yaw_deg = {T(1), T(15), T(90)};
    mp.heave_m = {T(0.2), T(7), T(10)};
    sss::receiver_params rx;
    rx.max_range_m = p.range_m;
    rx.sample_rate_hz = double(p.samples) * double(water.reference_speed_mps()) / (2.0 * p.range_m);
    return survey<T>{std::move(sc), sss::scattering::jackson<T>({.frequency_hz = T(p.frequency_hz), .sound_speed_mps = T(1500), .materials = {sand, rock}}), std::move(water),
                     sss::beam::planar_array<T>(ap), sss::motion::perturbed<T>(mp), rx};
}

/// One side of one ping, traced and sampled without the other side (what the accuracy tables compare).
template <class Sim, class Scene, class T>
std::vector<double> side_line(const Sim& sim, const Scene& scene, const sss::pose<T>& p, sss::side sd) {
    sss::time_sampler s(sim.samples_per_line(), sim.dt_s(), sim.receiver().pulse);
    sim.trace(scene, p, sd, [&](const sss::tube_echo<T>& e) { s.add_span(e.t0_s, e.t1_s, e.power); });
    std::vector<double> out;
    s.render(out);
    return out;
}

} // namespace sss_bench
