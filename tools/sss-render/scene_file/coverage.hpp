#pragma once
/// \file
/// Coverage problems of a scene, reported rather than left to show as black: a track or a swath that leaves
/// the seabed, a towfish less than 1 mm above the seabed.

#include "build.hpp"
#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace sss::scene_file {

/// The seabed's plan extent: west, south, east, north edges (m).
struct extent {
    double west_m = 0, south_m = 0, east_m = 0, north_m = 0;
};

[[nodiscard]] inline extent extent_of(const description& d) {
    const auto& b = d.bed;
    return {b.origin_m[0], b.origin_m[1], b.origin_m[0] + double(b.nx - 1) * b.cell_m, b.origin_m[1] + double(b.ny - 1) * b.cell_m};
}
template <Real T> [[nodiscard]] extent extent_of(const sss::scene::height_field<T>& h) {
    const double x0 = h.origin_m().x, y0 = h.origin_m().y, c = h.cell_m();
    return {x0, y0, x0 + double(h.nx() - 1) * c, y0 + double(h.ny() - 1) * c};
}

/// The problems of pings [first, first + count) of motion `tow` (motion_of(d, altitude_m)), every ping checked: for
/// the towfish and each swath edge that leaves the seabed, a sentence naming how many pings, the first of them and
/// the edges it crosses there. Planar geometry: the swath reaches sqrt(max_range^2 - altitude^2) to each side of the
/// track; the altitude is altitude_m, or with a trajectory each ping's z (a seabed near z = 0).
template <Real T>
[[nodiscard]] std::vector<std::string> swath_problems(const description& d, const extent& e, const scene_motion<T>& tow, std::size_t first,
                                                      std::size_t count) {
    std::vector<std::string> out;
    const bool sampled = d.tow.model == "trajectory";
    const double r = d.sensor.max_range_m;
    double alt = d.tow.altitude_m;
    // Distances printed to the millimetre (a float track's 0.699999 m reads 0.7 m).
    const auto mm = [](double v) { return detail::fmt(std::round(v * 1e3) / 1e3); };
    struct beyond {
        const char* what = "";
        std::size_t pings = 0, first_ping = 0;
        std::string edges{}; // at the first such ping
    } parts[3];
    parts[0].what = "the towfish";
    parts[1].what = "the port swath edge";
    parts[2].what = "the starboard swath edge";
    auto check = [&](beyond& b, std::size_t ping, double x, double y) {
        std::string edges;
        if (x < e.west_m - 1e-9) edges += " west by " + mm(e.west_m - x) + " m";
        if (x > e.east_m + 1e-9) edges += " east by " + mm(x - e.east_m) + " m";
        if (y < e.south_m - 1e-9) edges += " south by " + mm(e.south_m - y) + " m";
        if (y > e.north_m + 1e-9) edges += " north by " + mm(y - e.north_m) + " m";
        if (edges.empty()) return;
        if (b.pings++ == 0) {
            b.first_ping = ping;
            b.edges = edges;
        }
    };
    double lowest = sampled && count > 0 ? std::numeric_limits<double>::infinity() : alt; // a trajectory: its pings' z
    for (std::size_t ping = first; ping < first + count; ++ping) {
        const auto pose = tow.nominal_pose_at(ping);
        if (sampled) alt = pose.position.z;
        lowest = std::min(lowest, alt);
        const double reach = r > alt ? std::sqrt(r * r - alt * alt) : 0.0;
        const double x = pose.position.x, y = pose.position.y;
        const auto f = pose.to_world({T(1), T(0), T(0)});
        const double fl = std::hypot(double(f.x), double(f.y));
        const double fx = double(f.x) / fl, fy = double(f.y) / fl; // forward; starboard is (fy, -fx)
        check(parts[0], ping, x, y);
        check(parts[1], ping, x - reach * fy, y + reach * fx);
        check(parts[2], ping, x + reach * fy, y - reach * fx);
    }
    for (const beyond& b : parts)
        if (b.pings > 0)
            out.push_back(std::string(b.what) + (b.pings == 1 ? " at ping " + std::to_string(b.first_ping)
                                                                 : " at " + std::to_string(b.pings) + " of " + std::to_string(count) +
                                                                       " pings, first at ping " + std::to_string(b.first_ping) + ",") +
                          " lies beyond the seabed:" + b.edges);
    if (!(r > lowest)) {
        out.push_back("sonar.max_range_m (" + detail::fmt(r) + " m) does not reach the seabed " + mm(lowest) +
                      " m below: the image holds only water");
    } else if (count > 0) {
        // The range reaches the seabed, but the beam's steepest ray may meet it only beyond the range (a level
        // towfish over a level seabed at the lowest altitude).
        const double steepest = double(beam_of<T>(d).extent(sss::side::starboard).depression_max_rad);
        const double nearest = steepest > 0 ? lowest / std::sin(std::min(steepest, 1.5707963267948966))
                                            : std::numeric_limits<double>::infinity();
        if (nearest > r)
            out.push_back("the beam's steepest ray (depression " + mm(steepest * 57.29577951308232) + " deg) meets the seabed " +
                          mm(lowest) + " m below at " + (std::isfinite(nearest) ? mm(nearest) + " m" : std::string("no range")) +
                          ", beyond sonar.max_range_m (" + detail::fmt(r) + " m): the image holds only water");
    }
    return out;
}

