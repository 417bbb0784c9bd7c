// A scene file and the equivalent C++ program render bit-identical waterfalls: the scene file is a front door
// to the library, not a second model. tests/cli/scenes/small.toml is written out here by hand, with the
// library's parameter structs, and both are rendered for a few pings; so are planar.toml (a planar array) and
// trajectory.toml (a sampled track), whose beam and motion sss-render holds in run-time policies; and
// georeferenced.toml (small.toml moved to UTM coordinates) in double, the precision it asks for.

#include <doctest/doctest.h>

#include "scene_file/build.hpp"
#include "scene_file/read.hpp"
#include "scene_file/write.hpp"

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/composite.hpp>
#include <sss/seabed/sediment_region.hpp>
#include <sss/seabed/targets.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using T = float;
namespace sb = sss::seabed;

// small.toml, by hand, in scalar R, the whole scene moved by (x0_m, y0_m) (georeferenced.toml: 500 km east and
// 6000 km north). The seabed's heights are synthesised in float on the raster's own grid and widened to R, as
// sss-render builds them in either precision.
template <class R = T> auto hand_written_world(double x0_m = 0, double y0_m = 0) {
    const std::size_t nx = 256, ny = 256;
    const T cell = T(0.2);
    const std::vector<sb::sediment_region<T>> regions{
        {.id = 0, .sediment = sb::sediment_named<T>("medium_sand"),
         .ripples = {sb::ripple_params<T>{.wavelength_m = T(1.2), .height_m = T(0.1), .crest_heading_deg = T(0)}}},
        {.id = 1, .sediment = sb::sediment_named<T>("sandy_gravel")}};
    sb::voronoi_partition<T> part{.sites = {{.x_m = T(10), .y_m = T(20), .texture = 0}, {.x_m = T(40), .y_m = T(30), .texture = 1}},
                                  .warp_m = T(2)};
    const auto bed = sb::compose(sb::partition(nx, ny, cell, part, 7), sb::textures(regions), T(0.5), 3);
    std::vector<std::uint32_t> material((nx - 1) * (ny - 1));
    for (std::size_t iy = 0; iy + 1 < ny; ++iy)
        for (std::size_t ix = 0; ix + 1 < nx; ++ix) material[iy * (nx - 1) + ix] = bed.regions.values[iy * nx + ix];
    sss::scene::height_field<R> seabed({.nx = nx, .ny = ny, .cell_m = R(0.2), .origin_m = {R(x0_m), R(y0_m)},
                                        .heights_m = std::vector<R>(bed.height.values.begin(), bed.height.values.end()),
                                        .materials = material, .regions = material});
    std::vector<sss::scene::object<R>> objects{sb::lying_cylinder(
        sb::lying_cylinder_params<R>{.center_m = {R(x0_m + 38), R(y0_m + 12)}, .heading_deg = R(0), .length_m = R(2), .radius_m = R(0.3),
                                     .ids = {.material = 2, .object = 1, .label = 1}},
        sb::seabed_height_of(seabed))};
    return sss::scene::scene(std::move(seabed), sss::scene::object_set<R>(std::move(objects)));
}

// (Built with std::filesystem::path: GCC 12's -Warray-bounds misreads std::string's operator+ on a literal
// here when the tests' precompiled header is in use, a known false positive of that compiler.)
std::string scene_path(const char* name) { return (std::filesystem::path(SSS_SOURCE_DIR) / "tests/cli/scenes" / name).string(); }
std::string small_scene_path() { return scene_path("small.toml"); }

template <class R> bool bit_identical(const sss::waterfall<R>& a, const sss::waterfall<R>& b) {
    return a.values.size() == b.values.size() && std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(R)) == 0;
}
template <class R> double energy_of(const sss::waterfall<R>& w) {
    double e = 0;
    for (R v : w.values) e += double(v);
    return e;
}
/// Sum of |a - b| over sum of |a|: how far waterfall b is from a.
template <class R> double relative_difference(const sss::waterfall<R>& a, const sss::waterfall<R>& b) {
    double diff = 0, sum = 0;
    for (std::size_t i = 0; i < a.values.size(); ++i) {
        diff += std::abs(double(a.values[i]) - double(b.values[i]));
        sum += std::abs(double(a.values[i]));
    }
    return diff / sum;
}
/// Pings [first, first + count) of scene d in scalar R, as sss-render renders them with render.precision R.
template <class R> sss::waterfall<R> scene_lines(const sss::scene_file::description& d, std::size_t first, std::size_t count) {
    const auto w = sss::scene_file::make_world<R>(d);
    return sss::scene_file::with_simulator(d, w, [&](const auto& s) { return s.render(w, first, count, 1); });
}

} // namespace

