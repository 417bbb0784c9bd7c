#pragma once
// The flat-seabed oracle: expected mean power per time sample, by adaptive numerical integration of the sonar
// equation over the seabed plane (beam weights x scattering x spreading x absorption x pulse envelope).
// It shares no code with the tracer: no ray sampling, no intersection, no time sampler. It evaluates only the
// policies' pointwise physics (beam weight, scattering cross section), which their own tests check against
// closed forms and published values.
//
// Geometry: towfish at height H above the plane; a seabed point at slant range r and azimuth psi (world) lies in
// the direction d = (g cos psi, g sin psi, -H)/r, g = sqrt(r^2 - H^2), and the area element is r dr dpsi.
// Isovelocity water: the echo from dA has power SL b sigma(theta) 10^(-2 alpha r/10^4) dA / r^4 at two-way delay
// s = 2r/c, grazing angle sin(theta) = H/r. Sample k (delays [k dt, (k+1) dt)) records the mean of the echo
// density convolved with the pulse's power envelope p:
//     y_k = int rho(s) W_k(s) ds,  W_k(s) = (1/dt) int_{k dt}^{(k+1) dt} p(t - s) dt.
// The azimuth integral is split where the beam's extent edges and the side boundary cross the range circle;
// these are solved in closed form, because every edge is a plane through the transducer (n . d = c).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

#include <sss/beam/concept.hpp>
#include <sss/core/pose.hpp>
#include "quadrature.hpp"

