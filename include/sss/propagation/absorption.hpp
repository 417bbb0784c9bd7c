#pragma once
/// \file
/// Absorption of sound in sea water (dB/km), and its integral along a ray path.
///
/// Francois, R. E. & Garrison, G. R. (1982), "Sound absorption based on ocean measurements.
/// Part I: Pure water and magnesium sulfate contributions", J. Acoust. Soc. Am. 72(3), 896-907, and
/// "Part II: Boric acid contribution and equation for total absorption", JASA 72(6), 1879-1890.
/// With f in kHz, T in degC, S in ppt, D in m:
///
///     alpha = A1 P1 f1 f^2/(f1^2 + f^2) + A2 P2 f2 f^2/(f2^2 + f^2) + A3 P3 f^2     (dB/km)
///     c  = 1412 + 3.21 T + 1.19 S + 0.0167 D                       (m/s, the paper's own speed)
///     A1 = (8.86/c) 10^(0.78 pH - 5),   P1 = 1,   f1 = 2.8 sqrt(S/35) 10^(4 - 1245/(273 + T))
///     A2 = 21.44 (S/c)(1 + 0.025 T),    P2 = 1 - 1.37e-4 D + 6.2e-9 D^2
///     f2 = 8.17 10^(8 - 1990/(273 + T)) / (1 + 0.0018 (S - 35))
///     A3 = 4.937e-4 - 2.59e-5 T + 9.11e-7 T^2 - 1.50e-8 T^3        (T <= 20 degC)
///     A3 = 3.964e-4 - 1.146e-5 T + 1.45e-7 T^2 - 6.5e-10 T^3       (T > 20 degC)
///     P3 = 1 - 3.83e-5 D + 4.9e-10 D^2
///
/// (The first A3 coefficient is 4.937e-4; a widely copied program comment misprints it 4.397e-4.)
/// The three terms are the boric acid, magnesium sulphate and pure water (viscous) contributions; f1
/// and f2 are the boric acid and MgSO4 relaxation frequencies. Francois and Garrison estimate about 5%
/// accuracy. Validity, for frequencies up to 1 MHz: where MgSO4 dominates (about 10-500 kHz)
/// -2 < T < 22 degC, 30 < S < 35 ppt, 0 < D < 3500 m; above 500 kHz (pure water dominating)
/// 0 < T < 30 degC, 0 < S < 40 ppt, 0 < D < 10 km. Outside, the formula is evaluated unchanged
/// (an extrapolation); nothing is checked.
///
/// Ainslie, M. A. & McColm, J. G. (1998), "A simplified formula for viscous and chemical absorption in
/// sea water", J. Acoust. Soc. Am. 103(3), 1671-1672, with f in kHz and depth z in KILOMETRES:
///
///     alpha = 0.106 f1 f^2/(f1^2 + f^2) e^((pH - 8)/0.56)
///           + 0.52 (1 + T/43)(S/35) f2 f^2/(f2^2 + f^2) e^(-z/6)
///           + 0.00049 f^2 e^(-(T/27 + z/17))                                   (dB/km)
///     f1 = 0.78 sqrt(S/35) e^(T/26),   f2 = 42 e^(T/17)                         (kHz)
///
/// It stays within 10% of Francois-Garrison from 100 Hz to 1 MHz for -6 < T < 35 degC, 7.7 < pH < 8.3,
/// 5 < S < 50 ppt and 0 < z < 7 km (each range with the other parameters at T 10 degC, S 35 ppt,
/// pH 8, z 0). Its parameters here are SI like the rest of sss (f in Hz, depth in m); the conversion
/// to kHz and km happens inside.
///
/// Both formulas take temperature and salinity as single representative values for the water column:
/// only the pressure (depth) dependence is modelled along a path.

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"