/// The pings among [first, first + count) where the towfish is less than the simulator's least clearance (1 mm)
/// above the seabed (the first one), or "".
template <Real T>
[[nodiscard]] std::string below_seabed(const world<T>& w, const scene_motion<T>& tow, std::size_t first, std::size_t count) {
    for (std::size_t ping = first; ping < first + count; ++ping) {
        const auto pose = tow.pose_at(ping);
        const T z = pose.position.z;
        const T ground = w.seabed().seabed_height_m(pose.position.x, pose.position.y);
        if (std::isfinite(ground) && !(double(z) - double(ground) >= sss::simulator<>::min_clearance_m))
            return "the towfish (z " + detail::fmt(z) + " m) is not at least 1 mm above the seabed (z " +
                   detail::fmt(ground) + " m) at ping " + std::to_string(ping);
    }
    return "";
}

/// Where the towfish lies inside an object's solid (one of its spheres or cylinders): the object's index and the
/// ping, the first such among [first, first + count). Rays from inside an object meet its surface from within
/// (primitive.hpp), so that ping would image the inside of a casing: the scene is wrong (an object in the towfish's
/// path, or the towfish too low).
struct towfish_in_object {
    std::size_t object = 0;
    std::size_t ping = 0;
};
template <Real T>
[[nodiscard]] std::optional<towfish_in_object> inside_object(const world<T>& w, const scene_motion<T>& tow, std::size_t first,
                                                             std::size_t count) {
    const auto& set = w.objects();
    if (set.empty()) return std::nullopt;
    const auto& objects = set.objects();
    // Whether p is inside a solid: a ray from p (any direction: up) meets the solid from within.
    const auto inside = [](const auto& solids, const sss::vec3<T>& p) {
        const sss::ray<T> up{p, sss::vec3<T>{T(0), T(0), T(1)}};
        for (const auto& s : solids)
            if (s.bounds().contains(p))
                if (const auto c = s.first_crossing(up, std::numeric_limits<T>::infinity()); c && c->from_inside) return true;
        return false;
    };
    for (std::size_t ping = first; ping < first + count; ++ping) {
        const sss::vec3<T> p = tow.pose_at(ping).position;
        if (!set.bounds().contains(p)) continue;
        for (std::size_t k = 0; k < objects.size(); ++k)
            if (objects[k].bounds().contains(p) && (inside(objects[k].spheres(), p) || inside(objects[k].cylinders(), p)))
                return towfish_in_object{.object = k, .ping = ping};
    }
    return std::nullopt;
}

} // namespace sss::scene_file
