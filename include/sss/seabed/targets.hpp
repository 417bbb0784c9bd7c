#pragma once
/// \file
/// Builders of real targets from spheres and cylinders, placed on any seabed: a tethered mine, a pipeline
/// with free spans, a cylinder lying on the seabed at any heading, and a seeded debris cluster.
///
/// Every builder reads the seabed through a height function h(x_m, y_m) -> world z (m): any callable, e.g.
/// `seabed_height_of(scene)` for anything that models sss::Scene. Headings are in degrees clockwise from
/// north, as everywhere (docs/conventions.md). All hits of one target carry its object id and class
/// id (the ground-truth label); materials are per part.
///
/// Resting on a seabed is decided in the vertical plane through the target's axis (or route), from the
/// seabed sampled along it every `profile_step_m`; slopes across that plane are ignored, so on a seabed
/// sloping across a pipe or cylinder by beta its upslope side dips into the seabed by up to
/// r (1 - cos beta) (0.4 mm for r = 0.3 m, beta = 3 deg). The profile tools doing the work (a disc resting
/// on a profile, the taut string over it) are in seabed/profile_hull.hpp.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/scene/concept.hpp"
#include "sss/scene/object.hpp"
#include "sss/seabed/detail/resting_cylinder.hpp"
#include "sss/seabed/height_function.hpp"
#include "sss/seabed/lying_cylinder_params.hpp"
#include "sss/seabed/profile_hull.hpp"
#include "sss/seabed/random.hpp"

