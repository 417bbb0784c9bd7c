#pragma once
/// \file
/// The APL-UW high-frequency seafloor scattering model as a Scattering policy.
///
/// Backscatter: APL-UW TR 9407 (1994) Section IV (D. R. Jackson), tabulated per material over grazing angle
/// (jackson_table.hpp: within 0.01 dB of the direct model at the table's cell midpoints). Bistatic: Williams &
/// Jackson (1998), JASA 103, 169-181, evaluated directly (about 1 microsecond) from coefficients
/// precomputed per material; at the exact backscatter geometry it returns the tabulated backscatter, so that
/// `bistatic(g, g, pi, m) == backscatter(g, m)` holds exactly as the concept asks.
/// The terms, their equations and units are in jackson_terms.hpp and jackson_bistatic.hpp; the sediment
/// parameters and the TR 9407 Table 2 presets in sediments.hpp; reflection coefficients in reflection.hpp.
///
/// Example:
///
///     const jackson<float> s({.frequency_hz = 100e3f,
///                             .sound_speed_mps = 1500.f,
///                             .materials = {sediment_preset<float>(sediment::medium_sand),
///                                           sediment_preset<float>(sediment::rock)}});

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/scattering/concept.hpp"
#include "sss/scattering/jackson_bistatic.hpp"
#include "sss/scattering/jackson_table.hpp"
#include "sss/scattering/jackson_terms.hpp"
#include "sss/scattering/reflection.hpp"
#include "sss/scattering/sediments.hpp"

namespace sss::scattering {

/// Settings of the Jackson policy. Frequency and sound speed are named fields, so they cannot be swapped.
template <Real T> struct jackson_params {
    T frequency_hz = T(100000);   ///< sonar frequency (Hz), > 0 (TR 9407 fitted 10-100 kHz)
    T sound_speed_mps = T(1500);  ///< water sound speed at the seabed (m/s), > 0
    /// One sediment per material id; ids beyond the list use the last one. Not empty.
    std::vector<sediment_params<T>> materials{sediment_preset<T>(sediment::medium_sand)};
};

template <Real T> class jackson {
public:
    using value_type = T;

    /// Default parameters: 100 kHz, 1500 m/s, medium sand (non-explicit, so `{}` builds one).
    jackson() : jackson(jackson_params<T>{}) {}

    /// Throws invalid_parameter naming the parameter: "jackson.frequency_hz", "jackson.sound_speed_mps",
    /// "jackson.materials" (empty list) or "jackson.materials[i].rho" (etc.).
    explicit jackson(const jackson_params<T>& p) : f_hz_(p.frequency_hz), c_mps_(p.sound_speed_mps) {
        sss::require_positive(p.frequency_hz, "jackson.frequency_hz");
        sss::require_positive(p.sound_speed_mps, "jackson.sound_speed_mps");
        sss::require(!p.materials.empty(), "jackson.materials", "needs at least one material");
        materials_ = p.materials;
        for (std::size_t i = 0; i < materials_.size(); ++i) {
            const std::string who = "jackson.materials[" + std::to_string(i) + "]";
            validate(materials_[i], who);
            coefficients_.push_back(
                make_jackson_coefficients(to_double(materials_[i]), double(f_hz_), double(c_mps_), "jackson"));
            tables_.emplace_back(coefficients_.back());
        }
    }

    /// Backscattering cross section sigma (linear) at grazing angle graze_rad (rad, clamped to [0, pi/2]).
    [[nodiscard]] T backscatter(T graze_rad, std::uint32_t material) const noexcept { return tables_[index(material)](graze_rad); }

    /// Bistatic cross section sigma (linear): incident and scattered grazing angles (rad, clamped to
    /// [0, pi/2]), azimuth phi (rad, pi = backscatter).
    [[nodiscard]] T bistatic(T graze_in_rad, T graze_out_rad, T phi_rad, std::uint32_t material) const noexcept {
        const std::size_t m = index(material);
        const double ci = std::cos(double(phi_rad));
        // Backscatter geometry (to float rounding of pi): the tabulated value, identical to backscatter().
        if (graze_in_rad == graze_out_rad && ci <= -1.0 + 1e-10) return tables_[m](graze_in_rad);
        return T(jackson_bistatic(coefficients_[m], double(graze_in_rad), double(graze_out_rad), double(phi_rad)));
    }

    [[nodiscard]] std::size_t material_count() const noexcept { return materials_.size(); }

    /// The sediment parameters of a material id (the last one for ids beyond the list).
    [[nodiscard]] const sediment_params<T>& material(std::uint32_t id) const noexcept { return materials_[index(id)]; }
    /// The precomputed model coefficients of a material id.
    [[nodiscard]] const jackson_coefficients<double>& coefficients(std::uint32_t id) const noexcept { return coefficients_[index(id)]; }
    /// The backscatter table of a material id.
    [[nodiscard]] const jackson_backscatter_table<T>& table(std::uint32_t id) const noexcept { return tables_[index(id)]; }
    /// Coherent (specular) intensity reflection coefficient |R|^2 of a material at grazing angle graze_rad:
    /// the Rayleigh coefficient of the fluid sediment (rho, nu, delta) times the Kirchhoff roughness factor
    /// exp(-2 k^2 h^2 sin^2 theta) squared, h the RMS height of the roughness finer than patch_m (m; e.g. the
    /// scene's cell size: coarser relief is the scene's own geometry). In [0, 1]: a bounce never adds energy.
    [[nodiscard]] T reflection(T graze_rad, std::uint32_t material, T patch_m) const noexcept {
        const sediment_params<T>& p = materials_[index(material)];
        const double k = two_pi_v<double> * double(f_hz_) / double(c_mps_);
        const double h = roughness_rms_height_m(double(p.w2_cm4), double(p.gamma), two_pi_v<double> / double(patch_m));
        const double r = std::abs(rayleigh_reflection(p, graze_rad));
        const double f = coherent_roughness_factor(k, h, double(graze_rad));
        return static_cast<T>(std::min(1.0, r * r * f * f));
    }

    [[nodiscard]] T frequency_hz() const noexcept { return f_hz_; }
    [[nodiscard]] T sound_speed_mps() const noexcept { return c_mps_; }

private:
    [[nodiscard]] std::size_t index(std::uint32_t material) const noexcept {
        return std::min<std::size_t>(material, materials_.size() - 1);
    }

    T f_hz_;
    T c_mps_;
    std::vector<sediment_params<T>> materials_;
    std::vector<jackson_coefficients<double>> coefficients_;
    std::vector<jackson_backscatter_table<T>> tables_;
};

static_assert(Scattering<jackson<float>> && Scattering<jackson<double>>);

} // namespace sss::scattering
