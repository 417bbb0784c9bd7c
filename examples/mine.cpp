// A tethered mine in a sidescan waterfall: a spherical case 1 m across, moored 3 m above a rough sandy seabed
// by a 2 cm tether to a squat anchor, ensonified on the starboard side at 32 m slant range by a towfish 10 m above
// the seabed. The towfish runs north past it; each row of the PNG (argv[1], default sss_mine.png) is one ping
// (0.1 m of track), port on the left, starboard on the right, time going out from the middle.
//
// What to look for: the case's highlight at 32 m slant range, standing clear of its own acoustic shadow on the
// seabed further out (the case is in the water column, so echo and shadow are separated by lit seabed); the
// anchor as a small highlight with a short shadow at the foot of the tether; the tether, thinner than a
// sample, as a faint line joining them.
//
// Display: mean power x r^3 x absorption taken out (like a time-varied gain) over a 40 dB window.

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/targets.hpp>

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
    using namespace sss;
    const std::string out = argc > 1 ? argv[1] : "sss_mine.png";
    const auto t0 = std::chrono::steady_clock::now();

    // Seabed: 204.8 m across x 51.2 m along at 10 cm, medium sand roughness (APL-UW w2 = 0.004446 cm^4,
    // gamma = 3.25); world x east (across track), y north (along track).
    const std::size_t nx = 2048, ny = 512;
    const T cell = T(0.1);
    sb::fractal_params<T> rough;
    rough.spectrum = sb::jackson_spectrum(T(0.004446), T(3.25), T(20));
    const auto bed = sb::fractal_surface<T>(nx, ny, cell, rough, 3);
    const scene::height_field<T> seabed({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {T(0), T(0)}, .heights_m = bed.values});

    // The mine: case centre 3 m above the seabed, at 32 m slant range from a towfish at 10 m altitude on
    // x = 102.4 m: ground range sqrt(32^2 - 7^2) = 31.2 m.
    const T track_x = T(102.4), altitude = T(10), slant = T(32), case_height = T(3);
    const T ground_range = std::sqrt(slant * slant - (altitude - case_height) * (altitude - case_height));
    sb::tethered_mine_params<T> mp;
    mp.anchor_m = {track_x + ground_range, T(25.6)};
    mp.case_height_m = case_height;
    mp.case_radius_m = T(0.5);
    mp.tether_radius_m = T(0.01);
    mp.anchor_radius_m = T(0.4);
    mp.anchor_height_m = T(0.35);
    mp.object_id = 1;
    mp.class_id = 1;
    std::vector<scene::object<T>> objects{sb::tethered_mine(mp, sb::seabed_height_of(seabed))};
    const scene::scene world(seabed, scene::object_set<T>(std::move(objects)));

    // Sonar: Lambertian scattering, -27 dB for the sand (Mackenzie) and -8 dB for the mine's painted steel;
    // isovelocity water with 30 dB/km absorption; a 1 deg x 50 deg fan tilted 20 deg down; 20 kHz sampling.
    const scattering::lambertian<T> scatter({.mu_db = {T(-27), T(-8)}});
    const propagation::straight<T> water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    const beam::ideal_fan<T> fan({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)});
    motion::straight_line_params<T> tow;
    tow.start_m = {track_x, T(10.6)};
    tow.heading_deg = T(0);
    tow.speed_mps = T(1);
    tow.altitude_m = seabed.seabed_height_m(track_x, T(25.6)) + altitude;
    tow.ping_interval_s = T(0.1);
    receiver_params rx;
    rx.sample_rate_hz = 20000;
    rx.max_range_m = 55;
    rx.pulse = {100e-6, pulse_shape::rectangular};
    const simulator<scattering::lambertian<T>, propagation::straight<T>, beam::ideal_fan<T>, motion::straight_line<T>> sim(
        scatter, water, fan, motion::straight_line<T>(tow), rx);
    const auto t1 = std::chrono::steady_clock::now();

    const std::size_t pings = 300; // 30 m of track, the mine abeam at ping 150
    const auto w = sim.render(world, 0, pings, 2);
    const auto t2 = std::chrono::steady_clock::now();

    const std::vector<double> shown = sss_examples::range_compensated(w, 1500.0, 30.0);
    sss_examples::write_png_gray8(out, w.width(), w.pings, sss_examples::to_gray8_db(shown, 40.0));
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("sss mine: case at %.1f m ground range, %.1f m slant; %zu pings x 2 x %zu samples -> %s\n"
                "  scene %.0f ms, render %.0f ms (%.2f ms/ping)\n",
                double(ground_range), double(slant), w.pings, w.samples, out.c_str(), ms(t0, t1), ms(t1, t2),
                ms(t1, t2) / double(pings));
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_mine: %s\n", e.what());
    return 1;
}
