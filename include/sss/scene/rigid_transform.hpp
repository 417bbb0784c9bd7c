#pragma once
/// \file
/// A rotation followed by a translation: where an object's frame stands in the world. Part of scene/object.hpp,
/// which includes it.

#include "sss/core/types.hpp"

namespace sss::scene {

/// A rotation followed by a translation: world = rotation * local + translation_m.
template <Real T> struct rigid_transform {
    mat3<T> rotation{T(1)};  ///< proper rotation (orthonormal, determinant +1)
    vec3<T> translation_m{}; ///< world position of the object frame's origin (m)

    [[nodiscard]] vec3<T> point(const vec3<T>& local) const noexcept { return rotation * local + translation_m; }
    [[nodiscard]] vec3<T> vector(const vec3<T>& local) const noexcept { return rotation * local; }
};

} // namespace sss::scene
