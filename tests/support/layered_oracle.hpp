#pragma once
// The flat-seabed oracle for layered water: expected mean power per time sample when the sound speed varies with
// depth, by adaptive quadrature over launch angle. Like flat_seabed_oracle.hpp it shares no code with the tracer:
// the rays are the closed-form arcs of a piecewise-linear profile written out again here in long double (no ray
// stepping, no scene, no chords, no time sampler), and only the policies' pointwise physics (beam weight,
// scattering cross section, absorption coefficient at a depth) is evaluated.
//
// One ray. A towfish at depth z_A (speed c_A) launches a ray down at grazing angle theta0; its Snell invariant
// xi = cos(theta0)/c_A fixes sin(theta(z)) = sqrt(1 - xi^2 c(z)^2). Between knots c is linear (gradient g) and,
// with s = sin(theta) at the ends a, b of a depth interval dz = z_b - z_a > 0 (rays that turn before the seabed
// are outside the oracle's domain):
//     dx   = xi (c_a + c_b) dz / (s_a + s_b)                        horizontal range; (sin_a - sin_b)/(xi g) rewritten
//     dt   = atanh(u)/g,  u = xi^2 (c_a + c_b) g dz / ((s_a + s_b) D),  D = 1 - s_a s_b
//                                                                   (1/g) ln[((1+s_a)/cos_a)/((1+s_b)/cos_b)] rewritten
//     dX/dxi = dx / (xi s_a s_b) = (c_a + c_b) dz / ((s_a + s_b) s_a s_b)
// (the rewritten forms hold at g = 0 and at xi = 0, vertical, without cancellation; D = (xi^2 c_a^2 + xi^2 c_b^2
// + (s_a - s_b)^2)/2 likewise). The ray-tube spreading at the seabed, range X and grazing theta_B, is
//     S_AB = cos(theta0) / (X sin(theta_B) |dX/dtheta0|),  dX/dtheta0 = -(sin(theta0)/c_A) dX/dxi,
// evaluated as c_A^2 / (Q sin(theta_B) sin(theta0) dX/dxi) with X = xi Q. Absorption: integral of alpha ds by 5-point
// Gauss-Legendre per depth interval, in grazing angle along the arc (ds = dtheta / (xi |g|)) where the angle changes,
// else in depth (ds = dz / sin(theta)).
//
// The line. The seabed patch between launch angles theta0 and theta0 + dtheta0 and azimuths psi and psi + dpsi
// has area dA = X |dX/dtheta0| dtheta0 dpsi. Its echo power (the derivation is energy conservation along the
// outgoing tube and the reversed one):
//     dP = SL b(theta0, psi) sigma(theta_B) A^2 S_AB S_BA dA,   S_BA = (c_B/c_A)^2 S_AB  (reciprocity),
// where b is the two-way beam weight in the launch direction (cos theta0 cos psi, cos theta0 sin psi, -sin theta0)
// and A the one-way absorption. With S_AB dA = cos(theta0) dtheta0 dpsi / sin(theta_B):
//     dP = SL sigma(theta_B) A^2 (c_B/c_A)^2 S_AB cos(theta0) / sin(theta_B) W(theta0) dtheta0,
//     W(theta0) = integral over psi of b (azimuth_weight of flat_seabed_oracle.hpp on the unit sphere).
// Isovelocity: S_AB = 1/R^2, theta_B = theta0, and with R = H/sin(theta0) this is the straight oracle's
// SL sigma A^2 W / R^3 dR. The echo arrives at two-way time 2 t(theta0), which falls monotonically as theta0
// rises towards the vertical; sample k integrates it against the pulse window exactly as the straight oracle
// does, over theta0 split where 2 t(theta0) meets the window's corners.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "flat_seabed_oracle.hpp"
#include "quadrature.hpp"

namespace sss_test {

// The water the layered oracle sees.
struct layered_water {
    std::vector<double> depth_m;                        // knots (m, positive down), increasing
    std::vector<double> speed_mps;                      // c at the knots (m/s): linear between, constant beyond
    double seabed_depth_m = 0.0;                        // depth of the flat seabed (m)
    std::function<double(double)> absorption_db_per_km; // alpha at a depth (m); empty: no absorption
};

// One ray from the towfish to the seabed.
struct layered_ray {
    bool reaches = false;    // false: it turns before the seabed (outside the oracle's domain)
    double range_m = 0;      // horizontal range X at the seabed (m)
    double time_s = 0;       // one-way time (s)
    double graze_rad = 0;    // grazing angle at the seabed (rad)
    double spreading = 0;    // S_AB: intensity at the seabed relative to 1 m from the source
    double absorption = 1;   // one-way intensity ratio
    double c_source = 0;     // c_A (m/s)
    double c_seabed = 0;     // c_B (m/s)
};

inline long double water_speed(const layered_water& w, long double z) {
    const auto& d = w.depth_m;
    const auto& c = w.speed_mps;
    if (z <= d.front()) return c.front();
    if (z >= d.back()) return c.back();
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(d.begin(), d.end(), static_cast<double>(z)) - d.begin());
    const long double z0 = d[i - 1], z1 = d[i], c0 = c[i - 1], c1 = c[i];
    return c0 + (c1 - c0) * (z - z0) / (z1 - z0);
}

