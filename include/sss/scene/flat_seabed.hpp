#pragma once
/// \file
/// The flat seabed: the horizontal plane z = height_m, one material and one region.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/concept.hpp"
#include "sss/scene/sloping_plane.hpp"

namespace sss::scene {

template <Real T> class flat_seabed {
public:
    using value_type = T;

    /// \param height_m world z of the seabed (m)
    /// \param material scattering material id
    /// \param region   seabed region id (the ground-truth label of its returns)
    explicit flat_seabed(T height_m = T(0), std::uint32_t material = 0, std::uint32_t region = 0)
        : height_m_(height_m), material_(material), region_(region) {
        sss::require_finite(height_m, "flat_seabed.height_m");
    }

    /// Nearest hit of a downward-going ray with the plane from above (rays from below or parallel miss).
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        const T dz = r.direction.z;
        const T above = r.origin.z - height_m_;
        if (!(dz < T(0)) || !(above > T(0))) return std::nullopt;
        const T s = above / -dz;
        if (!(s <= t_max_m)) return std::nullopt;
        // Built in place in the returned optional (no copy of the record through the stack).
        std::optional<hit<T>> out(std::in_place);
        hit<T>& h = *out;
        h.distance_m = s;
        h.point = vec3<T>{r.origin.x + r.direction.x * s, r.origin.y + r.direction.y * s, height_m_};
        h.normal = vec3<T>{T(0), T(0), T(1)};
        h.shading_normal = h.normal;
        h.material = material_;
        h.object = no_object;
        h.label = region_;
        return out;
    }

    /// How far r runs with the seabed more than band_m below it (ClearanceScene): t_max_m, where r lowered by
    /// band_m meets the plane, or 0 where it starts on or below it.
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const noexcept {
        const T above = r.origin.z - band_m - height_m_;
        if (!(band_m >= T(0)) || !(above > T(0))) return T(0);
        if (!(r.direction.z < T(0))) return t_max_m;
        return std::min(t_max_m, above / -r.direction.z);
    }

    [[nodiscard]] T seabed_height_m(T, T) const noexcept { return height_m_; }
    [[nodiscard]] T top_m() const noexcept { return height_m_; }
    /// The plane lies under every rectangle.
    [[nodiscard]] T top_m(const vec2<T>&, const vec2<T>&) const noexcept { return height_m_; }
    /// How far the seabed rises above `plane` over the rectangle [lo, hi] (PlaneBoundedScene): exactly, at a corner.
    [[nodiscard]] double rise_above_m(const vec2<T>& lo, const vec2<T>& hi, const sloping_plane& plane) const noexcept {
        return double(height_m_) - plane.lowest_m(double(lo.x), double(lo.y), double(hi.x), double(hi.y));
    }

private:
    T height_m_;
    std::uint32_t material_;
    std::uint32_t region_;
};

static_assert(Scene<flat_seabed<float>> && Scene<flat_seabed<double>>);

} // namespace sss::scene
