// Layered water: the propagation policy that refracts rays through a sound-speed profile, checked against the
// closed-form constant-gradient arc, the straight-ray policy in uniform water, finite differences of the ray
// family (ray-tube spreading), reciprocity, the long-double layered oracle, and the hard cases (ducts, horizontal
// launches, a turning point on the seabed, a thousand thin layers, the sea surface).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/propagation/layered.hpp"
#include "sss/propagation/straight.hpp"
#include "sss/scene/flat_seabed.hpp"
#include "sss/scene/height_field.hpp"
#include "sss/scene/object_set.hpp"
#include "sss/scene/scene.hpp"
#include "support/layered_oracle.hpp"

using namespace sss;
using namespace sss::propagation;
using ld = long double;

namespace {

constexpr double deg = 3.14159265358979323846 / 180;

double rel(double got, long double want) {
    return want == 0 ? std::abs(got) : static_cast<double>(std::abs((static_cast<ld>(got) - want) / want));
}

// A ray from depth depth_m below a surface at world z surface_z, going down at grazing angle graze (rad; negative
// is up) towards azimuth az (rad, from +x).
template <class T> ray<T> launch(T surface_z, T depth_m, double graze, double az) {
    return ray<T>{vec3<T>{T(3), T(-2), surface_z - depth_m},
                  vec3<T>{T(std::cos(graze) * std::cos(az)), T(std::cos(graze) * std::sin(az)), T(-std::sin(graze))}};
}

// Exact tracing (no launch table: tests/propagation/test_layered_table.cpp covers it) under a surface at world z.
template <class T = double> layered_params<T> exact(T surface_z = T(0)) {
    layered_params<T> p;
    p.surface_z_m = surface_z;
    p.launch_table = false;
    return p;
}

template <class T> T horizontal_distance(const vec3<T>& a, const vec3<T>& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// A plane n . X = d, hit from either side; geometry everywhere below top (m).
template <class T> struct plane_scene {
    using value_type = T;
    vec3<T> n{T(0), T(0), T(1)};
    T d{};
    T top = std::numeric_limits<T>::infinity();
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max) const {
        const T denom = glm::dot(n, r.direction);
        if (denom == T(0)) return std::nullopt;
        const T s = (d - glm::dot(n, r.origin)) / denom;
        if (!(s > T(0) && s <= t_max)) return std::nullopt;
        hit<T> h;
        h.distance_m = s;
        h.point = r.at(s);
        h.normal = denom < T(0) ? n : -n;
        h.shading_normal = h.normal;
        return h;
    }
    [[nodiscard]] T seabed_height_m(T, T) const { return -std::numeric_limits<T>::infinity(); }
    [[nodiscard]] T top_m() const { return top; }
};
static_assert(Scene<plane_scene<double>>);

// Records every chord it is handed and hits nothing.
struct recording_scene {
    using value_type = double;
    struct chord { vec3<double> a, b; };
    mutable std::vector<chord> chords;
    [[nodiscard]] std::optional<hit<double>> intersect(const ray<double>& r, double t_max) const {
        chords.push_back({r.origin, r.at(t_max)});
        return std::nullopt;
    }
    [[nodiscard]] double seabed_height_m(double, double) const { return -1e9; }
    [[nodiscard]] double top_m() const { return 1e9; }
};

// Signed textbook constant-gradient arc from inclination phi0 (+ down) over a depth change dz != 0: range, time, arc
// length, end inclination. x = (sin phi0 - sin phi1)/kappa, s = (phi0 - phi1)/kappa, t = (atanh sin phi0 - atanh
// sin phi1)/g, with kappa = g cos(phi0)/c0; the ray arrives moving the way dz points, turned or not.
struct textbook { ld x, t, s, phi1; };
textbook textbook_arc(ld c0, ld g, ld phi0, ld dz) {
    const ld xi = std::cos(phi0) / c0, c1 = c0 + g * dz, cos1 = xi * c1;
    ld sin1 = std::sqrt((1 - cos1) * (1 + cos1));
    if (dz < 0) sin1 = -sin1;
    const ld phi1 = std::atan2(sin1, cos1), kappa = xi * g;
    return {(std::sin(phi0) - sin1) / kappa, (std::atanh(std::sin(phi0)) - std::atanh(sin1)) / g, (phi0 - phi1) / kappa, phi1};
}

sss_test::layered_water water_of(const sound_speed_profile<double>& p, double seabed_depth,
                                 std::function<double(double)> alpha = {}) {
    sss_test::layered_water w;
    w.depth_m.assign(p.depths_m().begin(), p.depths_m().end());
    w.speed_mps.assign(p.speeds_mps().begin(), p.speeds_mps().end());
    w.seabed_depth_m = seabed_depth;
    w.absorption_db_per_km = std::move(alpha);
    return w;
}

// The thermocline used below: 1500 m/s at the surface, 1499 at 44 m, down 20 m/s to 54 m, then +0.0165 1/s.
sound_speed_profile<double> thermocline() { return {{0, 44, 54, 200}, {1500, 1499, 1479, 1481.409}}; }

} // namespace

TEST_CASE("a constant-gradient layer reproduces the closed-form arc (range, time, path, grazing) to 1e-9") {
    // c0 1500 m/s at the source (10 m), g 0.1 1/s, 20 deg down to a seabed 100 m below: the reference example.
    for (int split : {1, 100}) {
        std::vector<double> d, c;
        for (int k = 0; k <= split; ++k) { d.push_back(10 + 1000.0 * k / split); c.push_back(1500 + 100.0 * k / split); }
        const layered<double> water(sound_speed_profile<double>(d, c), exact());
        const scene::flat_seabed<double> seabed(-110);
        const auto r = launch<double>(0, 10, 20 * deg, 0.7);
        const auto p = water.trace_path(r, seabed, 1.0);
        REQUIRE(p);
        const auto ref = textbook_arc(1500, 0.1L, 20 * static_cast<ld>(deg), 100);
        const double range = horizontal_distance(p->result.surface.point, r.origin);
        const double graze = std::asin(-p->result.arrival.z);
        const double err = std::max({rel(range, ref.x), rel(p->result.time_s, ref.t), rel(p->path_length_m, ref.s),
                                     rel(graze, ref.phi1), rel(p->result.surface.distance_m, ref.s)});
        MESSAGE(split << " layer(s): worst relative error vs the closed form " << err);
        CHECK(err < 1e-9);
        // The printed check values.
        CHECK(std::abs(range - 282.998) <= 5e-4);
        CHECK(std::abs(p->result.time_s - 0.1994308) <= 5e-8);
        CHECK(std::abs(graze / deg - 18.922649) <= 5e-7);
        // The hit is on the seabed, in the launch azimuth.
        CHECK(p->result.surface.point.z == doctest::Approx(-110).epsilon(1e-14));
        CHECK(std::atan2(p->result.surface.point.y - r.origin.y, p->result.surface.point.x - r.origin.x) ==
              doctest::Approx(0.7).epsilon(1e-13));
        CHECK(p->arcs == static_cast<std::size_t>(split == 1 ? 1 : 10));
    }
}

TEST_CASE("a ray launched upward turns inside a downward-refracting layer and lands where the closed form says") {
    // c falls 0.1 m/s per m of depth: a ray 5 deg up from 100 m turns and comes down to a seabed at 200 m.
    const layered<double> water(sound_speed_profile<double>({0, 1000}, {1550, 1450}), exact());
    const scene::flat_seabed<double> seabed(-200);
    const auto r = launch<double>(0, 100, -5 * deg, -2.0);
    const auto p = water.trace_path(r, seabed, 5.0);
    REQUIRE(p);
    const auto ref = textbook_arc(1540, -0.1L, -5 * static_cast<ld>(deg), 100);
    const double range = horizontal_distance(p->result.surface.point, r.origin);
    const double err = std::max({rel(range, ref.x), rel(p->result.time_s, ref.t), rel(p->path_length_m, ref.s),
                                 rel(std::asin(-p->result.arrival.z), ref.phi1)});
    MESSAGE("turning arc: worst relative error " << err << " (range " << range << " m)");
    CHECK(err < 1e-9);
}

