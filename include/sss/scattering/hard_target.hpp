#pragma once
/// \file
/// Scattering from hard man-made surfaces (mine casings, pipes, wrecks): a diffuse-plus-specular facet model.
///
/// sigma = sigma_diffuse + sigma_specular, both per unit area per unit solid angle (linear):
/// - diffuse: Lambert's law mu sin(g_i) sin(g_s) (Mackenzie, J. Acoust. Soc. Am. 33, 1961), for paint, fouling
///   and small features;
/// - specular: the Kirchhoff (geometric optics) cross section of a surface whose facet slopes are Gaussian with
///   RMS slope s (Beckmann & Spizzichino, "The Scattering of Electromagnetic Waves from Rough Surfaces", 1963;
///   in the form used for the seafloor by Jackson, Winebrenner & Ishimaru, J. Acoust. Soc. Am. 79(5), 1986):
///       sigma_s = |R|^2 |q|^4 / (4 q_z^4) exp(-|q_perp|^2 / (2 s^2 q_z^2)) / (2 pi s^2),
///   q = k_s - k_i (unit propagation directions of the scattered and incident sound, z the surface normal). In
///   backscatter this is |R|^2 exp(-tan^2 psi / (2 s^2)) / (8 pi s^2 cos^4 psi), psi = pi/2 - graze the angle
///   from the normal: the bright highlight of real records where a casing faces the sonar, falling off within
///   about s of normal incidence.
/// R is the normal-incidence amplitude reflection coefficient: (Z2 - Z1)/(Z2 + Z1), 0.94 for steel in water
/// (Z = 46 against 1.5 MRayl; Urick, "Principles of Underwater Sound", 3rd ed., 1983, ch. 9).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/decibel.hpp"
#include "sss/core/error.hpp"
#include "sss/scattering/concept.hpp"
#include "sss/scattering/lambertian.hpp"

namespace sss::scattering {

template <Real T> struct hard_target_params {
    T reflection = T(0.94);   ///< normal-incidence amplitude reflection coefficient |R|, in [0, 1]
    T rms_slope = T(0.1);     ///< RMS facet slope s (rad-like, tan of the tilt), > 0
    T diffuse_db = T(-20);    ///< Lambert parameter 10 log10(mu) of the diffuse part (dB), <= -4.9715 (mu <= 1/pi)
};

/// The specular (Kirchhoff geometric-optics) cross section for grazing angles g_i, g_s (rad) and azimuth phi
/// (rad; pi: backscatter, 0: forward), amplitude reflection r and RMS slope s (see the file comment).
[[nodiscard]] inline double kirchhoff_specular_sigma(double graze_in_rad, double graze_out_rad, double phi_rad, double r,
                                                     double rms_slope) noexcept {
    // Incident propagation (cos g_i, 0, -sin g_i); scattered (cos g_s cos phi, cos g_s sin phi, sin g_s).
    const double qx = std::cos(graze_out_rad) * std::cos(phi_rad) - std::cos(graze_in_rad);
    const double qy = std::cos(graze_out_rad) * std::sin(phi_rad);
    const double qz = std::sin(graze_out_rad) + std::sin(graze_in_rad);
    if (!(qz > 1e-9)) return 0.0;
    const double q2 = qx * qx + qy * qy + qz * qz, qz2 = qz * qz, s2 = rms_slope * rms_slope;
    return r * r * q2 * q2 / (4.0 * qz2 * qz2) * std::exp(-(qx * qx + qy * qy) / (2.0 * s2 * qz2)) / (two_pi_v<double> * s2);
}

template <Real T> class hard_target {
public:
    using value_type = T;

    /// Steel-like defaults (non-explicit, so `{}` builds one).
    hard_target() : hard_target(std::vector<hard_target_params<T>>{hard_target_params<T>{}}) {}

    /// One surface per material id; ids beyond the list use the last one.
    explicit hard_target(const std::vector<hard_target_params<T>>& materials) : materials_(materials) {
        sss::require(!materials_.empty(), "hard_target.materials", "needs at least one material");
        for (std::size_t i = 0; i < materials_.size(); ++i) {
            const std::string who = "hard_target.materials[" + std::to_string(i) + "]";
            sss::require_in_range(materials_[i].reflection, T(0), T(1), who + ".reflection");
            sss::require_positive(materials_[i].rms_slope, who + ".rms_slope");
            sss::require_finite(materials_[i].diffuse_db, who + ".diffuse_db");
            sss::require(materials_[i].diffuse_db <= T(lambert_max_db), who + ".diffuse_db",
                         "must be <= -4.9715 dB (mu <= 1/pi, energy conservation)");
            mu_.push_back(db_to_power(materials_[i].diffuse_db));
        }
    }

    explicit hard_target(const hard_target_params<T>& material) : hard_target(std::vector<hard_target_params<T>>{material}) {}

    [[nodiscard]] T backscatter(T graze_rad, std::uint32_t material) const noexcept {
        return bistatic(graze_rad, graze_rad, pi_v<T>, material);
    }

    [[nodiscard]] T bistatic(T graze_in_rad, T graze_out_rad, T phi_rad, std::uint32_t material) const noexcept {
        const std::size_t m = index(material);
        // Grazing angles clamped to [0, pi/2], NaN read as 0, and a NaN bistatic angle as backscatter, as the
        // Jackson policies read them: sigma stays finite.
        const auto graze = [](T g) { return std::isnan(g) ? 0.0 : std::clamp(double(g), 0.0, pi_v<double> / 2.0); };
        const double gi = graze(graze_in_rad), gs = graze(graze_out_rad);
        const double phi = std::isnan(phi_rad) ? pi_v<double> : double(phi_rad);
        const double diffuse = double(mu_[m]) * std::sin(gi) * std::sin(gs);
        return static_cast<T>(diffuse + kirchhoff_specular_sigma(gi, gs, phi, double(materials_[m].reflection),
                                                                 double(materials_[m].rms_slope)));
    }

    [[nodiscard]] std::size_t material_count() const noexcept { return materials_.size(); }
    [[nodiscard]] const hard_target_params<T>& material(std::uint32_t id) const noexcept { return materials_[index(id)]; }

private:
    [[nodiscard]] std::size_t index(std::uint32_t material) const noexcept {
        return std::min<std::size_t>(material, materials_.size() - 1);
    }

    std::vector<hard_target_params<T>> materials_;
    std::vector<T> mu_;
};

static_assert(Scattering<hard_target<float>> && Scattering<hard_target<double>>);

} // namespace sss::scattering
