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
/// the seabed: in the vertical plane of its axis its lower edge lies on an edge of the profile's upper hull (the
/// taut string), the lowest position that keeps it above the seabed, and its axis is that edge lifted by the radius,
/// perpendicular to it. On a slope a the axis's middle lies r sin(a) downslope of the point where the cylinder
/// touches the edge: the contact is taken r sin(a) upslope of center_m, on the edge under it, so that the middle
/// of the axis lies over center_m.
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
    const auto edge_at = [&](T at) { // the hull edge [hull[k], hull[k+1]] under s = at
        std::size_t k = 0;
        while (k + 2 < hull.size() && s[hull[k + 1]] <= at) ++k;
        return k;
    };
    const auto slope_of = [&](std::size_t k) { return (z[hull[k + 1]] - z[hull[k]]) / (s[hull[k + 1]] - s[hull[k]]); };
    // The contact r sin(a) upslope of the middle, on the edge under it (a the edge's slope angle): the edge under the
    // middle first, then the one under its contact; at a hull vertex between two edges either one's line bears on it.
    std::size_t k = edge_at(T(0));
    for (int pass = 0; pass < 2; ++pass) {
        const T m = slope_of(k);
        const std::size_t next = edge_at(p.radius_m * m / std::sqrt(T(1) + m * m));
        if (next == k) break;
        k = next;
    }
    const std::size_t a = hull[k];
    const T slope = slope_of(k);
    const T inv = T(1) / std::sqrt(T(1) + slope * slope);
    const T cos_a = inv, sin_a = slope * inv;
    const T contact = p.radius_m * sin_a;                  // along the axis from center_m (m)
    const T bottom = z[a] + slope * (contact - s[a]);      // the lower edge at the contact
    // Middle of the axis: the contact lifted by r along the edge's upward normal (-sin, cos): over center_m.
    const T sc = contact - p.radius_m * sin_a, zc = bottom + p.radius_m * cos_a;
    const T half = p.length_m / T(2);
    const vec2<T> q0 = p.center_m + dir * (sc - half * cos_a), q1 = p.center_m + dir * (sc + half * cos_a);
    const vec3<T> e0{q0.x, q0.y, zc - half * sin_a}, e1{q1.x, q1.y, zc + half * sin_a};
    return scene::object<T>({}, {scene::cylinder<T>(e0, e1, p.radius_m, p.ids)});
}

} // namespace sss::seabed::detail