TEST_CASE("in water of constant speed, layered equals straight rays to 1e-12 (hits, time, spreading, arrival)") {
    // Knots at odd depths, all 1500 m/s: every layer boundary is crossed, none bends anything.
    const std::vector<double> d{0, 5, 17, 40, 41, 50, 63, 90};
    const layered<double> water(sound_speed_profile<double>(d, std::vector<double>(d.size(), 1500.0)), exact(70.0));
    const straight<double> iso({.sound_speed_mps = 1500, .absorption_db_per_km = 40});
    const scene::flat_seabed<double> seabed(0);
    const francois_garrison<double> fg(300000, {});
    double worst = 0, worst_abs = 0, worst_db = 0;
    int hits = 0;
    for (double graze : {0.5, 2.0, 7.0, 15.0, 30.0, 45.0, 60.0, 75.0, 89.0, 90.0}) {
        for (double az : {0.0, 1.1, 2.5, -2.0}) {
            const auto r = launch<double>(70, 50, graze * deg, az);
            const auto a = water.trace_path(r, seabed, 1.0);
            const auto b = iso.trace(r, seabed, 1.0);
            REQUIRE(a.has_value() == b.has_value());
            if (!a) continue;
            ++hits;
            for (int k = 0; k < 3; ++k) {
                worst = std::max(worst, std::abs(a->result.surface.point[k] - b->surface.point[k]) /
                                            std::max(1.0, std::abs(b->surface.point[k])));
                worst_abs = std::max(worst_abs, std::abs(a->result.arrival[k] - b->arrival[k]));
            }
            const double s = b->surface.distance_m;
            worst = std::max({worst, rel(a->result.time_s, b->time_s), rel(a->result.spreading, b->spreading),
                              rel(a->outgoing_spreading, b->spreading), rel(a->result.surface.distance_m, s),
                              std::abs(a->range_m - std::hypot(b->surface.point.x - r.origin.x, b->surface.point.y - r.origin.y)) / s});
            // Spreading in decibels is 20 log10 r; absorption is Francois-Garrison along the straight line.
            worst_db = std::max(worst_db, std::abs(10 * std::log10(a->result.spreading) + 20 * std::log10(s)));
            const double want = std::pow(10.0, -straight_path_absorption_db(fg, 50.0, 70.0, s) / 10);
            worst = std::max(worst, rel(a->result.absorption, want));
        }
    }
    MESSAGE(hits << " rays: worst relative difference " << worst << ", arrival " << worst_abs << ", spreading "
                 << worst_db << " dB off 20 log10 r");
    CHECK(hits == 36); // 0.5 deg reaches the seabed beyond t_max: both miss
    CHECK(worst < 1e-12);
    CHECK(worst_abs < 1e-12);
    CHECK(worst_db < 0.01);
    CHECK(worst_db < 1e-10);
}

TEST_CASE("ray-tube spreading in a thermocline matches the section 4 formula by finite differences") {
    // S = cos(theta0) / (r sin(theta) |dr/dtheta0|), dr/dtheta0 by central differences of traced ranges.
    const layered<double> water(thermocline(), exact(60.0));
    const scene::flat_seabed<double> seabed(0);
    double worst = 0;
    for (double graze : {6.0, 12.0, 25.0, 45.0, 70.0, 88.0}) {
        auto range = [&](double th) {
            const auto r = launch<double>(60, 50, th, 0.3);
            return water.trace_path(r, seabed, 1.0)->range_m;
        };
        const double th = graze * deg, h = 1e-5;
        const auto p = water.trace_path(launch<double>(60, 50, th, 0.3), seabed, 1.0);
        REQUIRE(p);
        const double drdth = (range(th + h) - range(th - h)) / (2 * h);
        const double sin_b = -p->result.arrival.z;
        const double fd = std::cos(th) / (p->range_m * sin_b * std::abs(drdth));
        const double e = rel(p->outgoing_spreading, fd);
        worst = std::max(worst, e);
        // The return leg: (c_B/c_A)^2 times the outgoing tube.
        const double ratio = p->hit_speed_mps / p->source_speed_mps;
        CHECK(p->result.spreading == doctest::Approx(p->outgoing_spreading * ratio * ratio).epsilon(1e-14));
        CHECK(p->hit_speed_mps == doctest::Approx(1479 + 0.0165 * 6).epsilon(1e-12));
    }
    MESSAGE("worst relative difference from finite differences: " << worst);
    CHECK(worst < 1e-7);
}

TEST_CASE("the return leg's spreading is that of the reversed ray (reciprocity), and so is its travel time") {
    // Trace back from the seabed hit, against the arrival direction, to a plane at the towfish depth.
    const layered<double> water(thermocline(), exact(60.0));
    const scene::flat_seabed<double> seabed(0);
    plane_scene<double> ceiling;
    ceiling.d = 10; // world z of the towfish
    ceiling.top = 10;
    double worst = 0;
    for (double graze : {8.0, 20.0, 40.0, 65.0}) {
        const auto r = launch<double>(60, 50, graze * deg, -1.0);
        const auto fwd = water.trace_path(r, seabed, 1.0);
        REQUIRE(fwd);
        const ray<double> back{fwd->result.surface.point, -fwd->result.arrival};
        const auto rev = water.trace_path(back, ceiling, 1.0);
        REQUIRE(rev);
        worst = std::max({worst, rel(rev->outgoing_spreading, fwd->result.spreading), rel(rev->result.time_s, fwd->result.time_s),
                          rel(rev->range_m, fwd->range_m), rel(rev->result.absorption, fwd->result.absorption)});
        CHECK(glm::length(rev->result.surface.point - r.origin) < 1e-9);
        CHECK(glm::length(rev->result.arrival + r.direction) < 1e-12);
    }
    MESSAGE("worst relative difference, reversed vs forward: " << worst);
    CHECK(worst < 1e-10);
}

TEST_CASE("traced rays through a thermocline agree with the long-double layered oracle") {
    const auto profile = thermocline();
    const layered<double> water(profile, exact(60.0));
    const auto w = water_of(profile, 60.0, [&](double z) { return water.absorption_db_per_km(z); });
    const scene::flat_seabed<double> seabed(0);
    double worst = 0;
    for (double graze : {3.0, 9.0, 20.0, 40.0, 60.0, 80.0, 89.9}) {
        const auto p = water.trace_path(launch<double>(60, 50, graze * deg, 2.0), seabed, 1.0);
        REQUIRE(p);
        const auto o = sss_test::layered_ray_to_seabed(w, 50.0, graze * deg);
        REQUIRE(o.reaches);
        worst = std::max({worst, rel(p->range_m, o.range_m), rel(p->result.time_s, o.time_s),
                          rel(std::asin(-p->result.arrival.z), o.graze_rad), rel(p->outgoing_spreading, o.spreading),
                          rel(p->result.absorption, o.absorption)});
    }
    MESSAGE("worst relative difference from the oracle: " << worst);
    CHECK(worst < 1e-10);
}

TEST_CASE("rays trapped in a sound channel never reach the seabed: nullopt within t_max") {
    // A speed minimum at 50 m; the seabed at 300 m. Rays within about 9 deg of horizontal at 52 m are trapped.
    const layered<double> water(sound_speed_profile<double>({0, 50, 100, 300}, {1500, 1480, 1500, 1503}), exact(300.0));
    const scene::flat_seabed<double> seabed(0);
    for (double graze : {-3.0, 0.0, 1.0, 3.0, 6.0}) CHECK_FALSE(water.trace(launch<double>(300, 52, graze * deg, 0.0), seabed, 5.0));
    // Steeper rays escape and hit.
    for (double graze : {12.0, 30.0}) CHECK(water.trace(launch<double>(300, 52, graze * deg, 0.0), seabed, 5.0));

    // The same channel resolved into 1000 thin layers: still trapped, and the trace ends at t_max.
    std::vector<double> d, c;
    for (int k = 0; k <= 1000; ++k) {
        const double z = 0.1 * k;
        d.push_back(z);
        c.push_back(1480 + 20 * (1 - std::exp(-std::pow((z - 50) / 25, 2))));
    }
    d.push_back(300);
    c.push_back(1503);
    const layered<double> fine(sound_speed_profile<double>(d, c), exact(300.0));
    CHECK_FALSE(fine.trace(launch<double>(300, 52, 4 * deg, 0.0), seabed, 2.0));
    CHECK(fine.trace(launch<double>(300, 52, 30 * deg, 0.0), seabed, 2.0));
}