namespace sss::propagation {

/// Bulk properties of the water that absorption depends on. Plain data.
template <Real T> struct water_properties {
    T temperature_c{10}; ///< degC
    T salinity_ppt{35};  ///< ppt (practical salinity)
    T ph{8};             ///< dimensionless
};

/// Throws sss::invalid_parameter (naming the field) unless every field is finite and physically possible
/// for sea water: temperature in [-3, 40] degC, salinity in [0, 50] ppt, pH in [6, 10]. These bounds are
/// wider than the formulas' validity ranges (see the file comment), which are not enforced.
template <Real T> inline void check_water_properties(const water_properties<T>& w) {
    sss::require_in_range(w.temperature_c, T(-3), T(40), "water.temperature_c");
    sss::require_in_range(w.salinity_ppt, T(0), T(50), "water.salinity_ppt");
    sss::require_in_range(w.ph, T(6), T(10), "water.ph");
}

// ------------------------------------------------------------------------------------------------
// Francois & Garrison (1982)

/// Boric acid relaxation frequency f1 = 2.8 sqrt(S/35) 10^(4 - 1245/(273 + T)) kHz, returned in Hz.
template <Real T>
[[nodiscard]] inline T francois_garrison_boric_acid_relaxation_hz(T temperature_c, T salinity_ppt) noexcept {
    return T(2.8e3) * std::sqrt(salinity_ppt / T(35)) *
           std::pow(T(10), T(4) - T(1245) / (T(273) + temperature_c));
}

/// MgSO4 relaxation frequency f2 = 8.17 10^(8 - 1990/(273 + T)) / (1 + 0.0018 (S - 35)) kHz, in Hz.
template <Real T>
[[nodiscard]] inline T francois_garrison_magnesium_sulphate_relaxation_hz(T temperature_c, T salinity_ppt) noexcept {
    return T(8.17e3) * std::pow(T(10), T(8) - T(1990) / (T(273) + temperature_c)) /
           (T(1) + T(0.0018) * (salinity_ppt - T(35)));
}

/// Pure water coefficient A3 (dB/km/kHz^2), with the published switch at 20 degC.
template <Real T> [[nodiscard]] constexpr T francois_garrison_a3(T temperature_c) noexcept {
    const T t = temperature_c;
    if (t <= T(20)) return T(4.937e-4) + t * (T(-2.59e-5) + t * (T(9.11e-7) + t * T(-1.50e-8)));
    return T(3.964e-4) + t * (T(-1.146e-5) + t * (T(1.45e-7) + t * T(-6.5e-10)));
}

/// The three contributions to Francois-Garrison absorption and the two relaxation frequencies.
template <Real T> struct francois_garrison_terms {
    T boric_acid_db_per_km{};
    T magnesium_sulphate_db_per_km{};
    T pure_water_db_per_km{};
    T boric_acid_relaxation_hz{};
    T magnesium_sulphate_relaxation_hz{};

    [[nodiscard]] constexpr T total_db_per_km() const noexcept {
        return boric_acid_db_per_km + magnesium_sulphate_db_per_km + pure_water_db_per_km;
    }
};

/// Francois-Garrison term by term at frequency f_hz (Hz), temperature_c (degC), salinity_ppt (ppt),
/// depth_m (m) and ph.
template <Real T>
[[nodiscard]] inline francois_garrison_terms<T> francois_garrison_contributions(T f_hz, T temperature_c,
                                                                                 T salinity_ppt, T depth_m,
                                                                                 T ph) noexcept {
    const T f = f_hz / T(1000); // kHz
    const T f_sq = f * f;
    const T d = depth_m;
    const T c = T(1412) + T(3.21) * temperature_c + T(1.19) * salinity_ppt + T(0.0167) * d;
    const T f1_hz = francois_garrison_boric_acid_relaxation_hz(temperature_c, salinity_ppt);
    const T f2_hz = francois_garrison_magnesium_sulphate_relaxation_hz(temperature_c, salinity_ppt);
    const T f1 = f1_hz / T(1000);
    const T f2 = f2_hz / T(1000);
    const T a1 = T(8.86) / c * std::pow(T(10), T(0.78) * ph - T(5));
    const T a2 = T(21.44) * salinity_ppt / c * (T(1) + T(0.025) * temperature_c);
    const T p2 = T(1) + d * (T(-1.37e-4) + d * T(6.2e-9));
    const T p3 = T(1) + d * (T(-3.83e-5) + d * T(4.9e-10));
    return {a1 * f1 * f_sq / (f1 * f1 + f_sq), a2 * p2 * f2 * f_sq / (f2 * f2 + f_sq),
            francois_garrison_a3(temperature_c) * p3 * f_sq, f1_hz, f2_hz};
}

/// Francois-Garrison absorption (dB/km); see the file comment for formula, units and validity.
template <Real T>
[[nodiscard]] inline T francois_garrison_db_per_km(T f_hz, T temperature_c, T salinity_ppt, T depth_m, T ph) noexcept {
    return francois_garrison_contributions(f_hz, temperature_c, salinity_ppt, depth_m, ph).total_db_per_km();
}

/// (f_hz / 1000)^2, the squared frequency in kHz^2 that the absorption formulas take, once f_hz (> 0) and the
/// water (check_water_properties) are checked; throws sss::invalid_parameter otherwise.
template <Real T> [[nodiscard]] inline T checked_khz_squared(T f_hz, const water_properties<T>& water) {
    sss::require_positive(f_hz, "f_hz");
    check_water_properties(water);
    const T f = f_hz / T(1000);
    return f * f;
}

/// Francois-Garrison absorption for one frequency and water mass, as a function of depth only. Every
/// transcendental is evaluated once at construction; db_per_km(depth) then costs a few flops:
/// alpha(D) = (b + m P2(D))/c(D) + w P3(D), with c(D) = c_s + 0.0167 D.
template <Real T> class francois_garrison {
public:
    using value_type = T;

    /// Throws sss::invalid_parameter for f_hz not finite and > 0, or water outside check_water_properties.
    francois_garrison(T f_hz, const water_properties<T>& water) : f_hz_(f_hz) {
        const T f_sq = checked_khz_squared(f_hz, water);
        const T t = water.temperature_c;
        const T s = water.salinity_ppt;
        const T f1 = francois_garrison_boric_acid_relaxation_hz(t, s) / T(1000);
        const T f2 = francois_garrison_magnesium_sulphate_relaxation_hz(t, s) / T(1000);
        boric_ = T(8.86) * std::pow(T(10), T(0.78) * water.ph - T(5)) * f1 * f_sq / (f1 * f1 + f_sq);
        mgso4_ = T(21.44) * s * (T(1) + T(0.025) * t) * f2 * f_sq / (f2 * f2 + f_sq);
        water_ = francois_garrison_a3(t) * f_sq;
        c_surface_ = T(1412) + T(3.21) * t + T(1.19) * s;
    }

    [[nodiscard]] T frequency_hz() const noexcept { return f_hz_; }

    /// Absorption at depth_m (m), dB/km.
    [[nodiscard]] T db_per_km(T depth_m) const noexcept {
        const T d = depth_m;
        const T c = c_surface_ + T(0.0167) * d;
        const T p2 = T(1) + d * (T(-1.37e-4) + d * T(6.2e-9));
        const T p3 = T(1) + d * (T(-3.83e-5) + d * T(4.9e-10));
        return (boric_ + mgso4_ * p2) / c + water_ * p3;
    }

private:
    T f_hz_;
    T boric_{}, mgso4_{}, water_{}, c_surface_{};
};

// ------------------------------------------------------------------------------------------------
// Ainslie & McColm (1998)

/// Ainslie-McColm absorption (dB/km) at f_hz (Hz), temperature_c (degC), salinity_ppt (ppt),
/// depth_m (m; converted to km inside, as the formula wants) and ph.
template <Real T>
[[nodiscard]] inline T ainslie_mccolm_db_per_km(T f_hz, T temperature_c, T salinity_ppt, T depth_m, T ph) noexcept {
    const T f = f_hz / T(1000);     // kHz
    const T z_km = depth_m / T(1000); // km
    const T f_sq = f * f;
    const T t = temperature_c;
    const T f1 = T(0.78) * std::sqrt(salinity_ppt / T(35)) * std::exp(t / T(26));
    const T f2 = T(42) * std::exp(t / T(17));
    const T boric = T(0.106) * f1 * f_sq / (f1 * f1 + f_sq) * std::exp((ph - T(8)) / T(0.56));
    const T mgso4 = T(0.52) * (T(1) + t / T(43)) * (salinity_ppt / T(35)) * f2 * f_sq / (f2 * f2 + f_sq) *
                    std::exp(-z_km / T(6));
    const T water = T(0.00049) * f_sq * std::exp(-(t / T(27) + z_km / T(17)));
    return boric + mgso4 + water;
}

/// Ainslie-McColm absorption for one frequency and water mass as a function of depth (m) only.
template <Real T> class ainslie_mccolm {
public:
    using value_type = T;

    /// Throws sss::invalid_parameter for f_hz not finite and > 0, or water outside check_water_properties.
    ainslie_mccolm(T f_hz, const water_properties<T>& water) : f_hz_(f_hz) {
        const T f_sq = checked_khz_squared(f_hz, water);
        const T t = water.temperature_c;
        const T s = water.salinity_ppt;
        const T f1 = T(0.78) * std::sqrt(s / T(35)) * std::exp(t / T(26));
        const T f2 = T(42) * std::exp(t / T(17));
        boric_ = T(0.106) * f1 * f_sq / (f1 * f1 + f_sq) * std::exp((water.ph - T(8)) / T(0.56));
        mgso4_ = T(0.52) * (T(1) + t / T(43)) * (s / T(35)) * f2 * f_sq / (f2 * f2 + f_sq);
        water_ = T(0.00049) * f_sq * std::exp(-t / T(27));
    }

    [[nodiscard]] T frequency_hz() const noexcept { return f_hz_; }

    /// Absorption at depth_m (m), dB/km.
    [[nodiscard]] T db_per_km(T depth_m) const noexcept {
        const T z_km = depth_m / T(1000);
        return boric_ + mgso4_ * std::exp(-z_km / T(6)) + water_ * std::exp(-z_km / T(17));
    }

private:
    T f_hz_;
    T boric_{}, mgso4_{}, water_{};
};

// ------------------------------------------------------------------------------------------------
// Integration along a path

/// Mean of f over [a, b] by 5-point Gauss-Legendre quadrature (exact for polynomials of degree 9);
/// f(a) when a == b.
template <Real T, class F> [[nodiscard]] inline T gauss_legendre_mean(F&& f, T a, T b) {
    static constexpr std::array<double, 3> node{0.0, 0.5384693101056830910363144, 0.9061798459386639927976269};
    static constexpr std::array<double, 3> weight{0.5688888888888888888888889, 0.4786286704993664680412915,
                                                  0.2369268850561890875142640};
    if (a == b) return f(a);
    const T mid = (a + b) / T(2);
    const T half = (b - a) / T(2);
    T sum = T(weight[0]) * f(mid);
    for (std::size_t i = 1; i < 3; ++i) {
        const T h = half * T(node[i]);
        sum += T(weight[i]) * (f(mid - h) + f(mid + h));
    }
    return sum / T(2);
}

/// Mean absorption (dB/km) of `model` (anything with db_per_km(depth_m)) over the depths z0_m..z1_m:
/// (1/(z1 - z0)) integral alpha(z) dz. Both models are smooth in depth; over 0-6000 m in one piece the
/// quadrature error is below 1e-12 relative (3.5e-13 measured, tests/propagation/test_absorption.cpp).
template <class Model, Real T> [[nodiscard]] inline T depth_mean_db_per_km(const Model& model, T z0_m, T z1_m) {
    return gauss_legendre_mean([&](T z) { return model.db_per_km(z); }, z0_m, z1_m);
}

/// Absorption loss (dB, one way) along a straight path of length length_m from depth z0_m to z1_m.
/// Depth is linear in path length on a straight line, so this is length x depth mean, exact to the
/// quadrature error. A two-way (out and back) loss is twice this: absorption does not depend on the
/// direction of travel.
template <class Model, Real T>
[[nodiscard]] inline T straight_path_absorption_db(const Model& model, T z0_m, T z1_m, T length_m) {
    return depth_mean_db_per_km(model, z0_m, z1_m) * length_m / T(1000);
}

/// Absorption loss (dB, one way) along any path of length length_m whose depth at path length s is
/// depth_at(s) (for a ray arc: [&](T s) { return arc_point(arc, s).depth_m; }). 5-point Gauss-Legendre
/// in path length: for a circular arc inside one sound-speed layer the error is below 1e-12 relative.
template <class Model, Real T, class DepthAt>
[[nodiscard]] inline T path_absorption_db(const Model& model, T length_m, DepthAt&& depth_at) {
    return gauss_legendre_mean([&](T s) { return model.db_per_km(depth_at(s)); }, T(0), length_m) * length_m /
           T(1000);
}

} // namespace sss::propagation
