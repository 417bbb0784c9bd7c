#pragma once
/// \file
/// Internal to scene/object.hpp: the rigid transform of a placement given by angles in radians, counter-clockwise
/// from east. Not part of the API.

#include <cmath>

#include <glm/geometric.hpp>

#include "sss/core/types.hpp"
#include "sss/scene/rigid_transform.hpp"

namespace sss::scene::detail {

/// The placement R = Rz(theta) Ry(-pitch) Rx(roll) at `position_m`, theta counter-clockwise from east (all rad).
template <Real T>
[[nodiscard]] rigid_transform<T> placement_ccw_rad(const vec3<T>& position_m, T theta_rad = T(0), T pitch_rad = T(0),
                                                   T roll_rad = T(0)) noexcept {
    const T ch = std::cos(theta_rad), sh = std::sin(theta_rad);
    const T cp = std::cos(pitch_rad), sp = std::sin(pitch_rad);
    const T cr = std::cos(roll_rad), sr = std::sin(roll_rad);
    // Columns are the images of the local axes (GLM: m[col][row]).
    const vec3<T> ex{ch * cp, sh * cp, sp};                                  // local +x
    const vec3<T> ey{-sh * cr - ch * sp * sr, ch * cr - sh * sp * sr, cp * sr}; // local +y
    const vec3<T> ez = glm::cross(ex, ey);                                   // local +z
    rigid_transform<T> x;
    x.rotation = mat3<T>(ex, ey, ez);
    x.translation_m = position_m;
    return x;
}

} // namespace sss::scene::detail
