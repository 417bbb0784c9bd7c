#pragma once
/// \file
/// A plane that is not vertical, given by its height over the horizontal plane: the nominal seabed a side's rays
/// launch for where the seabed slopes (simulator.hpp, sampling/launch_angles.hpp), and what a scene bounds its
/// geometry against (PlaneBoundedScene, scene/concept.hpp).

#include <algorithm>
#include <cmath>

#include "sss/core/types.hpp"

namespace sss::scene {

/// The plane z = z_m + gradient.x (x - at.x) + gradient.y (y - at.y) (world, m; the gradient in m per m).
struct sloping_plane {
    vec2<double> at{};       ///< a point of the horizontal plane (world x, y, m)
    double z_m = 0.0;        ///< the plane's height over `at` (m)
    vec2<double> gradient{}; ///< dz/dx, dz/dy

    /// Height of the plane over (x, y) (m).
    [[nodiscard]] double height_m(double x_m, double y_m) const noexcept {
        return z_m + gradient.x * (x_m - at.x) + gradient.y * (y_m - at.y);
    }
    /// The plane's unit normal, pointing up: (-gx, -gy, 1) / sqrt(1 + gx^2 + gy^2).
    [[nodiscard]] vec3<double> up() const noexcept {
        const double n = std::sqrt(1.0 + gradient.x * gradient.x + gradient.y * gradient.y);
        return vec3<double>{-gradient.x / n, -gradient.y / n, 1.0 / n};
    }
    /// Lowest height of the plane over the rectangle x in [lo.x, hi.x], y in [lo.y, hi.y] (m): a plane is lowest at a
    /// corner.
    [[nodiscard]] double lowest_m(double lo_x, double lo_y, double hi_x, double hi_y) const noexcept {
        return std::min(std::min(height_m(lo_x, lo_y), height_m(hi_x, lo_y)),
                        std::min(height_m(lo_x, hi_y), height_m(hi_x, hi_y)));
    }
};

} // namespace sss::scene