namespace {

// The message of the scene error parsing `text` (as s.toml) gives, or "no error".
std::string error_of(const std::string& text) {
    try {
        (void)sss::scene_file::parse(text, "s.toml");
    } catch (const sss::scene_file::scene_error& e) {
        return std::string(e.what());
    }
    return std::string("no error");
}

} // namespace

TEST_CASE("a scene file and the equivalent C++ program render bit-identical waterfalls") {
    const auto d = sss::scene_file::parse_file(small_scene_path());
    const auto from_file = sss::scene_file::make_world(d);
    const auto by_hand = hand_written_world();
    REQUIRE(from_file.seabed().heights_m() == by_hand.seabed().heights_m());

    const T z = by_hand.seabed().seabed_height_m(T(25.5), T(8)) + T(6);
    const sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>,
                         sss::motion::perturbed<T>>
        sim(sss::scattering::lambertian<T>({.mu_db = {T(-27), T(-20), T(-8)}}),
            sss::propagation::straight<T>({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)}),
            sss::beam::ideal_fan<T>({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)}),
            sss::motion::perturbed<T>({.start_m = {T(25.5), T(8)}, .heading_deg = T(0), .speed_mps = T(2), .altitude_m = z,
                                           .ping_interval_s = T(0.1)}),
            sss::receiver_params{.sample_rate_hz = 20000, .max_range_m = 25});
    const auto expected = sim.render(by_hand, 0, 6, 1);
    const auto got = sss::scene_file::with_simulator(d, from_file, [&](const auto& s) { return s.render(from_file, 0, 6, 1); });
    REQUIRE(got.values.size() == expected.values.size());
    CHECK(std::memcmp(got.values.data(), expected.values.data(), got.values.size() * sizeof(T)) == 0);
    double energy = 0;
    for (T v : got.values) energy += double(v);
    CHECK(energy > 0.0); // the seabed is in view: the comparison is not between two black images
}

TEST_CASE("a georeferenced scene file in double and the equivalent C++ program in double render bit-identical waterfalls") {
    using D = double;
    const auto d = sss::scene_file::parse_file(scene_path("georeferenced.toml"));
    REQUIRE(d.run.precision == "double");
    const auto from_file = sss::scene_file::make_world<D>(d);
    const auto by_hand = hand_written_world<D>(500000, 6000000);
    REQUIRE(from_file.seabed().heights_m() == by_hand.seabed().heights_m());

    const D z = by_hand.seabed().seabed_height_m(500025.5, 6000008.0) + 6;
    const sss::simulator<sss::scattering::lambertian<D>, sss::propagation::straight<D>, sss::beam::ideal_fan<D>,
                         sss::motion::perturbed<D>>
        sim(sss::scattering::lambertian<D>({.mu_db = {-27, -20, -8}}),
            sss::propagation::straight<D>({.sound_speed_mps = 1500, .absorption_db_per_km = 30}),
            sss::beam::ideal_fan<D>({.along_width_deg = 1, .vertical_width_deg = 50, .depression_deg = 20}),
            sss::motion::perturbed<D>({.start_m = {500025.5, 6000008}, .heading_deg = 0, .speed_mps = 2, .altitude_m = z,
                                       .ping_interval_s = 0.1}),
            sss::receiver_params{.sample_rate_hz = 20000, .max_range_m = 25});
    const auto expected = sim.render(by_hand, 12, 6, 1);
    const auto got = sss::scene_file::with_simulator(d, from_file, [&](const auto& s) { return s.render(from_file, 12, 6, 1); });
    CHECK(bit_identical(got, expected));
    CHECK(energy_of(got) > 0.0);
}

