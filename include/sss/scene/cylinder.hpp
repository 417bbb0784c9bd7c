#pragma once
/// \file
/// A finite cylinder with flat caps and any axis: the two end centres, the radius and the ids its hits
/// carry, with exact ray intersection.
///
/// The solid is the intersection of a slab (0 <= s <= L along the unit axis u from end 0) and an infinite
/// circular cylinder of radius a about the axis. Along the ray o + t d, with f = o - end0:
/// - the slab holds t between the cap-plane crossings (-f.u)/(d.u) and (L - f.u)/(d.u) (all t when d.u = 0
///   and 0 <= f.u <= L, none otherwise);
/// - the infinite cylinder holds t between the roots of A t^2 + 2 B t + C = 0 with f' = f - (f.u) u,
///   d' = d - (d.u) u, A = d'.d', B = f'.d', C = f'.f' - a^2 (all t when A = 0 and f'.f' <= a^2, none otherwise).
///   The discriminant B^2 - A C is evaluated as A a^2 - |f' x d'|^2 (Lagrange's identity), which does not
///   cancel for thin or distant cylinders (the same idea as the sphere's, Haines et al. 2019, Ray Tracing
///   Gems ch. 7), and the roots as q / A and C / q, q = -(B + sign(B) sqrt(disc)).
/// The ray is inside the solid on the intersection of the two intervals; its ends say which face is met
/// (a cap when the slab bound is the tighter one, the side otherwise), so side and caps meet without a
/// gap at the rims. Rays along the axis hit the caps; rays parallel to the axis outside the radius miss.
/// Rules for rays from inside and tangent rays: primitive.hpp.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include <glm/geometric.hpp>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/primitive.hpp"

namespace sss::scene {

/// A cylinder by name: `cylinder<T>({.end0_m = a, .end1_m = b, .radius_m = r, .ids = {.material = 2, .object = 1}})`.
template <Real T> struct cylinder_params {
    vec3<T> end0_m{};     ///< centre of one cap (m), finite
    vec3<T> end1_m{};     ///< centre of the other cap (m), finite, distinct from end0_m
    T radius_m = T(1);    ///< radius (m), finite and > 0
    surface_ids ids{};    ///< material, object and class ids of its hits (object != no_object)
};

template <Real T> class cylinder {
public:
    using value_type = T;

    explicit cylinder(const cylinder_params<T>& p) : cylinder(p.end0_m, p.end1_m, p.radius_m, p.ids) {}

    /// \param end0_m   centre of one cap (m), finite
    /// \param end1_m   centre of the other cap (m), finite, distinct from end0_m (length > 0)
    /// \param radius_m radius (m), finite and > 0
    /// \param ids      material, object and class ids of its hits (object != no_object)
    cylinder(const vec3<T>& end0_m, const vec3<T>& end1_m, T radius_m, const surface_ids& ids = {})
        : end0_(end0_m), end1_(end1_m), radius_(radius_m), ids_(ids) {
        detail::require_finite_vec(end0_m, "cylinder.end0_m");
        detail::require_finite_vec(end1_m, "cylinder.end1_m");
        sss::require_positive(radius_m, "cylinder.radius_m");
        detail::require_object_ids(ids, "cylinder");
        const vec3<T> axis = end1_m - end0_m;
        length_ = glm::length(axis);
        sss::require(length_ > T(0) && std::isfinite(length_), "cylinder.length_m",
                             "the ends must be distinct (length > 0) and the length finite");
        axis_ = axis / length_;
        radius2_ = radius_m * radius_m;
        sss::require(radius2_ > T(0) && std::isfinite(radius2_), "cylinder.radius_m",
                             "its square must be a finite positive number");
    }

    [[nodiscard]] const vec3<T>& end0_m() const noexcept { return end0_; }
    [[nodiscard]] const vec3<T>& end1_m() const noexcept { return end1_; }
    [[nodiscard]] vec3<T> center_m() const noexcept { return (end0_ + end1_) * T(0.5); }
    /// Unit axis from end 0 to end 1.
    [[nodiscard]] const vec3<T>& axis() const noexcept { return axis_; }
    [[nodiscard]] T length_m() const noexcept { return length_; }
    [[nodiscard]] T radius_m() const noexcept { return radius_; }
    [[nodiscard]] const surface_ids& ids() const noexcept { return ids_; }

    /// The smallest axis-aligned box containing the cylinder: the ends' box grown by the caps' half-extent
    /// a sqrt(1 - u_i^2) along each world axis i, taken as a sqrt(u_j^2 + u_k^2) (the other two components of the unit
    /// axis u). 1 - u_i^2 cancels for an axis near world axis i: for tilts of 1e-6 to 0.1 rad from it, a box grown
    /// by that would fall up to 0.6 mm short of the rims in float (tests/scene/test_cylinder.cpp).
    [[nodiscard]] box<T> bounds() const noexcept {
        const vec3<T> e{radius_ * std::sqrt(axis_.y * axis_.y + axis_.z * axis_.z),
                        radius_ * std::sqrt(axis_.x * axis_.x + axis_.z * axis_.z),
                        radius_ * std::sqrt(axis_.x * axis_.x + axis_.y * axis_.y)};
        return {glm::min(end0_, end1_) - e, glm::max(end0_, end1_) + e};
    }

    /// Nearest crossing with 0 < distance <= t_max_m (primitive.hpp); normals face the ray.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        const auto c = first_crossing(r, t_max_m);
        if (!c) return std::nullopt;
        return hit_at(r, *c);
    }

