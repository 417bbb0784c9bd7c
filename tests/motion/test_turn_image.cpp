// The constant-rate turn seen in the image: sand ripples whose crests cross the track are imaged at a ping
// spacing set by how far the seabed point under each range cell moves per ping.
//
// On a turn of radius R (towfish speed V, ping interval dt) the fan at each ping lies along the radius through
// the towfish, so the seabed point at ground range y lies on a circle about the turn centre of radius R - y on
// the inner side and R + y on the outer side, and moves (R -+ y) / R V dt per ping. Straight crests of
// wavelength lambda, perpendicular to the heading in the middle of a short stretch, therefore repeat every
//     P(y) = lambda / ((R -+ y) / R V dt)   pings
// (to first order in the heading change over the stretch; here it changes by 2.3 deg, a relative error of
// 1 - cos(1.15 deg) = 2e-4). The period is measured on the rendered waterfall at the sample for slant range
// sqrt(y^2 + H^2), H the altitude, by the peak of the Hann-windowed spectrum of the detrended intensity.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "sss/beam/ideal_fan.hpp"
#include "sss/core/constants.hpp"
#include "sss/motion/perturbed.hpp"
#include "sss/propagation/straight.hpp"
#include "sss/scattering/lambertian.hpp"
#include "sss/scene/height_field.hpp"
#include "sss/seabed/ripples.hpp"
#include "sss/simulator.hpp"

namespace {

using T = float;
constexpr double pi = sss::pi_v<double>;

/// The scene of the check (lengths in m, times in s).
struct turn_case {
    sss::side toward = sss::side::starboard; ///< side the towfish turns to: the inner side
    double radius_m = 150.0;                 ///< turn radius R
    double speed_mps = 1.0;                  ///< V
    double ping_interval_s = 0.05;           ///< dt: V dt = 5 cm per ping at the towfish
    double altitude_m = 5.0;                 ///< H
    double wavelength_m = 0.75;              ///< lambda: 15 pings per ripple at the towfish
    double ripple_height_m = 0.04;           ///< crest to trough
    double symmetry_index = 1.0;             ///< stoss / lee length: symmetric, a sinusoidal profile
    std::size_t pings = 150;                 ///< the measured stretch: 7.5 m of track
    double near_m = 6.0, far_m = 33.0;       ///< ground ranges covered by the fan
};

/// The path: the middle ping at the origin heading north.
sss::motion::perturbed<T> turn_path(const turn_case& c) {
    sss::motion::perturbed_params<T> p;
    p.speed_mps = static_cast<T>(c.speed_mps);
    p.altitude_m = static_cast<T>(c.altitude_m);
    p.ping_interval_s = static_cast<T>(c.ping_interval_s);
    p.turn = sss::motion::constant_turn<T>{c.toward, static_cast<T>(c.radius_m), T(0)};
    const double sign = c.toward == sss::side::starboard ? 1.0 : -1.0;
    const double mid_t = 0.5 * static_cast<double>(c.pings) * c.ping_interval_s;
    p.heading_deg = static_cast<T>(-sign * c.speed_mps / c.radius_m * mid_t * 180.0 / pi);
    const auto mid = sss::motion::perturbed<T>(p).nominal_pose_at(c.pings / 2);
    p.start_m = {-mid.position.x, -mid.position.y};
    return sss::motion::perturbed<T>(p);
}

/// Ripples with crests along x (east), i.e. across the track at the middle ping, on a grid of `cell_m`
/// covering every seabed point the fan reaches over the stretch.
sss::scene::height_field<T> rippled_seabed(const turn_case& c, const sss::motion::perturbed<T>& path, double cell_m) {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (std::size_t i = 0; i < c.pings; ++i) {
        const auto p = path.nominal_pose_at(i);
        const double psi = static_cast<double>(p.yaw_rad);
        for (double y : {-c.far_m, c.far_m}) { // starboard is (cos psi, -sin psi)
            const double ex = static_cast<double>(p.position.x) + y * std::cos(psi);
            const double ey = static_cast<double>(p.position.y) - y * std::sin(psi);
            x0 = std::min({x0, ex, double(p.position.x)});
            x1 = std::max({x1, ex, double(p.position.x)});
            y0 = std::min({y0, ey, double(p.position.y)});
            y1 = std::max({y1, ey, double(p.position.y)});
        }
    }
    const double margin = 0.5; // beyond the beam's along-track footprint
    x0 -= margin, y0 -= margin, x1 += margin, y1 += margin;
    const auto nx = static_cast<std::size_t>(std::ceil((x1 - x0) / cell_m)) + 1;
    const auto ny = static_cast<std::size_t>(std::ceil((y1 - y0) / cell_m)) + 1;
    sss::seabed::ripple_params<T> r;
    r.wavelength_m = static_cast<T>(c.wavelength_m);
    r.height_m = static_cast<T>(c.ripple_height_m);
    r.crest_direction_rad = T(0);
    r.symmetry_index = static_cast<T>(c.symmetry_index);
    auto h = sss::seabed::ripple_field<T>(nx, ny, static_cast<T>(cell_m), r, 1);
    return sss::scene::height_field<T>(nx, ny, static_cast<T>(cell_m), {static_cast<T>(x0), static_cast<T>(y0)},
                                       std::move(h.values));
}

using turn_simulator = sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>,
                                      sss::beam::ideal_fan<T>, sss::motion::perturbed<T>>;

/// A narrow ideal fan covering ground ranges [near_m, far_m] at 20 kHz sampling.
turn_simulator make_simulator(const turn_case& c) {
    const double lo = std::atan2(c.altitude_m, c.far_m) * 180.0 / pi;
    const double hi = std::atan2(c.altitude_m, c.near_m) * 180.0 / pi;
    sss::beam::ideal_fan_params<T> fan;
    fan.along_width_deg = T(0.25);
    fan.vertical_width_deg = static_cast<T>(hi - lo);
    fan.depression_deg = static_cast<T>(0.5 * (lo + hi));
    sss::receiver_params rx;
    rx.sample_rate_hz = 20000.0;
    rx.max_range_m = std::hypot(c.far_m, c.altitude_m);
    rx.pulse = {50e-6, sss::pulse_shape::rectangular};
    sss::ray_density density;
    density.along = 4;
    return turn_simulator(sss::scattering::lambertian<T>(), sss::propagation::straight<T>(),
                          sss::beam::ideal_fan<T>(fan), turn_path(c), rx, density);
}

/// The period (in samples) of the strongest oscillation of `x` with a period in [min_period, max_period]:
/// the peak of the Hann-windowed discrete-time Fourier transform of x less its least-squares line, located by a
/// fine scan and refined by golden-section search.
double dominant_period(const std::vector<double>& x, double min_period, double max_period) {
    const std::size_t n = x.size();
    double st = 0.0, sx = 0.0, stt = 0.0, stx = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i);
        st += t, sx += x[i], stt += t * t, stx += t * x[i];
    }
    const double nn = static_cast<double>(n);
    const double slope = (nn * stx - st * sx) / (nn * stt - st * st);
    const double icpt = (sx - slope * st) / nn;
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i);
        w[i] = (x[i] - icpt - slope * t) * (0.5 - 0.5 * std::cos(2.0 * pi * (t + 0.5) / nn));
    }
    auto power = [&](double f) { // f in cycles per sample
        double re = 0.0, im = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double a = 2.0 * pi * f * static_cast<double>(i);
            re += w[i] * std::cos(a);
            im += w[i] * std::sin(a);
        }
        return re * re + im * im;
    };
    const double f_lo = 1.0 / max_period, f_hi = 1.0 / min_period;
    const double step = 0.05 / nn;
    double best_f = f_lo, best_p = -1.0;
    for (double f = f_lo; f <= f_hi; f += step) {
        const double p = power(f);
        if (p > best_p) best_p = p, best_f = f;
    }
    double a = std::max(f_lo, best_f - step), b = std::min(f_hi, best_f + step);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 60; ++it) {
        const double c1 = b - g * (b - a), c2 = a + g * (b - a);
        if (power(c1) > power(c2)) b = c2; else a = c1;
    }
    return 2.0 / (a + b);
}

