// Target builders: the taut string is the upper convex hull (bridging hollows, following crests), a pipeline
// rests on the seabed where supported and spans depressions in a straight line, a lying cylinder rests on
// the seabed at any heading, a tethered mine is assembled as specified, and debris is reproducible.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <sss/scene/flat_seabed.hpp>
#include <sss/seabed/targets.hpp>

namespace {

using sss::ray;
using sss::vec2;
using sss::vec3;
namespace sb = sss::seabed;

template <class T> std::string param_of(auto&& make) {
    try {
        make();
    } catch (const sss::invalid_parameter& e) {
        return e.parameter();
    }
    return "(none)";
}

// The string's height at s, by linear interpolation between its supports.
double string_at(const std::vector<double>& s, const std::vector<double>& z, const std::vector<std::size_t>& sup, double x) {
    for (std::size_t k = 0; k + 1 < sup.size(); ++k) {
        const std::size_t a = sup[k], b = sup[k + 1];
        if (x <= s[b]) return z[a] + (z[b] - z[a]) * (x - s[a]) / (s[b] - s[a]);
    }
    return z[sup.back()];
}

// A flat seabed at -20 m with a smooth trench across x = 10 (along y): 6 m wide, 1 m deep.
double trench_depth(double x) {
    const double d = std::abs(x - 10.0);
    return d < 3.0 ? 0.5 * (1.0 + std::cos(3.141592653589793 * d / 3.0)) : 0.0;
}

} // namespace

TEST_CASE("The taut string bridges a V-shaped hollow from rim to rim and follows a crest sample by sample") {
    std::vector<double> s, z;
    for (int i = 0; i <= 100; ++i) {
        s.push_back(0.1 * i);
        z.push_back(i >= 40 && i <= 60 ? -0.05 * (10 - std::abs(i - 50)) : 0.0);
    }
    auto sup = sb::taut_string<double>(s, z);
    REQUIRE(sup.size() == 2u); // the flat stretches are collinear with the bridge: only the ends remain
    CHECK(sup.front() == 0u);
    CHECK(sup.back() == 100u);
    // A crest: z = -(s - 5)^2 is concave, every sample is a support.
    for (std::size_t i = 0; i < s.size(); ++i) z[i] = -(s[i] - 5) * (s[i] - 5);
    sup = sb::taut_string<double>(s, z);
    CHECK(sup.size() == s.size());
}

TEST_CASE("On a random profile the taut string lies on or above every sample and turns only downwards") {
    std::mt19937_64 g(2);
    std::normal_distribution<double> n(0, 1);
    std::vector<double> s, z;
    double level = 0;
    for (int i = 0; i < 2000; ++i) {
        s.push_back(0.05 * i + 0.01 * (i % 3));
        level += 0.02 * n(g);
        z.push_back(level);
    }
    for (double reach : {1e9, 20.0, 3.0}) {
        const auto sup = sb::taut_string<double>(s, z, reach);
        REQUIRE(sup.front() == 0u);
        REQUIRE(sup.back() == s.size() - 1);
        double worst = 0;
        for (std::size_t i = 0; i < s.size(); ++i) worst = std::max(worst, z[i] - string_at(s, z, sup, s[i]));
        CHECK(worst < 1e-12);
        for (std::size_t k = 0; k + 1 < sup.size(); ++k) CHECK(s[sup[k + 1]] - s[sup[k]] <= reach + 1e-9);
        if (reach > 1e6) { // unlimited: concave (slopes decrease)
            for (std::size_t k = 0; k + 2 < sup.size(); ++k) {
                const double m0 = (z[sup[k + 1]] - z[sup[k]]) / (s[sup[k + 1]] - s[sup[k]]);
                const double m1 = (z[sup[k + 2]] - z[sup[k + 1]]) / (s[sup[k + 2]] - s[sup[k + 1]]);
                CHECK(m1 < m0);
            }
        }
    }
}

