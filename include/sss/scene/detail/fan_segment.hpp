#pragma once
/// \file
/// Internal to scene/height_field_fan.hpp: a piece of a fan's profile on which rays come down, and the distance at
/// which a fan ray meets it. Not part of the API.

#include <algorithm>
#include <cstdint>
#include <limits>

#include "sss/core/types.hpp"
#include "sss/scene/detail/fan_run.hpp"
#include "sss/scene/height_grid.hpp"

namespace sss::scene::detail {

/// A piece of a fan's profile on which rays come down: rho in [rho_a, rho_b] (m) inside cell (ix, iy), the
/// profile's g = z0 - z_p at both ends (m), and the triangle holding the piece's midpoint.
template <Real T> struct fan_segment {
    T rho_a, g_a, rho_b, g_b;
    std::int32_t ix, iy;
    cell_triangle triangle;
};

/// What sweep_fan records for a ray that stays above the surface out to t_max.
inline constexpr std::uint32_t no_fan_segment = std::numeric_limits<std::uint32_t>::max();

/// The distance (m) at which the ray with slope `sl` crosses segment `sg`, on which its f = g - tau rho goes
/// from > 0 to <= 0: the linear root, s = rho_hit / |(dx, dy)|; 0 when that is not in (0, t_max_m].
///
/// f is evaluated here again, and a compiler that fuses multiply-adds may round it otherwise than the sweep
/// did: then fa <= fb is possible (fa = fb = 0 would make the root 0/0 and lose the hit). The ray is then at
/// or below the surface at rho_a to within rounding, and the root is taken there.
template <Real T>
[[nodiscard]] inline T fan_distance(const fan_segment<T>& sg, fan_slope<T> sl, T t_max_m) noexcept {
    const T fb = sg.g_b - sl.tau * sg.rho_b;
    const T fa = sg.g_a - sl.tau * sg.rho_a; // > 0: this ray, or a steeper one, was above at rho_a
    const T u = fa > fb ? fa / (fa - fb) : T(0);
    const T r_hit = std::clamp(sg.rho_a + (sg.rho_b - sg.rho_a) * u, sg.rho_a, sg.rho_b);
    const T s = r_hit * sl.inv_h;
    return s > T(0) && s <= t_max_m ? s : T(0);
}

} // namespace sss::scene::detail
