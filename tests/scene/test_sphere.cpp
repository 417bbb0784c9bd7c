// Ray-sphere intersection against closed forms, including the numerically hard cases: small far spheres,
// tangent rays, rays from inside or from the surface, and the inclusive t_max.

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include <sss/scene/sphere.hpp>

namespace {

using sss::ray;
using sss::vec3;
using sss::scene::sphere;
using sss::scene::surface_ids;

template <class T> ray<T> make_ray(vec3<T> o, vec3<T> d) { return ray<T>{o, glm::normalize(d)}; }

} // namespace

TEST_CASE_TEMPLATE("A ray through a sphere's centre hits at the centre distance minus the radius, normal outwards",
                   T, float, double) {
    const sphere<T> s(vec3<T>{T(1), T(2), T(3)}, T(2), surface_ids{7, 11, 13});
    const auto h = s.intersect(make_ray<T>({T(1), T(2), T(13)}, {T(0), T(0), T(-1)}), T(100));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(8.0));
    CHECK(h->point.z == doctest::Approx(5.0));
    CHECK(h->normal.z == doctest::Approx(1.0));
    CHECK(h->shading_normal.z == doctest::Approx(1.0));
    CHECK(h->material == 7u);
    CHECK(h->object == 11u);
    CHECK(h->label == 13u);
}

TEST_CASE_TEMPLATE("An off-centre ray at offset b hits at D - sqrt(a^2 - b^2) with normal (b, 0, sqrt(a^2 - b^2)) / a", T,
                   float, double) {
    const T a = T(1.5);
    const sphere<T> s(vec3<T>{}, a);
    for (T b : {T(0.1), T(0.7), T(1.2), T(1.49)}) {
        const auto h = s.intersect(make_ray<T>({b, T(0), T(20)}, {T(0), T(0), T(-1)}), T(100));
        REQUIRE(h);
        const double c = std::sqrt(double(a) * double(a) - double(b) * double(b));
        CHECK(h->distance_m == doctest::Approx(20.0 - c).epsilon(1e-5));
        CHECK(h->normal.x == doctest::Approx(double(b) / double(a)).epsilon(1e-4));
        CHECK(h->normal.z == doctest::Approx(c / double(a)).epsilon(1e-4));
    }
    CHECK_FALSE(s.intersect(make_ray<T>({T(1.51), T(0), T(20)}, {T(0), T(0), T(-1)}), T(100)));
}

TEST_CASE_TEMPLATE("A small sphere far away is hit at the right distance (no cancellation in the discriminant)", T, float,
                   double) {
    // Radius 1 cm at 1 km: the textbook b^2 - c loses every digit of the discriminant in float.
    const T a = T(0.01);
    const sphere<T> s(vec3<T>{T(1000), T(0), T(0)}, a);
    for (T b : {T(0), T(0.005), T(0.0099)}) {
        const auto h = s.intersect(make_ray<T>({T(0), b, T(0)}, {T(1), T(0), T(0)}), T(2000));
        REQUIRE(h);
        const double expected = 1000.0 - std::sqrt(0.01 * 0.01 - double(b) * double(b));
        CHECK(std::abs(double(h->distance_m) - expected) < (sizeof(T) == 4 ? 2e-4 : 1e-10));
        CHECK(std::abs(double(h->normal.y) - double(b) / 0.01) < (sizeof(T) == 4 ? 2e-2 : 1e-6));
    }
    CHECK_FALSE(s.intersect(make_ray<T>({T(0), T(0.0101), T(0)}, {T(1), T(0), T(0)}), T(2000)));
}

TEST_CASE_TEMPLATE("A tangent ray touches the sphere with a normal perpendicular to it; just outside it misses", T, float,
                   double) {
    const sphere<T> s(vec3<T>{}, T(1));
    const auto h = s.intersect(make_ray<T>({T(1), T(0), T(5)}, {T(0), T(0), T(-1)}), T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(5.0));
    CHECK(std::abs(double(h->normal.z)) < 1e-6);
    CHECK(h->normal.x == doctest::Approx(1.0));
    const T out = sizeof(T) == 4 ? T(1.0001) : T(1.000000001);
    CHECK_FALSE(s.intersect(make_ray<T>({out, T(0), T(5)}, {T(0), T(0), T(-1)}), T(10)));
}

TEST_CASE_TEMPLATE("A ray from inside hits the inside where it leaves, its normal facing the ray", T, float, double) {
    const sphere<T> s(vec3<T>{T(0), T(0), T(0)}, T(2));
    auto h = s.intersect(make_ray<T>({T(0), T(0), T(0)}, {T(1), T(0), T(0)}), T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(2.0));
    CHECK(h->normal.x == doctest::Approx(-1.0)); // inwards: towards the ray
    h = s.intersect(make_ray<T>({T(1), T(0), T(0)}, {T(0), T(1), T(0)}), T(10));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(std::sqrt(3.0)));
    CHECK(glm::dot(h->normal, vec3<T>{T(0), T(1), T(0)}) < T(0));
}