namespace sss::seabed {

// --------------------------------------------------------------------------------------------------
// Tethered mine

enum class mine_case : unsigned char { sphere, cylinder };

template <Real T> struct tethered_mine_params {
    vec2<T> anchor_m{T(0), T(0)};    ///< world (x, y) of the anchor and of the tether (m)
    T case_height_m = T(5);          ///< height of the case's centre above the seabed at anchor_m (m)
    mine_case shape = mine_case::sphere;
    T case_radius_m = T(0.5);        ///< radius of the case (m), > 0
    T case_length_m = T(1.5);        ///< cylindrical case: length along its axis (m), > 0
    T case_heading_deg = T(90);      ///< cylindrical case: direction of its axis, clockwise from north (deg)
    T case_tilt_deg = T(0);          ///< cylindrical case: axis elevation above horizontal (deg), in [0, 90]
    T tether_radius_m = T(0.01);     ///< tether radius (m), > 0 and < case and anchor radii
    T anchor_radius_m = T(0.4);      ///< anchor: a short vertical cylinder of this radius (m), > 0
    T anchor_height_m = T(0.3);      ///< and this height (m), > 0
    std::uint32_t object_id = 0;     ///< object id of all parts (not sss::no_object)
    std::uint32_t class_id = 1;      ///< class id (ground-truth label) of all parts
    std::uint32_t case_material = 1, tether_material = 1, anchor_material = 1;
};

/// A moored mine: a spherical or cylindrical case with its centre case_height_m above the seabed at
/// anchor_m, a vertical tether from the anchor's top to the case's centre (its part inside the case is
/// hidden), and an anchor resting on the seabed (its flat base at the highest of the seabed heights under
/// its centre and 16 points of its rim). Throws invalid_parameter unless the case clears the anchor.
template <Real T, HeightFunction<T> F>
[[nodiscard]] scene::object<T> tethered_mine(const tethered_mine_params<T>& p, const F& seabed_height_m) {
    sss::require_finite(p.anchor_m.x, "tethered_mine.anchor_m.x");
    sss::require_finite(p.anchor_m.y, "tethered_mine.anchor_m.y");
    require_positive(p.case_height_m, "tethered_mine.case_height_m");
    require_positive(p.case_radius_m, "tethered_mine.case_radius_m");
    require_positive(p.tether_radius_m, "tethered_mine.tether_radius_m");
    require_positive(p.anchor_radius_m, "tethered_mine.anchor_radius_m");
    require_positive(p.anchor_height_m, "tethered_mine.anchor_height_m");
    require(p.tether_radius_m < p.case_radius_m && p.tether_radius_m < p.anchor_radius_m, "tethered_mine.tether_radius_m",
            "must be smaller than the case and anchor radii");
    T down_m = p.case_radius_m; // from the case's centre down to its lowest point
    vec3<T> axis{T(0), T(0), T(1)};
    if (p.shape == mine_case::cylinder) {
        require_positive(p.case_length_m, "tethered_mine.case_length_m");
        sss::require_finite(p.case_heading_deg, "tethered_mine.case_heading_deg");
        sss::require_in_range(p.case_tilt_deg, T(0), T(90), "tethered_mine.case_tilt_deg");
        const T tilt = deg_to_rad(p.case_tilt_deg), az = heading_to_ccw_from_east_rad(p.case_heading_deg);
        const T ct = std::cos(tilt), st = std::sin(tilt);
        axis = vec3<T>{ct * std::cos(az), ct * std::sin(az), st};
        // The lowest point: the lower end's rim, (L/2) sin(tilt) + r cos(tilt) below the centre.
        down_m = p.case_length_m / T(2) * st + p.case_radius_m * ct;
    }
    const T x = p.anchor_m.x, y = p.anchor_m.y;
    const T ground = static_cast<T>(seabed_height_m(x, y));
    sss::require_finite(ground, "tethered_mine.seabed_height_m(anchor)");
    T base = ground;
    for (int k = 0; k < 16; ++k) {
        const T a = two_pi_v<T> * static_cast<T>(k) / T(16);
        const T rx = x + p.anchor_radius_m * std::cos(a), ry = y + p.anchor_radius_m * std::sin(a);
        const T rim = static_cast<T>(seabed_height_m(rx, ry)); // -infinity beyond the seabed: nothing to rest on
        sss::require(!std::isnan(rim) && rim != std::numeric_limits<T>::infinity(), "tethered_mine.seabed_height_m(anchor rim)",
                     [&] { return "is " + std::to_string(rim) + " at (" + std::to_string(rx) + ", " + std::to_string(ry) + ")"; });
        base = std::max(base, rim);
    }
    const T center_z = ground + p.case_height_m, anchor_top = base + p.anchor_height_m;
    require(center_z - down_m > anchor_top, "tethered_mine.case_height_m",
            [&] { return "the case must clear the anchor: its lowest point " + std::to_string(center_z - down_m) +
                " m is not above the anchor's top " + std::to_string(anchor_top) + " m"; });
    if (p.shape == mine_case::cylinder) {
        // A tilted or lying case reaches out beside the anchor: its underside (the generator line under its axis,
        // from end to end) must clear the seabed there too.
        const vec3<T> centre{x, y, center_z};
        const T ct = std::sqrt(std::max(T(0), T(1) - axis.z * axis.z));
        const vec3<T> under = ct > T(0) ? (vec3<T>{T(0), T(0), -T(1)} + axis * axis.z) / ct : vec3<T>{T(1), T(0), T(0)};
        for (int k = 0; k <= 8; ++k) {
            const T s = p.case_length_m * (static_cast<T>(k) / T(8) - T(0.5));
            const vec3<T> q = centre + axis * s + under * p.case_radius_m;
            const T floor_z = static_cast<T>(seabed_height_m(q.x, q.y)); // -infinity beyond the seabed: nothing to clear
            sss::require(!std::isnan(floor_z), "tethered_mine.seabed_height_m(case)", "is not a number under the case");
            require(q.z > floor_z, "tethered_mine.case_height_m", [&] {
                return "the case must clear the seabed: its underside at (" + std::to_string(q.x) + ", " + std::to_string(q.y) +
                       ") lies at " + std::to_string(q.z) + " m, not above the seabed's " + std::to_string(floor_z) + " m";
            });
        }
    }
    const scene::surface_ids case_ids{p.case_material, p.object_id, p.class_id};
    const scene::surface_ids tether_ids{p.tether_material, p.object_id, p.class_id};
    const scene::surface_ids anchor_ids{p.anchor_material, p.object_id, p.class_id};
    // Parts in the mine's frame: origin at the anchor's base centre, z up.
    const T h = center_z - base;
    std::vector<scene::sphere<T>> spheres;
    std::vector<scene::cylinder<T>> cylinders;
    const vec3<T> c{T(0), T(0), h};
    if (p.shape == mine_case::sphere) spheres.emplace_back(c, p.case_radius_m, case_ids);
    else cylinders.emplace_back(c - axis * (p.case_length_m / T(2)), c + axis * (p.case_length_m / T(2)), p.case_radius_m, case_ids);
    cylinders.emplace_back(vec3<T>{T(0), T(0), p.anchor_height_m}, c, p.tether_radius_m, tether_ids);
    cylinders.emplace_back(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(0), T(0), p.anchor_height_m}, p.anchor_radius_m, anchor_ids);
    return scene::object<T>(spheres, cylinders, scene::detail::placement_ccw_rad(vec3<T>{x, y, base}));
}