TEST_CASE("A disc rests at z + r on a flat profile and on the corner of a step near its edge") {
    std::vector<double> s, z;
    for (int i = 0; i <= 40; ++i) {
        s.push_back(0.05 * i);
        z.push_back(i <= 20 ? 1.0 : 0.0);
    }
    const auto c = sb::disc_rest_heights<double>(s, z, 0.3);
    CHECK(c[5] == doctest::Approx(1.3));
    CHECK(c[39] == doctest::Approx(0.3));
    // 0.2 m beyond the step's corner (s = 1) the disc leans on the corner: 1 + sqrt(0.3^2 - 0.2^2).
    CHECK(c[24] == doctest::Approx(1.0 + std::sqrt(0.09 - 0.04)));
}

TEST_CASE_TEMPLATE("A pipeline on a flat seabed lies on it: one straight segment per leg, joints closed by spheres", T,
                   float, double) {
    sb::pipeline_params<T> p;
    p.route_m = {{T(0), T(0)}, {T(30), T(0)}, {T(30), T(20)}};
    p.radius_m = T(0.4);
    const auto flat = [](T, T) { return T(-20); };
    const auto l = sb::lay_pipeline(p, flat);
    REQUIRE(l.axis_m.size() == 3u);
    for (const auto& v : l.axis_m) CHECK(v.z == doctest::Approx(-19.6));
    CHECK(l.axis_m[1].x == doctest::Approx(30.0));
    CHECK(l.spans.empty());
    const auto pipe = sb::pipeline(p, flat);
    CHECK(pipe.cylinders().size() == 2u);
    CHECK(pipe.spheres().size() == 1u);
    CHECK(pipe.bounds().lo.z == doctest::Approx(-20.0));
    const auto h = pipe.intersect(ray<T>{vec3<T>{T(15), T(0), T(0)}, vec3<T>{T(0), T(0), T(-1)}}, T(100));
    REQUIRE(h);
    CHECK(h->point.z == doctest::Approx(-19.2));
    CHECK(h->label == 2u);
}

TEST_CASE_TEMPLATE("A pipeline spans a trench in a straight line from rim to rim and rests on the seabed elsewhere", T,
                   float, double) {
    sb::pipeline_params<T> p;
    p.route_m = {{T(0), T(5)}, {T(25), T(5)}};
    p.radius_m = T(0.3);
    p.profile_step_m = T(0.05);
    const auto seabed = [](T x, T) { return T(-20.0 - trench_depth(double(x))); };
    const auto l = sb::lay_pipeline(p, seabed);
    REQUIRE(l.spans.size() == 1u);
    // A disc of radius r leaves the flat at the trench's rim (x = 7 and 13); the cosine wall falls away
    // faster than the disc can follow for only a few centimetres, so the supports are the rims.
    CHECK(double(l.spans[0].start_m) == doctest::Approx(7.0).epsilon(0.01));
    CHECK(double(l.spans[0].end_m) == doctest::Approx(13.0).epsilon(0.01));
    CHECK(double(l.spans[0].clearance_m) == doctest::Approx(1.0).epsilon(0.01));
    // The axis is straight and level at -19.7 all along (the rims are level).
    for (const auto& v : l.axis_m) CHECK(double(v.z) == doctest::Approx(-19.7).epsilon(1e-5));
    // Nowhere is the pipe's bottom below the seabed.
    const auto pipe = sb::pipeline_object(l, p);
    for (double x = 0.01; x < 25; x += 0.01) {
        const auto h = pipe.intersect(ray<T>{vec3<T>{T(x), T(5), T(0)}, vec3<T>{T(0), T(0), T(-1)}}, T(100));
        REQUIRE(h);
        CHECK(double(h->point.z) == doctest::Approx(-19.4).epsilon(1e-5)); // the top, over the span too
        const auto up = pipe.intersect(ray<T>{vec3<T>{T(x), T(5), T(-30)}, vec3<T>{T(0), T(0), T(1)}}, T(100));
        REQUIRE(up);
        CHECK(double(up->point.z) >= double(seabed(T(x), T(5))) - 1e-4);
    }
}

