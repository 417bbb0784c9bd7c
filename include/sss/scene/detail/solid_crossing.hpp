#pragma once
/// \file
/// Internal to the object primitives: the crossing a ray takes from its interval inside a closed solid, and the hit
/// made of it (see the rules of intersection in scene/primitive.hpp). Not part of the API.

#include <glm/geometric.hpp>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/surface_ids.hpp"

namespace sss::scene::detail {

/// Which surface bounds a crossing interval at one end (primitive-specific meaning).
enum class face : unsigned char { none, side, cap_lo, cap_hi };

/// The chosen crossing of a ray with a solid: distance, and which face it lies on.
template <Real T> struct crossing {
    T t;
    face where;
    bool from_inside; ///< the ray started inside the solid (the hit is where it leaves)
};

/// The hit a ray takes from its interval [t_in, t_out] inside a solid: t_in when 0 < t_in <= t_max,
/// else t_out when 0 < t_out <= t_max (the ray started inside), else none. NaNs give none.
/// Returns false when there is no hit.
template <Real T>
[[nodiscard]] inline bool choose_crossing(T t_in, face f_in, T t_out, face f_out, T t_max, crossing<T>& out) noexcept {
    if (!(t_in <= t_out)) return false;
    if (t_in > T(0)) {
        if (!(t_in <= t_max)) return false;
        out = {t_in, f_in, false};
        return true;
    }
    if (t_out > T(0) && t_out <= t_max) {
        out = {t_out, f_out, true};
        return true;
    }
    return false;
}

/// A hit at distance t along r with outward unit normal n (turned to face the ray) and the given ids.
template <Real T>
[[nodiscard]] inline hit<T> make_hit(const ray<T>& r, T t, vec3<T> n, const surface_ids& ids) noexcept {
    if (glm::dot(n, r.direction) > T(0)) n = -n;
    hit<T> h;
    h.distance_m = t;
    h.point = r.at(t);
    h.normal = n;
    h.shading_normal = n;
    h.material = ids.material;
    h.object = ids.object;
    h.label = ids.label;
    return h;
}

} // namespace sss::scene::detail