TEST_CASE("in double a scene moved 500 km east and 6000 km north renders what it renders at the origin; float cannot hold it") {
    // Float holds a northing of 6000 km to 0.5 m and an easting of 500 km to 3 cm: the track's 0.2 m between pings
    // and the seabed's 0.2 m cells are rounded away. Double holds both to a nanometre.
    const auto local = sss::scene_file::parse_file(small_scene_path());
    const auto geo = sss::scene_file::parse_file(scene_path("georeferenced.toml"));
    const auto at_origin = scene_lines<double>(local, 12, 6);
    const auto moved = scene_lines<double>(geo, 12, 6);
    REQUIRE(moved.values.size() == at_origin.values.size());
    const double in_double = relative_difference(at_origin, moved);
    CHECK(energy_of(at_origin) > 0.0);
    CHECK(in_double < 1e-6);
    const double in_float = relative_difference(scene_lines<float>(local, 12, 6), scene_lines<float>(geo, 12, 6));
    MESSAGE("sum |moved - at origin| / sum |at origin| over pings 12 to 17: double " << in_double << ", float " << in_float);
    CHECK(in_float > 1e-2);
    // The same in layered water: the rays bend through the profile below a surface placed from the towfish's
    // depth, and the track's coordinates are as large.
    auto local_layered = local, geo_layered = geo;
    for (auto* d : {&local_layered, &geo_layered}) {
        d->sea.model = "layered";
        d->sea.depth_m = {0, 10, 30};
        d->sea.speed_mps = {1500, 1495, 1485};
    }
    // (Measured 1e-5: the hits agree to a nanometre, but a hit's smooth shading normal is taken where the chord met
    // the facet, up to the chord tolerance off the arc, and near a joint rounding decides which of the two chords
    // finds it: a few normals differ by up to 1e-4. With chords of 0.1 um the difference is 1.4e-9; float is off by
    // 0.2.)
    const auto layered_at_origin = scene_lines<double>(local_layered, 12, 6);
    CHECK(energy_of(layered_at_origin) > 0.0);
    const double layered_moved = relative_difference(layered_at_origin, scene_lines<double>(geo_layered, 12, 6));
    MESSAGE("the same in layered water, double: " << layered_moved);
    CHECK(layered_moved < 1e-4);
}

TEST_CASE("the resolved scene read back is the same scene, with every default written out") {
    const auto d = sss::scene_file::parse_file(small_scene_path());
    const std::string text = sss::scene_file::to_toml(d);
    const auto again = sss::scene_file::parse(text, "resolved.toml");
    CHECK(sss::scene_file::to_toml(again) == text);
    CHECK(again.bed.regions.size() == 2);
    CHECK(again.bed.regions[0].ripple_sets[0].crest_heading_deg == 0.0);
    CHECK(again.sea.absorption_db_per_km == 30.0); // a default, written out and read back
    CHECK(again.run.precision == "float");
    CHECK(again.run.along_split_by_weight);
    CHECK(sss::scene_file::rays_of(again).along_split_by_weight);
    // The ray density's switches, each turned off, read back and reach the simulator's ray density.
    auto switched_off = [&](bool sss::scene_file::render::*key) {
        auto changed = d;
        changed.run.*key = false;
        return sss::scene_file::parse(sss::scene_file::to_toml(changed), "resolved.toml");
    };
    const auto even_again = switched_off(&sss::scene_file::render::along_split_by_weight);
    CHECK_FALSE(even_again.run.along_split_by_weight);
    CHECK_FALSE(sss::scene_file::rays_of(even_again).along_split_by_weight);
    CHECK(sss::scene_file::rays_of(again).refine_facets);
    const auto plain_again = switched_off(&sss::scene_file::render::refine_facets);
    CHECK_FALSE(plain_again.run.refine_facets);
    CHECK_FALSE(sss::scene_file::rays_of(plain_again).refine_facets);
    CHECK(sss::scene_file::rays_of(again).bracket_facet_edges);
    const auto halving_again = switched_off(&sss::scene_file::render::bracket_facet_edges);
    CHECK_FALSE(halving_again.run.bracket_facet_edges);
    CHECK_FALSE(sss::scene_file::rays_of(halving_again).bracket_facet_edges);
    CHECK(sss::scene_file::rays_of(again).along_split_sparse);
    const auto dense_again = switched_off(&sss::scene_file::render::along_split_sparse);
    CHECK_FALSE(dense_again.run.along_split_sparse);
    CHECK_FALSE(sss::scene_file::rays_of(dense_again).along_split_sparse);
    CHECK(sss::scene_file::rays_of(again).along_split_targets);
    const auto untargeted_again = switched_off(&sss::scene_file::render::along_split_targets);
    CHECK_FALSE(untargeted_again.run.along_split_targets);
    CHECK_FALSE(sss::scene_file::rays_of(untargeted_again).along_split_targets);
    CHECK(sss::scene_file::rays_of(again).along_split_nadir);
    const auto nadir_again = switched_off(&sss::scene_file::render::along_split_nadir);
    CHECK_FALSE(nadir_again.run.along_split_nadir);
    CHECK_FALSE(sss::scene_file::rays_of(nadir_again).along_split_nadir);
    CHECK(sss::scene_file::rays_of(again).sloping_launch);
    const auto level_again = switched_off(&sss::scene_file::render::sloping_launch);
    CHECK_FALSE(level_again.run.sloping_launch);
    CHECK_FALSE(sss::scene_file::rays_of(level_again).sloping_launch);
    // A number of [render] set to `value`, written and read back: it reaches the scene and its ray_density.
    auto set_to = [&](double sss::scene_file::render::*key, double value) {
        auto changed = d;
        changed.run.*key = value;
        return sss::scene_file::parse(sss::scene_file::to_toml(changed), "resolved.toml");
    };
    CHECK(sss::scene_file::rays_of(again).along_split_echo == 0.1);
    const auto echo_again = set_to(&sss::scene_file::render::along_split_echo, 0.25);
    CHECK(echo_again.run.along_split_echo == 0.25);
    CHECK(sss::scene_file::rays_of(echo_again).along_split_echo == 0.25);
    CHECK(sss::scene_file::rays_of(again).max_launch_step_deg == 1.0);
    const auto step_again = set_to(&sss::scene_file::render::max_launch_step_deg, 0.5);
    CHECK(step_again.run.max_launch_step_deg == 0.5);
    CHECK(sss::scene_file::rays_of(step_again).max_launch_step_deg == 0.5);
    const auto geo = sss::scene_file::parse_file(scene_path("georeferenced.toml"));
    const auto geo_again = sss::scene_file::parse(sss::scene_file::to_toml(geo), "resolved.toml");
    CHECK(sss::scene_file::to_toml(geo_again) == sss::scene_file::to_toml(geo));
    CHECK(geo_again.run.precision == "double");
    CHECK(geo_again.bed.origin_m == sss::scene_file::xy{500000, 6000000});
}