TEST_CASE("A pipeline follows a crest, is pulled straight from a level foot to it, and with a short reach comes down") {
    sb::pipeline_params<double> p;
    p.route_m = {{0, 0}, {40, 0}};
    p.radius_m = 0.25;
    // A parabolic mound 1 m high on level ground (curvature radius 50 m >> r). The string from the route's
    // level ends is tangent to the mound at |x - 20| = 20 - sqrt(300) = 2.68 m (tangent from (0, 0) to
    // z = 1 - (x - 20)^2 / 100): the pipe rests on the crest between and spans from each end to it.
    const auto mound = [](double x, double) { return -10.0 + std::max(0.0, 1.0 - (x - 20) * (x - 20) / 100.0); };
    auto l = sb::lay_pipeline(p, mound);
    REQUIRE(l.spans.size() == 2u);
    CHECK(l.spans[0].start_m == doctest::Approx(0.0));
    CHECK(l.spans[0].end_m == doctest::Approx(20 - 2.68).epsilon(0.02));
    CHECK(l.spans[1].start_m == doctest::Approx(20 + 2.68).epsilon(0.02));
    CHECK(l.spans[1].end_m == doctest::Approx(40.0));
    double worst = 0;
    for (std::size_t i = 0; i < l.axis_m.size(); ++i)
        if (std::abs(l.axis_m[i].x - 20) < 2.5) worst = std::max(worst, std::abs(l.axis_m[i].z - 0.25 - mound(l.axis_m[i].x, 0)));
    CHECK(worst < 0.002); // the disc's offset r (1/cos - 1) at slope 0.05, and the merging tolerance
    // A reach of 5 m: the pipe comes down to the level ground on both sides.
    p.max_span_m = 5;
    l = sb::lay_pipeline(p, mound);
    CHECK(l.axis_m.front().z == doctest::Approx(-9.75));
    for (const auto& sp : l.spans) CHECK(sp.end_m - sp.start_m <= 5.0 + 1e-9);
    // A hollow 30 m wide and 2 m deep: unlimited reach spans it whole, a 10 m reach comes down into it.
    const auto hollow = [](double x, double) {
        const double d = std::abs(x - 20);
        return -10.0 - (d < 15 ? 1.0 + std::cos(3.141592653589793 * d / 15) : 0.0);
    };
    p.max_span_m = std::numeric_limits<double>::infinity();
    l = sb::lay_pipeline(p, hollow);
    REQUIRE(l.spans.size() == 1u);
    CHECK(l.spans[0].clearance_m == doctest::Approx(2.0).epsilon(0.01));
    p.max_span_m = 10;
    l = sb::lay_pipeline(p, hollow);
    CHECK(l.spans.size() >= 2u);
    for (const auto& sp : l.spans) CHECK(sp.end_m - sp.start_m <= 10.0 + 1e-9);
    double lowest = 0;
    for (const auto& v : l.axis_m) lowest = std::min(lowest, v.z);
    CHECK(lowest < -10.5);
}