TEST_CASE("horizontal launches: bent down by a negative gradient, straight on in uniform water, held on a speed minimum") {
    const scene::flat_seabed<double> seabed(0);
    // (a) Mid-layer, c falling 2 m/s per m: the ray curves down onto the seabed 4 m below.
    {
        const layered<double> water(sound_speed_profile<double>({40, 60}, {1500, 1460}), exact(60.0));
        const auto r = launch<double>(60, 56, 0.0, 0.4);
        const auto p = water.trace_path(r, seabed, 1.0);
        REQUIRE(p);
        const auto ref = textbook_arc(1468, -2.0L, 0.0L, 4);
        CHECK(rel(p->range_m, ref.x) < 1e-9);
        CHECK(rel(p->result.time_s, ref.t) < 1e-9);
        CHECK(rel(std::asin(-p->result.arrival.z), ref.phi1) < 1e-9);
        CHECK(p->outgoing_spreading > 0);
        CHECK(std::isfinite(p->outgoing_spreading));
    }
    // (b) Uniform water: it never comes down.
    {
        const layered<double> water(sound_speed_profile<double>::constant(1500), exact(60.0));
        CHECK_FALSE(water.trace(launch<double>(60, 56, 0.0, 0.4), seabed, 1.0));
    }
    // (c) Exactly on a knot that is a speed minimum: both layers bend it back, it runs along the knot.
    {
        const layered<double> water(sound_speed_profile<double>({0, 50, 100}, {1500, 1480, 1500}), exact(300.0));
        CHECK_FALSE(water.trace(launch<double>(300, 50, 0.0, 0.0), seabed, 1.0));
    }
    // (d) Exactly on a knot with uniform water above and a falling speed below: it curves down from the knot.
    {
        const layered<double> water(sound_speed_profile<double>({50, 100}, {1500, 1400}), exact(60.0));
        const auto p = water.trace_path(launch<double>(60, 50, 0.0, 0.0), seabed, 1.0);
        REQUIRE(p);
        const auto ref = textbook_arc(1500, -2.0L, 0.0L, 10);
        CHECK(rel(p->range_m, ref.x) < 1e-9);
        CHECK(rel(p->result.time_s, ref.t) < 1e-9);
    }
}

TEST_CASE("a turning point exactly at the seabed gives a grazing hit or none, and neighbours behave") {
    // Uniform above 50 m, +0.2 1/s below; from 50 m a ray turns where c = 1500/cos(phi0): put that on the seabed at 60 m.
    const layered<double> water(sound_speed_profile<double>({50, 100}, {1500, 1510}), exact(60.0));
    const scene::flat_seabed<double> seabed(0);
    const double phi_star = std::acos(1500.0 / 1502.0);
    const auto at = water.trace_path(launch<double>(60, 50, phi_star, 0.0), seabed, 1.0);
    if (at) {
        CHECK(std::abs(at->result.arrival.z) < 1e-3);
        CHECK(std::isfinite(at->result.time_s));
        CHECK(std::isfinite(at->result.spreading));
        CHECK(at->result.surface.point.z == doctest::Approx(0.0).epsilon(1e-9));
    }
    MESSAGE("exactly at the turning depth: " << std::string(at ? "grazing hit" : "no hit"));
    // Slightly steeper: a shallow hit where the closed form puts it.
    const double steeper = phi_star * (1 + 1e-3);
    const auto p = water.trace_path(launch<double>(60, 50, steeper, 0.0), seabed, 1.0);
    REQUIRE(p);
    const auto ref = textbook_arc(1500, 0.2L, static_cast<ld>(steeper), 10);
    CHECK(rel(p->range_m, ref.x) < 1e-9);
    CHECK(rel(p->result.time_s, ref.t) < 1e-9);
    CHECK(rel(std::asin(-p->result.arrival.z), ref.phi1) < 1e-6);
    CHECK(std::asin(-p->result.arrival.z) < 0.003);
    // Slightly shallower: turns above the seabed and climbs to the surface.
    CHECK_FALSE(water.trace(launch<double>(60, 50, phi_star * (1 - 1e-3), 0.0), seabed, 1.0));
}

TEST_CASE("a thousand thin layers: one gradient split 1000 ways, and a smooth thermocline, agree with closed forms") {
    const scene::flat_seabed<double> seabed(0);
    // One constant gradient cut into 1000 layers over 100 m.
    {
        std::vector<double> d, c;
        for (int k = 0; k <= 1000; ++k) { d.push_back(0.1 * k); c.push_back(1500 - 0.3 * 0.1 * k); }
        const layered<double> water(sound_speed_profile<double>(d, c), exact(100.0));
        double worst = 0;
        for (double graze : {5.0, 30.0, 80.0}) {
            const auto p = water.trace_path(launch<double>(100, 20, graze * deg, 0.0), seabed, 1.0);
            REQUIRE(p);
            const auto ref = textbook_arc(1500 - 0.3 * 20, -0.3L, static_cast<ld>(graze * deg), 80);
            worst = std::max({worst, rel(p->range_m, ref.x), rel(p->result.time_s, ref.t), rel(p->path_length_m, ref.s)});
            CHECK(p->arcs == 800u);
        }
        MESSAGE("1000 layers of one gradient: worst relative error " << worst);
        CHECK(worst < 1e-10);
    }
    // A smooth tanh thermocline on 1000 knots, against the oracle on the same knots.
    {
        std::vector<double> d, c;
        for (int k = 0; k <= 1000; ++k) { d.push_back(0.1 * k); c.push_back(1500 - 10 * std::tanh((0.1 * k - 50) / 5)); }
        const sound_speed_profile<double> profile(d, c);
        const layered<double> water(profile, exact(90.0));
        const auto w = water_of(profile, 90.0);
        double worst = 0;
        for (double graze : {4.0, 30.0, 60.0}) {
            const auto p = water.trace_path(launch<double>(90, 30, graze * deg, 0.0), seabed, 1.0);
            REQUIRE(p);
            const auto o = sss_test::layered_ray_to_seabed(w, 30.0, graze * deg);
            REQUIRE(o.reaches);
            worst = std::max({worst, rel(p->range_m, o.range_m), rel(p->result.time_s, o.time_s),
                              rel(p->outgoing_spreading, o.spreading), rel(std::asin(-p->result.arrival.z), o.graze_rad)});
        }
        MESSAGE("smooth thermocline on 1000 knots: worst relative difference from the oracle " << worst);
        CHECK(worst < 1e-9);
    }
}

TEST_CASE("the sea surface ends a climbing ray, and a ray cannot start above it") {
    const layered<double> water(sound_speed_profile<double>::constant(1500), exact(60.0));
    const scene::flat_seabed<double> seabed(0);
    CHECK_FALSE(water.trace(launch<double>(60, 20, -10 * deg, 0.0), seabed, 10.0));
    CHECK_FALSE(water.trace(launch<double>(60, 0, -1 * deg, 0.0), seabed, 10.0));
    CHECK(water.trace(launch<double>(60, 0, 30 * deg, 0.0), seabed, 10.0)); // from the surface itself, down
    CHECK_THROWS_AS((void)water.trace(launch<double>(60, -1, 30 * deg, 0.0), seabed, 10.0), sss::invalid_parameter);
    // Time limit: the seabed is 40 m away along this ray.
    const auto r = launch<double>(60, 20, 90 * deg, 0.0);
    CHECK(water.trace(r, seabed, 40.0 / 1500 * (1 + 1e-9)));
    CHECK_FALSE(water.trace(r, seabed, 40.0 / 1500 * (1 - 1e-9)));
}

TEST_CASE_TEMPLATE("a ray going up from a source above the geometry comes back to the seabed exactly when Snell's law "
                   "turns it below the surface",
                   T, float, double) {
    // The survey's water under a surface at world z 40 m, a source 10 m above a flat seabed at z 0 (depth 30 m, where c
    // is 1487.07 m/s): the fastest water above it is the surface's 1500 m/s, so a ray launched up turns back down
    // where it is shallower than acos(c0 / 1500), about 7.53 deg, and reaches the surface (meeting nothing) where it is
    // steeper.
    for (const bool table : {false, true}) {
        layered_params<T> p = exact<T>(T(40));
        p.launch_table = table;
        const layered<T> water(sound_speed_profile<T>({T(0), T(8), T(20), T(40.5)}, {T(1500), T(1499), T(1490), T(1484)}), p);
        const scene::flat_seabed<T> seabed(T(0));
        const double c0 = double(water.profile().speed_mps(T(30)));
        const double critical = std::acos(c0 / 1500.0);
        std::size_t back = 0, gone = 0;
        std::vector<ray<T>> rays;
        for (int k = 0; k < 80; ++k) {
            const double up = (1.0 + 0.25 * k) * deg;
            if (std::abs(up - critical) < 0.02 * deg) continue; // within rounding of the turn at the surface itself
            rays.push_back(launch<T>(T(40), T(30), -up, 0.3));
            const auto path = water.trace(rays.back(), seabed, T(1));
            CHECK_MESSAGE(path.has_value() == (up < critical), "up " << up / deg << " deg, critical " << critical / deg);
            if (path) CHECK(path->surface.point.z == doctest::Approx(0.0).epsilon(1e-5));
            back += path.has_value();
            gone += !path.has_value();
        }
        // The batch method agrees ray by ray.
        std::vector<std::optional<path<T>>> together(rays.size());
        water.trace_many(std::span<const ray<T>>(rays), seabed, T(1), std::span<std::optional<path<T>>>(together));
        for (std::size_t k = 0; k < rays.size(); ++k) CHECK(together[k].has_value() == water.trace(rays[k], seabed, T(1)).has_value());
        CHECK(back > 20);
        CHECK(gone > 20);
    }
}

