#pragma once
/// \file
/// What a ray met: the plain record every scene's intersection returns.

#include <cstdint>
#include <limits>

#include "sss/core/types.hpp"

namespace sss {

/// Object id of a hit on the seabed (no object).
inline constexpr std::uint32_t no_object = std::numeric_limits<std::uint32_t>::max();

template <Real T> struct hit {
    T distance_m{};            ///< distance along the ray from its origin (m)
    vec3<T> point{};           ///< world position of the hit (m)
    vec3<T> normal{};          ///< unit geometric normal, on the side the ray came from
    vec3<T> shading_normal{};  ///< unit interpolated (smooth) normal, same side as `normal`
    std::uint32_t material = 0;       ///< scattering material id (index into the scattering policy's table)
    std::uint32_t object = no_object; ///< object id, or `no_object` for the seabed
    std::uint32_t label = 0;          ///< object class id, or seabed region id: the ground-truth label
};

/// True when two hits lie on the same continuous surface: same object (or both seabed) and same material.
/// Energy between two adjacent rays is spread between their hits only when this holds.
template <Real T> [[nodiscard]] constexpr bool same_surface(const hit<T>& a, const hit<T>& b) noexcept {
    return a.object == b.object && a.material == b.material;
}

} // namespace sss
