#pragma once
/// \file
/// A ray: origin and unit direction in world coordinates (metres).

#include "sss/core/types.hpp"

namespace sss {

template <Real T> struct ray {
    vec3<T> origin{};    ///< world position (m)
    vec3<T> direction{}; ///< unit vector, world frame

    /// The point at distance `s_m` along the ray (m).
    [[nodiscard]] constexpr vec3<T> at(T s_m) const noexcept { return origin + direction * s_m; }
};

} // namespace sss