TEST_CASE("an unknown key is an error naming its line and column and the closest valid key") {
    try {
        (void)sss::scene_file::parse("[water]\nsound_speed_mps = 1500\nabsorbtion_db_per_km = 20\n", "typo.toml");
        FAIL("no error");
    } catch (const sss::scene_file::scene_error& e) {
        CHECK(std::string(e.what()) == "typo.toml:3:1: water.absorbtion_db_per_km: unknown key; did you mean 'absorption_db_per_km'?");
    }
}

TEST_CASE("receiver.tvg raises each sample by N log10 r + 2 alpha r / 1000 dB, r = c (k + 1/2) dt / 2 (Urick 1983)") {
    auto d = sss::scene_file::parse_file(small_scene_path());
    const auto w = sss::scene_file::make_world(d);
    const auto plain = sss::scene_file::with_simulator(d, w, [&](const auto& s) { return s.render(w, 0, 2, 1); });
    d.rx.tvg = true;
    d.rx.tvg_spreading_n = 30;
    const auto gained = sss::scene_file::with_simulator(d, w, [&](const auto& s) { return s.render(w, 0, 2, 1); });
    REQUIRE(plain.values.size() == gained.values.size());
    std::size_t compared = 0;
    for (std::size_t k = 0; k < plain.samples; ++k) {
        const std::size_t col = plain.samples + k; // starboard sample k of ping 0
        const double before = double(plain.at(0, col)), after = double(gained.at(0, col));
        if (!(before > 0)) continue;
        const double r = std::max(1.0, 0.5 * 1500.0 * (double(k) + 0.5) * plain.dt_s);
        const double expected_db = 30.0 * std::log10(r) + 2.0 * 30.0 * r / 1000.0;
        CHECK(10.0 * std::log10(after / before) == doctest::Approx(expected_db).epsilon(1e-4));
        ++compared;
    }
    CHECK(compared > plain.samples / 2); // most of the line sees the seabed
}

TEST_CASE("receiver.speckle keeps the mean power of the seabed within 10 % over many samples (exponential intensity)") {
    auto d = sss::scene_file::parse_file(small_scene_path());
    const auto w = sss::scene_file::make_world(d);
    const auto mean = sss::scene_file::with_simulator(d, w, [&](const auto& s) { return s.render(w, 0, 12, 1); });
    d.rx.speckle = true;
    const auto speckled = sss::scene_file::with_simulator(d, w, [&](const auto& s) { return s.render(w, 0, 12, 1); });
    double a = 0, b = 0;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < mean.values.size(); ++i) {
        a += double(mean.values[i]);
        b += double(speckled.values[i]);
        differ += mean.values[i] != speckled.values[i] ? 1 : 0;
    }
    CHECK(differ > mean.values.size() / 4); // speckle touches every sample that has an echo
    CHECK(b / a == doctest::Approx(1.0).epsilon(0.1));
}

