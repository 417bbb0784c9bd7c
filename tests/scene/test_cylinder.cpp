// Ray-cylinder intersection against closed forms, for axes in any direction, and the hard cases: rays along
// the axis onto the caps, rays parallel to the axis inside, on and outside the radius, rays in a cap's plane,
// rays through the rims (no slipping between side and cap), rays from inside, thin far cylinders.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <sss/scene/cylinder.hpp>
#include <sss/scene/object.hpp>

namespace {

using sss::ray;
using sss::vec3;
using sss::scene::cylinder;
using sss::scene::surface_ids;

template <class T> ray<T> make_ray(vec3<T> o, vec3<T> d) { return ray<T>{o, glm::normalize(d)}; }

// A frame whose first column is the given axis: maps canonical (axis = +x) geometry into any orientation.
template <class T> sss::mat3<T> frame_for(T heading, T pitch, T roll) {
    return sss::scene::detail::placement_ccw_rad<T>(vec3<T>{}, heading, pitch, roll).rotation;
}

} // namespace

TEST_CASE_TEMPLATE("A ray across the middle of a cylinder hits its side at D - a, in any orientation", T, float, double) {
    std::mt19937_64 g(1);
    std::uniform_real_distribution<double> ang(-3.1, 3.1);
    const T a = T(0.4), L = T(3);
    for (int k = 0; k < 200; ++k) {
        const auto R = frame_for<T>(T(ang(g)), T(ang(g) / 2), T(ang(g)));
        const vec3<T> c{T(5), T(-3), T(2)};
        const vec3<T> u = R[0], v = R[1], w = R[2];
        const cylinder<T> cyl(c - u * (L / 2), c + u * (L / 2), a, surface_ids{2, 3, 4});
        // Canonical ray: from 10 m along w, offset b along v and s along u, travelling along -w.
        const T b = T(0.25), s = T(0.6);
        const auto h = cyl.intersect(make_ray<T>(c + w * T(10) + v * b + u * s, -w), T(20));
        REQUIRE(h);
        const double expected = 10.0 - std::sqrt(double(a) * double(a) - double(b) * double(b));
        CHECK(std::abs(double(h->distance_m) - expected) < (sizeof(T) == 4 ? 1e-5 : 1e-12));
        const vec3<T> n_expected = glm::normalize(v * b + w * std::sqrt(a * a - b * b));
        CHECK(glm::dot(h->normal, n_expected) > T(0.99999));
        CHECK(h->material == 2u);
        CHECK(h->object == 3u);
        CHECK(h->label == 4u);
    }
}

TEST_CASE_TEMPLATE("A ray along the axis hits the near cap at the cap's distance, normal facing it", T, float, double) {
    const cylinder<T> cyl(vec3<T>{T(0), T(0), T(1)}, vec3<T>{T(0), T(0), T(3)}, T(0.5));
    auto h = cyl.intersect(make_ray<T>({T(0), T(0), T(10)}, {T(0), T(0), T(-1)}), T(20));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(7.0));
    CHECK(h->normal.z == doctest::Approx(1.0));
    h = cyl.intersect(make_ray<T>({T(0), T(0), T(-4)}, {T(0), T(0), T(1)}), T(20));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(5.0));
    CHECK(h->normal.z == doctest::Approx(-1.0));
}

TEST_CASE_TEMPLATE("A ray parallel to the axis hits the cap inside the radius, grazes the rim on it, misses outside", T,
                   float, double) {
    const cylinder<T> cyl(vec3<T>{T(-2), T(0), T(0)}, vec3<T>{T(2), T(0), T(0)}, T(1));
    auto h = cyl.intersect(make_ray<T>({T(-9), T(0.5), T(-0.3)}, {T(1), T(0), T(0)}), T(20));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(7.0));
    CHECK(h->normal.x == doctest::Approx(-1.0));
    h = cyl.intersect(make_ray<T>({T(-9), T(1), T(0)}, {T(1), T(0), T(0)}), T(20)); // exactly on the radius
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(7.0));
    CHECK_FALSE(cyl.intersect(make_ray<T>({T(-9), T(1.001), T(0)}, {T(1), T(0), T(0)}), T(20)));
    CHECK_FALSE(cyl.intersect(make_ray<T>({T(-9), T(0), T(-1.001)}, {T(1), T(0), T(0)}), T(20)));
}