// The ray launched down at grazing angle theta0 (rad, in (0, pi/2]) from source_depth_m to the seabed.
inline layered_ray layered_ray_to_seabed(const layered_water& w, double source_depth_m, double theta0_rad) {
    using ld = long double;
    static constexpr ld gx[5] = {-0.906179845938663992797626878299392965L, -0.538469310105683091036314420700208805L, 0.0L,
                                 0.538469310105683091036314420700208805L, 0.906179845938663992797626878299392965L};
    static constexpr ld gw[5] = {0.236926885056189087514264040719917363L, 0.478628670499366468041291514835638192L,
                                 0.568888888888888888888888888888888889L, 0.478628670499366468041291514835638192L,
                                 0.236926885056189087514264040719917363L};
    layered_ray out;
    const ld za = source_depth_m, zb = w.seabed_depth_m, th0 = theta0_rad;
    const ld ca0 = water_speed(w, za);
    const ld xi = std::cos(th0) / ca0;
    const ld sin0 = std::sin(th0);
    out.c_source = static_cast<double>(ca0);
    out.c_seabed = static_cast<double>(water_speed(w, zb));
    if (!(zb > za)) return out;
    auto sin_at = [&](ld c) { const ld q = xi * c; return std::sqrt((1 - q) * (1 + q)); };
    // Depth intervals: the source, the knots strictly between, the seabed.
    std::vector<ld> z{za};
    for (double k : w.depth_m) if (k > za && k < zb) z.push_back(k);
    z.push_back(zb);
    ld q_sum = 0, dxdxi = 0, t = 0, absorption_db = 0;
    for (std::size_t i = 0; i + 1 < z.size(); ++i) {
        const ld z1 = z[i], z2 = z[i + 1], dz = z2 - z1;
        const ld c1 = water_speed(w, z1), c2 = water_speed(w, z2);
        if (!(xi * c1 < 1) || !(xi * c2 < 1)) return out; // turns (c is linear: its largest value is at an end)
        const ld s1 = sin_at(c1), s2 = sin_at(c2), g = (c2 - c1) / dz;
        const ld q = (c1 + c2) * dz / (s1 + s2); // dx / xi
        q_sum += q;
        dxdxi += q / (s1 * s2);
        const ld d = (xi * xi * (c1 * c1 + c2 * c2) + (s1 - s2) * (s1 - s2)) / 2;
        const ld base = xi * xi * q / d; // time when g -> 0
        const ld u = g * base;
        t += std::abs(u) < 1e-8L ? base * (1 + u * u / 3) : base * std::atanh(u) / u;
        if (w.absorption_db_per_km) {
            auto alpha = [&](ld zk) { return static_cast<ld>(w.absorption_db_per_km(static_cast<double>(zk))); };
            const ld th1 = std::atan2(s1, xi * c1), th2 = std::atan2(s2, xi * c2);
            ld sum = 0;
            if (std::abs(th2 - th1) < 0.01L) { // sin(theta) nearly constant: in depth, ds = dz / sin(theta)
                for (int k = 0; k < 5; ++k) {
                    const ld zk = (z1 + z2) / 2 + dz / 2 * gx[k];
                    sum += gw[k] * alpha(zk) / sin_at(water_speed(w, zk));
                }
                absorption_db += sum * dz / 2 / 1000;
            } else { // in grazing angle along the arc: ds = dtheta / (xi |g|), c(z) = cos(theta) / xi
                for (int k = 0; k < 5; ++k) {
                    const ld th = (th1 + th2) / 2 + (th2 - th1) / 2 * gx[k];
                    sum += gw[k] * alpha(z1 + (std::cos(th) / xi - c1) / g);
                }
                absorption_db += sum * std::abs(th2 - th1) / 2 / (xi * std::abs(g)) / 1000;
            }
        }
    }
    const ld cb = water_speed(w, zb), sb = sin_at(cb);
    out.reaches = true;
    out.range_m = static_cast<double>(xi * q_sum);
    out.time_s = static_cast<double>(t);
    out.graze_rad = static_cast<double>(std::atan2(sb, xi * cb));
    out.spreading = static_cast<double>(ca0 * ca0 / (q_sum * sb * sin0 * dxdxi));
    out.absorption = static_cast<double>(std::pow(10.0L, -absorption_db / 10));
    return out;
}

