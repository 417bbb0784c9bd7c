#pragma once
/// \file
/// Geoacoustic and roughness parameters of a seafloor sediment as the APL-UW high-frequency model takes
/// them, the 15 sediment types of APL-UW TR 9407 (1994) Table 2, and the regressions on mean grain size
/// behind that table.
///
/// Source: APL-UW High-Frequency Ocean Environmental Acoustic Models Handbook, APL-UW TR 9407 (October
/// 1994), Section IV (seafloor), Table 2 and the grain-size regressions that generate it.

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/scattering/detail/sediment_name.hpp"

namespace sss::scattering {

/// The six inputs of the APL-UW model (TR 9407 Section IV). All ratios are sediment over water.
/// The defaults are TR 9407 Table 2 "medium sand" (Mz = 1.5 phi).
template <Real T> struct sediment_params {
    T rho = T(1.845);      ///< density ratio rho_sediment / rho_water (dimensionless)
    T nu = T(1.1782);      ///< sound-speed ratio c_sediment / c_water (dimensionless; < 1 for silt and clay)
    T delta = T(0.01624);  ///< loss parameter: complex wavenumber ratio kappa = (1 + i delta) / nu (dimensionless)
    T sigma2 = T(0.002);   ///< volume parameter: volume scattering coefficient over attenuation coefficient
                           ///< (dimensionless); 0 switches sediment volume scattering off
    T gamma = T(3.25);     ///< exponent of the roughness spectrum (dimensionless, 2 < gamma < 4)
    T w2_cm4 = T(0.004446);///< strength of the roughness spectrum W(K) = w2 / (h0 K)^gamma with h0 = 1 cm,
                           ///< K in rad/cm and W in cm^4, so w2 is in cm^4.
                           ///< SI: w2 [m^(4 - gamma)] = w2 [cm^4] * 10^(2 gamma - 8).
};

/// The same sediment in double precision (the model's coefficients are always computed in double).
template <Real T> [[nodiscard]] constexpr sediment_params<double> to_double(const sediment_params<T>& p) noexcept {
    return {double(p.rho), double(p.nu), double(p.delta), double(p.sigma2), double(p.gamma), double(p.w2_cm4)};
}

/// Throws invalid_parameter, named `who` + ".rho", ".nu", ..., unless the parameters lie in the domain the
/// model's formulas hold on: rho > 0, nu > 0, delta > 0 (the volume term divides by the sediment's
/// attenuation), sigma2 >= 0, 2.1 <= gamma <= 3.9 (0 < alpha = gamma/2 - 1 < 1 keeps the slope variance
/// and the Kirchhoff closed form finite; the ends are kept off for conditioning) and w2_cm4 > 0.
/// TR 9407 Table 2 spans 1.145 <= rho <= 2.5, 0.98 <= nu <= 2.5, 0.00148 <= delta <= 0.0216 with
/// gamma = 3.25; outside that the model extrapolates.
template <Real T> void validate(const sediment_params<T>& p, const std::string& who) {
    sss::require_positive(p.rho, who + ".rho");
    sss::require_positive(p.nu, who + ".nu");
    sss::require_positive(p.delta, who + ".delta");
    sss::require_non_negative(p.sigma2, who + ".sigma2");
    sss::require_in_range(p.gamma, T(2.1), T(3.9), who + ".gamma");
    sss::require_positive(p.w2_cm4, who + ".w2_cm4");
}

/// The sediment types of TR 9407 Table 2, coarsest first.
enum class sediment : unsigned char {
    rough_rock,       ///< rough rock
    rock,             ///< rock
    cobble,           ///< cobble / gravel
    sandy_gravel,     ///< sandy gravel, Mz = -1 phi
    very_coarse_sand, ///< very coarse sand, Mz = -0.5 phi
    coarse_sand,      ///< coarse sand, Mz = 0.5 phi
    medium_sand,      ///< medium sand, Mz = 1.5 phi
    fine_sand,        ///< fine / silty sand, Mz = 2.5 phi
    very_fine_sand,   ///< very fine sand, Mz = 3.5 phi
    coarse_silt,      ///< coarse silt, Mz = 4.5 phi
    sandy_silt,       ///< sandy silt, Mz = 5 phi
    sandy_mud,        ///< sandy mud / silt, Mz = 6 phi
    sandy_clay,       ///< sandy clay, Mz = 7 phi
    silty_clay,       ///< silty clay, Mz = 8 phi
    clay,             ///< clay, Mz = 9 phi
};

/// One row of TR 9407 Table 2 (gamma = 3.25 in every row).
struct sediment_table_row {
    sediment id;
    std::string_view name;  ///< canonical name, e.g. "medium_sand"
    std::string_view alias; ///< second accepted name ("" if none), e.g. "gravel" for cobble
    double mz_phi;          ///< mean grain size (phi); NaN for the rock and cobble rows
    double rho, nu, delta, sigma2, w2_cm4;
};

/// TR 9407 Table 2, as printed.
inline constexpr std::array<sediment_table_row, 15> sediment_table{{
    {sediment::rough_rock, "rough_rock", "", std::numeric_limits<double>::quiet_NaN(), 2.5, 2.5, 0.01374, 0.002, 0.20693},
    {sediment::rock, "rock", "", std::numeric_limits<double>::quiet_NaN(), 2.5, 2.5, 0.01374, 0.002, 0.01862},
    {sediment::cobble, "cobble", "gravel", std::numeric_limits<double>::quiet_NaN(), 2.5, 1.8, 0.01374, 0.002, 0.016},
    {sediment::sandy_gravel, "sandy_gravel", "", -1.0, 2.492, 1.337, 0.01705, 0.002, 0.012937},
    {sediment::very_coarse_sand, "very_coarse_sand", "", -0.5, 2.401, 1.3067, 0.01667, 0.002, 0.010573},
    {sediment::coarse_sand, "coarse_sand", "", 0.5, 2.231, 1.2503, 0.01638, 0.002, 0.006957},
    {sediment::medium_sand, "medium_sand", "", 1.5, 1.845, 1.1782, 0.01624, 0.002, 0.004446},
    {sediment::fine_sand, "fine_sand", "silty_sand", 2.5, 1.451, 1.1073, 0.01602, 0.002, 0.002715},
    {sediment::very_fine_sand, "very_fine_sand", "", 3.5, 1.268, 1.0568, 0.01875, 0.002, 0.001544},
    {sediment::coarse_silt, "coarse_silt", "", 4.5, 1.195, 1.0179, 0.02158, 0.002, 0.000781},
    {sediment::sandy_silt, "sandy_silt", "", 5.0, 1.169, 0.9999, 0.01261, 0.002, 0.000518},
    {sediment::sandy_mud, "sandy_mud", "silt", 6.0, 1.149, 0.9873, 0.00386, 0.001, 0.000518},
    {sediment::sandy_clay, "sandy_clay", "", 7.0, 1.147, 0.9849, 0.00242, 0.001, 0.000518},
    {sediment::silty_clay, "silty_clay", "", 8.0, 1.146, 0.9824, 0.00163, 0.001, 0.000518},
    {sediment::clay, "clay", "", 9.0, 1.145, 0.9800, 0.00148, 0.001, 0.000518},
}};

/// The parameters of a Table 2 sediment type.
template <Real T> [[nodiscard]] constexpr sediment_params<T> sediment_preset(sediment s) noexcept {
    const sediment_table_row& r = sediment_table[static_cast<std::size_t>(s)];
    return sediment_params<T>{T(r.rho), T(r.nu), T(r.delta), T(r.sigma2), T(3.25), T(r.w2_cm4)};
}

/// The canonical names of the Table 2 types, comma separated (for messages and help texts).
[[nodiscard]] inline std::string sediment_names() {
    std::string all;
    for (const sediment_table_row& r : sediment_table) {
        if (!all.empty()) all += ", ";
        all += r.name;
        if (!r.alias.empty()) all += " (or " + std::string(r.alias) + ")";
    }
    return all;
}

/// The Table 2 type with that name (canonical or alias; case, spaces and hyphens ignored).
/// Throws invalid_parameter (parameter "sediment") naming the unknown name and listing the valid ones.
[[nodiscard]] inline sediment sediment_from_name(std::string_view name) {
    const std::string key = sss::detail::normalise_sediment_name(name);
    for (const sediment_table_row& r : sediment_table)
        if (key == r.name || (!r.alias.empty() && key == r.alias)) return r.id;
    throw invalid_parameter("sediment", "unknown sediment '" + std::string(name) + "'; valid names: " + sediment_names());
}

/// The parameters of the Table 2 type with that name; see sediment_from_name.
template <Real T> [[nodiscard]] sediment_params<T> sediment_preset(std::string_view name) {
    return sediment_preset<T>(sediment_from_name(name));
}

/// Lowest and highest mean grain size (phi) the TR 9407 regressions cover.
inline constexpr double min_grain_size_phi = -1.0;
inline constexpr double max_grain_size_phi = 9.0;

/// Sediment parameters from mean grain size Mz (phi), by the TR 9407 regressions behind Table 2:
///
///   rho:  Mz < 1:   0.007797 Mz^2 - 0.17057 Mz + 2.3139
///         Mz < 5.3: -0.0165406 Mz^3 + 0.2290201 Mz^2 - 1.1069031 Mz + 3.0455
///         else:     -0.0012973 Mz + 1.1565
///   nu:   Mz < 1:   0.002709 Mz^2 - 0.056452 Mz + 1.2778
///         Mz < 5.3: -0.0014881 Mz^3 + 0.0213937 Mz^2 - 0.1382798 Mz + 1.3425
///         else:     -0.0024324 Mz + 1.0019
///   delta = k_p nu 1.528 ln(10) / (40 pi), with the attenuation slope k_p (dB / (m kHz)):
///         Mz < 0: 0.4556;  < 2.6: 0.4556 + 0.0245 Mz;  < 4.5: 0.1978 + 0.1245 Mz;
///         < 6: 8.0399 - 2.5228 Mz + 0.20098 Mz^2;  else: 0.9431 - 0.2041 Mz + 0.0117 Mz^2
///   w2 = 0.00207 h^2 (cm^4), h = (2.03846 - 0.26923 Mz) / (1 + 0.076923 Mz) for Mz < 5, else 0.5
///   sigma2 = 0.002 for Mz < 5.5, else 0.001;  gamma = 3.25.
///
/// The pieces join as published: nu, delta and sigma2 jump slightly at some joins (e.g. sigma2 halves at
/// 5.5 phi); nothing is smoothed. Mz must lie in [-1, 9] phi, the span of the sediments the regressions
/// were fitted to, ends included; outside it this throws invalid_parameter ("mz_phi") rather than
/// extrapolate (for coarser beds use the rock, cobble or sandy_gravel presets).
template <Real T> [[nodiscard]] sediment_params<T> sediment_from_grain_size(T mz_phi) {
    sss::require_in_range(mz_phi, T(min_grain_size_phi), T(max_grain_size_phi), "mz_phi");
    const double m = double(mz_phi);
    double rho = 0, nu = 0, kp = 0;
    if (m < 1.0) {
        rho = 0.007797 * m * m - 0.17057 * m + 2.3139;
        nu = 0.002709 * m * m - 0.056452 * m + 1.2778;
    } else if (m < 5.3) {
        rho = ((-0.0165406 * m + 0.2290201) * m - 1.1069031) * m + 3.0455;
        nu = ((-0.0014881 * m + 0.0213937) * m - 0.1382798) * m + 1.3425;
    } else {
        rho = -0.0012973 * m + 1.1565;
        nu = -0.0024324 * m + 1.0019;
    }
    if (m < 0.0) kp = 0.4556;
    else if (m < 2.6) kp = 0.4556 + 0.0245 * m;
    else if (m < 4.5) kp = 0.1978 + 0.1245 * m;
    else if (m < 6.0) kp = 8.0399 - 2.5228 * m + 0.20098 * m * m;
    else kp = 0.9431 - 0.2041 * m + 0.0117 * m * m;
    const double delta = kp * nu * 1.528 * ln10_v<double> / (40.0 * pi_v<double>);
    const double h = m < 5.0 ? (2.03846 - 0.26923 * m) / (1.0 + 0.076923 * m) : 0.5;
    const double w2 = 0.00207 * h * h;
    const double sigma2 = m < 5.5 ? 0.002 : 0.001;
    return sediment_params<T>{T(rho), T(nu), T(delta), T(sigma2), T(3.25), T(w2)};
}

} // namespace sss::scattering
