#pragma once
/// \file
/// The part of the plane that one side of one ping can reach: the horizontal rectangle (world x, y) that every ray
/// launched within the side's beam extent stays over for its whole one-way time.
///
/// A ray that keeps its heading (straight rays; rays refracted in horizontally layered water, which stay in the
/// vertical plane of their launch) and moves at most k t sqrt(d.x^2 + d.y^2) horizontally in one-way time t
/// (propagation: ReachBoundedPropagation) stays on the segment from its origin to origin + k t (d.x, d.y), d its
/// unit launch direction in the world. The rectangle is the bounding box of those segments over every direction
/// of the extent, widened by a margin. Its corners come from the extent's four edges, each sampled at 17 angles
/// (between two samples the horizontal part of a unit direction leaves their chord by at most delta^2 / 8, delta
/// the angle between them: below 0.5 % of the reach for edges up to pi long), and from the four horizontal world axes where they lie inside the
/// extent (the only directions inside it where a horizontal component can be extreme). The margin (1 % of the
/// reach) covers both with room to spare. A bounced path (specular_bounce) changes heading at the seabed: its
/// rectangle is the square of half-side k t around the origin.

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/matrix.hpp>

#include "sss/beam/concept.hpp"
#include "sss/core/pose.hpp"
#include "sss/core/types.hpp"

namespace sss {

/// A rectangle of the horizontal plane: x in [lo.x, hi.x], y in [lo.y, hi.y] (world, m).
template <Real T> struct plane_rectangle {
    vec2<T> lo{};
    vec2<T> hi{};
};

/// The rectangle that the rays of side `sd` launched from pose `p` within `ext` stay over, each reaching at most
/// `reach_m` = k t (see the file comment); with `keeps_heading` false, the square of half-side reach_m.
template <Real T>
[[nodiscard]] plane_rectangle<T> side_reach(const pose<T>& p, side sd, const beam_extent<T>& ext, double reach_m,
                                            bool keeps_heading) {
    const double x0 = double(p.position.x), y0 = double(p.position.y);
    const double margin = 0.01 * reach_m + 64.0 * std::numeric_limits<T>::epsilon() * (std::abs(x0) + std::abs(y0) + reach_m);
    if (!keeps_heading) {
        const double r = reach_m + margin;
        return {vec2<T>{static_cast<T>(x0 - r), static_cast<T>(y0 - r)}, vec2<T>{static_cast<T>(x0 + r), static_cast<T>(y0 + r)}};
    }
    double lo_x = x0, hi_x = x0, lo_y = y0, hi_y = y0;
    const auto add_world = [&](double dx, double dy) {
        lo_x = std::min(lo_x, x0 + reach_m * dx);
        hi_x = std::max(hi_x, x0 + reach_m * dx);
        lo_y = std::min(lo_y, y0 + reach_m * dy);
        hi_y = std::max(hi_y, y0 + reach_m * dy);
    };
    const auto add = [&](double a, double e) {
        const vec3<T> d = p.to_world(beam_direction(sd, static_cast<T>(a), static_cast<T>(e)));
        add_world(double(d.x), double(d.y));
    };
    const double a0 = double(ext.along_min_rad), a1 = double(ext.along_max_rad);
    const double e0 = double(ext.depression_min_rad), e1 = double(ext.depression_max_rad);
    constexpr int steps = 16;
    for (int i = 0; i <= steps; ++i) {
        const double f = double(i) / steps;
        const double a = a0 + (a1 - a0) * f, e = e0 + (e1 - e0) * f;
        add(a0, e);
        if (a1 == a0) { // one along-track angle (a column): the other edges repeat this one's points
            if (i == steps) add(a0, e1);
            continue;
        }
        add(a1, e);
        add(a, e0);
        add(a, e1);
    }
    // The horizontal world axes, where inside the extent: body direction b = R^T axis, along = asin(b.x),
    // depression = atan2(b.z, side_sign b.y) (beam_direction inverted).
    const double s = double(side_sign<T>(sd));
    const double axes[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& ax : axes) {
        const vec3<T> w{static_cast<T>(ax[0]), static_cast<T>(ax[1]), T(0)};
        const vec3<T> b = glm::transpose(p.body_to_world) * w;
        const double a = std::asin(std::clamp(double(b.x), -1.0, 1.0));
        const double e = std::atan2(double(b.z), s * double(b.y));
        if (a >= a0 && a <= a1 && e >= e0 && e <= e1) add_world(ax[0], ax[1]);
    }
    return {vec2<T>{static_cast<T>(lo_x - margin), static_cast<T>(lo_y - margin)},
            vec2<T>{static_cast<T>(hi_x + margin), static_cast<T>(hi_y + margin)}};
}

} // namespace sss
