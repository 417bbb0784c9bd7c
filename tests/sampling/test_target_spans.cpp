// Where small targets lie among a side's launch angles (sampling/target_spans.hpp): every ray that meets a sphere or a
// cylinder in the beam leaves within one of the spans, straight or refracted, level or tilted; what lies beyond the
// line's range, outside the beam or on the other side gives none; a long cylinder is cut into pieces narrower along
// track than a column, and never into more than the cap allows.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/matrix.hpp>

#include <sss/beam/concept.hpp>
#include <sss/core/pose.hpp>
#include <sss/propagation/layered.hpp>
#include <sss/propagation/straight.hpp>
#include <sss/sampling/target_spans.hpp>
#include <sss/scene/object.hpp>
#include <sss/scene/object_set.hpp>

#include "support/rough_scenes.hpp"

namespace {

const double deg = 3.141592653589793 / 180.0;
using sss::vec3;

constexpr double range_m = 60.0;   // the line's range
constexpr double t_max_s = 0.06;   // one way: 90 m at 1500 m/s
constexpr double column_rad = 0.005;

// A 3.4 deg beam along track, from 10 deg above the horizontal to straight down.
const sss::beam_extent<double> extent{-0.03, 0.03, -10 * deg, 90 * deg};

sss::pose<double> towfish(bool tilted) {
    return tilted ? sss::make_pose<double>(0.0, vec3<double>{0.0, 0.0, 10.0}, 6 * deg, 4 * deg, 20 * deg)
                  : sss::make_pose<double>(0.0, vec3<double>{0.0, 0.0, 10.0}, 0.0, 0.0, 0.0);
}

// The launch angles (body frame: along track, depression) of the ray from the towfish that passes point q, found by
// bisection on the propagation's own height at q's range (independently of target_spans' Newton steps); nullopt where
// no ray between 80 deg up and 86 deg down does.
template <class P>
std::optional<std::pair<double, double>> launch_through(const P& water, const sss::pose<double>& p, sss::side sd,
                                                        const vec3<double>& q) {
    const double dx = q.x - p.position.x, dy = q.y - p.position.y, rho = std::hypot(dx, dy);
    if (!(rho > 0.0)) return std::nullopt;
    const double hx = dx / rho, hy = dy / rho, geometric = std::atan2(p.position.z - q.z, rho);
    const auto height = [&](double e) {
        const sss::ray<double> r{p.position, vec3<double>{std::cos(e) * hx, std::cos(e) * hy, -std::sin(e)}};
        if (const auto z = water.height_at_range_m(r, rho, t_max_s)) return *z;
        return e > geometric ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    };
    double lo = -80 * deg, hi = 86 * deg;
    if (!(height(lo) >= q.z && height(hi) <= q.z)) return std::nullopt;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (height(mid) >= q.z ? lo : hi) = mid;
    }
    const double e = 0.5 * (lo + hi);
    const vec3<double> b =
        glm::transpose(p.body_to_world) * vec3<double>{std::cos(e) * hx, std::cos(e) * hy, -std::sin(e)};
    const double s = sss::side_sign<double>(sd);
    if (!(s * b.y > 0.0)) return std::nullopt;
    return std::pair{std::asin(std::clamp(b.x, -1.0, 1.0)), std::atan2(b.z, s * b.y)};
}

// Points on the surface of a sphere and of a cylinder's side (random, from a fixed seed).
std::vector<vec3<double>> surface_points(const sss::scene::sphere<double>& sp, std::size_t n, std::mt19937& g) {
    std::normal_distribution<double> gauss;
    std::vector<vec3<double>> out;
    for (std::size_t i = 0; i < n; ++i) {
        vec3<double> u{gauss(g), gauss(g), gauss(g)};
        out.push_back(sp.center_m() + sp.radius_m() * u / std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z));
    }
    return out;
}