TEST_CASE("a planar-array scene file renders what sss::beam::planar_array renders, bit for bit") {
    const auto d = sss::scene_file::parse_file(scene_path("planar.toml"));
    const auto w = sss::scene_file::make_world(d);
    const T z = w.seabed().seabed_height_m(T(25.5), T(8)) + T(6);
    namespace bm = sss::beam;
    const bm::planar_array<T> array({.frequency_hz = T(100000), .sound_speed_mps = T(1500), .depression_deg = T(20),
                                     .transmit = {.along = {.count = 4, .element_m = T(0.05), .pitch_m = T(0.05)},
                                                  .vertical = {.count = 1, .element_m = T(0.02)}},
                                     .receive = bm::array_layout<T>{.along = {.count = 4, .element_m = T(0.05), .pitch_m = T(0.05),
                                                                              .shading = {T(0.5), T(1), T(1), T(0.5)}},
                                                                    .vertical = {.count = 1, .element_m = T(0.03)}},
                                     .threshold_db = T(-40)});
    const sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, bm::planar_array<T>, sss::motion::perturbed<T>>
        sim(sss::scattering::lambertian<T>({.mu_db = {T(-27), T(-8)}}),
            sss::propagation::straight<T>({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)}), array,
            sss::motion::perturbed<T>({.start_m = {T(25.5), T(8)}, .heading_deg = T(0), .speed_mps = T(1), .altitude_m = z,
                                       .ping_interval_s = T(0.1)}),
            sss::receiver_params{.sample_rate_hz = 20000, .max_range_m = 25});
    const auto expected = sim.render(w, 0, 4, 1);
    const auto got = sss::scene_file::with_simulator(d, w, [&](const auto& s) {
        // The scene's beam states the array's along-track step (a third of lambda / L), so it launches as many columns.
        const auto sd = sss::side::starboard;
        CHECK(s.beam().along_resolution_rad(sd) == doctest::Approx(1500.0 / 100000.0 / 0.2 / 3.0).epsilon(1e-5));
        CHECK(s.along_columns(s.beam().extent(sd), sd) == sim.along_columns(array.extent(sd), sd));
        return s.render(w, 0, 4, 1);
    });
    CHECK(bit_identical(got, expected));
    CHECK(energy_of(got) > 0.0);
}

TEST_CASE("a trajectory scene file renders what sss::motion::trajectory renders, bit for bit, and turns with it") {
    // A starboard turn, a sixth of a 20 m circle in 10 s, sampled once a second, written to the scratch directory.
    sss::motion::trajectory_samples<T> samples;
    std::string csv = "time_s,x_m,y_m,z_m\n";
    const auto text = [](double v) {
        char buf[32];
        return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
    };
    for (int i = 0; i <= 10; ++i) {
        const double phi = 3.14159265358979323846 / 3.0 * double(i) / 10.0;
        const double x = 45.0 - 20.0 * std::cos(phi), y = 5.0 + 20.0 * std::sin(phi);
        samples.time_s.push_back(double(i));
        samples.position_m.push_back({T(x), T(y), T(6)});
        csv += text(double(i)) + "," + text(x) + "," + text(y) + ",6\n";
    }
    std::ofstream("turn_scratch.csv") << csv;
    auto d = sss::scene_file::parse_file(scene_path("trajectory.toml"));
    d.tow.trajectory_file = "turn_scratch.csv";
    const auto w = sss::scene_file::make_world(d);
    const sss::motion::trajectory<T> track(samples, {.ping_interval_s = T(0.1), .method = sss::motion::interpolation::cubic});
    REQUIRE(track.ping_count() == 101);
    const sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>, sss::motion::trajectory<T>>
        sim(sss::scattering::lambertian<T>({.mu_db = {T(-27), T(-20), T(-8)}}),
            sss::propagation::straight<T>({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)}),
            sss::beam::ideal_fan<T>({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)}), track,
            sss::receiver_params{.sample_rate_hz = 20000, .max_range_m = 25});
    const auto expected = sim.render(w, 60, 4, 1);
    double end_heading_deg = 0;
    const auto got = sss::scene_file::with_simulator(d, w, [&](const auto& s) {
        end_heading_deg = double(s.motion().pose_at(100).yaw_rad) * 180.0 / 3.14159265358979323846;
        return s.render(w, 60, 4, 1);
    });
    CHECK(bit_identical(got, expected));
    CHECK(energy_of(got) > 0.0);
    // The heading follows the track's tangent: 60 deg of starboard turn after 10 s (the samples are exact).
    CHECK(end_heading_deg == doctest::Approx(60.0).epsilon(1e-3));
    // XTF times follow the trajectory's clock: its ping 0 is at time_s = 0 here, so ping 60 is 6 s after the offset.
    d.out.xtf_start_unix_s = 1.7e9;
    const auto tow = sss::scene_file::motion_of(d, T(0));
    CHECK(sss::scene_file::xtf_start_unix_s(d, tow, 60) == doctest::Approx(1.7e9 + 6.0));
}

