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
/// Example: `jackson<float> s(100e3f, 1500.f, {sediment_preset<float>("medium_sand"), sediment_preset<float>(sediment::rock)});`

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
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

template <Real T> class jackson {
public:
    using value_type = T;

    /// One sediment per material id; ids beyond the list use the last one. f_hz (Hz) > 0 and c_water_mps
    /// (m/s) > 0: the sonar frequency and the water sound speed at the seabed (TR 9407 fitted 10-100 kHz).
    /// Throws invalid_parameter naming the parameter: "jackson.f_hz", "jackson.c_water_mps",
    /// "jackson.materials" (empty list) or "jackson.materials[i].rho" (etc.).
    jackson(T f_hz, T c_water_mps, const std::vector<sediment_params<T>>& materials) : f_hz_(f_hz), c_mps_(c_water_mps) {
        sss::detail::require_positive(f_hz, "jackson.f_hz");
        sss::detail::require_positive(c_water_mps, "jackson.c_water_mps");
        sss::detail::require(!materials.empty(), "jackson.materials", "needs at least one material");
        materials_ = materials;
        for (std::size_t i = 0; i < materials.size(); ++i) {
            const std::string who = "jackson.materials[" + std::to_string(i) + "]";
            validate(materials[i], who);
            const sediment_params<T>& p = materials[i];
            const sediment_params<double> pd{double(p.rho), double(p.nu), double(p.delta), double(p.sigma2), double(p.gamma), double(p.w2_cm4)};
            coefficients_.push_back(make_jackson_coefficients(pd, double(f_hz), double(c_water_mps), "jackson"));
            tables_.emplace_back(coefficients_.back());
        }
    }

    jackson(T f_hz, T c_water_mps, std::initializer_list<sediment_params<T>> materials)
        : jackson(f_hz, c_water_mps, std::vector<sediment_params<T>>(materials)) {}

    /// One sediment for every material id.
    jackson(T f_hz, T c_water_mps, const sediment_params<T>& material)
        : jackson(f_hz, c_water_mps, std::vector<sediment_params<T>>{material}) {}

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
