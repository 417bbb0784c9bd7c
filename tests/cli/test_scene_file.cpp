// A scene file and the equivalent C++ program render bit-identical waterfalls: the scene file is a front door
// to the library, not a second model. tests/cli/scenes/small.toml is written out here by hand, with the
// library's parameter structs, and both are rendered for a few pings.

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
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace {

using T = float;
namespace sb = sss::seabed;

// small.toml, by hand.
auto hand_written_world() {
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
    sss::scene::height_field<T> seabed(
        {.nx = nx, .ny = ny, .cell_m = cell, .heights_m = bed.height.values, .materials = material, .regions = material});
    std::vector<sss::scene::object<T>> objects{sb::lying_cylinder(
        sb::lying_cylinder_params<T>{.center_m = {T(38), T(12)}, .heading_deg = T(0), .length_m = T(2), .radius_m = T(0.3),
                                     .ids = {.material = 2, .object = 1, .label = 1}},
        sb::seabed_height_of(seabed))};
    return sss::scene::scene(std::move(seabed), sss::scene::object_set<T>(std::move(objects)));
}

std::string small_scene_path() { return std::string(SSS_SOURCE_DIR) + "/tests/cli/scenes/small.toml"; }

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

TEST_CASE("the resolved scene read back is the same scene, with every default written out") {
    const auto d = sss::scene_file::parse_file(small_scene_path());
    const std::string text = sss::scene_file::to_toml(d);
    const auto again = sss::scene_file::parse(text, "resolved.toml");
    CHECK(sss::scene_file::to_toml(again) == text);
    CHECK(again.bed.regions.size() == 2);
    CHECK(again.bed.regions[0].ripple_sets[0].crest_heading_deg == 0.0);
    CHECK(again.sea.absorption_db_per_km == 30.0); // a default, written out and read back
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
