// A record as a sidescan writes it: the demo's kind of seabed (rippled medium sand beside sandy gravel, each region
// made from one sediment description that sets both its relief and its Jackson scattering) with a steel cylinder
// under the hard-target model, rendered through the receiver: seabed-anchored K speckle, sea-state noise and volume
// reverberation, then a 30 log r TVG, then 8-bit amplitude quantisation. Writes two PNGs (argv[1], default
// sss_record.png: slant range; argv[2], default sss_record_ground.png: ground range, water column removed).
//
// What to look for: grain that is the same from ping to ping for about the transducer's length (0.5 m, 2.5 pings)
// and belongs to the seabed (the ripples and the region boundary carry it); the gravel brighter than the sand;
// a grey water column before the first bottom return instead of black; the cylinder's highlight saturating the 8 bits, with its shadow behind. At 100 kHz and 50 m the
// seabed stays some 30 dB above sea-state 2 noise (as it does at sea), so the noise shows only where nothing else
// returns.

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>

#include "common/png.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <span>
#include <string>
#include <vector>

int main(int argc, char** argv) try {
    using T = float;
    namespace sb = sss::seabed;
    using namespace sss;
    const std::string out = argc > 1 ? argv[1] : "sss_record.png";
    const std::string out_ground = argc > 2 ? argv[2] : "sss_record_ground.png";
    const auto t0 = std::chrono::steady_clock::now();

    // Seabed: 102.4 m x 51.2 m at 10 cm; two sediment regions in warped Voronoi cells.
    const std::size_t nx = 1024, ny = 512;
    const T cell = T(0.1);
    sb::voronoi_partition<T> partition;
    partition.sites = {{T(30), T(15), 0}, {T(80), T(20), 1}, {T(70), T(45), 0}};
    partition.warp_m = T(4);
    partition.warp_scale_m = T(20);
    const std::vector<sb::sediment_region<T>> regions{
        {.id = 0, .sediment = sb::sediment_named<T>("medium_sand"),
         .ripples = {sb::ripple_params<T>{.wavelength_m = T(0.9), .height_m = T(0.08), .crest_heading_deg = T(21.25), .symmetry_index = T(2)}}},
        {.id = 1, .sediment = sb::sediment_named<T>("sandy_gravel"), .mean_height_m = T(0.2)}};
    const auto bed = sb::compose(sb::partition(nx, ny, cell, partition, 7), sb::textures(regions), T(0.5), 11);
    std::vector<std::uint32_t> material((nx - 1) * (ny - 1));
    for (std::size_t iy = 0; iy + 1 < ny; ++iy)
        for (std::size_t ix = 0; ix + 1 < nx; ++ix) material[iy * (nx - 1) + ix] = bed.regions.values[iy * nx + ix];
    const scene::height_field<T> seabed(
        {.nx = nx, .ny = ny, .cell_m = cell, .heights_m = bed.height.values, .materials = material, .regions = material});
    // A steel cylinder 2 m long, 0.6 m across, 30 m to starboard; material 2: the first target material.
    const T track_x = T(51.2);
    const T base = seabed.seabed_height_m(track_x + T(30), T(25));
    std::vector<scene::object<T>> objects{scene::object<T>(
        {}, {scene::cylinder<T>({.end0_m = vec3<T>(track_x + T(30), T(24), base + T(0.3)),
                                 .end1_m = vec3<T>(track_x + T(30), T(26), base + T(0.3)),
                                 .radius_m = T(0.3),
                                 .ids = {.material = 2, .object = 1, .label = 1}})})};
    const scene::scene world(seabed, scene::object_set<T>(std::move(objects)));

    // Sonar: sediments under Jackson, the cylinder under the hard-target facet model, at 100 kHz.
    using scatter = scattering::by_material<scattering::jackson<T>, scattering::hard_target<T>>;
    const scatter scattering(sb::jackson_for(regions, {.frequency_hz = T(100000), .sound_speed_mps = T(1500)}), scattering::hard_target<T>{});
    const propagation::straight<T> water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    const beam::ideal_fan<T> fan({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)});
    const motion::straight_line<T> tow(motion::straight_line_params<T>{
        .start_m = {track_x, T(5)}, .speed_mps = T(2), .altitude_m = T(10), .ping_interval_s = T(0.1)});
    const receiver_params rx{.sample_rate_hz = 20000, .max_range_m = 50, .pulse = {.length_s = 100e-6},
                             .source_level_db = 210};
    // The receiver: K speckle (nu = 4) anchored to the seabed, sea state 2 noise, volume reverberation of a dense
    // plankton layer (S_v = -60 dB) in the fan's own solid angle (psi_sr = 0) above the seabed, then TVG 30 log r
    // with the water's absorption.
    using chain = line_chain<echo_statistics, tvg>;
    const echo_statistics statistics(echo_statistics_params{
        .seed = 1,
        .speckle = speckle_params{.transducer_length_m = 0.5, .k_shape = 4.0, .texture_patch_m = 0.5},
        .noise = noise_params{.frequency_hz = 100e3, .sea_state = 2.0, .directivity_index_db = 25.0, .source_level_db = 210.0},
        .volume = volume_params{.sv_db = -60.0, .psi_sr = 0.0, .absorption_db_per_m = 0.03}});
    const tvg gain(tvg_params{.spreading_n = 30.0, .absorption_db_per_km = 30.0});
    const simulator<scatter, propagation::straight<T>, beam::ideal_fan<T>, motion::straight_line<T>, chain> sim(
        scattering, water, fan, tow, rx, ray_density{}, chain(statistics, gain));
    const auto t1 = std::chrono::steady_clock::now();

    const std::size_t pings = 200; // 40 m of track
    const auto w = sim.render(world, 0, pings);
    const auto t2 = std::chrono::steady_clock::now();

    // 8 bits of amplitude, the record's 95th percentile at 100 counts (highlights saturate).
    std::vector<T> sorted(w.values);
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() * 95 / 100), sorted.end());
    const quantise_params q{.gain = quantise_gain(double(sorted[sorted.size() * 95 / 100]), 100.0)};
    const auto counts = quantise<std::uint8_t>(std::span<const T>(w.values), q);
    sss_examples::write_png_gray8(out, w.width(), w.pings, counts);
    const auto ground = to_ground_range(w, std::vector<double>(pings, 10.0), 1500.0, 0.1, 490);
    sss_examples::write_png_gray8(out_ground, ground.width(), ground.pings, quantise<std::uint8_t>(std::span<const T>(ground.values), q));
    std::size_t saturated = 0;
    for (auto c : counts) saturated += c == 255 ? 1 : 0;
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("sss record: %zu pings x 2 x %zu samples -> %s, %s (ground range, 0.1 m)\n"
                "  scene %.0f ms, render %.0f ms (%.2f ms/ping); %zu samples saturate the 8 bits\n",
                w.pings, w.samples, out.c_str(), out_ground.c_str(), ms(t0, t1), ms(t1, t2), ms(t1, t2) / double(pings),
                saturated);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_record: %s\n", e.what());
    return 1;
}