// --------------------------------------------------------------------------------------------------
// Pipeline

template <Real T> struct pipeline_params {
    std::vector<vec2<T>> route_m;             ///< plan route, world (x, y) (m): >= 2 points, consecutive distinct
    T radius_m = T(0.3);                      ///< outer radius (m), > 0
    T profile_step_m = T(0.1);                ///< seabed sample spacing along the route (m), > 0
    T max_span_m = std::numeric_limits<T>::infinity(); ///< reach of the taut string (m), > 0 (see the file comment)
    T tolerance_m = T(0.001);                 ///< straight runs merged while the axis moves less than this (m), >= 0
    scene::surface_ids ids{.material = 1, .object = 0, .label = 2}; ///< the pipe's ids
};

/// A stretch where the pipe does not touch the seabed.
template <Real T> struct free_span {
    T start_m{}, end_m{}; ///< along-route distances where the pipe leaves and meets the seabed (m)
    T clearance_m{};      ///< largest height of the pipe above where it would rest on the seabed (m)
};

template <Real T> struct pipeline_layout {
    std::vector<vec3<T>> axis_m;          ///< vertices of the pipe's axis, world (m)
    std::vector<T> axis_s_m;              ///< their along-route distances (m)
    std::vector<free_span<T>> spans;      ///< the free spans, in route order
};

