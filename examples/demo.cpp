// The main demo: a sidescan waterfall over a composite seabed (rippled sand, rough gravel and smooth mud in regions
// with fractal boundaries), with Jackson (APL-UW) scattering for each sediment, a 100 kHz planar array and a towfish
// that rolls and yaws a little. Writes an 8-bit PNG (argv[1], default sss_demo.png): port on the left, starboard on
// the right, one row per ping, time going down.
//
// Display: the simulator returns mean received power per sample; like a sidescan's time-varied gain, the image is
// shown with spreading and absorption taken out (power x r^3 x 10^(2 alpha r / 10^4)) over a 36 dB window.

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/seabed/composite.hpp>

#include "common/display.hpp"
#include "common/png.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

int main(int argc, char** argv) try {
    using T = float;
    namespace sb = sss::seabed;
    const std::string out = argc > 1 ? argv[1] : "sss_demo.png";
    const auto t0 = std::chrono::steady_clock::now();

    // Seabed: 204.8 m x 102.4 m at 10 cm (power-of-two grids keep the FFT synthesis fast), three textures in
    // warped Voronoi regions.
    const std::size_t nx = 2048, ny = 1024;
    const T cell = T(0.1);
    sb::voronoi_partition<T> regions;
    regions.sites = {{.x_m = T(60), .y_m = T(25), .texture = 0},  {.x_m = T(150), .y_m = T(20), .texture = 1},
                     {.x_m = T(100), .y_m = T(60), .texture = 2}, {.x_m = T(50), .y_m = T(90), .texture = 1},
                     {.x_m = T(160), .y_m = T(85), .texture = 0}};
    regions.warp_m = T(6);
    regions.warp_scale_m = T(30);
    const auto index = sb::partition(nx, ny, cell, regions, 7);

    std::vector<sb::region_texture<T>> textures(3);
    textures[0].id = 0; // medium sand with two sets of ripples
    textures[0].roughness.spectrum = sb::jackson_spectrum(T(0.004446), T(3.25), T(20));
    textures[0].ripples.push_back({.wavelength_m = T(0.9),
                                   .height_m = T(0.08),
                                   .crest_heading_deg = T(21.25),
                                   .symmetry_index = T(2.0),
                                   .sinuosity_m = T(0.15),
                                   .sinuosity_wavelength_m = T(7),
                                   .perturbation_m = T(0.05),
                                   .height_variation = T(0.2)});
    textures[0].ripples.push_back(
        {.wavelength_m = T(3.5), .height_m = T(0.12), .crest_heading_deg = T(32.7), .symmetry_index = T(1.5)});
    textures[1].id = 1; // sandy gravel: rough
    textures[1].mean_height_m = T(0.2);
    textures[1].roughness.spectrum = sb::jackson_spectrum(T(0.2), T(3.25), T(20));
    textures[2].id = 2; // sandy mud: smooth and a little lower
    textures[2].mean_height_m = T(-0.3);
    textures[2].roughness.spectrum = sb::jackson_spectrum(T(0.000518), T(3.25), T(20));
    const auto bed = sb::compose(index, textures, T(0.5), 11);

    // Materials and regions per cell: the id at each cell's south-west vertex.
    std::vector<std::uint32_t> material((nx - 1) * (ny - 1));
    for (std::size_t iy = 0; iy + 1 < ny; ++iy)
        for (std::size_t ix = 0; ix + 1 < nx; ++ix) material[iy * (nx - 1) + ix] = bed.regions.values[iy * nx + ix];
    const sss::scene::height_field<T> seabed({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {T(0), T(0)}, .heights_m = bed.height.values, .materials = material, .regions = material});

    // Sonar: Jackson scattering per material at 100 kHz; isovelocity water; a 100 kHz planar array on each side.
    using namespace sss;
    const scattering::jackson<T> jackson({.frequency_hz = T(100000), .sound_speed_mps = T(1500), .materials = {scattering::sediment_preset<T>(scattering::sediment::medium_sand),
                                          scattering::sediment_preset<T>(scattering::sediment::sandy_gravel),
                                          scattering::sediment_preset<T>(scattering::sediment::sandy_mud)}});
    const propagation::straight<T> water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    beam::planar_array_params<T> array;
    array.frequency_hz = T(100000);
    array.depression_deg = T(20);
    array.transmit.along = {.count = 1, .element_m = T(0.8)};
    array.transmit.vertical = {.count = 1, .element_m = T(0.025)};
    array.threshold_db = T(-30);
    motion::perturbed_params<T> tow;
    tow.start_m = {T(102), T(4)};
    tow.heading_deg = T(0);
    tow.speed_mps = T(2);
    tow.altitude_m = T(10);
    tow.ping_interval_s = T(0.1);
    tow.roll_deg = {.amplitude = T(1.5), .period_s = T(9)};
    tow.yaw_deg = {.amplitude = T(1.0), .period_s = T(14), .phase_deg = T(40)};
    receiver_params rx;
    rx.sample_rate_hz = 20000;
    rx.max_range_m = 60;
    rx.pulse = {100e-6, pulse_shape::rectangular};
    const simulator<scattering::jackson<T>, propagation::straight<T>, beam::planar_array<T>, motion::perturbed<T>> sim(
        jackson, water, beam::planar_array<T>(array), motion::perturbed<T>(tow), rx);
    const auto t1 = std::chrono::steady_clock::now();

    const std::size_t pings = 470; // 94 m of track
    const auto w = sim.render(seabed, 0, pings);
    const auto t2 = std::chrono::steady_clock::now();

    const std::vector<double> shown = sss_examples::range_compensated(w, 1500.0, 30.0);
    sss_examples::write_png_gray8(out, w.width(), w.pings, sss_examples::to_gray8_db(shown, 36.0));
    const auto t3 = std::chrono::steady_clock::now();
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("sss demo: %zu pings x 2 x %zu samples -> %s\n  seabed %.0f ms, render %.0f ms (%.2f ms/ping), png %.0f ms\n",
                w.pings, w.samples, out.c_str(), ms(t0, t1), ms(t1, t2), ms(t1, t2) / double(pings), ms(t2, t3));
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_demo: %s\n", e.what());
    return 1;
}