namespace sss_test {

enum class envelope { rectangular, hann };

struct oracle_setup {
    double altitude_m = 10.0;           // towfish above the seabed (m)
    double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
    double c_mps = 1500.0;
    double absorption_db_per_km = 0.0;
    double dt_s = 1.0 / 20000.0;
    std::size_t samples = 1000;
    envelope pulse = envelope::rectangular;
    double pulse_length_s = 100e-6;
    double source_level = 1.0;          // linear
    double rel_tol = 1e-7;              // outer (range) integral; the checks need ~1e-3
};

// Integral of the power envelope from 0 to t.
inline double envelope_cumulative(const oracle_setup& o, double t) {
    const double L = o.pulse_length_s;
    t = std::min(std::max(t, 0.0), L);
    if (o.pulse == envelope::rectangular) return t;
    // integral of sin^4: by the power-reduction identity sin^4 x = 3/8 - cos(2x)/2 + cos(4x)/8.
    const double w = 3.141592653589793238 / L;
    return 0.375 * t - std::sin(2 * w * t) / (4 * w) + std::sin(4 * w * t) / (32 * w);
}

// Azimuths (rad) where n . d(psi) = c on the circle of slant range r (d as above, n in world coordinates).
inline void circle_crossings(std::vector<double>& out, const sss::vec3<double>& n, double c, double r, double H) {
    const double g = std::sqrt(std::max(r * r - H * H, 0.0));
    const double A = n.x * g, B = n.y * g, C = c * r + n.z * H;
    const double rho = std::hypot(A, B);
    if (!(rho > 0) || std::abs(C) > rho) return;
    const double base = std::atan2(B, A), off = std::acos(C / rho);
    for (double psi : {base - off, base + off}) {
        psi = std::fmod(psi, 2 * 3.141592653589793238);
        if (psi < 0) psi += 2 * 3.141592653589793238;
        out.push_back(psi);
    }
}

// Integral over azimuth of the two-way beam weight on one side at slant range r (rad).
template <class Beam> double azimuth_weight(const oracle_setup& o, const Beam& beam, sss::side sd, double r,
                                            const sss::mat3<double>& R) {
    using T = typename Beam::value_type;
    const double H = o.altitude_m, g = std::sqrt(std::max(r * r - H * H, 0.0));
    const double s = sd == sss::side::starboard ? 1.0 : -1.0;
    const auto ext = beam.extent(sd);
    const sss::mat3<double> Rt = glm::transpose(R);
    // Body-frame planes bounding the extent, mapped to world: n_world = R n_body.
    std::vector<double> cuts;
    circle_crossings(cuts, R * sss::vec3<double>{0, 1, 0}, 0.0, r, H);
    circle_crossings(cuts, R * sss::vec3<double>{1, 0, 0}, std::sin(double(ext.along_min_rad)), r, H);
    circle_crossings(cuts, R * sss::vec3<double>{1, 0, 0}, std::sin(double(ext.along_max_rad)), r, H);
    for (double e : {double(ext.depression_min_rad), double(ext.depression_max_rad)})
        circle_crossings(cuts, R * sss::vec3<double>{0, -s * std::sin(e), std::cos(e)}, 0.0, r, H);
    auto weight = [&](double psi) {
        const sss::vec3<double> d{g * std::cos(psi) / r, g * std::sin(psi) / r, -H / r};
        const sss::vec3<double> b = Rt * d;
        if (!(s * b.y > 0)) return 0.0;
        const double along = std::asin(std::min(1.0, std::max(-1.0, b.x)));
        const double depression = std::atan2(b.z, s * b.y);
        return double(beam.weight(sd, static_cast<T>(along), static_cast<T>(depression)));
    };
    // The weight is at most 1 over 2 pi of azimuth. A float beam's edges sit a rounding away from the breakpoints
    // solved here, leaving slivers of discontinuity inside pieces: resolve those only to the policy's precision.
    constexpr bool single = std::is_same_v<T, float>;
    return integrate_pieces(weight, 0.0, 2 * 3.141592653589793238, cuts, single ? 1e-6 : 1e-9, single ? 1e-6 : 1e-11).value;
}

// Expected line (mean power per sample) for one side.
template <class Beam, class Scattering>
std::vector<double> oracle_line(const oracle_setup& o, const Beam& beam, const Scattering& scat, sss::side sd) {
    using T = typename Beam::value_type;
    const sss::mat3<double> R = sss::body_to_world_rotation(o.roll_rad, o.pitch_rad, o.yaw_rad);
    const double H = o.altitude_m, c = o.c_mps, dt = o.dt_s, L = o.pulse_length_s;
    const double k_abs = std::log(10.0) * o.absorption_db_per_km / 1e4; // one-way intensity loss rate (1/m)
    // Echo power per metre of slant range (dr), before the pulse window.
    auto density = [&](double r) {
        const double graze = std::asin(std::min(1.0, H / r));
        const double sigma = double(scat.backscatter(static_cast<T>(graze), 0u));
        return o.source_level * sigma * std::exp(-2.0 * k_abs * r) / (r * r * r) * azimuth_weight(o, beam, sd, r, R);
    };
    const auto ext = beam.extent(sd);
    // Float policies return values with rounding noise near 1e-7: ask no more of the quadrature than that.
    const double rel_tol = std::is_same_v<T, float> ? std::max(o.rel_tol, 1e-6) : o.rel_tol;
    std::vector<double> y(o.samples, 0.0);
    for (std::size_t k = 0; k < o.samples; ++k) {
        const double t0 = double(k) * dt, t1 = t0 + dt;
        const double s_lo = std::max(t0 - L, 2.0 * H / c), s_hi = t1;
        if (!(s_hi > s_lo)) continue;
        auto window = [&](double s) { return (envelope_cumulative(o, t1 - s) - envelope_cumulative(o, t0 - s)) / dt; };
        auto f = [&](double r) { return density(r) * window(2.0 * r / c); };
        std::vector<double> cuts;
        for (double s : {t0 - L, t1 - L, t0, t1}) cuts.push_back(0.5 * c * s);
        for (double e : {double(ext.depression_min_rad), double(ext.depression_max_rad)})
            if (e > 0) cuts.push_back(H / std::sin(e));
        y[k] = integrate_pieces(f, 0.5 * c * s_lo, 0.5 * c * s_hi, cuts, rel_tol).value;
    }
    return y;
}

} // namespace sss_test