/// Lays a pipe along the route: its axis is the taut string (reach max_span_m) over the heights at which a
/// disc of the pipe's radius rests on the seabed profile along the route; it therefore touches the seabed
/// where supported and spans depressions in straight lines. Straight runs are merged (tolerance_m) and the
/// route's vertices are kept as axis vertices. A free span is a run of samples where the axis lies above
/// the resting height by more than max(tolerance_m, 1 mm); it is reported from the last sample before the
/// run to the first after it.
template <Real T, HeightFunction<T> F>
[[nodiscard]] pipeline_layout<T> lay_pipeline(const pipeline_params<T>& p, const F& seabed_height_m) {
    const auto& route = p.route_m;
    sss::require(route.size() >= 2, "pipeline.route_m", "needs at least 2 points");
    sss::require_positive(p.radius_m, "pipeline.radius_m");
    sss::require_positive(p.profile_step_m, "pipeline.profile_step_m");
    sss::require(p.max_span_m > T(0), "pipeline.max_span_m", "must be > 0 (infinity: unlimited)");
    sss::require_non_negative(p.tolerance_m, "pipeline.tolerance_m");
    std::vector<T> leg_s{T(0)};
    for (std::size_t i = 0; i < route.size(); ++i) {
        const std::string name = "pipeline.route_m[" + std::to_string(i) + "]";
        sss::require_finite(route[i].x, name + ".x");
        sss::require_finite(route[i].y, name + ".y");
        if (i == 0) continue;
        const T len = glm::length(route[i] - route[i - 1]);
        sss::require(len > T(0), name, "must differ from the point before it");
        leg_s.push_back(leg_s.back() + len);
    }
    const T total = leg_s.back();
    sss::require(total / p.profile_step_m < T(1e8), "pipeline.profile_step_m", "gives more than 1e8 samples");
    // Plan position at along-route distance s.
    auto plan_at = [&](T s) {
        const auto it = std::upper_bound(leg_s.begin() + 1, leg_s.end() - 1, s);
        const std::size_t k = static_cast<std::size_t>(it - leg_s.begin()); // leg from route[k-1] to route[k]
        const T f = (s - leg_s[k - 1]) / (leg_s[k] - leg_s[k - 1]);
        return route[k - 1] + (route[k] - route[k - 1]) * f;
    };
    // Samples every profile_step_m and at the route's vertices; a sample closer than step/1000 to a
    // vertex gives way to it.
    const T close = p.profile_step_m / T(1000);
    auto merged = [&](std::vector<T> regular) {
        std::vector<T> m;
        std::size_t j = 0;
        for (std::size_t i = 0; i < leg_s.size(); ++i) {
            for (; j < regular.size() && regular[j] < leg_s[i]; ++j)
                if (regular[j] - (m.empty() ? -std::numeric_limits<T>::infinity() : m.back()) >= close &&
                    leg_s[i] - regular[j] >= close)
                    m.push_back(regular[j]);
            if (m.empty() || m.back() < leg_s[i]) m.push_back(leg_s[i]);
        }
        return m;
    };
    const auto steps = static_cast<std::size_t>(std::ceil(total / p.profile_step_m));
    std::vector<T> regular;
    for (std::size_t k = 1; k < steps; ++k) regular.push_back(static_cast<T>(k) * p.profile_step_m);
    const std::vector<T> s = merged(std::move(regular));
    std::vector<T> z(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) {
        const vec2<T> q = plan_at(s[i]);
        z[i] = static_cast<T>(seabed_height_m(q.x, q.y));
        sss::require_finite(z[i], "pipeline.seabed_height_m(route)");
    }
    const std::vector<T> rest = disc_rest_heights<T>(s, z, p.radius_m);
    const std::vector<std::size_t> sup = taut_string<T>(s, rest, p.max_span_m);

    pipeline_layout<T> out;
    const T span_floor = std::max(p.tolerance_m, T(0.001));
    for (std::size_t k = 0; k + 1 < sup.size(); ++k) {
        const std::size_t a = sup[k], b = sup[k + 1];
        free_span<T> run{};
        bool open = false;
        for (std::size_t i = a + 1; i <= b; ++i) {
            const T gap = i == b ? T(0) : rest[a] + (rest[b] - rest[a]) * (s[i] - s[a]) / (s[b] - s[a]) - rest[i];
            if (gap > span_floor) {
                if (!open) run = {s[i - 1], s[i], gap};
                open = true;
                run.clearance_m = std::max(run.clearance_m, gap);
            } else if (open) {
                run.end_m = s[i];
                out.spans.push_back(run);
                open = false;
            }
        }
    }
    // Merge supports while the dropped ones stay within tolerance of the chord.
    std::vector<T> kept_s;
    std::vector<T> kept_z;
    std::size_t from = 0; // index in sup of the last kept support
    kept_s.push_back(s[sup[0]]);
    kept_z.push_back(rest[sup[0]]);
    for (std::size_t k = 1; k < sup.size(); ++k) {
        bool drop = k + 1 < sup.size();
        if (drop) {
            const std::size_t a = sup[from], c = sup[k + 1];
            for (std::size_t j = from + 1; drop && j <= k; ++j) {
                const std::size_t i = sup[j];
                drop = std::abs(rest[a] + (rest[c] - rest[a]) * (s[i] - s[a]) / (s[c] - s[a]) - rest[i]) <= p.tolerance_m;
            }
        }
        if (drop) continue;
        kept_s.push_back(s[sup[k]]);
        kept_z.push_back(rest[sup[k]]);
        from = k;
    }
    // Axis vertices: the kept supports and the route's vertices, on the string.
    const std::vector<T> vs = merged(std::vector<T>(kept_s.begin() + 1, kept_s.end() - 1));
    std::size_t seg = 0;
    for (const T sv : vs) {
        while (seg + 2 < kept_s.size() && kept_s[seg + 1] < sv) ++seg;
        const T f = (sv - kept_s[seg]) / (kept_s[seg + 1] - kept_s[seg]);
        const vec2<T> q = plan_at(sv);
        out.axis_m.push_back(vec3<T>{q.x, q.y, kept_z[seg] + (kept_z[seg + 1] - kept_z[seg]) * f});
        out.axis_s_m.push_back(sv);
    }
    return out;
}

