// A compile-time model comparison: one scene (rippled medium sand beside sandy gravel, a lying cylinder), two
// simulator types that differ in one policy only, the scattering: Lambert's law (mu -27 dB sand, -20 dB gravel)
// against Jackson's model of each sediment (APL-UW TR 9407) at 100 kHz. Writes, under argv[1] (default
// sss_compare): lambert.png, jackson.png (range-compensated, one 40 dB window for both, so that levels
// compare), difference_db.png (10 log10 jackson / lambert, mid-grey 0 dB, black -20 dB, white +20 dB), and
// prints the time per ping of each type: the library's intended use for model studies and micro-benchmarks.

#include <sss/sss.hpp>
#include <sss/io/png.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/composite.hpp>
#include <sss/seabed/sediment_region.hpp>
#include <sss/seabed/targets.hpp>

#include "common/display.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

int main(int argc, char** argv) try {
    using T = float;
    using P = sss::policies<T>;
    namespace sb = sss::seabed;
    const std::string dir = argc > 1 ? argv[1] : "sss_compare";
    std::filesystem::create_directories(dir);

    // The scene, built once.
    const std::size_t nx = 512, ny = 512;
    const T cell = T(0.1);
    const std::vector<sb::sediment_region<T>> regions{
        {.id = 0, .sediment = sb::sediment_named<T>("medium_sand"),
         .ripples = {sb::ripple_params<T>{.wavelength_m = T(0.9), .height_m = T(0.08), .crest_heading_deg = T(20)}}},
        {.id = 1, .sediment = sb::sediment_named<T>("sandy_gravel"), .mean_height_m = T(0.2)}};
    const sb::voronoi_partition<T> part{.sites = {{.x_m = T(10), .y_m = T(25), .texture = 0}, {.x_m = T(45), .y_m = T(25), .texture = 1}},
                                        .warp_m = T(3), .warp_scale_m = T(15)};
    const auto bed = sb::compose(sb::partition(nx, ny, cell, part, 7), sb::textures(regions), T(0.5), 11);
    std::vector<std::uint32_t> material((nx - 1) * (ny - 1));
    for (std::size_t iy = 0; iy + 1 < ny; ++iy)
        for (std::size_t ix = 0; ix + 1 < nx; ++ix) material[iy * (nx - 1) + ix] = bed.regions.values[iy * nx + ix];
    sss::scene::height_field<T> seabed({.nx = nx, .ny = ny, .cell_m = cell, .heights_m = bed.height.values,
                                        .materials = material, .regions = material});
    std::vector<sss::scene::object<T>> objects{sb::lying_cylinder(
        sb::lying_cylinder_params<T>{.center_m = {T(40), T(25)}, .heading_deg = T(0), .length_m = T(2), .radius_m = T(0.3),
                                     .ids = {.material = 2, .object = 1, .label = 1}},
        sb::seabed_height_of(seabed))};
    const sss::scene::scene world(std::move(seabed), sss::scene::object_set<T>(std::move(objects)));

    // Everything but the scattering is shared.
    const P::straight water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    const P::ideal_fan fan({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)});
    const P::straight_line tow({.start_m = {T(25.6), T(10)}, .heading_deg = T(0), .speed_mps = T(2),
                                .altitude_m = world.seabed().seabed_height_m(T(25.6), T(10)) + T(8), .ping_interval_s = T(0.1)});
    const sss::receiver_params rx{.sample_rate_hz = 10000, .max_range_m = 25};
    using jackson_with_targets = sss::scattering::by_material<P::jackson, P::lambertian>;
    const P::simulator<P::lambertian, P::straight, P::ideal_fan, P::straight_line> lambert(
        P::lambertian({.mu_db = {T(-27), T(-20), T(-8)}}), water, fan, tow, rx);
    const P::simulator<jackson_with_targets, P::straight, P::ideal_fan, P::straight_line> jackson(
        jackson_with_targets(sb::jackson_for(regions, {.frequency_hz = T(100000), .sound_speed_mps = T(1500)}),
                             P::lambertian({.mu_db = {T(-8)}})),
        water, fan, tow, rx);

    const std::size_t pings = 120;
    auto timed = [&](const auto& sim, double& ms_per_ping) {
        const auto t0 = std::chrono::steady_clock::now();
        auto w = sim.render(world, 0, pings, 1);
        ms_per_ping = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / double(pings);
        return w;
    };
    double ms_lambert = 0, ms_jackson = 0;
    const auto a = timed(lambert, ms_lambert);
    const auto b = timed(jackson, ms_jackson);

    // One display window for both images: white at the brighter image's 99.5th percentile.
    const auto sa = sss_examples::range_compensated(a, 1500.0, 30.0), sb_ = sss_examples::range_compensated(b, 1500.0, 30.0);
    std::vector<double> all(sa);
    all.insert(all.end(), sb_.begin(), sb_.end());
    std::nth_element(all.begin(), all.begin() + std::ptrdiff_t(double(all.size() - 1) * 0.995), all.end());
    const sss::io::display_params window{.dynamic_range_db = 40.0, .top_db = 10.0 * std::log10(all[std::size_t(double(all.size() - 1) * 0.995)])};
    sss::io::write_png_grey8(dir + "/lambert.png", a.width(), a.pings, sss::io::to_grey_db<std::uint8_t>(std::span<const double>(sa), window));
    sss::io::write_png_grey8(dir + "/jackson.png", b.width(), b.pings, sss::io::to_grey_db<std::uint8_t>(std::span<const double>(sb_), window));
    std::vector<std::uint8_t> diff(a.values.size(), 0);
    double sum_db = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < diff.size(); ++i) {
        if (!(a.values[i] > 0) || !(b.values[i] > 0)) continue;
        const double db = 10.0 * std::log10(double(b.values[i]) / double(a.values[i]));
        sum_db += db;
        ++n;
        diff[i] = static_cast<std::uint8_t>(std::clamp(128.0 + db * 127.0 / 20.0, 1.0, 255.0));
    }
    sss::io::write_png_grey8(dir + "/difference_db.png", a.width(), a.pings, diff);
    std::printf("sss compare: %zu pings x 2 x %zu samples -> %s/{lambert,jackson,difference_db}.png\n"
                "  lambertian %.2f ms/ping, jackson %.2f ms/ping (ratio %.2f); mean difference %.1f dB over %zu samples\n",
                pings, a.samples, dir.c_str(), ms_lambert, ms_jackson, ms_jackson / ms_lambert, n ? sum_db / double(n) : 0.0, n);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_compare_models: %s\n", e.what());
    return 1;
}
