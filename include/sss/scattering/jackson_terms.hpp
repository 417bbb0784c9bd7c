#pragma once
/// \file
/// The APL-UW high-frequency seafloor backscattering model, term by term, as free functions.
///
/// Source: APL-UW High-Frequency Ocean Environmental Acoustic Models Handbook, APL-UW TR 9407 (1994),
/// Section IV (D. R. Jackson). theta is the grazing angle (rad), k = 2 pi f / c the water wavenumber in
/// rad/cm (the roughness spectrum is in cm units), and
///   S_b = 10 log10(sigma_r + sigma_v),   sigma: linear, dimensionless, per unit area per unit solid angle,
/// with sigma_r the interface-roughness term (Kirchhoff, composite roughness or large roughness, blended)
/// and sigma_v the sediment-volume term. The model was fitted for 10-100 kHz; above that it extrapolates.
///
/// Every function here works for T = float and double; `jackson_backscatter(params, ...)` evaluates in
/// double whatever T is. Angles outside [0, pi/2] are clamped into it.

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/scattering/concept.hpp"
#include "sss/scattering/reflection.hpp"
#include "sss/scattering/sediments.hpp"

namespace sss::scattering {

/// Roughness spectrum W(K) = w2 / (h0 K)^gamma, h0 = 1 cm (TR 9407 Section IV): w2_cm4 (cm^4),
/// K_radpcm (rad/cm). Returns cm^4.
template <Real T> [[nodiscard]] inline T jackson_spectrum_cm4(T w2_cm4, T gamma, T k_radpcm) noexcept {
    return w2_cm4 * std::pow(k_radpcm, -gamma);
}

/// Structure-function constant of the power-law surface, <[h(x + r) - h(x)]^2> = C_h^2 r^(2 alpha):
///   C_h^2 = 2 pi w2 Gamma(2 - alpha) 2^(-2 alpha) / [alpha (1 - alpha) Gamma(1 + alpha)],  alpha = gamma/2 - 1.
/// w2_cm4 (cm^4); returns cm^(2 - 2 alpha).
template <Real T> [[nodiscard]] inline T jackson_structure_constant(T w2_cm4, T gamma) noexcept {
    const T a = gamma / T(2) - T(1);
    return two_pi_v<T> * w2_cm4 * std::tgamma(T(2) - a) * std::pow(T(2), T(-2) * a) /
           (a * (T(1) - a) * std::tgamma(T(1) + a));
}

/// RMS slope squared of the roughness that the composite-roughness approximation treats as tilt:
///   s^2 = (2 pi w2)^(1/alpha) / (2 (1 - alpha)) * (k^2 / alpha)^((1 - alpha)/alpha)   (TR 9407).
/// w2_cm4 (cm^4), k_radpcm (rad/cm); dimensionless.
template <Real T> [[nodiscard]] inline T jackson_slope_variance(T w2_cm4, T gamma, T k_radpcm) noexcept {
    const T a = gamma / T(2) - T(1);
    return std::pow(two_pi_v<T> * w2_cm4, T(1) / a) / (T(2) * (T(1) - a)) *
           std::pow(k_radpcm * k_radpcm / a, (T(1) - a) / a);
}

/// Everything in the model that depends on the sediment and the frequency only, computed once.
template <Real T> struct jackson_coefficients {
    sediment_params<T> sediment{};
    T k_radpcm{};          ///< water wavenumber 2 pi f / c (rad/cm)
    std::complex<T> kappa{};///< (1 + i delta) / nu
    T alpha{};             ///< gamma/2 - 1
    T ch2{};               ///< C_h^2 (cm^(2 - 2 alpha))
    T q_c{};               ///< C_h^2 2^(1 - 2 alpha) k^(2 (1 - alpha)) (dimensionless)
    T a_kr{}, b_kr{};      ///< constants of the Kirchhoff approximation
    T r90_sq{};            ///< |R(90 deg)|^2
    T s2{}, s{};           ///< slope variance and RMS slope; theta_s = s (rad)
    T theta_c_rad{};       ///< critical angle acos(1/nu), 2.5613 deg when nu < 1.001
    T m_lr{};              ///< large-roughness exponent 0.7263 s^(-1/3)
    T sigma1_lr{};         ///< large-roughness diffuse level sigma1
    T cos_theta_kdb{};     ///< cosine of the Kirchhoff / composite-roughness crossover angle
};

/// The logistic switch of the model, f(x) = 1 / (1 + e^x), with x clamped to [-40, 40] (TR 9407).
template <Real T> [[nodiscard]] inline T jackson_logistic(T x) noexcept {
    return T(1) / (T(1) + std::exp(std::clamp(x, T(-40), T(40))));
}

/// Precomputes the model's constants for one sediment at one frequency (TR 9407 Section IV):
///   a = [8 alpha^2 Gamma(1/(2 alpha) + 1/2) / (Gamma(1/2) Gamma(1/alpha) Gamma(1/(2 alpha)))]^(2 alpha),
///   b = a^((1 + alpha)/(2 alpha)) Gamma(1/alpha) / (2 alpha),
///   theta_c = acos(1/nu) (2.5613 deg if nu < 1.001),  m = 0.7263 s^(-1/3),
///   sigma1 = 0.04682 s^1.25 nu^3.25 [(1 - 2/rho) nu^-2 + 1]^2 / (1 + 3.54 theta_s / theta_c),
///   c4 = 1000^(1/(1 + alpha)) (a q_c^2)^(1/alpha),  cos(theta_kdb) = (1/c4 + 4)^(-1/4).
/// f_hz (Hz) > 0, c_water_mps (m/s) > 0. Throws invalid_parameter naming `who`.f_hz, `who`.c_water_mps or
/// the sediment parameter (`who`.sediment.rho, ...).
template <Real T>
[[nodiscard]] jackson_coefficients<T> make_jackson_coefficients(const sediment_params<T>& p, T f_hz, T c_water_mps,
                                                                const std::string& who = "jackson") {
    validate(p, who + ".sediment");
    sss::require_positive(f_hz, who + ".f_hz");
    sss::require_positive(c_water_mps, who + ".c_water_mps");
    jackson_coefficients<T> c;
    c.sediment = p;
    c.k_radpcm = two_pi_v<T> * f_hz / (T(100) * c_water_mps);
    c.kappa = wavenumber_ratio(p.nu, p.delta);
    const T a = p.gamma / T(2) - T(1);
    c.alpha = a;
    c.ch2 = jackson_structure_constant(p.w2_cm4, p.gamma);
    c.q_c = c.ch2 * std::pow(T(2), T(1) - T(2) * a) * std::pow(c.k_radpcm, T(2) * (T(1) - a));
    const T ratio = T(8) * a * a * std::tgamma(T(1) / (T(2) * a) + T(0.5)) /
                    (std::tgamma(T(0.5)) * std::tgamma(T(1) / a) * std::tgamma(T(1) / (T(2) * a)));
    c.a_kr = std::pow(ratio, T(2) * a);
    c.b_kr = std::pow(c.a_kr, (T(1) + a) / (T(2) * a)) * std::tgamma(T(1) / a) / (T(2) * a);
    c.r90_sq = std::norm(rayleigh_reflection(p, half_pi_v<T>));
    c.s2 = jackson_slope_variance(p.w2_cm4, p.gamma, c.k_radpcm);
    c.s = std::sqrt(c.s2);
    c.theta_c_rad = p.nu >= T(1.001) ? std::acos(T(1) / p.nu) : deg_to_rad(T(2.5613));
    c.m_lr = T(0.7263) * std::pow(c.s, T(-1) / T(3));
    const T bracket = (T(1) - T(2) / p.rho) / (p.nu * p.nu) + T(1);
    c.sigma1_lr = T(0.04682) * std::pow(c.s, T(1.25)) * std::pow(p.nu, T(3.25)) * bracket * bracket /
                  (T(1) + T(3.54) * c.s / c.theta_c_rad);
    const T c4 = std::pow(T(1000), T(1) / (T(1) + a)) * std::pow(c.a_kr * c.q_c * c.q_c, T(1) / a);
    c.cos_theta_kdb = std::pow(T(1) / c4 + T(4), T(-0.25));
    return c;
}

/// Kirchhoff approximation, backscatter (TR 9407):
///   sigma_kr = b q_c |R(90 deg)|^2 / (8 pi [cos^(4 alpha) theta + a q_c^2 sin^4 theta]^((1 + alpha)/(2 alpha))).
template <Real T> [[nodiscard]] inline T jackson_sigma_kr(const jackson_coefficients<T>& c, T graze_rad) noexcept {
    const T g = clamp_graze(graze_rad);
    const T sn = std::sin(g), cs = std::cos(g);
    const T sn2 = sn * sn;
    const T den = std::pow(cs, T(4) * c.alpha) + c.a_kr * c.q_c * c.q_c * sn2 * sn2;
    return c.b_kr * c.q_c * c.r90_sq / (T(8) * pi_v<T> * std::pow(den, (T(1) + c.alpha) / (T(2) * c.alpha)));
}

/// The perturbation and volume terms at one geometry, before shadowing and slope averaging.
template <Real T> struct jackson_pr_pv {
    T pr; ///< sigma_pr
    T pv; ///< sigma_pv
};

/// sigma_pr and sigma_pv at one grazing angle in [0, pi/2] (rad), sharing P and R (formulas below).
template <Real T> [[nodiscard]] inline jackson_pr_pv<T> jackson_perturbation_and_volume(const jackson_coefficients<T>& c, T g) noexcept {
    const T sn = std::sin(g), cs = std::cos(g);
    const sediment_params<T>& p = c.sediment;
    const std::complex<T> pp = vertical_wavenumber_ratio(c.kappa, g);
    const T rs = p.rho * sn;
    const std::complex<T> den = rs + pp;
    const std::complex<T> y = ((p.rho - T(1)) * (p.rho - T(1)) * cs * cs + p.rho * p.rho - c.kappa * c.kappa) / (den * den);
    const T k = c.k_radpcm;
    const T big_k = std::sqrt(T(4) * k * k * cs * cs + T(0.01) * k * k);
    const T k2s2 = k * k * sn * sn;
    const T pr = T(4) * k2s2 * k2s2 * std::norm(y) * jackson_spectrum_cm4(p.w2_cm4, p.gamma, big_k);
    const T t = std::norm(T(2) * rs / den); // |1 + R|^2
    const T pv = p.sigma2 > T(0) ? T(5) * p.delta * p.sigma2 * t * t / (p.nu * ln10_v<T> * p.rho * p.rho * pp.imag()) : T(0);
    return {pr, pv};
}

/// First-order perturbation (Bragg) term, backscatter (TR 9407):
///   sigma_pr = 4 k^4 sin^4 theta |Y|^2 W(K),  Y = [(rho - 1)^2 cos^2 theta + rho^2 - kappa^2] / (rho sin theta + P)^2,
///   K = sqrt(4 k^2 cos^2 theta + (k/10)^2) (rad/cm; the k/10 term keeps W finite at normal incidence).
template <Real T> [[nodiscard]] inline T jackson_sigma_pr(const jackson_coefficients<T>& c, T graze_rad) noexcept {
    return jackson_perturbation_and_volume(c, clamp_graze(graze_rad)).pr;
}

/// Sediment volume scattering before shadowing and slope averaging (TR 9407):
///   sigma_pv = 5 delta sigma2 |1 - R^2|^2 sin^2 theta / (nu ln10 |P|^2 Im P)
///            = 5 delta sigma2 |1 + R|^4 / (nu ln10 rho^2 Im P)
/// (the two are identical since 1 - R = (1 + R) P / (rho sin theta); the second has no 0/0 at theta = 0).
template <Real T> [[nodiscard]] inline T jackson_sigma_pv(const jackson_coefficients<T>& c, T graze_rad) noexcept {
    return jackson_perturbation_and_volume(c, clamp_graze(graze_rad)).pv;
}

/// The shadowing exponent Q of TR 9407 for t = tan(theta) / s:
///   Q = [e^(-t^2) / sqrt(pi) - t erfc(t)] / (4 t);  Q = 0 for t > 2 (no shadowing), +inf for t <= 0.
template <Real T> [[nodiscard]] inline T jackson_shadowing_q(T t) noexcept {
    if (!(t > T(0))) return std::numeric_limits<T>::infinity();
    if (t > T(2)) return T(0);
    return (std::exp(-t * t) / std::sqrt(pi_v<T>) - t * std::erfc(t)) / (T(4) * t);
}

/// Shadowing factor from Q: S = (1 - e^(-2Q)) / (2Q); 1 at Q = 0, 0 at Q = inf.
template <Real T> [[nodiscard]] inline T jackson_shadowing_from_q(T q) noexcept {
    if (q <= T(0)) return T(1);
    if (!std::isfinite(q)) return T(0);
    return -std::expm1(T(-2) * q) / (T(2) * q);
}

/// Shadowing (Wagner-type) of the composite-roughness and volume terms, backscatter (TR 9407):
///   S(theta) = (1 - e^(-2Q)) / (2Q),  Q from t = tan(theta) / s;  S = 1 for t > 2, S(0) = 0.
/// s: RMS slope (dimensionless).
template <Real T> [[nodiscard]] inline T jackson_shadowing(T graze_rad, T s) noexcept {
    const T g = clamp_graze(graze_rad);
    return jackson_shadowing_from_q(jackson_shadowing_q(std::tan(g) / s));
}

/// 3-point Gauss-Hermite nodes and weights (weight e^(-x^2)); TR 9407 prints them to 6 digits:
/// nodes -1.224745, 0, 1.224745; weights 0.295410, 1.181636, 0.295410 (they sum to sqrt(pi)).
template <Real T> inline constexpr T gauss_hermite3_node = T(1.2247448713915890491);
template <Real T> inline constexpr T gauss_hermite3_weight_outer = T(0.29540897515091934);
template <Real T> inline constexpr T gauss_hermite3_weight_centre = T(1.1816359006036774);

/// Average of sigma(theta) over the large-scale slopes in the plane of incidence (TR 9407):
///   avg sigma(theta) = (1/sqrt(pi)) sum_j w_j sigma(theta - x_j theta_s),  angles clipped to [0, pi/2],
/// with the 3-point Gauss-Hermite rule (x_j, w_j) and theta_s = s (rad; "s in degrees" in the report,
/// which works in degrees). `sigma` is any callable T -> T of the grazing angle (rad).
template <Real T, class F> [[nodiscard]] inline T gauss_hermite_slope_average(F&& sigma, T graze_rad, T theta_s_rad) {
    const T d = gauss_hermite3_node<T> * theta_s_rad;
    const auto at = [&](T g) { return sigma(std::clamp(g, T(0), half_pi_v<T>)); };
    return (gauss_hermite3_weight_outer<T> * at(graze_rad + d) + gauss_hermite3_weight_centre<T> * at(graze_rad) +
            gauss_hermite3_weight_outer<T> * at(graze_rad - d)) /
           std::sqrt(pi_v<T>);
}

/// 1 / crit = theta^2 / (theta^2 + 0.81 theta_c^2), the large-roughness critical-angle factor (in [0, 1)).
template <Real T> [[nodiscard]] inline T jackson_inverse_crit(T graze_rad, T theta_c_rad) noexcept {
    const T g2 = graze_rad * graze_rad;
    return g2 / (g2 + T(0.81) * theta_c_rad * theta_c_rad);
}

/// Large-roughness term, an empirical fit for very rough beds (TR 9407):
///   sigma_lr = sigma1 sin^m(180 deg / crit) + 0.0260 |R(90)|^2 / [s^2 (1 + (theta - 90)^2 / (2.6 theta_s^2))^1.9 crit],
///   crit = 1 + 0.81 theta_c^2 / theta^2   (angles in any one unit; sigma_lr(0) = 0).
template <Real T> [[nodiscard]] inline T jackson_sigma_lr(const jackson_coefficients<T>& c, T graze_rad) noexcept {
    const T g = clamp_graze(graze_rad);
    const T ic = jackson_inverse_crit(g, c.theta_c_rad);
    const T lobe = std::pow(std::sin(pi_v<T> * ic), c.m_lr);
    const T dg = g - half_pi_v<T>;
    const T peak = T(0.0260) * c.r90_sq * ic / (c.s2 * std::pow(T(1) + dg * dg / (T(2.6) * c.s2), T(1.9)));
    return c.sigma1_lr * lobe + peak;
}

/// Weight w of the moderate-roughness branch (Kirchhoff and composite roughness) against the large-roughness
/// fit (TR 9407): w = f((atan(s) [deg] - 7) / 0.5), f(x) = 1 / (1 + e^x); s the RMS slope (dimensionless).
template <Real T> [[nodiscard]] inline T jackson_moderate_weight(T s) noexcept {
    return jackson_logistic((rad_to_deg(std::atan(s)) - T(7)) / T(0.5));
}

/// The roughness blend of TR 9407, shared by backscatter and bistatic scattering:
///   sigma_mr = f_k sigma_kr + (1 - f_k) sigma_cr,   f_k = f((cos_theta - cos theta_kdb) / 0.0125),
///   sigma_r  = w sigma_mr + (1 - w) sigma_lr,        w = f((atan(s) [deg] - 7) / 0.5),
/// with f(x) = 1 / (1 + e^x) and 1 - f(x) = f(-x). cos_theta: cos of the grazing angle at backscatter, of the
/// half-angle between the incident and scattered directions (delta_t / delta) in the bistatic case.
template <Real T>
[[nodiscard]] inline T jackson_roughness_blend(const jackson_coefficients<T>& c, T cos_theta, T sigma_kr, T sigma_cr,
                                               T sigma_lr) noexcept {
    const T x = (cos_theta - c.cos_theta_kdb) / T(0.0125);
    const T moderate = jackson_logistic(x) * sigma_kr + jackson_logistic(-x) * sigma_cr;
    const T xw = (rad_to_deg(std::atan(c.s)) - T(7)) / T(0.5);
    return jackson_logistic(xw) * moderate + jackson_logistic(-xw) * sigma_lr;
}

/// Each term of the backscattering cross section at one angle (linear, dimensionless).
template <Real T> struct jackson_terms {
    T kirchhoff{};       ///< sigma_kr
    T composite{};       ///< sigma_cr = S avg(sigma_pr), avg the slope average below
    T large_roughness{}; ///< sigma_lr
    T roughness{};       ///< sigma_r, the blend of the three above
    T volume{};          ///< sigma_v = S avg(sigma_pv)
    T total{};           ///< sigma_r + sigma_v
};

/// The whole model, term by term (TR 9407):
///   sigma = sigma_r + sigma_v,  sigma_r the roughness blend of sigma_kr, sigma_cr and sigma_lr
///   (jackson_roughness_blend).
template <Real T> [[nodiscard]] inline jackson_terms<T> jackson_backscatter_terms(const jackson_coefficients<T>& c, T graze_rad) noexcept {
    const T g = clamp_graze(graze_rad);
    // Perturbation and volume terms share P and R at each of the three slope-averaging angles.
    T pr_sum = T(0), pv_sum = T(0);
    const T d = gauss_hermite3_node<T> * c.s;
    const T angles[3] = {g + d, g, g - d};
    const T weights[3] = {gauss_hermite3_weight_outer<T>, gauss_hermite3_weight_centre<T>, gauss_hermite3_weight_outer<T>};
    for (int j = 0; j < 3; ++j) {
        const jackson_pr_pv<T> local = jackson_perturbation_and_volume(c, std::clamp(angles[j], T(0), half_pi_v<T>));
        pr_sum += weights[j] * local.pr;
        pv_sum += weights[j] * local.pv;
    }
    const T shadow = jackson_shadowing(g, c.s) / std::sqrt(pi_v<T>);
    jackson_terms<T> t;
    t.kirchhoff = jackson_sigma_kr(c, g);
    t.composite = shadow * pr_sum;
    t.volume = shadow * pv_sum;
    t.large_roughness = jackson_sigma_lr(c, g);
    t.roughness = jackson_roughness_blend(c, std::cos(g), t.kirchhoff, t.composite, t.large_roughness);
    t.total = t.roughness + t.volume;
    return t;
}

/// Backscattering cross section sigma (linear; S_b = 10 log10 sigma) from precomputed coefficients.
template <Real T> [[nodiscard]] inline T jackson_backscatter(const jackson_coefficients<T>& c, T graze_rad) noexcept {
    return jackson_backscatter_terms(c, graze_rad).total;
}

/// Backscattering cross section sigma (linear, dimensionless; S_b = 10 log10 sigma) of a sediment by the
/// APL-UW model (TR 9407 Section IV), evaluated in double. f_hz (Hz), c_water_mps (m/s) and graze_rad in
/// [0, pi/2] (rad). Throws invalid_parameter for invalid sediment parameters, f_hz or c_water_mps
/// ("jackson.sediment.rho", "jackson.f_hz", ...) or a grazing angle outside [0, pi/2] ("graze_rad").
template <Real T>
[[nodiscard]] T jackson_backscatter(const sediment_params<T>& p, T f_hz, T c_water_mps, T graze_rad) {
    sss::require_in_range(graze_rad, T(0), half_pi_v<T>, "graze_rad");
    const sediment_params<double> pd = to_double(p);
    const jackson_coefficients<double> c = make_jackson_coefficients(pd, double(f_hz), double(c_water_mps));
    return T(jackson_backscatter(c, double(graze_rad)));
}

} // namespace sss::scattering