TEST_CASE("a trajectory timed in Unix seconds stamps its pings with those times in the XTF file") {
    std::ofstream("unix_scratch.csv") << "time_s,x_m,y_m,z_m\n1700000000,40,5,6\n1700000010,40,25,6\n1700000020,40,45,6\n"
                                     "1700000030,40,65,6\n";
    auto d = sss::scene_file::parse("[motion]\nmodel = \"trajectory\"\ntrajectory_file = \"unix_scratch.csv\"\n", "s.toml");
    const auto tow = sss::scene_file::motion_of(d, T(0));
    CHECK(sss::scene_file::xtf_start_unix_s(d, tow, 0) == 1700000000.0);
    CHECK(sss::scene_file::xtf_start_unix_s(d, tow, 25) == doctest::Approx(1700000002.5));
}

TEST_CASE("the planar array's and the trajectory's keys read back from the resolved scene unchanged") {
    for (const char* name : {"planar.toml", "trajectory.toml"}) {
        auto d = sss::scene_file::parse_file(scene_path(name));
        d.tow.ping_zero_at = 0.5;
        const std::string text = sss::scene_file::to_toml(d);
        const auto again = sss::scene_file::parse(text, "resolved.toml");
        CHECK(sss::scene_file::to_toml(again) == text);
        if (d.sensor.beam == "planar_array") {
            REQUIRE(again.sensor.receive);
            CHECK(again.sensor.receive->along.shading == std::vector<double>{0.5, 1, 1, 0.5});
            CHECK(again.sensor.transmit.along.pitch_m == 0.05); // defaults to the element length
        } else {
            CHECK(again.tow.model == "trajectory");
            CHECK(again.tow.ping_zero_at == 0.5);
        }
    }
}

TEST_CASE("the planar array's elements and the trajectory's keys are rejected where they cannot apply, naming the key") {
    CHECK(error_of("[sonar.transmit]\nalong_count = 2\n") ==
          "s.toml:1:1: sonar.transmit: needs beam = \"planar_array\" (the ideal fan has no elements; its keys are along_width_deg, "
          "vertical_width_deg and depression_deg)");
    CHECK(error_of("[sonar]\nbeam = \"planar_array\"\n[sonar.transmit]\nalong_count = 3\nalong_element_m = 0.1\nalong_pitch_m = 0.05\n")
              .find("sonar.transmit.along_pitch_m: must be at least along_element_m (0.1 m)") != std::string::npos);
    CHECK(error_of("[sonar]\nbeam = \"planar_array\"\n[sonar.receive]\nalong_count = 3\nalong_shading = [1, 1]\n")
              .find("sonar.receive.along_shading: must hold one weight per element (along_count = 3), got 2") != std::string::npos);
    CHECK(error_of("[motion]\ntrajectory_file = \"t.csv\"\n").find("motion.trajectory_file: needs model = \"trajectory\"") !=
          std::string::npos);
    CHECK(error_of("[motion]\nmodel = \"trajectory\"\n").find("motion.model: a trajectory needs motion.trajectory_file") !=
          std::string::npos);
    // The perturbed motion's cross-checks apply only to it: a turn without a radius is ignored under a trajectory.
    CHECK(error_of("[motion]\nturn = \"port\"\n").find("motion.turn: a turn needs turn_radius_m > 0") != std::string::npos);
    CHECK(error_of("[motion]\nmodel = \"trajectory\"\ntrajectory_file = \"t.csv\"\nturn = \"port\"\n") == "no error");
}

TEST_CASE("a trajectory file that cannot be read is a scene error naming the key and the file") {
    auto d = sss::scene_file::parse("[motion]\nmodel = \"trajectory\"\ntrajectory_file = \"no_such_track.csv\"\n", "s.toml");
    try {
        (void)sss::scene_file::motion_of(d, T(10));
        FAIL("no error");
    } catch (const sss::scene_file::scene_error& e) {
        CHECK(std::string(e.what()) == "s.toml: motion.trajectory_file: no_such_track.csv: cannot open for reading");
    }
}

TEST_CASE("the XTF beam angles of a uniform array are its two-way half-power widths: sinc^4 = 1/2 at pi L u / lambda = 1.0019") {
    // Eight 5 cm elements edge to edge are one 0.4 m aperture, and one 2 cm element vertically: the two-way
    // pattern is sinc^4(pi L u / lambda) (Kinsler et al., 2000, "Fundamentals of Acoustics", ch. 8), half power
    // where sinc = 2^(-1/4), at pi L u / lambda = 1.0019; lambda = 1500 / 100000 m.
    auto d = sss::scene_file::parse("[sonar]\nbeam = \"planar_array\"\n[sonar.transmit]\nalong_count = 8\nalong_element_m = 0.05\n"
                                    "vertical_element_m = 0.02\n",
                                    "s.toml");
    const auto widths = sss::scene_file::widths_of(sss::scene_file::beam_of(d), d.sensor.depression_deg);
    const double lambda = 0.015, y = 1.0019064, deg = 180.0 / 3.14159265358979323846;
    CHECK(widths.along_deg == doctest::Approx(2.0 * std::asin(y * lambda / (3.14159265358979323846 * 0.4)) * deg).epsilon(1e-3));
    CHECK(widths.vertical_deg == doctest::Approx(2.0 * std::asin(y * lambda / (3.14159265358979323846 * 0.02)) * deg).epsilon(1e-3));
    // The ideal fan's widths are its own.
    d.sensor.beam = "ideal_fan";
    const auto fan = sss::scene_file::widths_of(sss::scene_file::beam_of(d), d.sensor.depression_deg);
    CHECK(fan.along_deg == doctest::Approx(1.0));
    CHECK(fan.vertical_deg == doctest::Approx(50.0));
}

