#pragma once
/// \file
/// Axis-aligned boxes: the bounds of object primitives and objects. Part of scene/primitive.hpp, which includes it.

#include <limits>

#include <glm/common.hpp>

#include "sss/core/types.hpp"

namespace sss::scene {

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

} // namespace sss::scene