TEST_CASE("the reference speed is the harmonic mean over the water column, unless given") {
    // c from 1500 at the surface to 1400 at 100 m: 100 m / integral dz/c = 100 g / ln(c1/c0), g = -1 1/s.
    const layered<double> water(sound_speed_profile<double>({0, 100}, {1500, 1400}), exact());
    CHECK(rel(water.reference_speed_mps(), 100.0L * -1 / std::log(1400.0L / 1500)) < 1e-13);
    // A knot below the surface: uniform above it counts with its own speed.
    const layered<double> w2(sound_speed_profile<double>({20, 30}, {1500, 1490}), exact());
    const ld slowness = 20.0L / 1500 + 10.0L * std::log(1500.0L / 1490) / 10; // 20/1500 + (1/|g|) ln(c0/c1), |g| = 1
    CHECK(rel(w2.reference_speed_mps(), 30 / slowness) < 1e-13);
    CHECK(layered<double>(sound_speed_profile<double>::constant(1493), {}).reference_speed_mps() == 1493);
    layered_params<double> p;
    p.reference_speed_mps = 1510;
    CHECK(layered<double>(sound_speed_profile<double>({0, 100}, {1500, 1400}), p).reference_speed_mps() == 1510);
}

TEST_CASE("curved rays land exactly on a tilted plane whatever the chord tolerance") {
    // A plane tilted 20 deg, crossing the thermocline: chords of 0.1 mm to 3 m all refine to the same point.
    const auto profile = thermocline();
    plane_scene<double> slope;
    slope.n = glm::normalize(vec3<double>{std::sin(20 * deg), 0.0, std::cos(20 * deg)});
    slope.d = glm::dot(slope.n, vec3<double>{40, 0, 5});
    const auto r = launch<double>(60, 50, 7 * deg, 0.05);
    std::vector<vec3<double>> hits;
    double worst_plane = 0;
    for (double tol : {1e-4, 1e-3, 1e-1, 3.0}) {
        layered_params<double> p = exact(60.0);
        p.chord_tolerance_m = tol;
        const layered<double> water(profile, p);
        const auto h = water.trace_path(r, slope, 1.0);
        REQUIRE(h);
        hits.push_back(h->result.surface.point);
        worst_plane = std::max(worst_plane, std::abs(glm::dot(slope.n, h->result.surface.point) - slope.d));
        // On the arc: a flat seabed at the hit's depth is met at the same point.
        const layered<double> water2(profile, p);
        const auto f = water2.trace_path(r, scene::flat_seabed<double>(h->result.surface.point.z), 1.0);
        REQUIRE(f);
        CHECK(glm::length(f->result.surface.point - h->result.surface.point) < 1e-9);
        CHECK(rel(f->result.time_s, h->result.time_s) < 1e-12);
    }
    double spread = 0;
    for (const auto& h : hits) spread = std::max(spread, glm::length(h - hits.front()));
    MESSAGE("tilted plane: distance from the plane " << worst_plane << " m, spread over tolerances " << spread << " m");
    CHECK(worst_plane < 1e-10);
    CHECK(spread < 1e-9);
}

TEST_CASE("chords stay within the stated sagitta tolerance of the arc, and the bound is tight") {
    for (double k : {1e-5, 1e-3, 0.1}) {
        for (double tol : {1e-4, 1e-3, 1e-1}) {
            const double ds = chord_arc_length_m(k, tol);
            const double sagitta = 2 * std::pow(std::sin(k * ds / 4), 2) / k; // (1 - cos(k ds/2))/k
            CHECK(sagitta <= tol * (1 + 1e-12));
            CHECK(sagitta >= tol * (1 - k * tol / 5)); // within k tol / 6 of the longest chord
        }
    }
    CHECK(chord_arc_length_m(0.0, 1e-3) == std::numeric_limits<double>::infinity());
    // Every chord handed to the scene in a strong thermocline, against points sampled along the true arcs.
    layered_params<double> p = exact(60.0);
    p.chord_tolerance_m = 1e-3;
    const layered<double> water(sound_speed_profile<double>({0, 44, 54, 200}, {1500, 1499, 1440, 1442}), p);
    recording_scene rec;
    (void)water.trace(launch<double>(60, 45, 3 * deg, 0.0), rec, 0.03);
    REQUIRE(rec.chords.size() > 10);
    // The path, sampled every 5 cm with the exact arcs.
    std::vector<vec3<double>> pts;
    {
        const auto profile = water.profile();
        double z = 45, phi = 3 * deg, x = 0;
        std::size_t i = profile.layer_index(z);
        for (int n = 0; n < 3; ++n) {
            const auto st = step_through_layer(profile.layer(i), z, phi, vertical_direction::down);
            const double len = std::min(st.arc.length_m, 45.0);
            for (double s = 0; s <= len; s += 0.05) {
                const auto a = arc_point(st.arc, s);
                pts.push_back({3 + x + a.range_m, -2, 60 - a.depth_m});
            }
            if (st.boundary != layer_exit::bottom) break;
            x += st.exit.range_m;
            z = st.exit.depth_m;
            phi = st.exit.graze_rad();
            ++i;
        }
    }
    double worst = 0;
    for (const auto& q : pts) {
        double best = 1e9;
        for (const auto& c : rec.chords) {
            const vec3<double> ab = c.b - c.a;
            const double u = std::clamp(glm::dot(q - c.a, ab) / glm::dot(ab, ab), 0.0, 1.0);
            best = std::min(best, glm::length(q - (c.a + ab * u)));
        }
        if (q.x - 3 < 40) worst = std::max(worst, best);
    }
    MESSAGE(rec.chords.size() << " chords; largest arc-to-chord distance " << worst << " m (tolerance 1e-3 m)");
    CHECK(worst <= 1e-3 * (1 + 1e-6));
    CHECK(worst > 0.5e-3);
}

namespace {

// The scene S without clear_length_m: the plain chord walk.
template <class S> struct without_clearance {
    using value_type = typename S::value_type;
    using T = value_type;
    const S* s;
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max) const { return s->intersect(r, t_max); }
    [[nodiscard]] T seabed_height_m(T x, T y) const { return s->seabed_height_m(x, y); }
    [[nodiscard]] T top_m() const { return s->top_m(); }
};

// `s` with its clearance but not its arcs (ArcScene): a bent ray is handed to it chord by chord.
template <class S> struct chords_only {
    using value_type = typename S::value_type;
    using T = value_type;
    const S* s;
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max) const { return s->intersect(r, t_max); }
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max, T band) const { return s->clear_length_m(r, t_max, band); }
    [[nodiscard]] T seabed_height_m(T x, T y) const { return s->seabed_height_m(x, y); }
    [[nodiscard]] T top_m() const { return s->top_m(); }
};

// 100 m x 100 m of rippled, bumpy seabed at 0.25 m around z = 0 (crests 0.35 m high, a 1.2 m mound), with spheres
// floating over it and cylinders lying on it.
template <class T> scene::scene<scene::height_field<T>> rough_scene_with_objects() {
    const std::size_t n = 401;
    std::vector<T> h(n * n);
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i) {
            const double x = -50 + 0.25 * double(i), y = -50 + 0.25 * double(j);
            h[j * n + i] = T(0.35 * std::sin(2.1 * x + 0.3 * y) + 0.2 * std::sin(0.37 * y - 0.11 * x) +
                             1.2 * std::exp(-((x - 20) * (x - 20) + (y - 5) * (y - 5)) / 30));
        }
    std::vector<scene::object<T>> objs;
    for (int k = 0; k < 12; ++k) { // in the rays' way (below): 30 to 63 m from (-45, -20), across their azimuths
        const double az = -0.22 + 0.04 * k, range = 30 + 3 * k;
        const T x = T(-45 + range * std::cos(az)), y = T(-20 + range * std::sin(az));
        const scene::surface_ids ids{1, std::uint32_t(k), 1};
        if (k % 2 == 0) {
            objs.emplace_back(std::vector<scene::sphere<T>>{scene::sphere<T>({x, y, T(1.5 + 0.5 * (k % 3))}, T(1), ids)},
                              std::vector<scene::cylinder<T>>{});
        } else {
            objs.emplace_back(std::vector<scene::sphere<T>>{},
                              std::vector<scene::cylinder<T>>{scene::cylinder<T>({x, y - 2, T(0.6)}, {x + 1, y + 2, T(0.6)}, T(0.6), ids)});
        }
    }
    return scene::scene<scene::height_field<T>>(
        scene::height_field<T>({.nx = n, .ny = n, .cell_m = T(0.25), .origin_m = {T(-50), T(-50)}, .heights_m = h}),
        scene::object_set<T>(std::move(objs)));
}

