#pragma once
/// \file
/// The Beam concept: where the transducers send and hear, in the towfish body frame.
///
/// A launch direction is given by two angles (rad): `along`, the angle out of the across-track plane (positive
/// forward), and `depression`, the angle below the horizontal within the tilted across-track plane. In body FRD
/// coordinates the direction on side s (sign +1 starboard, -1 port) is
/// (sin along, s cos along cos depression, cos along sin depression); its solid angle element is
/// cos(along) d(along) d(depression).
///
/// | expression                         | type              | meaning                                                   |
/// |------------------------------------|-------------------|-----------------------------------------------------------|
/// | `B::value_type`                    | T                 | float or double                                           |
/// | `b.extent(side)`                   | `beam_extent<T>`  | the angular box holding every direction the sampling must |
/// |                                    |                   | cover on that side (main lobe and wanted sidelobes)       |
/// | `b.weight(side, along, depression)`| T                 | two-way intensity weight: transmit power pattern times    |
/// |                                    |                   | receive power pattern (linear, 1 on the maximum axis)     |
///
/// `weight` is `noexcept` and zero outside the extent. A beam whose pattern has structure along track may also
/// provide `b.along_resolution_rad(side)` (T, rad): the along-track angular step that resolves it; the simulator
/// then launches at least extent / step columns (see `ray_density`).

#include <cmath>
#include <concepts>

#include "sss/core/types.hpp"

namespace sss {

/// Angular box of a beam, body frame (rad). depression_max <= pi/2: each side covers its own half-space.
template <Real T> struct beam_extent {
    T along_min_rad{};
    T along_max_rad{};
    T depression_min_rad{};
    T depression_max_rad{};
};

/// The body-frame unit direction of a launch angle pair on one side.
template <Real T> [[nodiscard]] inline vec3<T> beam_direction(side s, T along_rad, T depression_rad) noexcept {
    const T ca = std::cos(along_rad);
    return vec3<T>{std::sin(along_rad), side_sign<T>(s) * ca * std::cos(depression_rad), ca * std::sin(depression_rad)};
}

template <class B>
concept Beam = Real<typename B::value_type> && requires(const B& b, side s, typename B::value_type a) {
    { b.extent(s) } -> std::same_as<beam_extent<typename B::value_type>>;
    { b.weight(s, a, a) } noexcept -> std::same_as<typename B::value_type>;
};

/// True when a beam states the along-track angular step that resolves its pattern.
template <class B>
concept AlongResolvedBeam = Beam<B> && requires(const B& b, side s) {
    { b.along_resolution_rad(s) } -> std::same_as<typename B::value_type>;
};

} // namespace sss