// Launch angle (rad) at which the two-way time is tau_s, on [theta_lo, pi/2] where two_way(theta) falls monotonically
// (clamped to the ends).
template <class F> double launch_angle_at_time(F&& two_way, double tau_s, double theta_lo, double t_lo, double t_hi) {
    const double half_pi = 1.57079632679489661923;
    if (tau_s >= t_lo) return theta_lo;
    if (tau_s <= t_hi) return half_pi;
    double a = theta_lo, b = half_pi, fa = t_lo - tau_s, fb = t_hi - tau_s; // fa > 0 > fb
    int side = 0;
    for (int it = 0; it < 200 && b - a > 1e-15; ++it) { // Illinois regula falsi
        const double m = std::clamp(b - fb * (b - a) / (fb - fa), a, b);
        const double fm = two_way(m) - tau_s;
        if (std::abs(fm) <= 1e-15 * tau_s) return m;
        if (fm > 0) { a = m; fa = fm; if (side == -1) fb /= 2; side = -1; }
        else { b = m; fb = fm; if (side == 1) fa /= 2; side = 1; }
    }
    return 0.5 * (a + b);
}

// Expected line (mean power per sample) for one side over a flat seabed in layered water. The towfish is o.altitude_m
// above the seabed (so at depth w.seabed_depth_m - o.altitude_m); o.c_mps and o.absorption_db_per_km are not used.
// Rays launched below theta_floor_rad are left out: it throws std::runtime_error if any of them could arrive within
// the line, or if two-way time is not monotone in launch angle (a caustic: outside the oracle's domain).
template <class Beam, class Scattering>
std::vector<double> oracle_line_layered(const oracle_setup& o, const layered_water& w, const Beam& beam,
                                        const Scattering& scat, sss::side sd, double theta_floor_rad = 0.01) {
    using T = typename Beam::value_type;
    const double half_pi = 1.57079632679489661923;
    const sss::mat3<double> R = sss::body_to_world_rotation(o.roll_rad, o.pitch_rad, o.yaw_rad);
    const double z_src = w.seabed_depth_m - o.altitude_m, dt = o.dt_s, L = o.pulse_length_s;
    const double t_end = double(o.samples) * dt;
    auto two_way = [&](double th) { return 2.0 * layered_ray_to_seabed(w, z_src, th).time_s; };

    const double t_lo = two_way(theta_floor_rad), t_hi = two_way(half_pi);
    if (!layered_ray_to_seabed(w, z_src, theta_floor_rad).reaches || !(t_lo > t_end))
        throw std::runtime_error("oracle_line_layered: launches below theta_floor_rad arrive within the line");
    {
        double prev = t_lo;
        for (int i = 1; i <= 4000; ++i) {
            const double th = theta_floor_rad + (half_pi - theta_floor_rad) * i / 4000.0;
            const double tt = two_way(th);
            if (!(tt < prev)) throw std::runtime_error("oracle_line_layered: two-way time not monotone in launch angle");
            prev = tt;
        }
    }
    // Launch angles at the window corners: times k dt and k dt - L.
    std::vector<double> at_k(o.samples + 1), at_k_minus_l(o.samples + 1);
    for (std::size_t k = 0; k <= o.samples; ++k) {
        at_k[k] = launch_angle_at_time(two_way, double(k) * dt, theta_floor_rad, t_lo, t_hi);
        at_k_minus_l[k] = launch_angle_at_time(two_way, double(k) * dt - L, theta_floor_rad, t_lo, t_hi);
    }

    // Echo power per radian of launch angle, before the pulse window.
    auto density = [&](double th, const layered_ray& ray) {
        if (!ray.reaches) return 0.0;
        oracle_setup unit = o;
        unit.altitude_m = std::sin(th); // azimuth_weight on the unit sphere: direction (cos th cos psi, cos th sin psi, -sin th)
        const double W = azimuth_weight(unit, beam, sd, 1.0, R);
        if (W == 0.0) return 0.0;
        const double sigma = double(scat.backscatter(static_cast<T>(ray.graze_rad), 0u));
        const double ratio = ray.c_seabed / ray.c_source;
        return o.source_level * W * sigma * ray.absorption * ray.absorption * ratio * ratio * ray.spreading * std::cos(th) /
               std::sin(ray.graze_rad);
    };
    const auto ext = beam.extent(sd);
    const double rel_tol = std::is_same_v<T, float> ? std::max(o.rel_tol, 1e-6) : o.rel_tol;
    std::vector<double> y(o.samples, 0.0);
    for (std::size_t k = 0; k < o.samples; ++k) {
        const double t0 = double(k) * dt, t1 = t0 + dt;
        const double lo = at_k[k + 1], hi = at_k_minus_l[k];
        if (!(hi > lo)) continue;
        auto window = [&](double s) { return (envelope_cumulative(o, t1 - s) - envelope_cumulative(o, t0 - s)) / dt; };
        auto f = [&](double th) {
            const layered_ray ray = layered_ray_to_seabed(w, z_src, th);
            return density(th, ray) * window(2.0 * ray.time_s);
        };
        std::vector<double> cuts{at_k[k], at_k_minus_l[k + 1]};
        for (double e : {double(ext.depression_min_rad), double(ext.depression_max_rad)})
            if (e > 0 && e < half_pi) cuts.push_back(e);
        y[k] = integrate_pieces(f, lo, hi, cuts, rel_tol).value;
    }
    return y;
}

} // namespace sss_test
