// A pipeline with a free span in a sidescan waterfall: a 0.8 m pipe laid north-south on a rough sandy height field,
// crossing a trench 8 m wide and 1.5 m deep that runs east-west. The pipe rests on the seabed where supported and
// spans the trench in a straight line (targets.hpp: the taut string over the seabed profile under the pipe, with a
// 12 m reach). The towfish runs north, 25 m west of the pipe, 10 m above the seabed. Writes an 8-bit PNG (argv[1],
// default sss_pipeline.png): one row per ping (0.1 m of track), port on the left, starboard on the right.
//
// What to look for, on the starboard side: the pipe as a bright line along the track with its shadow right behind
// it; the trench as a band across the swath where the seabed lies deeper, so that its first return comes later (a
// notch in the edge of the dark water column); and where the pipe spans the trench, its shadow moved out in range
// with lit trench floor between pipe and shadow: the sidescan signature of a free span.
//
// Display: mean power x r^3 x absorption taken out (like a time-varied gain) over a 40 dB window.

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/stamps.hpp>
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
    const std::string out = argc > 1 ? argv[1] : "sss_pipeline.png";
    const auto t0 = std::chrono::steady_clock::now();

    // Seabed: 204.8 m across x 51.2 m along at 10 cm, medium sand roughness, and a trench across the pipe's route.
    const std::size_t nx = 2048, ny = 512;
    const T cell = T(0.1);
    sb::fractal_params<T> rough;
    rough.spectrum = sb::jackson_spectrum(T(0.004446), T(3.25), T(20));
    auto bed = sb::fractal_surface<T>(nx, ny, cell, rough, 5);
    const T track_x = T(102.4), pipe_x = track_x + T(25), trench_y = T(27);
    sb::trench<T> cut;
    cut.x0_m = pipe_x - T(15);
    cut.y0_m = trench_y;
    cut.x1_m = pipe_x + T(20);
    cut.y1_m = trench_y;
    cut.width_m = T(8);
    cut.floor_width_m = T(3);
    cut.depth_m = T(1.5);
    sb::stamp(bed, cut);
    const scene::height_field<T> seabed({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {T(0), T(0)}, .heights_m = bed.values});

    // The pipe: radius 0.4 m, concrete-coated (material 1), along the full length of the seabed.
    sb::pipeline_params<T> pp;
    pp.route_m = {{pipe_x, T(0.5)}, {pipe_x, T(50.7)}};
    pp.radius_m = T(0.4);
    pp.profile_step_m = T(0.05);
    pp.max_span_m = T(12);
    pp.ids = {.material = 1, .object = 1, .label = 2};
    const auto layout = sb::lay_pipeline(pp, sb::seabed_height_of(seabed));
    std::printf("sss pipeline: %zu axis vertices; free spans higher than 5 cm:\n", layout.axis_m.size());
    for (const auto& s : layout.spans)
        if (s.clearance_m > T(0.05))
            std::printf("  y %.2f to %.2f m (%.2f m long), %.2f m above the seabed at most\n", double(s.start_m) + 0.5,
                        double(s.end_m) + 0.5, double(s.end_m - s.start_m), double(s.clearance_m));
    std::vector<scene::object<T>> objects{sb::pipeline_object(layout, pp)};
    const scene::scene world(seabed, scene::object_set<T>(std::move(objects)));

    // Sonar: Lambertian scattering, -27 dB for the sand, -12 dB for the pipe's coating; 30 dB/km absorption;
    // a 1 deg x 50 deg fan tilted 20 deg down; 20 kHz sampling, 40 m range.
    const scattering::lambertian<T> scatter({.mu_db = {T(-27), T(-12)}});
    const propagation::straight<T> water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    const beam::ideal_fan<T> fan({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)});
    motion::straight_line_params<T> tow;
    tow.start_m = {track_x, T(2)};
    tow.heading_deg = T(0);
    tow.speed_mps = T(1);
    tow.altitude_m = seabed.seabed_height_m(track_x, T(25.6)) + T(10);
    tow.ping_interval_s = T(0.1);
    receiver_params rx;
    rx.sample_rate_hz = 20000;
    rx.max_range_m = 40;
    rx.pulse = {100e-6, pulse_shape::rectangular};
    const simulator<scattering::lambertian<T>, propagation::straight<T>, beam::ideal_fan<T>, motion::straight_line<T>> sim(
        scatter, water, fan, motion::straight_line<T>(tow), rx);
    const auto t1 = std::chrono::steady_clock::now();

    const std::size_t pings = 470; // 47 m of track
    const auto w = sim.render(world, 0, pings, 2);
    const auto t2 = std::chrono::steady_clock::now();

    const std::vector<double> shown = sss_examples::range_compensated(w, 1500.0, 30.0);
    sss_examples::write_png_gray8(out, w.width(), w.pings, sss_examples::to_gray8_db(shown, 40.0));
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("  %zu pings x 2 x %zu samples -> %s\n  scene %.0f ms, render %.0f ms (%.2f ms/ping)\n", w.pings,
                w.samples, out.c_str(), ms(t0, t1), ms(t1, t2), ms(t1, t2) / double(pings));
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_pipeline: %s\n", e.what());
    return 1;
}