TEST_CASE_TEMPLATE("A ray nearly parallel to the axis still hits the cap where its line crosses it", T, float, double) {
    const cylinder<T> cyl(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(0), T(0), T(5)}, T(0.3));
    for (T tilt : {T(1e-3), T(1e-6), T(1e-9), T(1e-20), T(0)}) {
        const vec3<T> d = glm::normalize(vec3<T>{tilt, T(0), T(-1)});
        const auto h = cyl.intersect(ray<T>{vec3<T>{T(0.1), T(0), T(50)}, d}, T(100));
        REQUIRE(h);
        const double expected = 45.0 / double(-d.z);
        CHECK(h->distance_m == doctest::Approx(expected).epsilon(1e-6));
        CHECK(h->normal.z == doctest::Approx(1.0).epsilon(1e-6));
        CHECK(std::isfinite(double(h->point.x)));
    }
}

TEST_CASE_TEMPLATE("A ray perpendicular to the axis beyond the caps misses; one in a cap's plane hits the side", T, float,
                   double) {
    const cylinder<T> cyl(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(0), T(0), T(2)}, T(1));
    CHECK_FALSE(cyl.intersect(make_ray<T>({T(-5), T(0), T(2.01)}, {T(1), T(0), T(0)}), T(20)));
    CHECK_FALSE(cyl.intersect(make_ray<T>({T(-5), T(0), T(-0.01)}, {T(1), T(0), T(0)}), T(20)));
    auto h = cyl.intersect(make_ray<T>({T(-5), T(0), T(2)}, {T(1), T(0), T(0)}), T(20));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(4.0));
    h = cyl.intersect(make_ray<T>({T(-5), T(0), T(0)}, {T(1), T(0), T(0)}), T(20));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(4.0));
}

TEST_CASE_TEMPLATE("An oblique ray is met by the cap or the side, whichever bounds the solid first", T, float, double) {
    // Cylinder z in [0, 1], radius 1; rays at 45 deg in the x-z plane.
    const cylinder<T> cyl(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(0), T(0), T(1)}, T(1));
    const vec3<T> d = glm::normalize(vec3<T>{T(1), T(0), T(-1)});
    // Through the cap at (0.5, 0, 1): start 2 m up and back along -d.
    auto h = cyl.intersect(ray<T>{vec3<T>{T(0.5), T(0), T(1)} - d * T(2), d}, T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(2.0));
    CHECK(h->normal.z == doctest::Approx(1.0));
    // Through the side at (-1, 0, 0.5).
    h = cyl.intersect(ray<T>{vec3<T>{T(-1), T(0), T(0.5)} - d * T(2), d}, T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(2.0));
    CHECK(h->normal.x == doctest::Approx(-1.0));
}

TEST_CASE_TEMPLATE("A ray from inside hits the inside of the side or cap where it leaves, facing the ray", T, float,
                   double) {
    const cylinder<T> cyl(vec3<T>{T(0), T(0), T(-1)}, vec3<T>{T(0), T(0), T(1)}, T(0.5));
    auto h = cyl.intersect(make_ray<T>({T(0), T(0), T(0)}, {T(1), T(0), T(0)}), T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(0.5));
    CHECK(h->normal.x == doctest::Approx(-1.0));
    h = cyl.intersect(make_ray<T>({T(0), T(0), T(0)}, {T(0), T(0), T(1)}), T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(1.0));
    CHECK(h->normal.z == doctest::Approx(-1.0));
}