template <class T> void check_clearance_changes_nothing() {
    const auto sc = rough_scene_with_objects<T>();
    const without_clearance<scene::scene<scene::height_field<T>>> plain{&sc};
    const chords_only<scene::scene<scene::height_field<T>>> cleared{&sc};
    static_assert(ClearanceScene<decltype(cleared)> && !ClearanceScene<decltype(plain)> && !ArcScene<decltype(cleared)>);
    // Strong gradients down to the seabed, 10 m/s over 10 m then 20 m/s over 10.5 m (chords of about 0.6 m): speed
    // falling with depth (rays bend down, each chord below its arc) and rising (rays bend up, each chord above it).
    layered_params<T> p;
    p.surface_z_m = T(40);
    const std::vector<T> depths{T(0), T(20), T(30), T(40.5)};
    for (const auto& speeds : {std::vector<T>{T(1500), T(1500), T(1490), T(1470)}, std::vector<T>{T(1470), T(1470), T(1480), T(1500)}}) {
    const layered<T> water(sound_speed_profile<T>(depths, speeds), p);
    std::size_t rays = 0, hits = 0, object_hits = 0, chords_with = 0, chords_without = 0;
    for (int a = 0; a < 24; ++a)
        for (int g = 0; g < 60; ++g) {
            const double az = -0.25 + 0.02 * a, graze = (1.5 + 0.9 * g) * deg;
            const ray<T> r{vec3<T>{T(-45), T(-20), T(10)},
                           vec3<T>{T(std::cos(graze) * std::cos(az)), T(std::cos(graze) * std::sin(az)), T(-std::sin(graze))}};
            const auto with = water.trace_path(r, cleared, T(0.2));
            const auto without = water.trace_path(r, plain, T(0.2));
            ++rays;
            REQUIRE(with.has_value() == without.has_value());
            if (!with) continue;
            ++hits;
            object_hits += with->result.surface.object != no_object;
            chords_with += with->chords;
            chords_without += without->chords;
            const path<T>& x = with->result;
            const path<T>& y = without->result;
            const bool same = x.surface.point == y.surface.point && x.surface.normal == y.surface.normal &&
                              x.surface.object == y.surface.object && x.surface.distance_m == y.surface.distance_m &&
                              x.time_s == y.time_s && x.spreading == y.spreading && x.absorption == y.absorption &&
                              x.arrival == y.arrival;
            if (!same) FAIL_CHECK("ray " << a << ", " << g << ": the cleared walk differs from the plain one");
        }
    MESSAGE(hits << " of " << rays << " rays hit (" << object_hits << " an object); scene queries on chords " << chords_with
                 << " with clearance against " << chords_without << " without");
    CHECK(hits > rays / 2);
    CHECK(object_hits > 10);
    CHECK(chords_with * 2 < chords_without); // the clearance is used
    }
}

} // namespace

TEST_CASE_TEMPLATE("clearing chords in open water finds the plain chord walk's hits bit for bit, with fewer chords", T,
                   float, double) {
    check_clearance_changes_nothing<T>();
}

namespace {

// A scene that hands every query to `s` and counts the chords it is asked about; with `guided`, it is a GuidedScene
// and a ResumableScene too, and counts the bent rays it clears some distance for and the chords it resumes; with
// `arcs`, an ArcScene as well (the seabed meets arcs, the objects take chords).
template <class S, bool guided, bool arcs = false> struct counting_scene {
    using value_type = typename S::value_type;
    using T = value_type;
    const S* s;
    mutable long intersects = 0, cleared = 0, asked = 0, resumed = 0;
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max) const {
        ++intersects;
        return s->intersect(r, t_max);
    }
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max, T band) const { return s->clear_length_m(r, t_max, band); }
    [[nodiscard]] std::optional<hit<T>> intersect_beside(const ray<T>& r, T t, const ray<T>& a, T a_clear) const
        requires guided
    {
        return s->intersect_beside(r, t, a, a_clear);
    }
    [[nodiscard]] std::optional<hit<T>> intersect_after(const ray<T>& r, T t_max, T clear) const
        requires guided
    {
        ++intersects;
        ++resumed;
        return s->intersect_after(r, t_max, clear);
    }
    [[nodiscard]] T clear_range_beside_m(const scene::beside_rays<T>& b) const
        requires guided
    {
        const T d = s->clear_range_beside_m(b);
        ++asked;
        cleared += d > T(0);
        return d;
    }
    [[nodiscard]] std::optional<scene::arc_surface_hit<T>> intersect_arc(const scene::vertical_arc<T>& a, T x_clear,
                                                                         T x_end) const
        requires arcs
    {
        return s->intersect_arc(a, x_clear, x_end);
    }
    [[nodiscard]] auto arc_others() const
        requires arcs
    {
        return s->arc_others();
    }
    [[nodiscard]] T seabed_height_m(T x, T y) const { return s->seabed_height_m(x, y); }
    [[nodiscard]] T top_m() const { return s->top_m(); }
};

template <class T> bool same_path(const std::optional<path<T>>& x, const std::optional<path<T>>& y) {
    if (x.has_value() != y.has_value()) return false;
    if (!x) return true;
    return x->surface.point == y->surface.point && x->surface.normal == y->surface.normal &&
           x->surface.object == y->surface.object && x->surface.distance_m == y->surface.distance_m &&
           x->time_s == y->time_s && x->spreading == y->spreading && x->absorption == y->absorption &&
           x->arrival == y->arrival && x->clear_range_m == y->clear_range_m;
}

// Waters for the guided tests, under a surface at world z 40 m: strong gradients down to the seabed that bend rays
// down and up (as in the clearance test), and three layers like bench/bench_survey.cpp's.
template <class T> std::vector<layered<T>> guided_waters() {
    layered_params<T> p;
    p.surface_z_m = T(40);
    const std::vector<T> strong{T(0), T(20), T(30), T(40.5)};
    std::vector<layered<T>> out;
    out.emplace_back(sound_speed_profile<T>(strong, {T(1500), T(1500), T(1490), T(1470)}), p);
    out.emplace_back(sound_speed_profile<T>(strong, {T(1470), T(1470), T(1480), T(1500)}), p);
    out.emplace_back(sound_speed_profile<T>({T(0), T(12), T(25), T(60)}, {T(1510), T(1507), T(1494), T(1491)}), p);
    return out;
}

// A sidescan-like ray from `fish` at depression e (rad) on azimuth az (rad, from +x).
template <class T> ray<T> fan_ray(const vec3<T>& fish, double az, double e) {
    return ray<T>{fish, vec3<T>{T(std::cos(e) * std::cos(az)), T(std::cos(e) * std::sin(az)), T(-std::sin(e))}};
}

} // namespace

