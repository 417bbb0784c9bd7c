// A thermocline in the image: the same rippled sand rendered twice, through isovelocity water (left) and through a
// strong thermocline just below the towfish (right), side by side in one PNG (argv[1], default sss_thermocline.png).
// Each half is a two-sided waterfall: port on the left, starboard on the right, one row per ping, time going down.
//
// Water: 60 m deep, the towfish 30 m above the seabed (depth 30 m). Isovelocity: 1500 m/s throughout. Thermocline:
// 1520 m/s down to 32 m, falling 50 m/s to 1470 m/s at 42 m, then the pressure gradient (+0.0165 1/s). Both use
// Francois-Garrison absorption at 200 kHz. Sound leaving the towfish is bent down by the falling speed: a ray
// launched 10 deg below the horizontal leaves the thermocline at 18 deg and lands 108 m out instead of 170 m. So
// each patch of seabed is lit by a shallower launch and met more steeply: at 90 m of slant (time) range the
// grazing angle is 21.2 deg instead of 19.5 deg, and under Lambert's law the far swath comes out brighter (by
// 1.8 dB at 80-88 m, 0.8 dB at 50-58 m, measured on these images). Where a given echo time lands on the seabed
// hardly moves (84 m of ground range instead of 85 m at 90 m): the bent path is longer but runs partly in slower
// water. Ripple shadows shorten a little with the steeper grazing.
//
// Display as in demo.cpp: spreading and absorption of isovelocity water taken out (power x r^3 x 10^(2 alpha r /
// 10^4) at the nominal 1500 m/s), one 30 dB window for both halves so that their levels compare.

#include <sss/sss.hpp>
#include <sss/propagation/layered.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/ripples.hpp>

#include "common/png.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

using T = float;

constexpr double surface_z_m = 60.0;    // world z of the sea surface; the mean seabed is z = 0
constexpr double altitude_m = 30.0;     // towfish above the mean seabed
constexpr double max_range_m = 90.0;    // slant range recorded per side
constexpr double frequency_hz = 200000.0;
constexpr std::size_t pings = 400;      // 0.15 m of track per ping

/// Sand ripples of 2.5 m wavelength, crests at 40 degrees to the track, on fractal roughness.
sss::scene::height_field<T> rippled_sand() {
    namespace sb = sss::seabed;
    const T cell = T(0.1);
    const double x0 = -88, y0 = -2, x1 = 88, y1 = 0.15 * pings + 2; // the swaths of all pings
    const auto n = [&](double a, double b) { return static_cast<std::size_t>(std::ceil((b - a) / double(cell))) + 1; };
    const std::size_t nx = n(x0, x1), ny = n(y0, y1);
    sb::ripple_params<T> ripples;
    ripples.wavelength_m = T(2.5);
    ripples.height_m = T(0.2);
    ripples.crest_heading_deg = T(50.4); // 39.6 degrees off the track
    ripples.sinuosity_m = T(0.1);
    ripples.sinuosity_wavelength_m = T(10);
    ripples.height_variation = T(0.2);
    sb::raster<T> h = sb::ripple_field<T>(nx, ny, cell, ripples, 17);
    sb::fractal_params<T> rough;
    rough.spectrum = sb::jackson_spectrum(T(0.002), T(3.25), T(20));
    const sb::raster<T> r = sb::fractal_surface<T>(nx, ny, cell, rough, 19);
    for (std::size_t i = 0; i < h.values.size(); ++i) h.values[i] += r.values[i];
    return sss::scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {T(x0), T(y0)}, .heights_m = std::move(h.values)});
}

sss::propagation::layered<T> water(bool thermocline) {
    using namespace sss::propagation;
    layered_params<T> p;
    p.surface_z_m = T(surface_z_m);
    p.frequency_hz = T(frequency_hz);
    if (!thermocline) return layered<T>(sound_speed_profile<T>::constant(T(1500)), p);
    return layered<T>(sound_speed_profile<T>({T(0), T(32), T(42), T(200)}, {T(1520), T(1520), T(1470), T(1472.6)}), p);
}

sss::waterfall<T> render(const sss::scene::height_field<T>& seabed, bool thermocline) {
    using namespace sss;
    beam::ideal_fan_params<T> fan;
    fan.along_width_deg = T(0.5);
    fan.vertical_width_deg = T(80);
    fan.depression_deg = T(40);
    receiver_params rx;
    rx.sample_rate_hz = 3750.0; // 20 cm of slant range per sample
    rx.max_range_m = max_range_m;
    rx.pulse = {100e-6, pulse_shape::rectangular};
    ray_density density;
    density.along = 4;
    density.per_sample = 2.0;
    const motion::straight_line<T> track({.start_m = {T(0), T(0)}, .heading_deg = T(0), .speed_mps = T(1.5), .altitude_m = T(altitude_m), .ping_interval_s = T(0.1)});
    const simulator<scattering::lambertian<T>, propagation::layered<T>, beam::ideal_fan<T>, motion::straight_line<T>> sim(
        scattering::lambertian<T>(T(-27)), water(thermocline), beam::ideal_fan<T>(fan), track, rx, density);
    return sim.render(seabed, 0, pings);
}

} // namespace

int main(int argc, char** argv) try {
    const std::string out = argc > 1 ? argv[1] : "sss_thermocline.png";
    const auto t0 = std::chrono::steady_clock::now();
    const auto seabed = rippled_sand();
    const auto t1 = std::chrono::steady_clock::now();
    const auto iso = render(seabed, false);
    const auto t2 = std::chrono::steady_clock::now();
    const auto thermo = render(seabed, true);
    const auto t3 = std::chrono::steady_clock::now();

    // Side by side with a 16-column black gap; one display gain for both.
    const std::size_t gap = 16, width = iso.width() + gap + thermo.width(), rows = std::min(iso.pings, thermo.pings);
    const double alpha_db_km = double(water(false).absorption_db_per_km(T(45)));
    std::vector<double> shown(width * rows, 0.0);
    for (const auto* w : {&iso, &thermo}) {
        const std::size_t offset = w == &iso ? 0 : iso.width() + gap;
        for (std::size_t p = 0; p < rows; ++p)
            for (std::size_t c = 0; c < w->width(); ++c) {
                const std::size_t k = c < w->samples ? w->samples - 1 - c : c - w->samples;
                const double r = (double(k) + 0.5) * w->dt_s * 750.0;
                shown[p * width + offset + c] = double(w->at(p, c)) * r * r * r * std::pow(10.0, 2.0 * alpha_db_km * r / 1e4);
            }
    }
    sss_examples::write_png_gray8(out, width, rows, sss_examples::to_gray8_db(shown, 30.0));
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("sss thermocline: %zu pings, isovelocity | thermocline -> %s\n  seabed %.0f ms, isovelocity %.0f ms, "
                "thermocline %.0f ms\n",
                rows, out.c_str(), ms(t0, t1), ms(t1, t2), ms(t2, t3));
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_thermocline: %s\n", e.what());
    return 1;
}