TEST_CASE_TEMPLATE("A cylinder lying on a flat seabed at any heading (clockwise from north) has its axis r above it along the heading",
                   T, float, double) {
    for (T heading : {T(0), T(30), T(90), T(160), T(-115)}) {
        sb::lying_cylinder_params<T> p;
        p.center_m = {T(3), T(-4)};
        p.heading_deg = heading;
        p.length_m = T(4);
        p.radius_m = T(0.35);
        const auto o = sb::lying_cylinder(p, [](T, T) { return T(-15); });
        REQUIRE(o.cylinders().size() == 1u);
        const auto& c = o.cylinders()[0];
        CHECK(c.end0_m().z == doctest::Approx(-14.65));
        CHECK(c.end1_m().z == doctest::Approx(-14.65));
        // Heading h clockwise from north: the axis points (east, north) = (sin h, cos h), up to its sign.
        const double sign = c.axis().y * std::cos(sss::deg_to_rad(double(heading))) + c.axis().x * std::sin(sss::deg_to_rad(double(heading))) < 0 ? -1.0 : 1.0;
        CHECK(sign * c.axis().x == doctest::Approx(std::sin(sss::deg_to_rad(double(heading)))).epsilon(1e-5));
        CHECK(sign * c.axis().y == doctest::Approx(std::cos(sss::deg_to_rad(double(heading)))).epsilon(1e-5));
        CHECK(c.center_m().x == doctest::Approx(3.0));
        CHECK(c.length_m() == doctest::Approx(4.0));
        CHECK(o.bounds().lo.z == doctest::Approx(-15.0));
    }
}

TEST_CASE("A cylinder on a slope lies along it at distance r, and one over a hollow rests on both rims") {
    sb::lying_cylinder_params<double> p;
    p.center_m = {0, 0};
    p.heading_deg = 90.0 - sss::rad_to_deg(0.3); // 0.3 rad counter-clockwise from east
    p.length_m = 5;
    p.radius_m = 0.5;
    const double m = 0.2; // slope along the heading
    const auto slope = [&](double x, double y) { return m * (x * std::cos(0.3) + y * std::sin(0.3)); };
    auto c = sb::lying_cylinder(p, slope).cylinders()[0];
    // Perpendicular distance from the axis to the plane z = m s is r.
    const auto dist = [&](vec3<double> q) {
        const double s = q.x * std::cos(0.3) + q.y * std::sin(0.3);
        return (q.z - m * s) / std::sqrt(1 + m * m);
    };
    CHECK(dist(c.end0_m()) == doctest::Approx(0.5));
    CHECK(dist(c.end1_m()) == doctest::Approx(0.5));
    CHECK(c.length_m() == doctest::Approx(5.0));
    // The middle of its axis lies over center_m, as its parameters say (it lay r sin(a) = 0.098 m downslope of it).
    const vec3<double> middle = 0.5 * (c.end0_m() + c.end1_m());
    CHECK(middle.x == doctest::Approx(0.0).scale(1.0).epsilon(1e-12));
    CHECK(middle.y == doctest::Approx(0.0).scale(1.0).epsilon(1e-12));
    // A 2 m wide, 0.5 m deep hollow under the middle: the cylinder bridges it, level at z = r.
    p.heading_deg = 90; // east
    const auto hollow = [](double x, double) { return std::abs(x) < 1 ? -0.5 * (1 - x * x) : 0.0; };
    c = sb::lying_cylinder(p, hollow).cylinders()[0];
    CHECK(c.end0_m().z == doctest::Approx(0.5));
    CHECK(c.end1_m().z == doctest::Approx(0.5));
}

