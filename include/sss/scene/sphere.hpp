#pragma once
/// \file
/// A sphere: centre, radius and the ids its hits carry, with exact ray intersection.
///
/// With f = o - c and a unit direction d, the ray o + t d meets the sphere of radius a where
/// t^2 + 2 b t + (|f|^2 - a^2) = 0, b = f.d. The roots are computed as in Haines, Guenther &
/// Akenine-Moeller (2019), "Precision improvements for ray/sphere intersection", Ray Tracing Gems, ch. 7:
/// the discriminant as a^2 - |f - b d|^2 (the closest approach, free of the cancellation in b^2 - c when
/// the sphere is small and far), and the two roots as q and c / q with q = -(b + sign(b) sqrt(disc))
/// (no cancellation between b and the root). Rules for rays from inside and tangent rays: primitive.hpp.

#include <cmath>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/primitive.hpp"

namespace sss::scene {

/// A sphere by name: `sphere<T>({.center_m = {x, y, z}, .radius_m = r, .ids = {.material = 2, .object = 1}})`.
template <Real T> struct sphere_params {
    vec3<T> center_m{};   ///< world (or object-local) centre (m), finite
    T radius_m = T(1);    ///< radius (m), finite and > 0
    surface_ids ids{};    ///< material, object and class ids of its hits (object != no_object)
};

template <Real T> class sphere {
public:
    using value_type = T;

    explicit sphere(const sphere_params<T>& p) : sphere(p.center_m, p.radius_m, p.ids) {}

    /// \param center_m world (or object-local) centre (m), finite
    /// \param radius_m radius (m), finite and > 0
    /// \param ids      material, object and class ids of its hits (object != no_object)
    sphere(const vec3<T>& center_m, T radius_m, const surface_ids& ids = {})
        : center_(center_m), radius_(radius_m), ids_(ids) {
        detail::require_finite_vec(center_m, "sphere.center_m");
        sss::require_positive(radius_m, "sphere.radius_m");
        detail::require_object_ids(ids, "sphere");
        radius2_ = radius_m * radius_m;
        sss::require(radius2_ > T(0) && std::isfinite(radius2_), "sphere.radius_m",
                             "its square must be a finite positive number");
    }

    [[nodiscard]] const vec3<T>& center_m() const noexcept { return center_; }
    [[nodiscard]] T radius_m() const noexcept { return radius_; }
    [[nodiscard]] const surface_ids& ids() const noexcept { return ids_; }

    /// The smallest axis-aligned box containing the sphere.
    [[nodiscard]] box<T> bounds() const noexcept { return {center_ - vec3<T>(radius_), center_ + vec3<T>(radius_)}; }

    /// Nearest crossing with 0 < distance <= t_max_m (primitive.hpp); normals face the ray.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        const auto c = first_crossing(r, t_max_m);
        if (!c) return std::nullopt;
        return hit_at(r, *c);
    }

    /// The hit of ray r at its crossing c (first_crossing's), without solving for the crossing again.
    [[nodiscard]] hit<T> hit_at(const ray<T>& r, const detail::crossing<T>& c) const noexcept {
        const vec3<T> radial = (r.origin - center_) + r.direction * c.t;
        return detail::make_hit(r, c.t, glm::normalize(radial), ids_);
    }

    /// The crossing alone (distance, whether the ray started inside), without building the hit.
    [[nodiscard]] std::optional<detail::crossing<T>> first_crossing(const ray<T>& r, T t_max_m) const noexcept {
        const vec3<T> f = r.origin - center_;
        const T b = glm::dot(f, r.direction);
        const vec3<T> g = f - r.direction * b; // closest approach of the ray's line to the centre
        const T disc = radius2_ - glm::dot(g, g);
        if (!(disc >= T(0))) return std::nullopt;
        const T c = glm::dot(f, f) - radius2_;
        const T q = -(b + std::copysign(std::sqrt(disc), b));
        T t0 = q, t1 = q;
        if (q != T(0)) t1 = c / q; // q = 0 only when the origin lies on the sphere and the ray is tangent
        if (t0 > t1) std::swap(t0, t1);
        detail::crossing<T> out{};
        if (!detail::choose_crossing(t0, detail::face::side, t1, detail::face::side, t_max_m, out)) return std::nullopt;
        return out;
    }

private:
    vec3<T> center_;
    T radius_;
    T radius2_{};
    surface_ids ids_;
};

} // namespace sss::scene