namespace {
// Pairs of bent rays, each beside a steeper neighbour: the guided trace against the plain one, by chords or, with `arcs`,
// with the seabed meeting arcs itself (the objects by chords).
template <class T, bool arcs> void check_beside_a_steeper_neighbour() {
    const auto sc = rough_scene_with_objects<T>();
    using Sc = scene::scene<scene::height_field<T>>;
    static_assert(GuidedScene<Sc> && ResumableScene<Sc> && GuidedPropagation<layered<T>, Sc>);
    std::size_t pairs = 0, hits = 0, objects = 0;
    long guided_chords = 0, plain_chords = 0, cleared = 0, resumed = 0;
    for (const layered<T>& water : guided_waters<T>()) {
        // Towfish 10 m and 3 m above the mean seabed, and one below the mound's top.
        for (const vec3<T> fish : {vec3<T>{T(-45), T(-20), T(10)}, vec3<T>{T(-40), T(10), T(3)}, vec3<T>{T(18), T(4), T(1.1)}})
            for (int a = 0; a < 6; ++a)
                for (int g = 0; g < 40; ++g) {
                    const double az = -0.3 + 0.1 * a + (fish.x > T(0) ? 2.0 : 0.0), e = (2 + 1.3 * g) * deg;
                    // Neighbours as the refinement meets them, down to 2^-12 of a first-pass step, some turned by up to
                    // a degree (another column of a conical beam).
                    const double de = 1.3 * deg * std::ldexp(1.0, -(g * 7 + a) % 13);
                    const double turn = (g + a) % 5 == 0 ? ((g % 3) - 1) * 1.0 * deg : 0.0;
                    const ray<T> steep = fan_ray(fish, az, e), r = fan_ray(fish, az + turn, e - de);
                    const T t_max = T(0.2);
                    const auto a_path = water.trace(steep, counting_scene<Sc, false, arcs>{&sc}, t_max);
                    if (!a_path) continue;
                    const counting_scene<Sc, true, arcs> guided{&sc};
                    const counting_scene<Sc, false, arcs> plain{&sc};
                    const auto want = water.trace(r, plain, t_max);
                    const auto got = water.trace_beside(r, guided, t_max, steep.direction, a_path->clear_range_m);
                    ++pairs;
                    hits += want.has_value();
                    objects += want && want->surface.object != no_object;
                    if (!same_path(got, want)) FAIL_CHECK("fish " << fish.z << " ray " << a << ", " << g << ": differs");
                    guided_chords += guided.intersects;
                    plain_chords += plain.intersects;
                    cleared += guided.cleared;
                    resumed += guided.resumed;
                    // The wrong way round: the shallower ray is no guide for the steeper one.
                    if (want) {
                        const counting_scene<Sc, true, arcs> back{&sc};
                        CHECK(same_path(water.trace_beside(steep, back, t_max, r.direction, want->clear_range_m), a_path));
                        CHECK(back.cleared == 0);
                    }
                }
    }
    MESSAGE(pairs << " pairs, " << hits << " hits (" << objects << " on objects), " << cleared << " guided; chords "
                  << guided_chords << " guided against " << plain_chords << " plain, " << resumed
                  << " of them resumed past what the guide vouches for" << std::string(arcs ? " (the seabed by arcs)" : ""));
    CHECK(hits > pairs / 2);
    CHECK(objects > 20);
    CHECK(cleared > std::int64_t(pairs) / 3);
    if constexpr (!arcs) {
        CHECK(guided_chords < plain_chords);
        // Most guided rays hand the scene the chord that reaches past the guide's vouching with its first part known
        // clear.
        CHECK(resumed > cleared / 2);
    }
}
} // namespace

TEST_CASE_TEMPLATE("A bent ray traced beside a steeper neighbour gets the plain trace's path to the last bit, in fewer "
                   "chords",
                   T, float, double) {
    check_beside_a_steeper_neighbour<T, false>();
}

TEST_CASE_TEMPLATE("A bent ray traced beside a steeper neighbour, some turned to another column, gets the plain trace's "
                   "path to the last bit where the seabed meets arcs itself",
                   T, float, double) {
    check_beside_a_steeper_neighbour<T, true>();
}

TEST_CASE_TEMPLATE("A bent ray too close to its steeper neighbour for the bound is guided by a farther one, and still "
                   "gets the plain trace's path to the last bit",
                   T, float, double) {
    const auto sc = rough_scene_with_objects<T>();
    using Sc = scene::scene<scene::height_field<T>>;
    std::size_t rays = 0, objects = 0, near_only = 0, far_only = 0;
    long near_chords = 0, both_chords = 0;
    for (const layered<T>& water : guided_waters<T>())
        for (const vec3<T> fish : {vec3<T>{T(-45), T(-20), T(10)}, vec3<T>{T(-40), T(10), T(3)}, vec3<T>{T(18), T(4), T(1.1)}})
            for (int a = 0; a < 4; ++a)
                for (int g = 0; g < 30; ++g) {
                    const double az = -0.3 + 0.15 * a + (fish.x > T(0) ? 2.0 : 0.0), e = (2 + 1.7 * g) * deg;
                    const double step = 1.3 * deg;
                    // r, a neighbour 2^-14 to 2^-10 of a first-pass step steeper (as deep refinement meets it), and the
                    // first-pass ray a whole step steeper.
                    const ray<T> r = fan_ray(fish, az, e);
                    const ray<T> near = fan_ray(fish, az, e + step * std::ldexp(1.0, -10 - (g + a) % 5));
                    const ray<T> far = fan_ray(fish, az, e + step);
                    const T t_max = T(0.2);
                    const auto near_path = water.trace(near, sc, t_max), far_path = water.trace(far, sc, t_max);
                    if (!near_path || !far_path) continue;
                    const counting_scene<Sc, false> plain{&sc};
                    const counting_scene<Sc, true> one{&sc}, two{&sc};
                    const auto want = water.trace(r, plain, t_max);
                    const auto got_one = water.trace_beside(r, one, t_max, near.direction, near_path->clear_range_m);
                    const auto got_two = water.trace_beside(r, two, t_max, near.direction, near_path->clear_range_m,
                                                            far.direction, far_path->clear_range_m);
                    ++rays;
                    objects += want && want->surface.object != no_object;
                    if (!same_path(got_one, want) || !same_path(got_two, want))
                        FAIL_CHECK("fish " << fish.z << " ray " << a << ", " << g << ": differs");
                    // b is asked only where a gives nothing.
                    if (one.cleared > 0) CHECK(two.asked == one.asked);
                    near_only += one.cleared > 0;
                    far_only += one.cleared == 0 && two.cleared > 0;
                    near_chords += one.intersects;
                    both_chords += two.intersects;
                }
    MESSAGE(rays << " rays with both guides' hits (" << objects << " meet objects); the near guide alone clears "
                 << near_only << ", the far one " << far_only << " more; chords " << both_chords << " with both against "
                 << near_chords);
    CHECK(rays > 600);
    CHECK(objects > 10);
    CHECK(far_only > rays / 4);
    CHECK(both_chords < near_chords);
}

namespace {
// Column a (0 to 7) of 120 rays from (-45, -20, 10), depressions 3 to 50.6 degrees, steepest first or last.
template <class T> std::vector<ray<T>> column_rays(int a, bool down_first) {
    std::vector<ray<T>> rays;
    for (int g = 0; g < 120; ++g) {
        const double e = (3 + 0.4 * g) * deg;
        rays.push_back(fan_ray(vec3<T>{T(-45), T(-20), T(10)}, -0.3 + 0.08 * a, down_first ? 50 * deg - e + 3 * deg : e));
    }
    return rays;
}
} // namespace

TEST_CASE_TEMPLATE("A column traced together over a GuidedScene gets each ray's own trace bit for bit, either way round",
                   T, float, double) {
    const auto sc = rough_scene_with_objects<T>();
    using Sc = scene::scene<scene::height_field<T>>;
    long cleared = 0, compared = 0;
    for (const layered<T>& water : guided_waters<T>())
        for (int a = 0; a < 8; ++a)
            for (const bool down_first : {true, false}) {
                const std::vector<ray<T>> rays = column_rays<T>(a, down_first);
                const counting_scene<Sc, true> guided{&sc};
                std::vector<std::optional<path<T>>> together(rays.size());
                water.trace_many(std::span<const ray<T>>(rays), guided, T(0.2), std::span<std::optional<path<T>>>(together));
                for (std::size_t k = 0; k < rays.size(); ++k) {
                    ++compared;
                    if (!same_path(together[k], water.trace(rays[k], counting_scene<Sc, false>{&sc}, T(0.2))))
                        FAIL_CHECK("column " << a << ", ray " << k << (down_first ? " (steepest first)" : " (shallowest first)"));
                }
                cleared += guided.cleared;
            }
    MESSAGE(compared << " rays, " << cleared << " guided");
    CHECK(cleared > compared / 2);
}