TEST_CASE_TEMPLATE("A tethered mine has its case at the given height, a vertical tether and an anchor on the seabed", T,
                   float, double) {
    sb::tethered_mine_params<T> p;
    p.anchor_m = {T(32), T(7)};
    p.case_height_m = T(4);
    p.object_id = 12;
    p.class_id = 6;
    p.case_material = 2;
    p.tether_material = 3;
    p.anchor_material = 4;
    const auto seabed = [](T x, T y) { return T(-20) + T(0.01) * x - T(0.02) * y; };
    const T ground = seabed(T(32), T(7));
    const auto mine = sb::tethered_mine(p, seabed);
    REQUIRE(mine.spheres().size() == 1u);
    REQUIRE(mine.cylinders().size() == 2u);
    CHECK(mine.spheres()[0].center_m().z == doctest::Approx(double(ground) + 4.0));
    CHECK(mine.spheres()[0].center_m().x == doctest::Approx(32.0));
    const auto& tether = mine.cylinders()[0];
    const auto& anchor = mine.cylinders()[1];
    CHECK(tether.axis().z == doctest::Approx(1.0));
    CHECK(tether.end1_m().z == doctest::Approx(double(ground) + 4.0));
    CHECK(tether.end0_m().z == doctest::Approx(double(anchor.end1_m().z)));
    // The anchor's base is at the highest seabed point under its rim (the slope rises to -x... and -y).
    const double highest = double(ground) + 0.4 * std::sqrt(0.01 * 0.01 + 0.02 * 0.02);
    CHECK(double(anchor.end0_m().z) == doctest::Approx(highest).epsilon(1e-4));
    // A ray from the side at mid-tether height hits the tether: tether material, the mine's ids.
    const T zt = ground + T(2);
    const auto h = mine.intersect(ray<T>{vec3<T>{T(0), T(7), zt}, vec3<T>{T(1), T(0), T(0)}}, T(100));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(32.0 - 0.01));
    CHECK(h->material == 3u);
    CHECK(h->object == 12u);
    CHECK(h->label == 6u);
}

TEST_CASE("A cylindrical mine case clears its anchor by its true downward extent, and too low a case is rejected") {
    sb::tethered_mine_params<double> p;
    p.shape = sb::mine_case::cylinder;
    p.case_radius_m = 0.3;
    p.case_length_m = 2.0;
    p.case_tilt_deg = sss::rad_to_deg(0.5);
    p.case_height_m = 2.0;
    const auto flat = [](double, double) { return 0.0; };
    const auto mine = sb::tethered_mine(p, flat);
    const auto& c = mine.cylinders()[0];
    CHECK(c.axis().z == doctest::Approx(std::sin(0.5)));
    CHECK(c.center_m().z == doctest::Approx(2.0));
    // Straight down from the centre the side is r / cos(tilt) = 0.342 m away (the caps 1 / sin(tilt) = 2.09 m).
    const auto h = mine.intersect(ray<double>{vec3<double>{0, 0, 2.0}, vec3<double>{0, 0, -1}}, 10.0);
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(0.3 / std::cos(0.5)));
    // Its lowest point is the lower end's rim, (L/2) sin(tilt) + r cos(tilt) = 0.743 m below the centre: a case
    // centred 1 m up reaches 0.257 m, below the anchor's top at 0.3 m (straight down it would have cleared it).
    p.case_height_m = 1.0;
    CHECK(param_of<double>([&] { return sb::tethered_mine(p, flat); }) == "tethered_mine.case_height_m");
    p.case_height_m = 1.1;
    CHECK(sb::tethered_mine(p, flat).cylinders()[0].bounds().lo.z == doctest::Approx(1.1 - std::sin(0.5) - 0.3 * std::cos(0.5)).epsilon(1e-4));
    // A lying case reaching over a rise beside the anchor: clear of the anchor, not of the seabed.
    p.case_tilt_deg = 0.0;
    p.case_heading_deg = 90.0; // along +x
    p.case_length_m = 4.0;
    p.case_height_m = 1.0; // underside 0.7 m up
    const auto rise = [](double x, double) { return x > 1.5 ? 0.8 : 0.0; };
    CHECK(param_of<double>([&] { return sb::tethered_mine(p, rise); }) == "tethered_mine.case_height_m");
    CHECK_NOTHROW((void)sb::tethered_mine(p, flat));
    p.case_tilt_deg = sss::rad_to_deg(0.5);
    p.case_height_m = 2.0;
    p.tether_radius_m = 0.5;
    CHECK(param_of<double>([&] { return sb::tethered_mine(p, flat); }) == "tethered_mine.tether_radius_m");
}

