#pragma once
/// \file
/// Numeric vocabulary shared by every part of sss: vectors and matrices over GLM, templated on the
/// scalar type `T` (float or double), and the `Real` concept that names those scalar types.
///
/// Frames used throughout the library:
/// - world: right-handed, x east, y north, z up (metres). Heights and altitudes are world z.
/// - body (towfish): x forward, y starboard, z down (FRD), the usual marine and aerospace convention.

#include <concepts>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sss {

/// The scalar types sss is instantiated for.
template <class T>
concept Real = std::same_as<T, float> || std::same_as<T, double>;

template <Real T> using vec2 = glm::vec<2, T, glm::defaultp>;
template <Real T> using vec3 = glm::vec<3, T, glm::defaultp>;
template <Real T> using mat3 = glm::mat<3, 3, T, glm::defaultp>;

/// Which side of the towfish a beam, ray or line belongs to.
enum class side : unsigned char { port = 0, starboard = 1 };

/// +1 for starboard, -1 for port: the sign of the body y component of that side's rays.
template <Real T> [[nodiscard]] constexpr T side_sign(side s) noexcept {
    return s == side::starboard ? T(1) : T(-1);
}

} // namespace sss