TEST_CASE("a Lambert parameter above -4.9715 dB (mu above 1/pi) is refused where Lambert's law is used, with its key and line") {
    CHECK(error_of("[seabed]\n[[seabed.region]]\nmu_db = -4\n").starts_with("s.toml:3:9: seabed.region[0].mu_db: must be <= -4.9715 dB"));
    CHECK(error_of("[sonar]\ntarget_mu_db = 0\n").starts_with("s.toml:2:16: sonar.target_mu_db: must be <= -4.9715 dB"));
    CHECK(error_of("[sonar]\ntarget_mu_db = -4.971\n").starts_with("s.toml:2:16: sonar.target_mu_db: must be <= -4.9715 dB"));
    CHECK(error_of("[sonar]\ntarget_mu_db = -4.9715\n") == "no error");
    CHECK(error_of("[seabed]\n[[seabed.region]]\nmu_db = -5\n") == "no error");
    // Under Jackson's model neither is used: left as given.
    CHECK(error_of("[seabed]\n[[seabed.region]]\nmu_db = 0\n[sonar]\nscattering = \"jackson\"\ntarget_mu_db = 0\n") == "no error");
}

TEST_CASE("a loaded seabed, or a flat generated one, refuses the keys it would ignore, and its resolved scene leaves them "
          "out and reads back") {
    // A .asc or .raw brings its size, cell and place; a .pgm its size only; a generated seabed has no samples
    // to scale, without regions nothing to seed, partition or blend, and with one region no boundary. Each refused key
    // is named with its line and column.
    CHECK(error_of("[seabed]\nfile = \"b.asc\"\ncell_m = 0.5\n").starts_with("s.toml:3:10: seabed.cell_m: a loaded .asc seabed is placed by its header"));
    CHECK(error_of("[seabed]\nfile = \"b.raw\"\norigin_m = [1, 2]\n").starts_with("s.toml:3:12: seabed.origin_m: a loaded .raw seabed is placed by its .raw.txt sidecar"));
    CHECK(error_of("[seabed]\nfile = \"b.pgm\"\nnx = 64\n").starts_with("s.toml:3:6: seabed.nx: a loaded seabed's size is its file's"));
    CHECK(error_of("[seabed]\nfile = \"b.asc\"\nblend_m = 1\n").starts_with("s.toml:3:11: seabed.blend_m: sets the generated seabed"));
    CHECK(error_of("[seabed]\npgm_offset_m = 1\n").starts_with("s.toml:2:16: seabed.pgm_offset_m: applies only to a .pgm seabed.file"));
    CHECK(error_of("[seabed]\nfile = \"b.asc\"\n[[seabed.site]]\nx_m = 1\n").find("seabed.site: a loaded seabed takes no [[seabed.site]] tables") !=
          std::string::npos);
    // What each one uses is taken.
    CHECK(error_of("[seabed]\nfile = \"b.pgm\"\ncell_m = 0.5\norigin_m = [1, 2]\npgm_scale_m = 0.1\npgm_offset_m = -3\n") == "no error");
    const std::string region = "[[seabed.region]]\nsediment = \"medium_sand\"\n";
    const std::string two_regions = region + "[[seabed.region]]\nsediment = \"coarse_sand\"\n[[seabed.site]]\nx_m = 1\ny_m = 1\n"
                                             "region = 0\n[[seabed.site]]\nx_m = 20\ny_m = 20\nregion = 1\n";
    CHECK(error_of("[seabed]\nnx = 64\nseed = 3\nblend_m = 1\nwarp_m = 2\nwarp_scale_m = 5\npartition_seed = 4\n" + two_regions) ==
          "no error");
    CHECK(error_of("[seabed]\nnx = 64\nseed = 3\n" + region) == "no error");
    CHECK(error_of("[seabed]\nnx = 64\nseed = 3\n").starts_with(
        "s.toml:3:8: seabed.seed: applies only to a seabed generated from [[seabed.region]] tables (without them there is no roughness"));
    CHECK(error_of("[seabed]\npartition_seed = 3\nregion = []\n").starts_with("s.toml:2:18: seabed.partition_seed: applies only"));
    CHECK(error_of("[seabed]\nwarp_m = 2\n" + region).starts_with(
        "s.toml:2:10: seabed.warp_m: applies only where [[seabed.region]] tables meet (with one region there is no boundary"));
    for (const auto& [file, regions] : {std::pair{"b.asc", 0}, {"b.raw", 0}, {"b.pgm", 0}, {"", 0}, {"", 1}, {"", 2}}) {
        CAPTURE(file);
        CAPTURE(regions);
        auto d = sss::scene_file::parse("[render]\npings = 3\n" + (regions == 1   ? "[seabed]\n" + region
                                                                   : regions == 2 ? "[seabed]\n" + two_regions
                                                                                  : std::string()),
                                        "s.toml");
        d.bed.file = file;
        const std::string text = sss::scene_file::to_toml(d);
        const auto again = sss::scene_file::parse(text, "resolved.toml");
        CHECK(sss::scene_file::to_toml(again) == text);
        const bool pgm = std::string(file).ends_with(".pgm"), loaded = *file != 0;
        const auto from = text.find("[seabed]\n");
        REQUIRE(from != std::string::npos);
        const std::string bed = text.substr(from, text.find("\n[", from) - from + 1);
        const auto has = [&](const char* key) {
            std::string line = "\n"; // piece by piece: GCC 12 at -O3 warns (falsely) of an overflow in "\n" + string
            line += key;
            line += " = ";
            return bed.find(line) != std::string::npos;
        };
        CHECK(has("file"));
        CHECK(has("pgm_scale_m") == pgm);
        CHECK(has("cell_m") == (pgm || !loaded));
        CHECK(has("origin_m") == (pgm || !loaded));
        CHECK(has("nx") == !loaded);
        CHECK(has("seed") == (regions > 0));
        CHECK(has("warp_m") == (regions > 1));
        CHECK(has("partition_seed") == (regions > 1));
    }
}

