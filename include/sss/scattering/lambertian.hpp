#pragma once
/// \file
/// Lambert's law for seabed scattering.
///
/// Backscatter S_b = 10 log10(mu) + 10 log10(sin^2 theta); bistatic sigma = mu sin(theta_i) sin(theta_s)
/// (theta: grazing angles, rad). Mackenzie (1961), JASA 33, 1498, found 10 log10(mu) = -27 dB for deep-sea
/// sediments at 530 and 1120 Hz; a perfectly diffuse, energy-conserving surface has mu = 1/pi (-4.9715 dB),
/// the physical upper bound.

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

namespace sss::scattering {

/// The largest Lambert parameter (dB): mu = 1/pi, 10 log10(1/pi) = -4.9715 dB, at which a perfectly diffuse surface
/// scatters all it receives (energy conservation).
inline constexpr double lambert_max_db = -4.971498726941338;

/// Lambert's law for one angle pair: sigma = mu sin(graze_in) sin(graze_out) (linear). The angles are read as the
/// Scattering concept says (`clamp_graze`: [0, pi/2], NaN as 0), so sigma is never negative or NaN.
template <Real T> [[nodiscard]] inline T lambert_sigma(T mu, T graze_in_rad, T graze_out_rad) noexcept {
    return mu * std::sin(clamp_graze(graze_in_rad)) * std::sin(clamp_graze(graze_out_rad));
}

/// Settings of the Lambertian policy.
template <Real T> struct lambertian_params {
    /// Lambert parameter 10 log10 mu (dB) per material id, <= -4.9715 dB (mu <= 1/pi); ids beyond the list use
    /// the last entry. Not empty. Default: Mackenzie's (1961) -27 dB.
    std::vector<T> mu_db{T(-27)};
};

template <Real T> class lambertian {
public:
    using value_type = T;

    /// Mackenzie's -27 dB for every material (non-explicit, so `{}` builds one).
    lambertian() : lambertian(T(-27)) {}

    /// One Lambert parameter for every material, given in dB (10 log10 mu).
    explicit lambertian(T mu_db) : lambertian(lambertian_params<T>{.mu_db = {mu_db}}) {}

    /// One Lambert parameter per material id, in dB (`lambertian<T>({.mu_db = {T(-27), T(-8)}})`).
    explicit lambertian(const lambertian_params<T>& p) {
        sss::require(!p.mu_db.empty(), "lambertian.mu_db", "needs at least one material");
        for (std::size_t i = 0; i < p.mu_db.size(); ++i) {
            const T db = p.mu_db[i];
            const auto name = [&] { return "lambertian.mu_db[" + std::to_string(i) + "]"; };
            if (!std::isfinite(db)) sss::require_finite(db, name());
            // mu = 1/pi is the energy-conserving bound for a perfectly diffuse surface.
            if (!(db <= T(lambert_max_db))) // in T: the bound itself, rounded to T, is within it
                sss::require(false, name(), "must be <= -4.9715 dB (mu <= 1/pi, energy conservation)");
            mu_.push_back(db_to_power(db));
        }
    }

    [[nodiscard]] T mu(std::uint32_t material) const noexcept { return mu_[std::min<std::size_t>(material, mu_.size() - 1)]; }

    [[nodiscard]] T backscatter(T graze_rad, std::uint32_t material) const noexcept {
        return lambert_sigma(mu(material), graze_rad, graze_rad);
    }
    [[nodiscard]] T bistatic(T graze_in_rad, T graze_out_rad, T, std::uint32_t material) const noexcept {
        return lambert_sigma(mu(material), graze_in_rad, graze_out_rad);
    }
    [[nodiscard]] std::size_t material_count() const noexcept { return mu_.size(); }

private:
    std::vector<T> mu_;
};

static_assert(Scattering<lambertian<float>> && Scattering<lambertian<double>>);

} // namespace sss::scattering