std::vector<vec3<double>> surface_points(const sss::scene::cylinder<double>& c, std::size_t n, std::mt19937& g) {
    std::uniform_real_distribution<double> u01;
    const vec3<double> a = c.end0_m(), d = c.end1_m() - c.end0_m();
    const vec3<double> axis = d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    vec3<double> e1 = std::abs(axis.z) < 0.9 ? vec3<double>{-axis.y, axis.x, 0.0} : vec3<double>{1.0, 0.0, 0.0};
    e1 -= (e1.x * axis.x + e1.y * axis.y + e1.z * axis.z) * axis;
    e1 /= std::sqrt(e1.x * e1.x + e1.y * e1.y + e1.z * e1.z);
    const vec3<double> e2{axis.y * e1.z - axis.z * e1.y, axis.z * e1.x - axis.x * e1.z, axis.x * e1.y - axis.y * e1.x};
    std::vector<vec3<double>> out;
    for (std::size_t i = 0; i < n; ++i) {
        const double f = u01(g), phi = 2.0 * 3.141592653589793 * u01(g);
        out.push_back(a + f * d + c.radius_m() * (std::cos(phi) * e1 + std::sin(phi) * e2));
    }
    return out;
}

std::vector<sss::target_span> spans_of(const auto& water, const sss::scene::object_set<double>& objects,
                                       const sss::pose<double>& p, sss::side sd, double column = column_rad) {
    std::vector<sss::target_span> out;
    sss::target_spans(water, objects, p, sd, extent, column, t_max_s, range_m, out);
    return out;
}

// Every point of the objects' surfaces that a ray of this side's beam can reach within the line's range (and more
// than `clear_m` out to the side, past the rays under the towfish) is passed by a ray launched within one of the
// spans. Spheres wider along track than three columns are left out: they give no span (the columns' own comparison
// sees their edges). Returns how many points were checked; each one outside every span fails the check.
template <class P>
std::size_t check_covered(const P& water, const sss::scene::object_set<double>& objects, const sss::pose<double>& p,
                          sss::side sd, const std::vector<sss::target_span>& spans, double clear_m) {
    std::mt19937 g(7);
    const double s = sss::side_sign<double>(sd);
    std::size_t checked = 0;
    const auto check = [&](const vec3<double>& q) {
        const vec3<double> w = q - p.position;
        const double dist = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        if (!(dist <= range_m) || !(s * (glm::transpose(p.body_to_world) * w).y > clear_m)) return;
        const auto a = launch_through(water, p, sd, q);
        if (!a || a->first < extent.along_min_rad || a->first > extent.along_max_rad) return;
        ++checked;
        const bool inside = std::any_of(spans.begin(), spans.end(), [&](const sss::target_span& t) {
            return a->first >= t.along_lo && a->first <= t.along_hi && a->second >= t.depression_lo &&
                   a->second <= t.depression_hi;
        });
        INFO("point (" << q.x << ", " << q.y << ", " << q.z << ") launched at along " << a->first << " rad, depression "
                       << a->second << " rad; " << spans.size() << " spans");
        CHECK(inside);
    };
    for (const auto& o : objects.objects()) {
        for (const auto& sp : o.spheres()) {
            const vec3<double> w = sp.center_m() - p.position;
            // Its span: its angular diameter widened by a tenth either way; within three columns with a margin.
            if (2.4 * std::asin(sp.radius_m() / std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z)) > 2.7 * column_rad)
                continue;
            for (const auto& q : surface_points(sp, 400, g)) check(q);
        }
        for (const auto& c : o.cylinders())
            for (const auto& q : surface_points(c, 4000, g)) check(q);
    }
    return checked;
}

sss::scene::object_set<double> one(std::vector<sss::scene::sphere<double>> spheres,
                                   std::vector<sss::scene::cylinder<double>> cylinders) {
    std::vector<sss::scene::object<double>> objs;
    objs.push_back(sss::scene::object<double>(std::move(spheres), std::move(cylinders)));
    return sss::scene::object_set<double>(std::move(objs));
}