namespace {
bool has_text(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
} // namespace

TEST_CASE("a millimetre seabed without region boundaries keeps the default blend; a whole number beyond 2^53 is named") {
    // The default blend_m (0.5 m) is 500 cells at cell_m = 1 mm: held to the blend's reach only where regions meet.
    const auto fine = sss::scene_file::parse("[seabed]\nnx = 64\nny = 64\ncell_m = 0.001\n", "fine.toml");
    CHECK(fine.bed.cell_m == 0.001);
    CHECK(has_text(error_of("[seabed]\nnx = 64\nny = 64\ncell_m = 0.001\nblend_m = 0.5\n[[seabed.region]]\nsediment = \"rock\"\n"
                            "[[seabed.region]]\nsediment = \"medium_sand\"\n"),
                   "seabed.blend_m: must be at most 256 cells"));
    // 2^53 + 1 is an integer no double holds: the bound names the key and line (it was "bad optional access").
    CHECK(has_text(error_of("[motion]\nstart_m = [9007199254740993, 0]\n"), "s.toml:2:11: motion.start_m: must lie within"));
    CHECK(has_text(error_of("[water]\nmodel = \"layered\"\ndepth_m = [0, 9007199254740993]\nspeed_mps = [1500, 1500]\n"),
                   "s.toml:3:11: water.depth_m: each value must lie within"));
}

TEST_CASE("a relative file key leads from the scene file's directory, and a resolved scene writes it absolute") {
    const std::string text = "[motion]\nmodel = \"trajectory\"\ntrajectory_file = \"tracks/turn.csv\"\n"
                             "[water]\nmodel = \"layered\"\nsvp_file = \"/data/profile.csv\"\n";
    const auto d = sss::scene_file::parse(text, "survey/north/scene.toml");
    CHECK(std::filesystem::path(d.tow.trajectory_file) == std::filesystem::path("survey/north") / "tracks/turn.csv");
    CHECK(d.sea.svp_file == "/data/profile.csv"); // absolute: as written
    CHECK(d.bed.file.empty());                    // no file: none
    const auto here = sss::scene_file::parse(text, "scene.toml");
    CHECK(here.tow.trajectory_file == "tracks/turn.csv"); // a scene in the working directory: from there
    const std::string resolved = sss::scene_file::to_toml(d);
    const std::string written = (std::filesystem::current_path() / "survey/north/tracks/turn.csv").string();
    CHECK(resolved.find("trajectory_file = \"" + written + "\"") != std::string::npos);
    // Read back from another directory, the resolved scene names the same files.
    const auto again = sss::scene_file::parse(resolved, "elsewhere/resolved.toml");
    CHECK(again.tow.trajectory_file == written);
    CHECK(sss::scene_file::to_toml(again) == resolved);
}
