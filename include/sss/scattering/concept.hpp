#pragma once
/// \file
/// The Scattering concept: how much sound a surface element sends back.
///
/// | expression                                   | type  | meaning                                                   |
/// |----------------------------------------------|-------|-----------------------------------------------------------|
/// | `S::value_type`                              | T     | float or double                                           |
/// | `s.backscatter(graze_rad, material)`         | T     | sigma: backscattering cross section per unit area per     |
/// |                                              |       | unit solid angle (linear, dimensionless), S_b = 10 log10  |
/// | `s.bistatic(gi_rad, gs_rad, phi_rad, m)`     | T     | bistatic sigma for incident grazing gi, scattered grazing |
/// |                                              |       | gs, azimuth phi between the planes (pi = backscatter)     |
/// | `s.material_count()`                         | size  | materials the policy has parameters for (>= 1)            |
///
/// Grazing angles are measured from the local tangent plane, in [0, pi/2] radians. `material` is the id a
/// scene's hit carries; ids at or beyond `material_count()` use the last material. Both evaluations are
/// `noexcept`, finite and non-negative for every grazing angle in range, and `bistatic(g, g, pi, m)` equals
/// `backscatter(g, m)`. The policies read an angle outside the range as the nearest end and NaN as 0 (`clamp_graze`),
/// so that sigma stays finite and non-negative whatever the geometry hands them.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include "sss/core/constants.hpp"
#include "sss/core/types.hpp"

namespace sss {

template <class S>
concept Scattering = Real<typename S::value_type> &&
    requires(const S& s, typename S::value_type a, std::uint32_t m) {
        { s.backscatter(a, m) } noexcept -> std::same_as<typename S::value_type>;
        { s.bistatic(a, a, a, m) } noexcept -> std::same_as<typename S::value_type>;
        { s.material_count() } -> std::convertible_to<std::size_t>;
    };

namespace scattering {

/// A grazing angle clamped to [0, pi/2] (rad); NaN becomes 0.
template <Real T> [[nodiscard]] inline T clamp_graze(T graze_rad) noexcept {
    return std::isnan(graze_rad) ? T(0) : std::clamp(graze_rad, T(0), half_pi_v<T>);
}

} // namespace scattering

} // namespace sss
