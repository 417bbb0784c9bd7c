#pragma once
/// \file
/// The towfish pose at one ping: time, world position and attitude.
///
/// Units: a pose is the pipeline's own form, so its angles are radians (`*_rad`), as docs/conventions.md
/// allows inside the pipeline; settings users write (the motion policies' parameters) are in degrees.
///
/// Attitude follows the marine convention: yaw (heading) clockwise from north, pitch bow-up positive, roll
/// starboard-down positive, applied as R = Rz(yaw) Ry(pitch) Rx(roll) from body (FRD) to north-east-down,
/// then mapped to the world's east-north-up axes.

#include <cmath>

#include "sss/core/types.hpp"

namespace sss {

template <Real T> struct pose {
    T time_s{};          ///< time of the ping (s)
    vec3<T> position{};  ///< acoustic centre in world coordinates (m)
    T roll_rad{};        ///< starboard down positive (rad)
    T pitch_rad{};       ///< bow up positive (rad)
    T yaw_rad{};         ///< heading, clockwise from north (rad)
    mat3<T> body_to_world{T(1)}; ///< rotates body FRD vectors into world ENU vectors

    /// A body-frame (FRD) vector expressed in the world frame.
    [[nodiscard]] constexpr vec3<T> to_world(const vec3<T>& body) const noexcept { return body_to_world * body; }
};

/// The rotation from body FRD to world ENU for the given attitude (radians).
template <Real T> [[nodiscard]] inline mat3<T> body_to_world_rotation(T roll_rad, T pitch_rad, T yaw_rad) noexcept {
    const T cr = std::cos(roll_rad), sr = std::sin(roll_rad);
    const T cp = std::cos(pitch_rad), sp = std::sin(pitch_rad);
    const T cy = std::cos(yaw_rad), sy = std::sin(yaw_rad);
    // Rows of R_ned_from_body = Rz(yaw) Ry(pitch) Rx(roll).
    const vec3<T> north{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr};
    const vec3<T> east{sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr};
    const vec3<T> down{-sp, cp * sr, cp * cr};
    // ENU rows: east, north, up = -down. GLM is column-major: m[col][row].
    mat3<T> m{};
    for (int c = 0; c < 3; ++c) {
        m[c][0] = east[c];
        m[c][1] = north[c];
        m[c][2] = -down[c];
    }
    return m;
}

/// A pose with its rotation filled in.
template <Real T>
[[nodiscard]] inline pose<T> make_pose(T time_s, const vec3<T>& position, T roll_rad, T pitch_rad, T yaw_rad) noexcept {
    return pose<T>{time_s, position, roll_rad, pitch_rad, yaw_rad, body_to_world_rotation(roll_rad, pitch_rad, yaw_rad)};
}

} // namespace sss
