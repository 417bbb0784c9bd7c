// The constant-rate turn seen in the image: sand ripples whose crests cross the track are imaged at a ping
// spacing set by how far the seabed point under each range cell moves per ping.
//
// On a turn of radius R (towfish speed V, ping interval dt) the fan at each ping lies along the radius through
// the towfish, so the seabed point at ground range y lies on a circle about the turn centre of radius R - y on
// the inner side and R + y on the outer side, and moves (R -+ y) / R V dt per ping. Straight crests of
// wavelength lambda, perpendicular to the heading in the middle of a short stretch, therefore repeat every
//     P(y) = lambda / ((R -+ y) / R V dt)   pings
// (to first order in the heading change over the stretch; here it changes by 2.9 deg, a relative error of
// 1 - cos(1.43 deg) = 3e-4). The period is measured on the rendered waterfall at the sample for slant range
// sqrt(y^2 + H^2), H the altitude, by a least-squares sinusoid fit. The crests are square to the fan only at the
// middle ping: elsewhere they lie at the heading change delta(t) to it, so their slope tilts the seabed across
// the fan by delta(t) times the along-track slope, which changes the Lambertian return in proportion to delta,
// i.e. linearly in time. The fit therefore lets each harmonic's complex amplitude vary linearly over the record
// (a constant-amplitude fit or spectral peak is pulled several per cent by that ramp). A straight-line answer
// (the towfish's own period at every range) would be 6 to 25 per cent off; the tolerance is 2 per cent.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
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
    double radius_m = 150.0;                 ///< turn radius R; infinite: a straight track
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
    if (std::isfinite(c.radius_m)) p.turn = sss::motion::constant_turn<T>{c.toward, static_cast<T>(c.radius_m), T(0)};
    const double sign = c.toward == sss::side::starboard ? 1.0 : -1.0;
    const double mid_t = static_cast<double>(c.pings / 2) * c.ping_interval_s;
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
    r.crest_heading_deg = T(90); // crests run east
    r.symmetry_index = static_cast<T>(c.symmetry_index);
    auto h = sss::seabed::ripple_field<T>(nx, ny, static_cast<T>(cell_m), r, 1);
    return sss::scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = static_cast<T>(cell_m), .origin_m = {static_cast<T>(x0), static_cast<T>(y0)}, .heights_m = std::move(h.values)});
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

/// The solution x of A x = b (A n x n, row-major; here the normal equations of a least-squares fit) by Gaussian
/// elimination with partial pivoting.
std::vector<double> solve(std::vector<double> a, std::vector<double> b) {
    const std::size_t n = b.size();
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t piv = c;
        for (std::size_t r = c + 1; r < n; ++r)
            if (std::abs(a[r * n + c]) > std::abs(a[piv * n + c])) piv = r;
        for (std::size_t k = 0; k < n; ++k) std::swap(a[c * n + k], a[piv * n + k]);
        std::swap(b[c], b[piv]);
        for (std::size_t r = c + 1; r < n; ++r) {
            const double f = a[r * n + c] / a[c * n + c];
            for (std::size_t k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
            b[r] -= f * b[c];
        }
    }
    std::vector<double> x(n);
    for (std::size_t c = n; c-- > 0;) {
        double s = b[c];
        for (std::size_t k = c + 1; k < n; ++k) s -= a[c * n + k] * x[k];
        x[c] = s / a[c * n + c];
    }
    return x;
}

/// The sum of squared residuals of the least-squares fit to x(t) (t = sample index, centred: u = t / n - 1/2) of
///     a0 + a1 u + sum_{m=1,2} [(b_m + c_m u) cos(2 pi m f t) + (d_m + e_m u) sin(2 pi m f t)]:
/// a linear trend and a periodic signal of frequency f (cycles per sample) with its second harmonic, each with a
/// complex amplitude that varies linearly over the record.
double fit_residual(const std::vector<double>& x, double f) {
    constexpr std::size_t k = 10;
    std::vector<double> ata(k * k, 0.0), atb(k, 0.0), row(k);
    const double n = static_cast<double>(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double t = static_cast<double>(i), u = t / n - 0.5;
        row[0] = 1.0, row[1] = u;
        for (std::size_t m = 1; m <= 2; ++m) {
            const double ph = 2.0 * pi * static_cast<double>(m) * f * t;
            const std::size_t j = 2 + 4 * (m - 1);
            row[j] = std::cos(ph), row[j + 1] = u * std::cos(ph), row[j + 2] = std::sin(ph), row[j + 3] = u * std::sin(ph);
        }
        for (std::size_t r = 0; r < k; ++r) {
            for (std::size_t c = 0; c < k; ++c) ata[r * k + c] += row[r] * row[c];
            atb[r] += row[r] * x[i];
        }
    }
    const std::vector<double> coef = solve(ata, atb);
    double ss = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double t = static_cast<double>(i), u = t / n - 0.5;
        double v = coef[0] + coef[1] * u;
        for (std::size_t m = 1; m <= 2; ++m) {
            const double ph = 2.0 * pi * static_cast<double>(m) * f * t;
            const std::size_t j = 2 + 4 * (m - 1);
            v += (coef[j] + coef[j + 1] * u) * std::cos(ph) + (coef[j + 2] + coef[j + 3] * u) * std::sin(ph);
        }
        ss += (x[i] - v) * (x[i] - v);
    }
    return ss;
}

