// The turn figures: a towfish turning at constant rate over sand ripples. The fan at each ping lies along the
// radius of the turn, so the seabed at ground range y on the inner side moves (R - y)/R of the towfish's own
// distance per ping and on the outer side (R + y)/R of it: ripples on the inner side appear stretched over more
// pings and those on the outer side compressed, the more so the farther out in range.
//
// Two figures, one per turn, and a straight run for reference, each a two-sided waterfall (port on the left,
// starboard on the right, one row per ping, time going down):
//   argv[1] (default turn_inward.png):   the towfish turns toward starboard, into the right-hand swath, which is
//                                        therefore on the inside of the turn (stretched); the port swath is outside;
//   argv[2] (default turn_outward.png):  it turns toward port, away from the right-hand swath, which is now on the
//                                        outside (compressed); the port swath is inside;
//   argv[3] (default turn_straight.png): no turn: the ripples are straight, evenly spaced stripes on both sides.
// All share the scene and the middle ping: at ping 150 the towfish is at the origin heading north; over the 300
// pings (45 m) it turns 32 degrees on a radius of 80 m. The ripple crests run north-east, at 45 degrees to the
// track in the middle ping, so that their slopes face the sonar and show clearly (crests square to the track
// would be seen end-on, as faint height variations).
//
// Display as in demo.cpp: spreading and absorption taken out (power x r^3 x 10^(2 alpha r / 10^4)), 30 dB window.

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/ripples.hpp>

#include "common/display.hpp"
#include "common/png.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace {

using T = float;

constexpr double radius_m = 80.0;        // turn radius
constexpr double speed_mps = 1.5;        // towfish speed
constexpr double ping_interval_s = 0.1;  // 15 cm of track per ping
constexpr double altitude_m = 6.0;       // above the mean seabed
constexpr double max_range_m = 40.0;     // slant range recorded per side
constexpr double absorption_db_km = 30.0;
constexpr std::size_t pings = 300;

/// The path turning toward `toward` (or, if `turning` is false, straight), with its middle ping at the origin
/// heading north.
sss::motion::perturbed<T> turn_path(sss::side toward, bool turning = true) {
    sss::motion::perturbed_params<T> p;
    p.speed_mps = T(speed_mps);
    p.altitude_m = T(altitude_m);
    p.ping_interval_s = T(ping_interval_s);
    if (turning) {
        p.turn = sss::motion::constant_turn<T>{.toward = toward, .radius_m = T(radius_m)};
        const double sign = toward == sss::side::starboard ? 1.0 : -1.0;
        const double mid_t = static_cast<double>(pings / 2) * ping_interval_s;
        p.heading_deg = static_cast<T>(-sign * speed_mps / radius_m * mid_t * 180.0 / sss::pi_v<double>);
    }
    const auto mid = sss::motion::perturbed<T>(p).nominal_pose_at(pings / 2);
    p.start_m = {-mid.position.x, -mid.position.y};
    return sss::motion::perturbed<T>(p);
}

