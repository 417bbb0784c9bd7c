#pragma once
/// \file
/// What every object primitive (sphere.hpp, cylinder.hpp) shares: the ids its hits carry, its bounding
/// box, and the rules of its ray intersection.
///
/// Rules of intersection, the same for every primitive:
/// - A primitive is a closed solid; a ray's hit is its nearest crossing of the solid's surface with
///   0 < t <= t_max_m. The crossings are found as the interval [t_in, t_out] of the ray inside the solid
///   (an intersection of intervals for a capped cylinder), so a ray can never slip between two faces.
/// - A ray that starts inside the solid hits the inside of its surface where it leaves (t_out), and the
///   hit's normals point inwards: `hit.normal` always faces the ray (dot(normal, direction) <= 0), which is
///   what the simulator expects. A ray that starts on the surface and leaves it does not hit (t = 0 is
///   excluded). Sonar rays start in the water, so this only matters for rays handed over by propagation
///   models, whose pieces start where the previous piece ended.
/// - A tangent ray (it touches the surface without entering, to rounding) hits at the touching point,
///   with a normal perpendicular to the ray; the simulator gives such a hit no energy (zero projected area).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"

namespace sss::scene {

/// The ids a primitive's hits carry (see core/hit.hpp).
struct surface_ids {
    std::uint32_t material = 0; ///< scattering material id
    std::uint32_t object = 0;   ///< object id; must not be `no_object` (that id means the seabed)
    std::uint32_t label = 0;    ///< object class id: the ground-truth label of the hits
};

/// An axis-aligned box [lo, hi] in world coordinates (m). Empty when lo > hi in any coordinate.
template <Real T> struct box {
    vec3<T> lo{std::numeric_limits<T>::infinity()};
    vec3<T> hi{-std::numeric_limits<T>::infinity()};

    [[nodiscard]] bool empty() const noexcept { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    [[nodiscard]] vec3<T> center() const noexcept { return (lo + hi) * T(0.5); }
    [[nodiscard]] vec3<T> extent() const noexcept { return hi - lo; }
    /// Half the surface area (m^2), the measure of the surface-area heuristic; 0 for an empty box.
    [[nodiscard]] T half_area() const noexcept {
        if (empty()) return T(0);
        const vec3<T> e = extent();
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
    /// Grows the box to contain `b`.
    void expand(const box& b) noexcept {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    /// Grows the box to contain the point `p`.
    void expand(const vec3<T>& p) noexcept {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    [[nodiscard]] bool contains(const vec3<T>& p) const noexcept {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    }
};

namespace detail {

/// Throws unless `ids.object` is a real object id; `who` prefixes the parameter name.
inline void require_object_ids(const surface_ids& ids, const std::string& who) {
    sss::require(ids.object != no_object, who + ".ids.object",
                         "must not be sss::no_object (reserved for the seabed)");
}

/// Throws unless every component of `v` is finite; `name` names it.
template <Real T> void require_finite_vec(const vec3<T>& v, const std::string& name) {
    sss::require_finite(v.x, name + ".x");
    sss::require_finite(v.y, name + ".y");
    sss::require_finite(v.z, name + ".z");
}

/// The box grown by 16 ulps of its largest coordinate (at least of 1 m): a culling box that rounding
/// in the box test cannot make too small.
template <Real T> [[nodiscard]] inline box<T> padded(box<T> b) noexcept {
    const T scale = std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x), std::abs(b.hi.y),
                              std::abs(b.hi.z), T(1)});
    const vec3<T> pad(T(16) * std::numeric_limits<T>::epsilon() * scale);
    b.lo -= pad;
    b.hi += pad;
    return b;
}

/// A ray prepared for many box tests: origin and reciprocal direction (+-inf where a component is 0).
template <Real T> struct box_ray {
    vec3<T> origin;
    vec3<T> inv;
    explicit box_ray(const ray<T>& r) noexcept
        : origin(r.origin), inv(T(1) / r.direction.x, T(1) / r.direction.y, T(1) / r.direction.z) {}
};

/// Whether the ray's piece [0, t_max] meets box b; the entry distance (>= 0) in t_entry.
template <Real T> [[nodiscard]] inline bool hits_box(const box<T>& b, const box_ray<T>& r, T t_max, T& t_entry) noexcept {
    T t0 = T(0), t1 = t_max;
    for (int i = 0; i < 3; ++i) {
        T a = (b.lo[i] - r.origin[i]) * r.inv[i];
        T c = (b.hi[i] - r.origin[i]) * r.inv[i];
        if (a > c) std::swap(a, c);
        // NaN (0 x inf: the origin in the face plane, the ray parallel to it) leaves the interval as is.
        t0 = a > t0 ? a : t0;
        t1 = c < t1 ? c : t1;
    }
    t_entry = t0;
    return t0 <= t1;
}

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

} // namespace detail

} // namespace sss::scene