template <class P> void check_every_target(const P& water) {
    for (const bool tilted : {false, true}) {
        CAPTURE(tilted);
        const auto p = towfish(tilted);
        // The towfish heads north (yaw 20 deg when tilted): starboard is east. Targets placed across and along its
        // heading (along: ahead positive).
        const auto at = [&](double across_m, double along_m, double z_m) {
            const vec3<double> fwd{std::sin(p.yaw_rad), std::cos(p.yaw_rad), 0.0};
            const vec3<double> right{std::cos(p.yaw_rad), -std::sin(p.yaw_rad), 0.0};
            return p.position + across_m * right + along_m * fwd + vec3<double>{0.0, 0.0, z_m - p.position.z};
        };
        {   // small spheres, on the seabed and moored
            std::vector<sss::scene::sphere<double>> spheres;
            for (const double x : {6.0, 15.0, 24.0, 40.0, 57.0})
                for (const double y : {-0.5, 0.0, 0.3})
                    for (const double z : {0.056, 5.0}) spheres.push_back({at(x, y, z), 0.08, {.material = 1}});
            const auto objects = one(spheres, {});
            const auto spans = spans_of(water, objects, p, sss::side::starboard);
            CHECK(check_covered(water, objects, p, sss::side::starboard, spans, 0.5) > 1000);
            for (const auto& t : spans) CHECK(t.depression_step_rad == doctest::Approx(0.5 * t.depression_thickness_rad).scale(0));
        }
        {   // cables at every angle to the track
            for (const double turned : {0.0, 15.0, 30.0, 60.0, 85.0}) {
                CAPTURE(turned);
                const vec3<double> mid = at(24.0, 0.1, 0.03);
                const vec3<double> dir = std::cos(turned * deg) * vec3<double>{std::cos(p.yaw_rad), -std::sin(p.yaw_rad), 0.0} +
                                         std::sin(turned * deg) * vec3<double>{std::sin(p.yaw_rad), std::cos(p.yaw_rad), 0.0};
                const auto objects = one({}, {sss::scene::cylinder<double>(mid - 5.0 * dir, mid + 5.0 * dir, 0.03, {.material = 1})});
                const auto spans = spans_of(water, objects, p, sss::side::starboard);
                CHECK(check_covered(water, objects, p, sss::side::starboard, spans, 0.5) > 100);
            }
        }
        {   // a cable 400 m long, across the track under the towfish, and oblique to it through the beam
            for (const double turned : {0.0, 45.0}) {
                CAPTURE(turned);
                const vec3<double> mid = at(turned == 0.0 ? 0.0 : 24.0, 0.2, 0.03);
                const vec3<double> dir = std::cos(turned * deg) * vec3<double>{std::cos(p.yaw_rad), -std::sin(p.yaw_rad), 0.0} +
                                         std::sin(turned * deg) * vec3<double>{std::sin(p.yaw_rad), std::cos(p.yaw_rad), 0.0};
                const auto objects = one({}, {sss::scene::cylinder<double>(mid - 200.0 * dir, mid + 200.0 * dir, 0.03, {.material = 1})});
                // Across the track it crosses both sides' beams; turned 45 deg through a point 24 m to starboard,
                // only starboard's.
                if (turned != 0.0) CHECK(spans_of(water, objects, p, sss::side::port).empty());
                for (const auto sd : {sss::side::port, sss::side::starboard}) {
                    if (turned != 0.0 && sd == sss::side::port) continue;
                    const auto spans = spans_of(water, objects, p, sd);
                    CHECK(check_covered(water, objects, p, sd, spans, 0.5) > 10);
                    // Cut into pieces where it crosses the beam (a handful across it, more where it runs along it),
                    // each that divides its columns narrower along track than one.
                    CHECK(spans.size() >= 2);
                    CHECK(spans.size() <= 64);
                    for (const auto& t : spans)
                        if (t.along) CHECK(t.thickness_rad < column_rad);
                }
            }
        }
        {   // a moored mine, abeam and ahead: its case (0.15 m in radius, 5 m up: narrower than three columns, a span
            // of its own) and its tether
            for (const double ahead_m : {0.0, 0.2}) {
                CAPTURE(ahead_m);
                const vec3<double> anchor = at(30.0, ahead_m, 0.0);
                const auto objects =
                    one({{anchor + vec3<double>{0.0, 0.0, 5.0}, 0.15, {.material = 1}}},
                        {sss::scene::cylinder<double>(anchor, anchor + vec3<double>{0.0, 0.0, 4.7}, 0.01, {.material = 1})});
                const auto spans = spans_of(water, objects, p, sss::side::starboard);
                CHECK(check_covered(water, objects, p, sss::side::starboard, spans, 0.5) > 1000);
                // Abeam of a level towfish the tether's ends share their along-track angle: it has no finite width
                // in depression (one column's rays meet it all along or not at all), and nothing to halve.
                if (!tilted && ahead_m == 0.0)
                    CHECK(std::any_of(spans.begin(), spans.end(),
                                      [](const sss::target_span& t) { return !std::isfinite(t.depression_step_rad); }));
            }
        }
    }
}

} // namespace