/// The pipe itself: one cylinder per axis segment, a sphere of the pipe's radius at every inner axis
/// vertex (the joints are smooth and closed), flat ends.
template <Real T> [[nodiscard]] scene::object<T> pipeline_object(const pipeline_layout<T>& l, const pipeline_params<T>& p) {
    sss::require(l.axis_m.size() >= 2, "pipeline.layout.axis_m", "needs at least 2 vertices");
    std::vector<scene::sphere<T>> joints;
    std::vector<scene::cylinder<T>> segments;
    for (std::size_t i = 0; i + 1 < l.axis_m.size(); ++i) {
        segments.emplace_back(l.axis_m[i], l.axis_m[i + 1], p.radius_m, p.ids);
        if (i > 0) joints.emplace_back(l.axis_m[i], p.radius_m, p.ids);
    }
    return scene::object<T>(joints, segments);
}

/// lay_pipeline then pipeline_object.
template <Real T, HeightFunction<T> F>
[[nodiscard]] scene::object<T> pipeline(const pipeline_params<T>& p, const F& seabed_height_m) {
    return pipeline_object(lay_pipeline(p, seabed_height_m), p);
}

// --------------------------------------------------------------------------------------------------
// A cylinder lying on the seabed

/// A rigid cylinder resting on the seabed: in the vertical plane of its axis its lower edge lies on the
/// edge of the profile's upper hull (the taut string) under its middle, the lowest position of its middle
/// that keeps it above the seabed; its axis is that edge lifted by the radius, perpendicular to it.
template <Real T, HeightFunction<T> F>
[[nodiscard]] scene::object<T> lying_cylinder(const lying_cylinder_params<T>& p, const F& seabed_height_m) {
    sss::require_finite(p.heading_deg, "lying_cylinder.heading_deg");
    const T theta = heading_to_ccw_from_east_rad(p.heading_deg);
    return detail::lying_cylinder_along(p, vec2<T>{std::cos(theta), std::sin(theta)}, seabed_height_m);
}

// --------------------------------------------------------------------------------------------------
// Debris

template <Real T> struct debris_params {
    vec2<T> center_m{T(0), T(0)};  ///< centre of the cluster, world (x, y) (m)
    T radius_m = T(5);             ///< pieces lie uniformly within this distance of the centre (m), > 0
    std::size_t count = 8;         ///< number of pieces, >= 1
    std::uint64_t seed = 1;        ///< the same seed gives the same cluster on every platform
    T min_size_m = T(0.15);        ///< smallest size of a piece (m), > 0
    T max_size_m = T(0.8);         ///< largest size (m), >= min_size_m
    T max_burial = T(0.3);         ///< largest buried fraction of a rock's diameter, in [0, 0.9]
    std::uint32_t first_object_id = 0; ///< piece k gets object id first_object_id + k
    std::uint32_t class_id = 4;
    std::uint32_t material = 1;
};