/// Sand: ripples of 1.5 m wavelength with crests running north-east (meandering a little, of varying height) on
/// a fractal roughness, over a rectangle that holds every swath of the given paths.
sss::scene::height_field<T> rippled_sand(const std::vector<sss::motion::perturbed<T>>& paths) {
    namespace sb = sss::seabed;
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const auto& path : paths)
        for (std::size_t i = 0; i < pings; ++i) {
            const auto p = path.nominal_pose_at(i);
            const double psi = double(p.yaw_rad);
            for (double y : {-max_range_m, 0.0, max_range_m}) { // starboard is (cos psi, -sin psi)
                const double ex = double(p.position.x) + y * std::cos(psi), ey = double(p.position.y) - y * std::sin(psi);
                x0 = std::min(x0, ex), x1 = std::max(x1, ex), y0 = std::min(y0, ey), y1 = std::max(y1, ey);
            }
        }
    const T cell = T(0.05);
    const auto n = [&](double a, double b) { return static_cast<std::size_t>(std::ceil((b - a + 2.0) / double(cell))) + 1; };
    const std::size_t nx = n(x0, x1), ny = n(y0, y1);

    sb::ripple_params<T> ripples;
    ripples.wavelength_m = T(1.5);
    ripples.height_m = T(0.15);
    ripples.crest_heading_deg = T(45); // crests running north-east
    ripples.symmetry_index = T(1.5);
    ripples.sinuosity_m = T(0.15);
    ripples.sinuosity_wavelength_m = T(12);
    ripples.perturbation_m = T(0.08);
    ripples.height_variation = T(0.2);
    sb::raster<T> h = sb::ripple_field<T>(nx, ny, cell, ripples, 3);
    sb::fractal_params<T> rough;
    rough.spectrum = sb::jackson_spectrum(T(0.001), T(3.25), T(20));
    const sb::raster<T> r = sb::fractal_surface<T>(nx, ny, cell, rough, 5);
    for (std::size_t i = 0; i < h.values.size(); ++i) h.values[i] += r.values[i];
    return sss::scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {static_cast<T>(x0 - 1.0), static_cast<T>(y0 - 1.0)}, .heights_m = std::move(h.values)});
}

using turn_simulator = sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>,
                                      sss::beam::ideal_fan<T>, sss::motion::perturbed<T>>;

turn_simulator make_simulator(sss::motion::perturbed<T> path) {
    sss::beam::ideal_fan_params<T> fan;
    fan.along_width_deg = T(0.4); // 28 cm at 40 m: the ripples stay resolved across the swath
    fan.vertical_width_deg = T(80);
    fan.depression_deg = T(45);
    sss::receiver_params rx;
    rx.sample_rate_hz = 7500.0; // 10 cm of slant range per sample
    rx.max_range_m = max_range_m;
    rx.pulse = {100e-6, sss::pulse_shape::rectangular};
    sss::ray_density density;
    density.along = 4;
    density.per_sample = 2.0;
    return turn_simulator(sss::scattering::lambertian<T>(T(-27)),
                          sss::propagation::straight<T>({.sound_speed_mps = T(1500), .absorption_db_per_km = T(absorption_db_km)}), sss::beam::ideal_fan<T>(fan),
                          std::move(path), rx, density);
}

void write_figure(const std::string& file, const sss::waterfall<T>& w) {
    const std::vector<double> shown = sss_examples::range_compensated(w, 1500.0, absorption_db_km);
    sss_examples::write_png_gray8(file, w.width(), w.pings, sss_examples::to_gray8_db(shown, 30.0));
}

} // namespace

int main(int argc, char** argv) try {
    const std::string inward = argc > 1 ? argv[1] : "turn_inward.png";
    const std::string outward = argc > 2 ? argv[2] : "turn_outward.png";
    const std::string straight = argc > 3 ? argv[3] : "turn_straight.png";
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<sss::motion::perturbed<T>> paths{turn_path(sss::side::starboard), turn_path(sss::side::port),
                                                        turn_path(sss::side::port, false)};
    const auto seabed = rippled_sand(paths);
    const auto t1 = std::chrono::steady_clock::now();
    const std::string files[3] = {inward, outward, straight};
    const char* what[3] = {"turning to starboard (right swath inside)", "turning to port (right swath outside)",
                           "straight (reference)"};
    for (std::size_t i = 0; i < 3; ++i) {
        const auto w = make_simulator(paths[i]).render(seabed, 0, pings);
        write_figure(files[i], w);
        std::printf("%s: %s, %zu pings x 2 x %zu samples\n", files[i].c_str(), what[i], w.pings, w.samples);
    }
    const auto t2 = std::chrono::steady_clock::now();
    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("seabed %.0f ms, rendering %.0f ms\n", ms(t0, t1), ms(t1, t2));
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_turns: %s\n", e.what());
    return 1;
}