TEST_CASE_TEMPLATE("Over a seabed that meets arcs itself, a bent ray's path is the same to the last bit alone, beside a "
                   "steeper neighbour and in a column, and its hit is the chord walk's to within the chord tolerance",
                   T, float, double) {
    const auto sc = rough_scene_with_objects<T>();
    using Sc = scene::scene<scene::height_field<T>>;
    using unguided_arcs = counting_scene<Sc, false, true>;
    static_assert(ArcScene<Sc> && ArcScene<unguided_arcs> && !ArcScene<counting_scene<Sc, false>>);
    long compared = 0, hits = 0, objects = 0, guided = 0, off_1mm = 0;
    double worst_m = 0;
    for (const layered<T>& water : guided_waters<T>())
        for (int a = 0; a < 8; ++a)
            for (const bool down_first : {true, false}) {
                const std::vector<ray<T>> rays = column_rays<T>(a, down_first);
                const counting_scene<Sc, true, true> column{&sc};
                std::vector<std::optional<path<T>>> together(rays.size());
                water.trace_many(std::span<const ray<T>>(rays), column, T(0.2), std::span<std::optional<path<T>>>(together));
                guided += column.cleared;
                for (std::size_t k = 0; k < rays.size(); ++k) {
                    ++compared;
                    const auto alone = water.trace(rays[k], unguided_arcs{&sc}, T(0.2));
                    if (!same_path(together[k], alone) || !same_path(water.trace(rays[k], sc, T(0.2)), alone))
                        FAIL_CHECK("column " << a << ", ray " << k << (down_first ? " (steepest first)" : " (shallowest first)"));
                    // Beside the previous ray, the steeper where the column comes steepest first.
                    if (down_first && k > 0 && together[k - 1]) {
                        const counting_scene<Sc, true, true> beside{&sc};
                        if (!same_path(water.trace_beside(rays[k], beside, T(0.2), rays[k - 1].direction,
                                                          together[k - 1]->clear_range_m),
                                       alone))
                            FAIL_CHECK("column " << a << ", ray " << k << " beside its steeper neighbour");
                    }
                    if (!alone) continue;
                    ++hits;
                    objects += alone->surface.object != no_object;
                    // The chord walk's hit: the same surface point to within its tolerance (0.1 mm of sagitta, more
                    // where a chord and the arc meet different facets near a crest at grazing incidence).
                    const auto by_chords = water.trace(rays[k], counting_scene<Sc, false>{&sc}, T(0.2));
                    REQUIRE(by_chords);
                    const double d = double(glm::length(alone->surface.point - by_chords->surface.point));
                    worst_m = std::max(worst_m, d);
                    off_1mm += d > 1e-3;
                }
            }
    MESSAGE(compared << " rays, " << hits << " hits (" << objects << " on objects), " << guided << " guided; hits off the "
                     << "chord walk's by over 1 mm: " << off_1mm << ", worst " << worst_m << " m");
    CHECK(guided > compared / 2);
    CHECK(objects > 20);
    CHECK(off_1mm * 200 < hits);
}

namespace {
// A flat seabed at world z `z` that records what a guided ray asks it (and clears nothing).
struct bound_probe {
    using value_type = double;
    double z;
    mutable std::optional<scene::beside_rays<double>> asked;
    [[nodiscard]] std::optional<hit<double>> intersect(const ray<double>& r, double t) const {
        return scene::flat_seabed<double>(z).intersect(r, t);
    }
    [[nodiscard]] std::optional<hit<double>> intersect_beside(const ray<double>& r, double t, const ray<double>&, double) const {
        return intersect(r, t);
    }
    [[nodiscard]] std::optional<hit<double>> intersect_after(const ray<double>& r, double t, double) const {
        return intersect(r, t);
    }
    [[nodiscard]] double clear_range_beside_m(const scene::beside_rays<double>& b) const {
        asked = b;
        return 0;
    }
    [[nodiscard]] double seabed_height_m(double, double) const { return z; }
    [[nodiscard]] double top_m() const { return z; }
};
} // namespace

TEST_CASE("A shallower bent ray lies at least the bound's gain times the range above its steeper neighbour, and comes "
          "down no faster than its slope, in water that bends rays down and up") {
    std::vector<layered<double>> waters = guided_waters<double>();
    layered_params<double> p;
    p.surface_z_m = 40;
    waters.emplace_back(sound_speed_profile<double>::constant(1500), p);
    const vec3<double> fish{0, 0, 10};
    // Depth (m below the source) of ray r at horizontal distance rho: where a flat seabed meets it there.
    const auto range_at = [&](const layered<double>& w, const ray<double>& r, double drop) {
        const auto h = w.trace(r, bound_probe{fish.z - drop, std::nullopt}, 1.0);
        return h ? std::hypot(h->surface.point.x - fish.x, h->surface.point.y - fish.y) : -1.0;
    };
    int checked = 0, refused = 0;
    double worst_iso = 0;
    for (std::size_t wi = 0; wi < waters.size(); ++wi) {
        const layered<double>& w = waters[wi];
        for (const double e : {4.0, 9.0, 20.0, 45.0})
            for (const double de : {0.5, 0.01, 1e-4}) {
                const ray<double> a = fan_ray(fish, 0.3, e * deg), r = fan_ray(fish, 0.3, (e - de) * deg);
                const bound_probe asked{fish.z - 35, std::nullopt};
                const auto a_path = w.trace(a, asked, 1.0);
                if (!a_path) continue; // turned back up before the seabed
                (void)w.trace_beside(r, asked, 1.0, a.direction, a_path->clear_range_m);
                if (!asked.asked) { // r may level off: no bound is claimed
                    ++refused;
                    continue;
                }
                const scene::beside_rays<double> b = *asked.asked;
                CHECK(b.rho_a_m == a_path->clear_range_m);
                for (const double drop : {0.5, 3.0, 10.0, 25.0, 34.0}) {
                    const double rho = range_at(w, a, drop);
                    if (!(rho > 0) || rho > b.rho_a_m) continue;
                    // r's depth at rho, by bisection over flat seabeds.
                    double lo = 0, hi = drop;
                    for (int it = 0; it < 60; ++it) {
                        const double mid = 0.5 * (lo + hi);
                        (range_at(w, r, mid) < rho ? lo : hi) = mid;
                    }
                    const double gap = drop - hi;
                    ++checked;
                    CHECK(gap >= b.gain * rho * (1 - 1e-9) - 1e-9);
                    CHECK(hi <= b.slope_r * rho + 1e-9);
                    if (wi == waters.size() - 1 && de < 0.1) // isovelocity, close neighbours: the bound is nearly tight
                        worst_iso = std::max(worst_iso, 1 - b.gain * rho / gap);
                }
            }
    }
    MESSAGE(checked << " depths checked, " << refused << " pairs refused; in isovelocity water the bound is within "
                    << worst_iso << " of the gap");
    CHECK(checked > 150);
    CHECK(worst_iso < 0.02);
}

TEST_CASE_TEMPLATE("a ray's height at a horizontal range is where its trace meets a vertical wall there, layered or "
                   "straight, and none where the trace never gets there", T, float, double) {
    // A thermocline (rays bend, some turn up), a sound channel (rays trapped) and uniform water; launches up and
    // down, ranges near and far. The wall faces the source along the ray's heading.
    const layered<T> thermo(sound_speed_profile<T>({0, 44, 54, 200}, {1500, 1499, 1479, 1481.409f}), exact<T>(T(200)));
    const layered<T> channel(sound_speed_profile<T>({0, 50, 100, 300}, {1500, 1480, 1500, 1503}), exact<T>(T(300)));
    const straight<T> uniform;
    const double tol = std::is_same_v<T, float> ? 2e-3 : 1e-8; // m per 100 m of range
    std::size_t compared = 0, both_none = 0;
    const auto check = [&](const auto& water, T surface_z, double depth, double graze_deg, double range_m, T t_max_s) {
        const double az = 0.7;
        const ray<T> r = launch<T>(surface_z, T(depth), graze_deg * deg, az);
        const vec3<T> n{T(std::cos(az)), T(std::sin(az)), T(0)};
        plane_scene<T> wall;
        wall.n = n;
        wall.d = glm::dot(n, r.origin) + T(range_m);
        const auto traced = water.trace(r, wall, t_max_s);
        const auto asked = water.height_at_range_m(r, T(range_m), t_max_s);
        CAPTURE(depth);
        CAPTURE(graze_deg);
        CAPTURE(range_m);
        REQUIRE(bool(traced) == bool(asked));
        if (!asked) {
            ++both_none;
            return;
        }
        ++compared;
        // (Near vertical, the height moves by the slope dz / dx for each error in range: float rounds the range.)
        const double slope = std::abs(double(*asked) - double(r.origin.z)) / range_m;
        CHECK(std::abs(double(*asked) - double(traced->surface.point.z)) <= tol * (1 + range_m / 100) * (1 + slope));
    };
    for (const double depth : {20.0, 49.0, 60.0})
        for (const double graze : {-30.0, -4.0, -0.5, 0.0, 0.5, 3.0, 8.0, 20.0, 60.0, 89.0})
            for (const double range : {0.5, 3.0, 40.0, 250.0, 2000.0}) {
                check(thermo, T(200), depth, graze, range, T(3));
                check(channel, T(300), depth + 3, graze, range, T(3));
                check(uniform, T(0), depth, graze, range, T(3));
            }
    // Horizontal on the channel's axis (a knot whose layers both bend it back): it runs along the knot.
    check(channel, T(300), 50.0, 0.0, 40.0, T(3));
    check(channel, T(300), 50.0, 0.0, 900.0, T(3));
    // Time runs out: a ray 1 s long reaches about 1500 m, no further.
    check(thermo, T(200), 30.0, 1.0, 1400.0, T(1));
    check(thermo, T(200), 30.0, 1.0, 1600.0, T(1));
    check(uniform, T(0), 30.0, 1.0, 1600.0, T(1));
    MESSAGE(compared << " heights compared, " << both_none << " rays that never get there");
    CHECK(compared > 200);
    CHECK(both_none > 20);
}

