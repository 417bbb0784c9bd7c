#pragma once
/// \file
/// A composite object: spheres and capped cylinders given in the object's own frame, placed in the world
/// by one rigid transform (rotation, then translation).
///
/// Spheres and cylinders stay spheres and cylinders under a rigid transform, so the object stores its
/// primitives already placed (world coordinates): intersection costs no per-ray transform, and the
/// distances, normals and ids are those of the placed primitives. An object intersects its primitives
/// one by one behind a test of its bounding box; for many objects, or objects of many primitives (a long
/// pipeline), put them in an object_set, whose hierarchy spans every primitive.
///
/// Frames: the object frame is right-handed (+x forward, +y left, +z up); `placement({.position_m, .heading_deg,
/// .pitch_deg, .roll_deg})` follows docs/conventions.md: heading clockwise from north turns the object's +x
/// axis (90 deg: east, the unturned frame), then pitch raises its +x end, then roll turns it about its own
/// +x axis (right-handed: the right side goes down), i.e. R = Rz(90 deg - heading) Ry(-pitch) Rx(roll).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/cylinder.hpp"
#include "sss/scene/detail/placement.hpp"
#include "sss/scene/primitive.hpp"
#include "sss/scene/rigid_transform.hpp"
#include "sss/scene/sphere.hpp"

namespace sss::scene {

/// Where an object stands: its frame's origin and attitude (see the file comment).
template <Real T> struct placement_params {
    vec3<T> position_m{};   ///< world position of the object frame's origin (m)
    T heading_deg = T(90);  ///< direction of the object's +x axis, clockwise from north (deg); 90: east (no turn)
    T pitch_deg = T(0);     ///< +x end up positive (deg)
    T roll_deg = T(0);      ///< about +x, the +y (left) side up positive, i.e. the right side down (deg)
};

/// The placement R = Rz(90 deg - heading) Ry(-pitch) Rx(roll) at `position_m`.
template <Real T> [[nodiscard]] rigid_transform<T> placement(const placement_params<T>& p) noexcept {
    return detail::placement_ccw_rad(p.position_m, heading_to_ccw_from_east_rad(p.heading_deg), deg_to_rad(p.pitch_deg),
                                     deg_to_rad(p.roll_deg));
}

/// Throws invalid_parameter naming `name` unless `x` is finite and its rotation is proper to within
/// 1e-4 (float) or 1e-9 (double) in every entry of R^T R - I and in det R - 1.
template <Real T> void require_rigid(const rigid_transform<T>& x, const std::string& name) {
    detail::require_finite_vec(x.translation_m, name + ".translation_m");
    const T tol = sizeof(T) == 4 ? T(1e-4) : T(1e-9);
    const mat3<T> g = glm::transpose(x.rotation) * x.rotation;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
            sss::require_finite(x.rotation[c][r], name + ".rotation");
            sss::require(std::abs(g[c][r] - (c == r ? T(1) : T(0))) <= tol, name + ".rotation",
                                 "must be orthonormal (R^T R = I)");
        }
    sss::require(std::abs(glm::determinant(x.rotation) - T(1)) <= tol, name + ".rotation",
                         "must be a proper rotation (determinant +1, no reflection)");
}

/// A bounding sphere (m).
template <Real T> struct bounding_sphere {
    vec3<T> center_m{};
    T radius_m{};
};

template <Real T> class object {
public:
    using value_type = T;

    /// \param spheres, cylinders primitives in the object's frame (at least one in all)
    /// \param where              the object's placement in the world (a proper rotation; see require_rigid)
    object(const std::vector<sphere<T>>& spheres, const std::vector<cylinder<T>>& cylinders,
           const rigid_transform<T>& where = {})
        : placement_(where) {
        sss::require(!spheres.empty() || !cylinders.empty(), "object.primitives",
                             "an object needs at least one sphere or cylinder");
        require_rigid(where, "object.placement");
        spheres_.reserve(spheres.size());
        cylinders_.reserve(cylinders.size());
        for (const sphere<T>& s : spheres) spheres_.emplace_back(where.point(s.center_m()), s.radius_m(), s.ids());
        for (const cylinder<T>& c : cylinders)
            cylinders_.emplace_back(where.point(c.end0_m()), where.point(c.end1_m()), c.radius_m(), c.ids());
        for (const sphere<T>& s : spheres_) bounds_.expand(s.bounds());
        for (const cylinder<T>& c : cylinders_) bounds_.expand(c.bounds());
        padded_ = detail::padded(bounds_);
        sphere_.center_m = bounds_.center();
        for (const sphere<T>& s : spheres_)
            sphere_.radius_m = std::max(sphere_.radius_m, glm::length(s.center_m() - sphere_.center_m) + s.radius_m());
        for (const cylinder<T>& c : cylinders_) {
            const T half = c.length_m() / T(2);
            sphere_.radius_m = std::max(sphere_.radius_m, glm::length(c.center_m() - sphere_.center_m) +
                                                              std::sqrt(half * half + c.radius_m() * c.radius_m()));
        }
    }

    /// Primitives as placed in the world.
    [[nodiscard]] const std::vector<sphere<T>>& spheres() const noexcept { return spheres_; }
    [[nodiscard]] const std::vector<cylinder<T>>& cylinders() const noexcept { return cylinders_; }
    [[nodiscard]] std::size_t primitive_count() const noexcept { return spheres_.size() + cylinders_.size(); }
    [[nodiscard]] const rigid_transform<T>& placement() const noexcept { return placement_; }

    /// World axis-aligned box containing every primitive (exact per primitive).
    [[nodiscard]] const box<T>& bounds() const noexcept { return bounds_; }
    /// A sphere containing every primitive (centred on the box; not the smallest).
    [[nodiscard]] const bounding_sphere<T>& bounding() const noexcept { return sphere_; }
    /// Highest world z of the object (m).
    [[nodiscard]] T top_m() const noexcept { return bounds_.hi.z; }

    /// Nearest hit over the primitives with 0 < distance <= t_max_m (behind a test of the bounding box).
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        std::optional<hit<T>> best;
        T t_entry;
        if (!detail::hits_box(padded_, detail::box_ray<T>(r), t_max_m, t_entry)) return best;
        T t_best = t_max_m;
        for (const sphere<T>& s : spheres_)
            if (auto h = s.intersect(r, t_best)) {
                t_best = h->distance_m;
                best = h;
            }
        for (const cylinder<T>& c : cylinders_)
            if (auto h = c.intersect(r, t_best)) {
                t_best = h->distance_m;
                best = h;
            }
        return best;
    }

private:
    std::vector<sphere<T>> spheres_;
    std::vector<cylinder<T>> cylinders_;
    rigid_transform<T> placement_;
    box<T> bounds_{};
    box<T> padded_{}; // bounds_ grown by a few ulps: rounding in the box test never culls a hit
    bounding_sphere<T> sphere_{};
};

} // namespace sss::scene
