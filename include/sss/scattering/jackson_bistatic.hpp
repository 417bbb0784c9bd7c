#pragma once
/// \file
/// The bistatic extension of the APL-UW seafloor scattering model.
///
/// Source: K. L. Williams and D. R. Jackson, "Bistatic bottom scattering: Model, experiments, and
/// model/data comparison", JASA 103(1), 169-181 (1998), built on APL-UW TR 9407 (1994) Section IV.
/// Geometry: theta_i, theta_s are the incident and scattered grazing angles (rad, in [0, pi/2]), phi the
/// azimuth of the scattered direction from the forward direction of the incident one (rad): phi = 0 is
/// forward (specular when theta_s = theta_i), phi = pi is backscatter. With
///   Delta_t = 1/2 sqrt(cos^2 th_i - 2 cos th_i cos th_s cos phi + cos^2 th_s),  Delta_z = 1/2 (sin th_i + sin th_s),
///   Delta = sqrt(Delta_t^2 + Delta_z^2)   (2 k Delta is the Bragg wavevector),
/// the terms taken from Williams & Jackson are the perturbation term
///   sigma_pr = 1/4 k^4 |1 + R_i|^2 |1 + R_s|^2 |G|^2 W(K),
///   G = (1/rho - 1)(cos th_i cos th_s cos phi - P_i P_s / rho) + 1 - kappa^2 / rho,
/// and the Kirchhoff term with |R(theta_is)|^2, theta_is = asin(Delta), in place of |R(90 deg)|^2.
/// The remaining pieces generalise TR 9407's backscatter forms so that each reduces to it exactly at
/// phi = pi, theta_i = theta_s, and each is symmetric in (theta_i, theta_s) (reciprocity):
/// - K = sqrt(4 k^2 Delta_t^2 + (k/10)^2) regularises W near the specular direction, as TR 9407 does at
///   normal incidence.
/// - Kirchhoff: sigma_kr = b q_c |R(theta_is)|^2 Delta^4 / (8 pi [Delta_t^(4 alpha) + a q_c^2 Delta_z^4]^((1+alpha)/(2 alpha))).
/// - Slope averaging tilts the mean plane about the horizontal axis normal to the Bragg vector's horizontal
///   part (in the plane of incidence at backscatter): the same 3-point Gauss-Hermite rule, each leg's
///   grazing angle moved by the tilt without crossing its facet normal (TR 9407 clips at 90 deg).
///   At the exact specular direction (Delta_t = 0) the axis is taken normal to the plane of incidence.
/// - Shadowing: S = (1 - e^(-2Q)) / (2Q), Q = max(Q_i, Q_s) + (1 + cos phi)/2 min(Q_i, Q_s): one common
///   shadow at backscatter, the two legs' shadows compounding towards forward scatter (as in Smith's
///   bistatic shadowing).
/// - Volume: sigma_pv = 5 delta sigma2 |1 + R_i|^2 |1 + R_s|^2 / (nu ln10 rho^2 Im(P_i + P_s)/2), the TR 9407
///   isotropic-volume form with one transmission factor per leg and the two legs' attenuation averaged.
///   (Williams & Jackson's fluctuation-spectrum volume model needs inputs TR 9407 Table 2 does not give.)
/// - Large roughness: sigma1 sqrt(L(th_i) L(th_s)) + 0.0260 |R(theta_is)|^2 sqrt(1/(crit_i crit_s)) /
///   [s^2 (1 + psi^2 / (2.6 theta_s^2))^1.9], L = sin^m(180 deg / crit), psi = atan(Delta_t / Delta_z) the
///   tilt of the specular facet (90 deg - theta at backscatter).
/// - Kirchhoff / composite blend: cos theta is replaced by Delta_t / Delta.
/// The Kirchhoff term grows without bound towards the forward specular direction at grazing incidence
/// (Delta_t = 0, Delta_z -> 0); it is finite at every other geometry and set to 0 at Delta = 0.

#include <algorithm>
#include <cmath>
#include <complex>

#include "sss/core/constants.hpp"
#include "sss/scattering/jackson_terms.hpp"