TEST_CASE_TEMPLATE("Rays aimed at points just inside the rims always hit, on the surface, facing the ray (watertight)", T,
                   float, double) {
    std::mt19937_64 g(9);
    std::uniform_real_distribution<double> u(0, 1);
    const vec3<T> e0{T(1), T(2), T(3)}, e1{T(2.5), T(1), T(4)};
    const T a = T(0.3);
    const cylinder<T> cyl(e0, e1, a);
    const vec3<T> ax = cyl.axis();
    const vec3<T> p = glm::normalize(glm::cross(ax, vec3<T>{T(0), T(0), T(1)})), q = glm::cross(ax, p);
    const double inset = sizeof(T) == 4 ? 2e-5 : 1e-10;
    int misses = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        // A point on a rim circle, moved inwards by `inset` both radially and axially.
        const double phi = 6.283185307179586 * u(g);
        const bool top = u(g) < 0.5;
        const T s = top ? T(double(cyl.length_m()) - inset) : T(inset);
        const T rad = T(double(a) - inset);
        const vec3<T> target = e0 + ax * s + (p * T(std::cos(phi)) + q * T(std::sin(phi))) * rad;
        const vec3<T> dir = glm::normalize(vec3<T>{T(u(g) - 0.5), T(u(g) - 0.5), T(u(g) - 0.5)});
        const vec3<T> o = target - dir * T(20);
        const auto h = cyl.intersect(ray<T>{o, dir}, T(40));
        if (!h) {
            ++misses;
            continue;
        }
        CHECK(glm::dot(h->normal, dir) <= T(0));
        // On the surface: on the side (radial distance a) or on a cap (axial 0 or L).
        const vec3<T> rel = h->point - e0;
        const double sa = double(glm::dot(rel, ax));
        const double radial = double(glm::length(rel - ax * glm::dot(rel, ax)));
        const double off = std::min({std::abs(radial - double(a)), std::abs(sa), std::abs(sa - double(cyl.length_m()))});
        worst = std::max(worst, off);
        CHECK(sa >= -1e-4);
        CHECK(sa <= double(cyl.length_m()) + 1e-4);
        CHECK(radial <= double(a) + 1e-4);
    }
    CHECK(misses == 0);
    CHECK(worst < (sizeof(T) == 4 ? 1e-5 : 1e-12));
}

TEST_CASE_TEMPLATE("A thin tether 100 m away is hit at the right distance", T, float, double) {
    const T a = T(0.01);
    const cylinder<T> cyl(vec3<T>{T(100), T(0), T(0)}, vec3<T>{T(100), T(0), T(20)}, a);
    for (T b : {T(0), T(0.006), T(0.0099)}) {
        const auto h = cyl.intersect(make_ray<T>({T(0), b, T(5)}, {T(1), T(0), T(0)}), T(200));
        REQUIRE(h);
        const double expected = 100.0 - std::sqrt(0.0001 - double(b) * double(b));
        CHECK(std::abs(double(h->distance_m) - expected) < (sizeof(T) == 4 ? 2e-5 : 1e-11));
    }
    CHECK_FALSE(cyl.intersect(make_ray<T>({T(0), T(0.0101), T(5)}, {T(1), T(0), T(0)}), T(200)));
}

TEST_CASE_TEMPLATE("A cylinder's box is tight: the ends' box grown by a sqrt(1 - u_i^2)", T, float, double) {
    const cylinder<T> along_x(vec3<T>{T(-1), T(0), T(0)}, vec3<T>{T(3), T(0), T(0)}, T(0.5));
    const auto b = along_x.bounds();
    CHECK(b.lo.x == doctest::Approx(-1.0));
    CHECK(b.hi.x == doctest::Approx(3.0));
    CHECK(b.lo.y == doctest::Approx(-0.5));
    CHECK(b.hi.z == doctest::Approx(0.5));
    const cylinder<T> diag(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(1), T(1), T(0)}, T(1));
    const auto d = diag.bounds();
    CHECK(d.hi.x == doctest::Approx(1.0 + std::sqrt(0.5)));
    CHECK(d.hi.z == doctest::Approx(1.0));
}