TEST_CASE("every ray that meets a small target leaves within its span, straight or refracted, level or tilted") {
    SUBCASE("straight") { check_every_target(sss::propagation::straight<double>{}); }
    SUBCASE("three-layer water") { check_every_target(sss_test::three_layer_water<double>()); }
}

TEST_CASE("targets beyond the line's range, outside the beam along track or on the other side give no span") {
    const auto water = sss::propagation::straight<double>{};
    const auto p = towfish(false);
    // 1.1 times the range out, 5 m behind the towfish (0.19 rad off the beam's axis, 0.16 rad outside it), and to port.
    const auto objects = one({{{std::sqrt(1.1 * range_m * 1.1 * range_m - 100.0), 0.0, 0.0}, 0.05, {.material = 1}},
                              {{24.0, -5.0, 0.0}, 0.05, {.material = 1}},
                              {{-24.0, 0.0, 0.0}, 0.05, {.material = 1}}},
                             {sss::scene::cylinder<double>({20.0, -8.0, 0.0}, {40.0, -8.0, 0.0}, 0.03, {.material = 1})});
    CHECK(spans_of(water, objects, p, sss::side::starboard).empty());
    // The sphere to port is seen from port, nothing else is.
    const auto port = spans_of(water, objects, p, sss::side::port);
    REQUIRE(port.size() == 1);
    CHECK(port[0].along_lo < 0.0);
    CHECK(port[0].along_hi > 0.0);
}

TEST_CASE("a cable is never cut into more than 4096 pieces, however narrow the columns") {
    const auto water = sss::propagation::straight<double>{};
    const auto p = towfish(false);
    // A wire 0.2 mm across, 400 m long at 45 deg to the track through the beam, under columns of 10 urad: each piece
    // half a column wide along track is thin enough to be a target, and the 0.06 rad beam alone would take about
    // 12,000 of them (more than 4096 spans without the cap).
    const vec3<double> mid{24.0, 0.1, 0.0001}, half{141.42, 141.42, 0.0};
    const auto wire = one({}, {sss::scene::cylinder<double>(mid - half, mid + half, 0.0001, {.material = 1})});
    CHECK(spans_of(water, wire, p, sss::side::starboard, 1e-5).size() <= 4096);
    // At a 5 mrad column the same wire's pieces in the beam are a few dozen.
    const auto spans = spans_of(water, wire, p, sss::side::starboard);
    CHECK(spans.size() > 0);
    CHECK(spans.size() < 64);
}