namespace sss::scattering {

/// The bistatic geometry of Williams & Jackson (1998), from grazing angles and azimuth (rad).
template <Real T> struct bistatic_geometry {
    T sin_i{}, cos_i{}, sin_s{}, cos_s{};
    T horizontal{}; ///< cos th_i cos th_s cos phi (dot product of the horizontal direction parts)
    T cos_phi{};
    T delta_t{}, delta_z{}, delta{};
};

/// Delta_t, Delta_z, Delta and the sines and cosines for grazing angles clamped to [0, pi/2] (NaN -> 0).
template <Real T> [[nodiscard]] inline bistatic_geometry<T> make_bistatic_geometry(T graze_in_rad, T graze_out_rad, T phi_rad) noexcept {
    const T gi = clamp_graze(graze_in_rad), gs = clamp_graze(graze_out_rad);
    bistatic_geometry<T> b;
    b.sin_i = std::sin(gi);
    b.cos_i = std::cos(gi);
    b.sin_s = std::sin(gs);
    b.cos_s = std::cos(gs);
    b.cos_phi = std::isnan(phi_rad) ? T(-1) : std::cos(phi_rad);
    b.horizontal = b.cos_i * b.cos_s * b.cos_phi;
    b.delta_t = T(0.5) * std::sqrt(std::max(T(0), b.cos_i * b.cos_i - T(2) * b.horizontal + b.cos_s * b.cos_s));
    b.delta_z = T(0.5) * (b.sin_i + b.sin_s);
    b.delta = std::min(T(1), std::sqrt(b.delta_t * b.delta_t + b.delta_z * b.delta_z));
    return b;
}

/// Bistatic Kirchhoff term (see the file comment). 0 at Delta = 0.
template <Real T> [[nodiscard]] inline T jackson_bistatic_sigma_kr(const jackson_coefficients<T>& c, const bistatic_geometry<T>& b) noexcept {
    if (!(b.delta > T(1e-12))) return T(0);
    const T r2 = std::norm(rayleigh_reflection(c.sediment, std::asin(b.delta)));
    const T dz2 = b.delta_z * b.delta_z;
    const T den = std::pow(b.delta_t, T(4) * c.alpha) + c.a_kr * c.q_c * c.q_c * dz2 * dz2;
    const T d2 = b.delta * b.delta;
    return c.b_kr * c.q_c * r2 * d2 * d2 / (T(8) * pi_v<T> * std::pow(den, (T(1) + c.alpha) / (T(2) * c.alpha)));
}

/// Bistatic perturbation and volume terms (before shadowing and slope averaging) for local grazing sines
/// sin_i, sin_s (>= 0) and horizontal product cos th_i cos th_s cos phi (see the file comment).
template <Real T>
[[nodiscard]] inline jackson_pr_pv<T> jackson_bistatic_local_terms(const jackson_coefficients<T>& c, T sin_i, T sin_s,
                                                                           T horizontal) noexcept {
    const sediment_params<T>& p = c.sediment;
    const T ci2 = std::max(T(0), T(1) - sin_i * sin_i), cs2 = std::max(T(0), T(1) - sin_s * sin_s);
    const std::complex<T> k2 = c.kappa * c.kappa;
    const std::complex<T> pi = std::sqrt((k2 - T(1)) + sin_i * sin_i); // P = sqrt(kappa^2 - cos^2), see reflection.hpp
    const std::complex<T> ps = std::sqrt((k2 - T(1)) + sin_s * sin_s);
    const T ri = p.rho * sin_i, rs = p.rho * sin_s;
    const T ti = std::norm(T(2) * ri / (ri + pi)); // |1 + R_i|^2
    const T ts = std::norm(T(2) * rs / (rs + ps)); // |1 + R_s|^2
    const std::complex<T> g = (T(1) / p.rho - T(1)) * (horizontal - pi * ps / p.rho) + T(1) - k2 / p.rho;
    const T dt2 = std::max(T(0), T(0.25) * (ci2 - T(2) * horizontal + cs2));
    const T k = c.k_radpcm;
    const T big_k = std::sqrt(T(4) * k * k * dt2 + T(0.01) * k * k);
    const T k2r = k * k;
    const T pr = T(0.25) * k2r * k2r * ti * ts * std::norm(g) * jackson_spectrum_cm4(p.w2_cm4, p.gamma, big_k);
    const T pv = p.sigma2 > T(0)
                     ? T(5) * p.delta * p.sigma2 * ti * ts / (p.nu * ln10_v<T> * p.rho * p.rho * T(0.5) * (pi.imag() + ps.imag()))
                     : T(0);
    return {pr, pv};
}

/// Bistatic shadowing (see the file comment); reduces to jackson_shadowing at backscatter.
template <Real T> [[nodiscard]] inline T jackson_bistatic_shadowing(const bistatic_geometry<T>& b, T s) noexcept {
    const T qi = jackson_shadowing_q(b.sin_i / (std::max(b.cos_i, T(0)) * s));
    const T qs = jackson_shadowing_q(b.sin_s / (std::max(b.cos_s, T(0)) * s));
    if (!std::isfinite(qi) || !std::isfinite(qs)) return T(0);
    const T w = std::clamp(T(0.5) * (T(1) + b.cos_phi), T(0), T(1));
    return jackson_shadowing_from_q(std::max(qi, qs) + w * std::min(qi, qs));
}

/// Slope-averaged bistatic perturbation and volume terms (see the file comment): the mean plane tilted by
/// tau = x_j s about the horizontal axis normal to the Bragg vector's horizontal part, 3-point
/// Gauss-Hermite weights, divided by sqrt(pi).
template <Real T>
[[nodiscard]] inline jackson_pr_pv<T> jackson_bistatic_slope_average(const jackson_coefficients<T>& c,
                                                                             const bistatic_geometry<T>& b) noexcept {
    // Each leg's local grazing sine under a tilt tau is A cos tau + B sin tau = r sin(base + tau), with
    // A the grazing sine and B the projection of the horizontal direction on the tilt direction.
    T bi = 0, bs = 0;
    if (b.delta_t > T(1e-9)) {
        bi = (b.cos_i * b.cos_i - b.horizontal) / (T(2) * b.delta_t);
        bs = (b.cos_s * b.cos_s - b.horizontal) / (T(2) * b.delta_t);
    } else { // specular: tilt in the plane of incidence
        bi = -b.cos_i;
        bs = b.cos_s * b.cos_phi;
    }
    const T ri = std::min(T(1), std::hypot(b.sin_i, bi)), rs = std::min(T(1), std::hypot(b.sin_s, bs));
    const T base_i = std::atan2(b.sin_i, bi), base_s = std::atan2(b.sin_s, bs);
    // The tilt never carries a leg across its facet normal (phase 90 deg) nor below the plane.
    const auto local = [](T r, T base, T tau) {
        const T ph = base <= half_pi_v<T> ? std::clamp(base + tau, T(0), half_pi_v<T>) : std::clamp(base + tau, half_pi_v<T>, pi_v<T>);
        return std::max(T(0), r * std::sin(ph));
    };
    const T invariant = b.horizontal - b.sin_i * b.sin_s; // dot product of the two propagation directions
    const T d = gauss_hermite3_node<T> * c.s;
    const T taus[3] = {d, T(0), -d}; // the order of jackson_backscatter_terms
    const T weights[3] = {gauss_hermite3_weight_outer<T>, gauss_hermite3_weight_centre<T>, gauss_hermite3_weight_outer<T>};
    jackson_pr_pv<T> sum{T(0), T(0)};
    for (int j = 0; j < 3; ++j) {
        const T si = local(ri, base_i, taus[j]), ss = local(rs, base_s, taus[j]);
        const T ci = std::sqrt(std::max(T(0), T(1) - si * si)), cs = std::sqrt(std::max(T(0), T(1) - ss * ss));
        const T h = std::clamp(invariant + si * ss, -ci * cs, ci * cs);
        const jackson_pr_pv<T> t = jackson_bistatic_local_terms(c, si, ss, h);
        sum.pr += weights[j] * t.pr;
        sum.pv += weights[j] * t.pv;
    }
    const T norm = std::sqrt(pi_v<T>);
    return {sum.pr / norm, sum.pv / norm};
}

/// Bistatic large-roughness term (see the file comment).
template <Real T> [[nodiscard]] inline T jackson_bistatic_sigma_lr(const jackson_coefficients<T>& c, const bistatic_geometry<T>& b) noexcept {
    const T gi = std::atan2(b.sin_i, b.cos_i), gs = std::atan2(b.sin_s, b.cos_s);
    const T ici = jackson_inverse_crit(gi, c.theta_c_rad), ics = jackson_inverse_crit(gs, c.theta_c_rad);
    const T lobe = std::pow(std::sin(pi_v<T> * ici) * std::sin(pi_v<T> * ics), T(0.5) * c.m_lr);
    const T psi = std::atan2(b.delta_t, b.delta_z);
    const T r2 = std::norm(rayleigh_reflection(c.sediment, std::asin(b.delta)));
    const T peak = T(0.0260) * r2 * std::sqrt(ici * ics) / (c.s2 * std::pow(T(1) + psi * psi / (T(2.6) * c.s2), T(1.9)));
    return c.sigma1_lr * lobe + peak;
}

/// Bistatic scattering cross section, term by term (see the file comment).
template <Real T>
[[nodiscard]] inline jackson_terms<T> jackson_bistatic_terms(const jackson_coefficients<T>& c, T graze_in_rad, T graze_out_rad,
                                                             T phi_rad) noexcept {
    const bistatic_geometry<T> b = make_bistatic_geometry(graze_in_rad, graze_out_rad, phi_rad);
    const jackson_pr_pv<T> avg = jackson_bistatic_slope_average(c, b);
    const T shadow = jackson_bistatic_shadowing(b, c.s);
    jackson_terms<T> t;
    t.kirchhoff = jackson_bistatic_sigma_kr(c, b);
    t.composite = shadow * avg.pr;
    t.volume = shadow * avg.pv;
    t.large_roughness = jackson_bistatic_sigma_lr(c, b);
    const T ratio = b.delta > T(0) ? b.delta_t / b.delta : T(1);
    t.roughness = jackson_roughness_blend(c, ratio, t.kirchhoff, t.composite, t.large_roughness);
    t.total = t.roughness + t.volume;
    return t;
}

/// Bistatic scattering cross section sigma (linear) from precomputed coefficients.
template <Real T>
[[nodiscard]] inline T jackson_bistatic(const jackson_coefficients<T>& c, T graze_in_rad, T graze_out_rad, T phi_rad) noexcept {
    return jackson_bistatic_terms(c, graze_in_rad, graze_out_rad, phi_rad).total;
}

/// Bistatic scattering cross section sigma (linear, dimensionless, per unit area per unit solid angle) of a
/// sediment, Williams & Jackson (1998) on TR 9407, evaluated in double. f_hz (Hz), c_water_mps (m/s),
/// grazing angles in [0, pi/2] (rad), phi_rad any angle (rad; pi = backscatter, where this equals
/// jackson_backscatter). Throws invalid_parameter for invalid sediment parameters, f_hz or c_water_mps,
/// or grazing angles outside [0, pi/2] ("graze_in_rad", "graze_out_rad") or a non-finite "phi_rad".
template <Real T>
[[nodiscard]] T jackson_bistatic(const sediment_params<T>& p, T f_hz, T c_water_mps, T graze_in_rad, T graze_out_rad, T phi_rad) {
    sss::require_in_range(graze_in_rad, T(0), half_pi_v<T>, "graze_in_rad");
    sss::require_in_range(graze_out_rad, T(0), half_pi_v<T>, "graze_out_rad");
    sss::require_finite(phi_rad, "phi_rad");
    const sediment_params<double> pd = to_double(p);
    const jackson_coefficients<double> c = make_jackson_coefficients(pd, double(f_hz), double(c_water_mps));
    return T(jackson_bistatic(c, double(graze_in_rad), double(graze_out_rad), double(phi_rad)));
}

} // namespace sss::scattering
