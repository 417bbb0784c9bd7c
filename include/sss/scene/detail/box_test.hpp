#pragma once
/// \file
/// Internal to the object primitives and their hierarchy: the ray-box test and the padded culling box.
/// Not part of the API.

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/box.hpp"

namespace sss::scene::detail {

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

} // namespace sss::scene::detail