/// The period (samples) in [min_period, max_period] whose fit (see fit_residual) leaves the least residual:
/// a fine scan in frequency refined by golden-section search.
double fitted_period(const std::vector<double>& x, double min_period, double max_period) {
    const double f_lo = 1.0 / max_period, f_hi = 1.0 / min_period;
    const double step = 0.02 / static_cast<double>(x.size());
    double best_f = f_lo, best = std::numeric_limits<double>::infinity();
    for (double f = f_lo; f <= f_hi; f += step) {
        const double r = fit_residual(x, f);
        if (r < best) best = r, best_f = f;
    }
    double a = std::max(f_lo, best_f - step), b = std::min(f_hi, best_f + step);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 40; ++it) {
        const double c1 = b - g * (b - a), c2 = a + g * (b - a);
        if (fit_residual(x, c1) < fit_residual(x, c2)) b = c2; else a = c1;
    }
    return 2.0 / (a + b);
}

struct measured {
    bool inner;
    double y_m, expected, period, error, explained;
};

/// The fraction of the variance of x about its least-squares line that the periodic fit at `period` explains.
double explained_fraction(const std::vector<double>& x, double period) {
    const double n = static_cast<double>(x.size());
    double su = 0.0, sx = 0.0, suu = 0.0, sux = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double u = static_cast<double>(i) / n - 0.5;
        su += u, sx += x[i], suu += u * u, sux += u * x[i];
    }
    const double slope = (n * sux - su * sx) / (n * suu - su * su), icpt = (sx - slope * su) / n;
    double var = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double d = x[i] - icpt - slope * (static_cast<double>(i) / n - 0.5);
        var += d * d;
    }
    return 1.0 - fit_residual(x, 1.0 / period) / var;
}

/// Renders the stretch and measures the ripple period at ground ranges `ys` on both sides.
std::vector<measured> measure_turn(const turn_case& c, const std::vector<double>& ys) {
    const auto sim = make_simulator(c);
    const auto bed = rippled_seabed(c, sim.motion(), 0.03);
    const auto w = sim.render(bed, 0, c.pings, 2);
    const double own = c.wavelength_m / (c.speed_mps * c.ping_interval_s); // period at the towfish (pings)
    std::vector<measured> out;
    for (sss::side sd : {sss::side::port, sss::side::starboard}) {
        const bool inner = sd == c.toward;
        for (double y : ys) {
            const double slant = std::hypot(y, c.altitude_m);
            const auto k = static_cast<std::size_t>(2.0 * slant / 1500.0 / w.dt_s);
            const std::size_t column = sd == sss::side::port ? w.samples - 1 - k : w.samples + k;
            std::vector<double> series(w.pings);
            for (std::size_t i = 0; i < w.pings; ++i) series[i] = static_cast<double>(w.at(i, column));
            const double factor = inner ? 1.0 - y / c.radius_m : 1.0 + y / c.radius_m;
            const double expected = own / factor;
            // Search periods from 0.6 to 1.6 times the towfish's own: wide enough to hold a straight-line answer
            // (factor 1) and every turn factor here (0.8 to 1.2), with neither half nor twice the true frequency.
            const double period = fitted_period(series, 0.6 * own, 1.6 * own);
            out.push_back({inner, y, expected, period, period / expected - 1.0, explained_fraction(series, period)});
        }
    }
    return out;
}

void check_turn(const turn_case& c) {
    for (const measured& m : measure_turn(c, {10.0, 20.0, 30.0})) {
        INFO((m.inner ? "inner" : "outer"), " side, y = ", m.y_m, " m: period ", m.period, " pings, expected ",
             m.expected, " (relative error ", m.error, "); the fit explains ", m.explained, " of the variance");
        CHECK(std::abs(m.error) < 0.02);
        CHECK(m.explained > 0.9); // the ripples, not noise, set the period
    }
}

} // namespace

TEST_CASE("on a starboard turn the seabed per ping is (R - y)/R of the towfish's to starboard and (R + y)/R to port") {
    turn_case c;
    c.toward = sss::side::starboard;
    check_turn(c);
}

TEST_CASE("on a straight track the ripple period in pings is the same at every range on both sides") {
    turn_case c;
    c.radius_m = std::numeric_limits<double>::infinity();
    check_turn(c);
}

TEST_CASE("on a port turn the seabed per ping is (R - y)/R of the towfish's to port and (R + y)/R to starboard") {
    turn_case c;
    c.toward = sss::side::port;
    check_turn(c);
}