TEST_CASE("absorption integrates Francois-Garrison and Ainslie-McColm along the path") {
    // A vertical ray through uniform water from 50 m to 1050 m: exactly length x depth mean.
    for (auto formula : {absorption_formula::francois_garrison, absorption_formula::ainslie_mccolm}) {
        layered_params<double> p = exact(1050.0);
        p.absorption = formula;
        p.frequency_hz = 100000;
        const layered<double> water(sound_speed_profile<double>::constant(1500), p);
        const auto h = water.trace(launch<double>(1050, 50, 90 * deg, 0.0), scene::flat_seabed<double>(0), 10.0);
        REQUIRE(h);
        const double want_db = formula == absorption_formula::francois_garrison
                                   ? straight_path_absorption_db(francois_garrison<double>(100000, {}), 50.0, 1050.0, 1000.0)
                                   : straight_path_absorption_db(ainslie_mccolm<double>(100000, {}), 50.0, 1050.0, 1000.0);
        const double e = rel(-10 * std::log10(h->absorption), want_db);
        MESSAGE("1000 m vertical path, relative error of the absorption (dB): " << e);
        CHECK(e < 1e-10);
    }
    // The two formulas differ by a few percent at 300 kHz, as published (Ainslie-McColm within 10% of F-G).
    layered_params<double> am = exact(60.0);
    am.absorption = absorption_formula::ainslie_mccolm;
    const layered<double> a(thermocline(), am), f(thermocline(), exact(60.0));
    const double ratio = a.absorption_db_per_km(50) / f.absorption_db_per_km(50);
    CHECK(ratio > 0.9);
    CHECK(ratio < 1.1);
    CHECK(ratio != 1.0);
}

TEST_CASE("float layered water matches the closed forms and the straight policy to float precision") {
    const layered<float> water(sound_speed_profile<float>({10.f, 1010.f}, {1500.f, 1600.f}), exact<float>());
    const auto r = launch<float>(0.f, 10.f, 20 * deg, 0.7);
    const auto p = water.trace_path(r, scene::flat_seabed<float>(-110.f), 1.f);
    REQUIRE(p);
    const auto ref = textbook_arc(1500, 0.1L, 20 * static_cast<ld>(deg), 100);
    CHECK(rel(p->range_m, ref.x) < 2e-6);
    CHECK(rel(p->result.time_s, ref.t) < 2e-6);
    const layered<float> iso(sound_speed_profile<float>({0.f, 30.f, 55.f}, {1500.f, 1500.f, 1500.f}), exact(70.f));
    const straight<float> st({.sound_speed_mps = 1500.f, .absorption_db_per_km = 40.f});
    for (double graze : {3.0, 20.0, 60.0, 90.0}) {
        const auto rr = launch<float>(70.f, 50.f, graze * deg, 1.0);
        const auto a = iso.trace(rr, scene::flat_seabed<float>(0.f), 1.f);
        const auto b = st.trace(rr, scene::flat_seabed<float>(0.f), 1.f);
        REQUIRE(a);
        REQUIRE(b);
        CHECK(rel(a->time_s, b->time_s) < 2e-6);
        CHECK(rel(a->spreading, b->spreading) < 5e-6);
        CHECK(glm::length(a->surface.point - b->surface.point) < 1e-4f);
    }
}

TEST_CASE("invalid layered parameters are rejected, naming the field") {
    const auto profile = sound_speed_profile<double>::constant(1500);
    auto throws_naming = [&](layered_params<double> p, const char* name) {
        try {
            (void)layered<double>(profile, p);
            return false;
        } catch (const sss::invalid_parameter& e) {
            return std::string(e.what()).find(name) != std::string::npos;
        }
    };
    layered_params<double> p;
    p.chord_tolerance_m = 0;
    CHECK(throws_naming(p, "layered.chord_tolerance_m"));
    p = {};
    p.frequency_hz = -1;
    CHECK(throws_naming(p, "layered.frequency_hz"));
    p = {};
    p.surface_z_m = std::numeric_limits<double>::quiet_NaN();
    CHECK(throws_naming(p, "layered.surface_z_m"));
    p = {};
    p.water.temperature_c = 80;
    CHECK(throws_naming(p, "water.temperature_c"));
    p = {};
    p.reference_speed_mps = -3;
    CHECK(throws_naming(p, "layered.reference_speed_mps"));
}

TEST_CASE("a ray launched horizontally on a knot where the gradient does not change spreads as with no knot there") {
    // 0.2 1/s from 0 to 100 m, given with and without a knot at 50 m; the ray leaves 50 m horizontally and bends up
    // to a ceiling at 20 m. The knot made a piece of no length first, and the next piece's lead 0/0: spreading 0.
    const layered<double> split(sound_speed_profile<double>({0, 50, 100}, {1500, 1510, 1520}), exact(100.0));
    const layered<double> whole(sound_speed_profile<double>({0, 100}, {1500, 1520}), exact(100.0));
    plane_scene<double> ceiling;
    ceiling.d = 80; // world z of 20 m depth
    for (double graze : {0.0, 1e-9, -1e-9}) {
        CAPTURE(graze);
        const ray<double> r{vec3<double>{0, 0, 50}, vec3<double>{std::cos(graze), 0, -std::sin(graze)}};
        const auto a = split.trace_path(r, ceiling, 1.0), b = whole.trace_path(r, ceiling, 1.0);
        REQUIRE(a);
        REQUIRE(b);
        CHECK(a->outgoing_spreading > 0.0);
        CHECK(rel(a->outgoing_spreading, b->outgoing_spreading) < 1e-9);
        CHECK(rel(a->result.spreading, b->result.spreading) < 1e-9);
    }
}

TEST_CASE("at a caustic the tube is held to 30 dB of focusing: spreading bounded and rising towards it, never 0") {
    // A tube with Q = 1300 m^2/s whose w = |sin_hit K + q lead| crosses 0: ray theory gives c^2 / (Q w), unbounded,
    // and gave 0 where w is exactly 0. Held at w >= Q / 1000: at most 1000 c^2 / Q^2.
    const ray_tube<double> tube{1500.0, 0.3, 1000.0, -1500.0, true};
    const double cap = 1000.0 * 1500.0 * 1500.0 / (1300.0 * 1300.0);
    CHECK(tube.outgoing_spreading(300.0, 0.3, 0.2) == doctest::Approx(cap).epsilon(1e-12));
    double last = 0.0;
    for (double off : {1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 0.0}) {
        const double s = tube.outgoing_spreading(300.0, 0.3, 0.2 + off);
        CAPTURE(off);
        CHECK(s <= cap * (1.0 + 1e-12));
        CHECK(s >= last);
        CHECK(1500.0 * 1500.0 * tube.inverse_qw(300.0, 0.3, 0.2 + off) == doctest::Approx(s).epsilon(1e-12));
        last = s;
    }
    // Away from it, nothing changes: 1e-2 off is 22 dB below the hold.
    CHECK(tube.outgoing_spreading(300.0, 0.3, 0.21) == doctest::Approx(1500.0 * 1500.0 / (1300.0 * 15.0)).epsilon(1e-12));
}

TEST_CASE("layered trace_many refuses too few slots, and a ray from no finite point, naming them") {
    const layered<double> water(thermocline(), exact(60.0));
    const scene::flat_seabed<double> seabed(0);
    const std::vector<ray<double>> rays(3, launch<double>(60, 50, 20 * deg, 0.3));
    std::vector<std::optional<path<double>>> paths(2);
    try {
        water.trace_many(std::span<const ray<double>>(rays), seabed, 1.0, std::span<std::optional<path<double>>>(paths));
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "layered.trace_many.paths");
    }
    ray<double> bad = rays[0];
    bad.origin.z = std::nan("");
    try {
        (void)water.trace(bad, seabed, 1.0);
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(std::string(e.what()).find("must be finite") != std::string::npos);
    }
}