struct measured {
    double y_m, expected, period, ratio_error;
};

/// Renders the stretch and measures the ripple period at ground ranges `ys` on the inner and outer sides.
std::vector<measured> measure_turn(const turn_case& c, const std::vector<double>& ys, bool inner) {
    const auto sim = make_simulator(c);
    const auto bed = rippled_seabed(c, sim.motion(), 0.03);
    const auto w = sim.render(bed, 0, c.pings, 2);
    const sss::side sd = inner ? c.toward : (c.toward == sss::side::port ? sss::side::starboard : sss::side::port);
    const double own = c.wavelength_m / (c.speed_mps * c.ping_interval_s); // period at the towfish (pings)
    std::vector<measured> out;
    for (double y : ys) {
        const double slant = std::hypot(y, c.altitude_m);
        const auto k = static_cast<std::size_t>(2.0 * slant / 1500.0 / w.dt_s);
        const std::size_t column = sd == sss::side::port ? w.samples - 1 - k : w.samples + k;
        std::vector<double> series(w.pings);
        for (std::size_t i = 0; i < w.pings; ++i) series[i] = static_cast<double>(w.at(i, column));
        const double factor = inner ? (c.radius_m - y) / c.radius_m : (c.radius_m + y) / c.radius_m;
        const double expected = own / factor;
        // Search between half and twice the towfish's own period: wide enough to hold a straight-line answer
        // (factor 1) and every turn factor here, narrow enough to exclude harmonics of the ripple profile.
        const double period = dominant_period(series, 0.6 * own, 1.6 * own);
        out.push_back({y, expected, period, period / expected - 1.0});
    }
    return out;
}

void check_turn(const turn_case& c) {
    const std::vector<double> ys{10.0, 20.0, 30.0};
    for (bool inner : {true, false}) {
        for (const measured& m : measure_turn(c, ys, inner)) {
            INFO((inner ? "inner" : "outer"), " side, y = ", m.y_m, " m: period ", m.period, " pings, expected ",
                 m.expected, " (relative error ", m.ratio_error, ")");
            MESSAGE((inner ? "inner" : "outer"), " y=", m.y_m, " period ", m.period, " expected ", m.expected,
                    " err ", m.ratio_error);
            CHECK(std::abs(m.ratio_error) < 0.02);
        }
    }
}

} // namespace

TEST_CASE("on a starboard turn the seabed per ping is (R - y)/R of the towfish's to starboard and (R + y)/R to port") {
    turn_case c;
    c.toward = sss::side::starboard;
    check_turn(c);
}

TEST_CASE("on a port turn the seabed per ping is (R - y)/R of the towfish's to port and (R + y)/R to starboard") {
    turn_case c;
    c.toward = sss::side::port;
    check_turn(c);
}