/// A reproducible cluster of `count` pieces, each its own object, drawn in turn from sss::seabed::rng(seed):
/// position (uniform in the disc), size d (uniform in [min, max]), and kind (one third each):
/// a rock (sphere of diameter d, a fraction in [0, max_burial] of it buried), a bar (lying_cylinder of length
/// d, radius d x [0.06, 0.2], random heading) or a drum (upright cylinder of height d, radius d x [0.25, 0.45],
/// its base at the highest seabed point under its centre and 8 rim points).
template <Real T, HeightFunction<T> F>
[[nodiscard]] std::vector<scene::object<T>> debris_cluster(const debris_params<T>& p, const F& seabed_height_m) {
    sss::require_finite(p.center_m.x, "debris.center_m.x");
    sss::require_finite(p.center_m.y, "debris.center_m.y");
    sss::require_positive(p.radius_m, "debris.radius_m");
    sss::require(p.count >= 1 && p.count <= 1000000, "debris.count", "must lie in [1, 10^6]");
    sss::require_positive(p.min_size_m, "debris.min_size_m");
    sss::require_finite(p.max_size_m, "debris.max_size_m");
    sss::require(p.max_size_m >= p.min_size_m, "debris.max_size_m", "must be >= min_size_m");
    sss::require_in_range(p.max_burial, T(0), T(0.9), "debris.max_burial");
    sss::require(std::uint64_t(p.first_object_id) + p.count <= std::uint64_t(no_object), "debris.first_object_id",
                         "the pieces' ids would reach sss::no_object");
    // The seabed under piece k: finite (a drum's rim may also lie beyond the seabed, -infinity), or an error naming
    // the cluster and the piece rather than the primitive the piece would have been built as.
    const auto ground = [&](std::size_t k, T qx, T qy, bool rim = false) {
        const T z = static_cast<T>(seabed_height_m(qx, qy));
        sss::require(std::isfinite(z) || (rim && z == -std::numeric_limits<T>::infinity()), "debris.seabed_height_m", [&] {
            return "is " + std::to_string(z) + " at (" + std::to_string(qx) + ", " + std::to_string(qy) + ") under piece " +
                   std::to_string(k) + ": every piece must lie on the seabed";
        });
        return z;
    };
    rng g(p.seed);
    std::vector<scene::object<T>> out;
    out.reserve(p.count);
    for (std::size_t k = 0; k < p.count; ++k) {
        const double rr = double(p.radius_m) * std::sqrt(g.uniform()), az = two_pi_v<double> * g.uniform();
        const T x = p.center_m.x + static_cast<T>(rr * std::cos(az)), y = p.center_m.y + static_cast<T>(rr * std::sin(az));
        const T d = static_cast<T>(g.uniform(double(p.min_size_m), double(p.max_size_m)));
        const double kind = g.uniform(), u1 = g.uniform(), u2 = g.uniform();
        const scene::surface_ids ids{
            .material = p.material, .object = p.first_object_id + static_cast<std::uint32_t>(k), .label = p.class_id};
        if (kind < 1.0 / 3.0) { // rock
            const T r = d / T(2), buried = static_cast<T>(u1) * p.max_burial * d;
            const T zc = ground(k, x, y) + r - buried;
            out.emplace_back(std::vector<scene::sphere<T>>{scene::sphere<T>(vec3<T>{x, y, zc}, r, ids)},
                             std::vector<scene::cylinder<T>>{});
        } else if (kind < 2.0 / 3.0) { // bar
            lying_cylinder_params<T> c;
            c.center_m = {x, y};
            const T az_piece = static_cast<T>(two_pi_v<double> * u1); // its axis, counter-clockwise from east
            c.length_m = d;
            c.radius_m = d * static_cast<T>(0.06 + 0.14 * u2);
            c.profile_step_m = std::min(c.radius_m, d / T(8));
            c.ids = ids;
            out.push_back(detail::lying_cylinder_along(c, vec2<T>{std::cos(az_piece), std::sin(az_piece)},
                                                       [&](T qx, T qy) { return ground(k, qx, qy); }));
        } else { // drum
            const T r = d * static_cast<T>(0.25 + 0.2 * u1);
            T base = ground(k, x, y);
            for (int j = 0; j < 8; ++j) {
                const T a = two_pi_v<T> * static_cast<T>(j) / T(8);
                base = std::max(base, ground(k, x + r * std::cos(a), y + r * std::sin(a), true));
            }
            out.emplace_back(std::vector<scene::sphere<T>>{},
                             std::vector<scene::cylinder<T>>{scene::cylinder<T>(vec3<T>{x, y, base}, vec3<T>{x, y, base + d}, r, ids)});
        }
    }
    return out;
}

} // namespace sss::seabed
