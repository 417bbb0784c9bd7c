#pragma once
/// \file
/// Internal to seabed/targets.hpp: a cylinder resting on the seabed with its axis along a given plan direction,
/// shared by the lying cylinder and the debris cluster. Not part of the API.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/cylinder.hpp"
#include "sss/scene/object.hpp"
#include "sss/seabed/height_function.hpp"
#include "sss/seabed/lying_cylinder_params.hpp"
#include "sss/seabed/profile_hull.hpp"

namespace sss::seabed::detail {

/// lying_cylinder with its axis along the unit plan vector `dir` (p.heading_deg unused). A rigid cylinder resting on
/// the seabed: in the vertical plane of its axis its lower edge lies on the
/// edge of the profile's upper hull (the taut string) under its middle, the lowest position of its middle
/// that keeps it above the seabed; its axis is that edge lifted by the radius, perpendicular to it.
template <Real T, HeightFunction<T> F>
[[nodiscard]] scene::object<T> lying_cylinder_along(const lying_cylinder_params<T>& p, const vec2<T>& dir,
                                                    const F& seabed_height_m) {
    sss::require_finite(p.center_m.x, "lying_cylinder.center_m.x");
    sss::require_finite(p.center_m.y, "lying_cylinder.center_m.y");
    sss::require_positive(p.length_m, "lying_cylinder.length_m");
    sss::require_positive(p.radius_m, "lying_cylinder.radius_m");
    sss::require_positive(p.profile_step_m, "lying_cylinder.profile_step_m");
    sss::require(p.length_m / p.profile_step_m < T(1e7), "lying_cylinder.profile_step_m", "gives more than 1e7 samples");
    const auto n = std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(p.length_m / p.profile_step_m)) + 1);
    std::vector<T> s(n), z(n);
    for (std::size_t i = 0; i < n; ++i) {
        s[i] = p.length_m * (static_cast<T>(i) / static_cast<T>(n - 1) - T(0.5));
        const vec2<T> q = p.center_m + dir * s[i];
        z[i] = static_cast<T>(seabed_height_m(q.x, q.y));
        sss::require_finite(z[i], "lying_cylinder.seabed_height_m(axis)");
    }
    const std::vector<std::size_t> hull = taut_string<T>(s, z);
    std::size_t k = 0; // the hull edge [hull[k], hull[k+1]] under the middle (s = 0)
    while (k + 2 < hull.size() && s[hull[k + 1]] <= T(0)) ++k;
    const std::size_t a = hull[k], b = hull[k + 1];
    const T slope = (z[b] - z[a]) / (s[b] - s[a]);
    const T bottom0 = z[a] + slope * (T(0) - s[a]); // lower edge under the middle
    const T inv = T(1) / std::sqrt(T(1) + slope * slope);
    const T cos_a = inv, sin_a = slope * inv;
    // Middle of the axis: the lower edge's point lifted by r along the edge's upward normal (-sin, cos).
    const T sc = -p.radius_m * sin_a, zc = bottom0 + p.radius_m * cos_a;
    const T half = p.length_m / T(2);
    const vec2<T> q0 = p.center_m + dir * (sc - half * cos_a), q1 = p.center_m + dir * (sc + half * cos_a);
    const vec3<T> e0{q0.x, q0.y, zc - half * sin_a}, e1{q1.x, q1.y, zc + half * sin_a};
    return scene::object<T>({}, {scene::cylinder<T>(e0, e1, p.radius_m, p.ids)});
}

} // namespace sss::seabed::detail