TEST_CASE_TEMPLATE("A ray starting on the surface hits the far side going in and nothing going out", T, float, double) {
    const sphere<T> s(vec3<T>{}, T(1));
    const auto in = s.intersect(make_ray<T>({T(0), T(0), T(1)}, {T(0), T(0), T(-1)}), T(10));
    REQUIRE(in);
    CHECK(in->distance_m == doctest::Approx(2.0));
    CHECK(in->normal.z == doctest::Approx(1.0)); // at (0, 0, -1) inside: facing the ray (up)
    CHECK_FALSE(s.intersect(make_ray<T>({T(0), T(0), T(1)}, {T(0), T(0), T(1)}), T(10)));
}

TEST_CASE_TEMPLATE("Hits count only for 0 < t <= t_max: behind the origin or beyond t_max is a miss", T, float, double) {
    const sphere<T> s(vec3<T>{T(0), T(0), T(0)}, T(1));
    const auto r = make_ray<T>({T(0), T(0), T(4)}, {T(0), T(0), T(-1)});
    CHECK(s.intersect(r, T(3)));                // exactly at t_max: inclusive
    CHECK_FALSE(s.intersect(r, T(2.999)));
    CHECK_FALSE(s.intersect(make_ray<T>({T(0), T(0), T(4)}, {T(0), T(0), T(1)}), T(100))); // sphere behind
}

TEST_CASE_TEMPLATE("Rays aimed at random interior points always hit the surface, at a point on it, facing the ray", T,
                   float, double) {
    std::mt19937_64 g(5);
    std::uniform_real_distribution<double> u(-1, 1);
    const vec3<T> c{T(3), T(-2), T(1)};
    const T a = T(0.75);
    const sphere<T> s(c, a);
    int misses = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        vec3<T> target;
        do target = vec3<T>{T(u(g)), T(u(g)), T(u(g))};
        while (glm::length(target) >= T(0.999));
        target = c + target * a;
        const vec3<T> o = c + glm::normalize(vec3<T>{T(u(g)), T(u(g)), T(u(g))}) * T(30);
        const auto h = s.intersect(make_ray<T>(o, target - o), T(100));
        if (!h) {
            ++misses;
            continue;
        }
        worst = std::max(worst, std::abs(double(glm::length(h->point - c)) - double(a)));
        CHECK(glm::dot(h->normal, glm::normalize(target - o)) <= T(0));
    }
    CHECK(misses == 0);
    CHECK(worst < (sizeof(T) == 4 ? 2e-5 : 1e-12));
}

TEST_CASE("Degenerate or non-finite spheres are rejected, naming the parameter") {
    auto param = [](auto&& make) {
        try {
            make();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(none)");
    };
    CHECK(param([] { return sphere<double>({0, 0, 0}, 0.0); }) == "sphere.radius_m");
    CHECK(param([] { return sphere<double>({0, 0, 0}, -1.0); }) == "sphere.radius_m");
    CHECK(param([] { return sphere<double>({0, 0, 0}, NAN); }) == "sphere.radius_m");
    CHECK(param([] { return sphere<float>({0, 0, 0}, 1e-30f); }) == "sphere.radius_m"); // its square underflows
    CHECK(param([] { return sphere<double>({0, NAN, 0}, 1.0); }) == "sphere.center_m.y");
    CHECK(param([] { return sphere<double>({0, 0, 0}, 1.0, {0, sss::no_object, 0}); }) == "sphere.ids.object");
}

TEST_CASE_TEMPLATE("A sphere given by name is the sphere given by position, and is checked the same way", T, float, double) {
    const sphere<T> named({.center_m = vec3<T>(T(1), T(2), T(3)), .radius_m = T(2), .ids = {.material = 7, .object = 11, .label = 13}});
    const sphere<T> positional(vec3<T>{T(1), T(2), T(3)}, T(2), surface_ids{7, 11, 13});
    const auto r = make_ray<T>({T(1.5), T(2), T(13)}, {T(0), T(0.1), T(-1)});
    const auto a = named.intersect(r, T(100));
    const auto b = positional.intersect(r, T(100));
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->distance_m == b->distance_m);
    CHECK(a->object == 11);
    CHECK(a->label == 13);
    CHECK_THROWS_AS(sphere<T>({.center_m = vec3<T>(T(0)), .radius_m = T(0), .ids = {.object = 1}}), sss::invalid_parameter);
}