TEST_CASE("A debris cluster is the same for the same seed, different for another, and rests on the seabed") {
    sb::debris_params<double> p;
    p.center_m = {10, -5};
    p.count = 30;
    p.seed = 77;
    p.first_object_id = 100;
    const auto seabed = [](double x, double y) { return -12.0 + 0.3 * std::sin(0.5 * x) * std::cos(0.4 * y); };
    const auto a = sb::debris_cluster(p, seabed), b = sb::debris_cluster(p, seabed);
    REQUIRE(a.size() == 30u);
    for (std::size_t k = 0; k < a.size(); ++k) {
        CHECK(a[k].bounds().lo.x == b[k].bounds().lo.x);
        CHECK(a[k].bounds().hi.z == b[k].bounds().hi.z);
        const auto ids = a[k].spheres().empty() ? a[k].cylinders()[0].ids() : a[k].spheres()[0].ids();
        CHECK(ids.object == 100u + k);
        CHECK(ids.label == p.class_id);
        const auto c = a[k].bounds().center();
        CHECK(std::hypot(c.x - 10, c.y + 5) < 5.0 + 0.8);
        // Resting: the lowest point is at or below the seabed under the centre (within the seabed's
        // variation over the piece), the top above it.
        const double ground = seabed(c.x, c.y);
        CHECK(a[k].bounds().lo.z <= ground + 0.1);
        CHECK(a[k].bounds().hi.z > ground);
    }
    p.seed = 78;
    const auto d = sb::debris_cluster(p, seabed);
    int same = 0;
    for (std::size_t k = 0; k < a.size(); ++k) same += a[k].bounds().lo.x == d[k].bounds().lo.x;
    CHECK(same == 0);
    int kinds[3] = {0, 0, 0};
    for (const auto& o : a) {
        if (!o.spheres().empty()) ++kinds[0];
        else if (std::abs(o.cylinders()[0].axis().z) > 0.99) ++kinds[2];
        else ++kinds[1];
    }
    CHECK(kinds[0] > 3);
    CHECK(kinds[1] > 3);
    CHECK(kinds[2] > 3);
}

TEST_CASE("Builders reject bad parameters, naming them") {
    const auto flat = [](double, double) { return 0.0; };
    sb::pipeline_params<double> p;
    p.route_m = {{0, 0}};
    CHECK(param_of<double>([&] { return sb::pipeline(p, flat); }) == "pipeline.route_m");
    p.route_m = {{0, 0}, {0, 0}};
    CHECK(param_of<double>([&] { return sb::pipeline(p, flat); }) == "pipeline.route_m[1]");
    p.route_m = {{0, 0}, {1, 0}};
    p.radius_m = 0;
    CHECK(param_of<double>([&] { return sb::pipeline(p, flat); }) == "pipeline.radius_m");
    p.radius_m = 0.2;
    p.max_span_m = -1;
    CHECK(param_of<double>([&] { return sb::pipeline(p, flat); }) == "pipeline.max_span_m");
    sb::lying_cylinder_params<double> c;
    c.length_m = 0;
    CHECK(param_of<double>([&] { return sb::lying_cylinder(c, flat); }) == "lying_cylinder.length_m");
    sb::debris_params<double> d;
    d.max_size_m = 0.1;
    CHECK(param_of<double>([&] { return sb::debris_cluster(d, flat); }) == "debris.max_size_m");
    d.max_size_m = 1;
    d.first_object_id = sss::no_object - 3;
    CHECK(param_of<double>([&] { return sb::debris_cluster(d, flat); }) == "debris.first_object_id");
}