TEST_CASE_TEMPLATE("A cylinder nearly along a world axis keeps its caps' rims inside its box", T, float, double) {
    // Tilted 1e-6 to 0.1 rad from an axis: the box's half-extent along that axis is a sin(tilt), which 1 - u_i^2
    // would lose to cancellation (u_i within rounding of 1). The rims, in double from the cylinder's own ends, radius
    // and axis, must lie in the box to a few roundings of its coordinates.
    std::mt19937_64 g(12);
    std::uniform_real_distribution<double> u(0, 1);
    double worst_m = 0.0;
    for (int k = 0; k < 3000; ++k) {
        const double tilt = std::pow(10.0, -6.0 + 5.0 * u(g)), turn = 6.283185307 * u(g);
        const int axis = k % 3;
        double d[3];
        d[axis] = 1.0;
        d[(axis + 1) % 3] = std::tan(tilt) * std::cos(turn);
        d[(axis + 2) % 3] = std::tan(tilt) * std::sin(turn);
        const double len = 0.5 + 10 * u(g), radius = 0.02 + 2 * u(g);
        const vec3<T> a{T(20 * u(g) - 10), T(20 * u(g) - 10), T(4 * u(g) - 2)};
        const vec3<T> b = a + vec3<T>{T(d[0] * len), T(d[1] * len), T(d[2] * len)};
        const cylinder<T> cyl(a, b, T(radius));
        const auto box = cyl.bounds();
        // The axis and two directions across it, in double from the ends as stored.
        const vec3<double> e0(a), e1(b);
        const vec3<double> w = glm::normalize(e1 - e0);
        const vec3<double> helper = std::abs(w.x) < 0.5 ? vec3<double>{1, 0, 0} : vec3<double>{0, 1, 0};
        const vec3<double> p = glm::normalize(glm::cross(w, helper)), q = glm::cross(w, p);
        const double slack = 8 * double(std::numeric_limits<T>::epsilon()) *
                             (1 + std::max({std::abs(double(box.lo.x)), std::abs(double(box.hi.x)), std::abs(double(box.lo.y)),
                                            std::abs(double(box.hi.y)), std::abs(double(box.lo.z)), std::abs(double(box.hi.z))}));
        for (int j = 0; j < 64; ++j) {
            const double phi = 6.283185307179586 * j / 64;
            for (const vec3<double>& c : {e0, e1}) {
                const vec3<double> rim = c + double(T(radius)) * (std::cos(phi) * p + std::sin(phi) * q);
                for (int i = 0; i < 3; ++i) {
                    worst_m = std::max(worst_m, double(box.lo[i]) - rim[i] - slack);
                    worst_m = std::max(worst_m, rim[i] - double(box.hi[i]) - slack);
                }
            }
        }
    }
    CHECK(worst_m <= 0.0);
    MESSAGE("the farthest a rim point lies outside the box, beyond the slack: " << worst_m << " m");
}

TEST_CASE("Degenerate or non-finite cylinders are rejected, naming the parameter") {
    auto param = [](auto&& make) {
        try {
            make();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(none)");
    };
    CHECK(param([] { return cylinder<double>({0, 0, 0}, {0, 0, 1}, 0.0); }) == "cylinder.radius_m");
    CHECK(param([] { return cylinder<double>({0, 0, 0}, {0, 0, 1}, -0.1); }) == "cylinder.radius_m");
    CHECK(param([] { return cylinder<double>({0, 0, 0}, {0, 0, 0}, 1.0); }) == "cylinder.length_m");
    CHECK(param([] { return cylinder<float>({1, 2, 3}, {1, 2, 3}, 1.0f); }) == "cylinder.length_m");
    CHECK(param([] { return cylinder<double>({0, 0, INFINITY}, {0, 0, 1}, 1.0); }) == "cylinder.end0_m.z");
    CHECK(param([] { return cylinder<double>({0, 0, 0}, {NAN, 0, 1}, 1.0); }) == "cylinder.end1_m.x");
    CHECK(param([] { return cylinder<double>({0, 0, 0}, {0, 0, 1}, 1.0, {0, sss::no_object, 0}); }) ==
          "cylinder.ids.object");
}

TEST_CASE_TEMPLATE("A cylinder given by name is the cylinder given by position, and is checked the same way", T, float,
                   double) {
    const cylinder<T> named({.end0_m = vec3<T>(T(0), T(0), T(-1)),
                             .end1_m = vec3<T>(T(0), T(0), T(2)),
                             .radius_m = T(0.5),
                             .ids = {.material = 2, .object = 5, .label = 3}});
    const cylinder<T> positional(vec3<T>(T(0), T(0), T(-1)), vec3<T>(T(0), T(0), T(2)), T(0.5), surface_ids{2, 5, 3});
    const auto r = make_ray<T>({T(-9), T(0.2), T(0.4)}, {T(1), T(0), T(0.01)});
    const auto a = named.intersect(r, T(20));
    const auto b = positional.intersect(r, T(20));
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->distance_m == b->distance_m);
    CHECK(a->object == 5);
    CHECK_THROWS_AS(cylinder<T>({.end0_m = vec3<T>(T(0)), .end1_m = vec3<T>(T(0)), .radius_m = T(1), .ids = {.object = 1}}),
                    sss::invalid_parameter);
}