    /// The hit of ray r at its crossing c (first_crossing's), without solving for the crossing again.
    [[nodiscard]] hit<T> hit_at(const ray<T>& r, const detail::crossing<T>& c) const noexcept {
        vec3<T> n = axis_;
        if (c.where == detail::face::cap_lo) {
            n = -axis_;
        } else if (c.where == detail::face::side) {
            const vec3<T> p = (r.origin - end0_) + r.direction * c.t;
            n = glm::normalize(p - axis_ * glm::dot(p, axis_));
        }
        return detail::make_hit(r, c.t, n, ids_);
    }

    /// The crossing alone (distance, face, whether the ray started inside), without building the hit.
    [[nodiscard]] std::optional<detail::crossing<T>> first_crossing(const ray<T>& r, T t_max_m) const noexcept {
        using detail::face;
        constexpr T inf = std::numeric_limits<T>::infinity();
        const vec3<T> f = r.origin - end0_;
        const T fa = glm::dot(f, axis_), da = glm::dot(r.direction, axis_);
        // The slab between the cap planes.
        T s_in = -inf, s_out = inf;
        face fs_in = face::cap_lo, fs_out = face::cap_hi;
        if (da != T(0)) {
            const T t_lo = -fa / da, t_hi = (length_ - fa) / da;
            if (da > T(0)) {
                s_in = t_lo;
                s_out = t_hi;
            } else {
                s_in = t_hi;
                s_out = t_lo;
                std::swap(fs_in, fs_out);
            }
        } else if (!(fa >= T(0) && fa <= length_)) {
            return std::nullopt;
        }
        // The infinite cylinder about the axis.
        const vec3<T> fp = f - axis_ * fa, dp = r.direction - axis_ * da;
        const T A = glm::dot(dp, dp);
        const T C = glm::dot(fp, fp) - radius2_;
        T c_in = -inf, c_out = inf;
        if (A > T(0)) {
            const T B = glm::dot(fp, dp);
            const vec3<T> w = glm::cross(fp, dp);
            const T disc = A * radius2_ - glm::dot(w, w);
            if (!(disc >= T(0))) return std::nullopt;
            const T q = -(B + std::copysign(std::sqrt(disc), B));
            c_in = q / A;
            c_out = q != T(0) ? C / q : c_in; // q = 0: origin on the side and the ray tangent to it
            if (c_in > c_out) std::swap(c_in, c_out);
        } else if (!(C <= T(0))) {
            return std::nullopt; // parallel to the axis, outside the radius
        }
        const T t_in = std::max(s_in, c_in), t_out = std::min(s_out, c_out);
        const face f_in = s_in >= c_in ? fs_in : face::side;
        const face f_out = s_out <= c_out ? fs_out : face::side;
        detail::crossing<T> out{};
        if (!detail::choose_crossing(t_in, f_in, t_out, f_out, t_max_m, out)) return std::nullopt;
        return out;
    }

private:
    vec3<T> end0_, end1_;
    vec3<T> axis_{};
    T length_{};
    T radius_;
    T radius2_{};
    surface_ids ids_;
};

} // namespace sss::scene