TEST_CASE("A seabed that is not a number or infinite under a mine's anchor or a debris piece is named as the builder's") {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    // Not a number on one side of the anchor's rim only (its centre and the other rim points are fine): it was
    // dropped by the rim's maximum, and the anchor rested on the rest.
    const auto nan_east = [&](double x, double) { return x > 0.3 ? nan : -20.0; };
    sb::tethered_mine_params<double> m;
    m.anchor_m = {0.0, 0.0};
    CHECK(param_of<double>([&] { return sb::tethered_mine(m, nan_east); }) == "tethered_mine.seabed_height_m(anchor rim)");
    // Beyond the seabed (-infinity) on one side of the rim: the anchor rests on the rest of it; +infinity is no seabed.
    const auto edge_east = [&](double x, double) { return x > 0.3 ? -inf : -20.0; };
    CHECK(param_of<double>([&] { return sb::tethered_mine(m, edge_east); }) == "(none)");
    const auto wall_east = [&](double x, double) { return x > 0.3 ? inf : -20.0; };
    CHECK(param_of<double>([&] { return sb::tethered_mine(m, wall_east); }) == "tethered_mine.seabed_height_m(anchor rim)");
    // Every kind of piece (rock, bar, drum) over a seabed that is not a number, or infinite, names the cluster, not
    // the sphere or cylinder it was building.
    for (const double bad : {nan, inf, -inf}) {
        CAPTURE(bad);
        const auto nowhere = [&](double, double) { return bad; };
        sb::debris_params<double> d;
        d.count = 12;
        try {
            (void)sb::debris_cluster(d, nowhere);
            FAIL("no exception");
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == "debris.seabed_height_m");
            CHECK(std::string(e.what()).find("under piece 0") != std::string::npos);
        }
    }
    // Each kind on its own: the first piece of a seed is a rock, a bar or a drum; the cluster's first few seeds give
    // all three, each named as the cluster's.
    const auto flat = [](double, double) { return -20.0; };
    bool kinds[3] = {false, false, false};
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        sb::debris_params<double> d;
        d.count = 1;
        d.seed = seed;
        const auto one = sb::debris_cluster(d, flat);
        REQUIRE(one.size() == 1u);
        const bool rock = !one[0].spheres().empty(), drum = one[0].cylinders().size() == 1 && !rock &&
                                                            std::abs(one[0].cylinders()[0].axis().z) > 0.99;
        const int kind = rock ? 0 : drum ? 2 : 1;
        if (kinds[kind]) continue;
        kinds[kind] = true;
        const auto hole = [&](double, double) { return nan; };
        CAPTURE(kind);
        CHECK(param_of<double>([&] { return sb::debris_cluster(d, hole); }) == "debris.seabed_height_m");
    }
    CHECK((kinds[0] && kinds[1] && kinds[2]));
    // A drum whose centre is on the seabed and whose rim is not: not a number there is an error naming the cluster;
    // beyond the seabed (-infinity) it stands on what is there.
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        sb::debris_params<double> d;
        d.count = 1;
        d.seed = seed;
        const auto one = sb::debris_cluster(d, flat);
        if (!one[0].spheres().empty() || std::abs(one[0].cylinders()[0].axis().z) < 0.99) continue;
        const auto& drum = one[0].cylinders()[0];
        const vec3<double> c = drum.end0_m(); // the base, at the seabed under its centre
        const double r = drum.radius_m();
        const auto ring = [&](double value) {
            return [=](double x, double y) { return std::hypot(x - c.x, y - c.y) > 0.5 * r ? value : -20.0; };
        };
        CHECK(param_of<double>([&] { return sb::debris_cluster(d, ring(nan)); }) == "debris.seabed_height_m");
        CHECK(param_of<double>([&] { return sb::debris_cluster(d, ring(inf)); }) == "debris.seabed_height_m");
        CHECK(param_of<double>([&] { return sb::debris_cluster(d, ring(-inf)); }) == "(none)");
        break;
    }
}

TEST_CASE("A scene's seabed serves as the builders' height function") {
    const sss::scene::flat_seabed<double> bed(-7.5);
    sb::lying_cylinder_params<double> p;
    const auto o = sb::lying_cylinder(p, sb::seabed_height_of(bed));
    CHECK(o.bounds().lo.z == doctest::Approx(-7.5));
}
