// The object set's hierarchy finds exactly the hit that testing every object finds, on 10^5 random rays
// among 1000 random objects; an empty set misses everything.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <sss/scene/object_set.hpp>

#include "support/fused.hpp"

namespace {

using sss::ray;
using sss::vec3;
using sss::scene::cylinder;
using sss::scene::object;
using sss::scene::object_set;
using sss::scene::placement;
using sss::scene::sphere;
using sss::scene::surface_ids;

// 1000 objects of 1 to 5 primitives each, randomly placed and turned over a 100 m x 100 m patch, from
// pebbles to 12 m pipes; a few long thin cylinders cross many others' boxes.
template <class T> std::vector<object<T>> random_objects(std::size_t n, unsigned seed) {
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<object<T>> out;
    for (std::size_t k = 0; k < n; ++k) {
        const auto id = static_cast<std::uint32_t>(k);
        std::vector<sphere<T>> s;
        std::vector<cylinder<T>> c;
        const int parts = 1 + int(5 * u(g));
        for (int p = 0; p < parts; ++p) {
            const surface_ids ids{static_cast<std::uint32_t>(p), id, static_cast<std::uint32_t>(k % 5)};
            const vec3<T> at{T(2 * u(g) - 1), T(2 * u(g) - 1), T(2 * u(g))};
            if (u(g) < 0.4) {
                s.emplace_back(at, T(0.05 + 0.8 * u(g)), ids);
            } else {
                const double len = u(g) < 0.1 ? 12.0 * u(g) + 0.1 : 2.0 * u(g) + 0.05;
                const vec3<T> dir = glm::normalize(vec3<T>{T(u(g) - 0.5), T(u(g) - 0.5), T(u(g) - 0.5)});
                c.emplace_back(at, at + dir * T(len), T(0.02 + 0.5 * u(g)), ids);
            }
        }
        const vec3<T> pos{T(100 * u(g) - 50), T(100 * u(g) - 50), T(3 * u(g) - 1)};
        out.emplace_back(s, c, sss::scene::detail::placement_ccw_rad<T>(pos, T(6.283 * u(g)), T(u(g) - 0.5), T(6.283 * u(g))));
    }
    return out;
}

template <class T> void check_against_brute_force(std::size_t rays, double distance_tol) {
    const object_set<T> set(random_objects<T>(1000, 17));
    REQUIRE(set.size() == 1000u);
    std::mt19937_64 g(23);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t hits = 0, ties = 0, mismatches = 0;
    for (std::size_t i = 0; i < rays; ++i) {
        ray<T> r;
        if (i % 2 == 0) { // sidescan-like: from 10 m up, down at shallow to steep angles
            r.origin = vec3<T>{T(120 * u(g) - 60), T(120 * u(g) - 60), T(10)};
            const double az = 6.283185307 * u(g), dep = 0.02 + 1.5 * u(g);
            r.direction = vec3<T>{T(std::cos(dep) * std::cos(az)), T(std::cos(dep) * std::sin(az)), T(-std::sin(dep))};
        } else { // anywhere, any direction, some starting inside objects
            r.origin = vec3<T>{T(120 * u(g) - 60), T(120 * u(g) - 60), T(8 * u(g) - 2)};
            r.direction = glm::normalize(vec3<T>{T(u(g) - 0.5), T(u(g) - 0.5), T(u(g) - 0.5)});
        }
        const T t_max = T(5 + 145 * u(g));
        const auto a = set.intersect(r, t_max);
        const auto b = set.intersect_brute_force(r, t_max);
        if (bool(a) != bool(b)) {
            ++mismatches;
            continue;
        }
        if (!a) continue;
        ++hits;
        // Fused multiply-adds (tests/support/fused.hpp) may round the two searches' solutions apart in the last bits.
        if (std::abs(double(a->distance_m) - double(b->distance_m)) > distance_tol &&
            !sss_test::same_to_rounding(a->distance_m, b->distance_m, double(b->distance_m))) {
            ++mismatches;
        } else if (a->object != b->object || a->material != b->material) {
            ++ties; // two primitives at the same distance
        }
    }
    CHECK(mismatches == 0u);
    CHECK(ties <= rays / 10000);
    CHECK(hits > rays / 20);
    MESSAGE(hits << " hits of " << rays << " rays; " << ties << " ties; " << set.primitive_count() << " primitives in "
                  << set.node_count() << " nodes");
}

} // namespace

// The brute force costs about 10 us per ray optimised and ten times that unoptimised: unoptimised builds check
// a fifth of the rays to stay within a few seconds.
#if defined(__OPTIMIZE__) || defined(NDEBUG)
constexpr std::size_t double_rays = 100000;
#else
constexpr std::size_t double_rays = 20000;
#endif

TEST_CASE("The hierarchy returns the brute-force nearest hit on 10^5 random rays among 1000 objects (double)") {
    check_against_brute_force<double>(double_rays, 0.0);
}

TEST_CASE("The hierarchy returns the brute-force nearest hit on 10^4 random rays among 1000 objects (float)") {
    check_against_brute_force<float>(10000, 0.0);
}

TEST_CASE_TEMPLATE("An empty object set misses every ray and has no top", T, float, double) {
    const object_set<T> empty;
    CHECK_FALSE(empty.intersect(ray<T>{vec3<T>{}, vec3<T>{T(0), T(0), T(-1)}}, T(100)));
    CHECK(empty.top_m() == -std::numeric_limits<T>::infinity());
    const object_set<T> none(std::vector<object<T>>{});
    CHECK(none.empty());
    CHECK_FALSE(none.intersect(ray<T>{vec3<T>{}, vec3<T>{T(1), T(0), T(0)}}, T(100)));
}

TEST_CASE_TEMPLATE("Rays along the axes and in the faces of boxes are culled correctly", T, float, double) {
    // Unit spheres on a grid; rays exactly along grid lines (direction components 0, origins on box faces).
    std::vector<object<T>> objs;
    std::uint32_t id = 0;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j)
            objs.emplace_back(std::vector<sphere<T>>{sphere<T>(vec3<T>{T(4 * i), T(4 * j), T(0)}, T(1), surface_ids{0, id++, 0})},
                              std::vector<cylinder<T>>{});
    const object_set<T> set(std::move(objs));
    CHECK(set.top_m() == doctest::Approx(1.0));
    for (int j = 0; j < 10; ++j) {
        const auto h = set.intersect(ray<T>{vec3<T>{T(-10), T(4 * j), T(0)}, vec3<T>{T(1), T(0), T(0)}}, T(100));
        REQUIRE(h);
        CHECK(h->distance_m == doctest::Approx(9.0));
        CHECK(h->object == std::uint32_t(j));
        // Along y at x = 1 (the spheres' box faces, tangent to the spheres): touches the first one.
        const auto t = set.intersect(ray<T>{vec3<T>{T(4 * j + 1), T(-10), T(0)}, vec3<T>{T(0), T(1), T(0)}}, T(100));
        REQUIRE(t);
        CHECK(t->distance_m == doctest::Approx(10.0));
    }
    CHECK_FALSE(set.intersect(ray<T>{vec3<T>{T(2), T(-10), T(0)}, vec3<T>{T(0), T(1), T(0)}}, T(100)));
}

TEST_CASE("Coincident and exponentially spaced objects build a valid hierarchy that still finds the nearest hit") {
    std::vector<object<double>> same, spread;
    for (std::uint32_t k = 0; k < 3000; ++k) {
        same.emplace_back(std::vector<sphere<double>>{sphere<double>(vec3<double>{1, 2, 3}, 0.5 + 1e-4 * k, surface_ids{0, k, 0})},
                          std::vector<cylinder<double>>{});
        const double x = std::ldexp(1.0, int(k % 60) - 20) * (1 + k / 60);
        spread.emplace_back(std::vector<sphere<double>>{sphere<double>(vec3<double>{x, 0, 0}, 1e-7 * x, surface_ids{0, k, 0})},
                            std::vector<cylinder<double>>{});
    }
    const object_set<double> a(same), b(spread);
    // The biggest of the coincident spheres is met first from outside.
    const auto h = a.intersect(ray<double>{vec3<double>{1, 2, 30}, vec3<double>{0, 0, -1}}, 100.0);
    REQUIRE(h);
    CHECK(h->object == 2999u);
    std::mt19937_64 g(8);
    std::uniform_real_distribution<double> u(-1, 1);
    int mismatches = 0, hits = 0;
    for (int i = 0; i < 2000; ++i) { // aimed at a random sphere, half of them within its radius
        const auto& s = spread[std::size_t(1500 + 1500 * u(g))].spheres()[0];
        const vec3<double> target = s.center_m() + vec3<double>{u(g), u(g), 0} * (1.4 * s.radius_m());
        const vec3<double> d = glm::normalize(vec3<double>{0.3 * u(g), 0.3 * u(g), -1});
        const ray<double> r{target - d * (10 * s.radius_m()), d};
        const auto x = b.intersect(r, 1e15), y = b.intersect_brute_force(r, 1e15);
        mismatches += bool(x) != bool(y) || (x && x->distance_m != y->distance_m);
        hits += bool(x);
    }
    CHECK(mismatches == 0);
    CHECK(hits > 500);
}

TEST_CASE_TEMPLATE("No object lies within the band of a segment over the object set's clear length", T, float, double) {
    const object_set<T> set(random_objects<T>(200, 5));
    std::mt19937_64 g(31);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t short_of_end = 0, to_end = 0;
    for (int k = 0; k < 2000; ++k) {
        const double az = 6.283 * u(g), graze = 0.3 * u(g), band = 0.5 * u(g);
        const ray<T> r{vec3<T>{T(120 * u(g) - 60), T(120 * u(g) - 60), T(4 + 2 * u(g))},
                       vec3<T>{T(std::cos(graze) * std::cos(az)), T(std::cos(graze) * std::sin(az)), T(-std::sin(graze))}};
        const T t_max = T(40);
        const T d = set.clear_length_m(r, t_max, T(band));
        REQUIRE(d >= T(0));
        REQUIRE(d <= t_max);
        (d < t_max ? short_of_end : to_end)++;
        // Vertical probes through the band every 5 cm up to d meet nothing.
        for (int s = 0; s * 0.05 <= double(d); ++s) {
            const vec3<T> q = r.at(T(0.05 * s));
            const ray<T> probe{q + vec3<T>{T(0), T(0), T(band)}, vec3<T>{T(0), T(0), T(-1)}};
            if (set.intersect(probe, T(2 * band))) {
                FAIL_CHECK("ray " << k << ": an object within the band at " << 0.05 * s << " m of a clear length " << d);
                break;
            }
        }
        // The segment itself meets nothing before d.
        if (const auto h = set.intersect(r, t_max)) CHECK(h->distance_m >= d);
    }
    MESSAGE(short_of_end << " segments stopped short by an object's box, " << to_end << " clear to the end");
    CHECK(short_of_end > 100);
    CHECK(to_end > 100);
    CHECK(object_set<T>{}.clear_length_m(ray<T>{vec3<T>{}, vec3<T>{T(1), T(0), T(0)}}, T(7), T(1)) == T(7));
    // A negative or NaN band promises nothing.
    CHECK(set.clear_length_m(ray<T>{vec3<T>{T(0), T(0), T(50)}, vec3<T>{T(1), T(0), T(0)}}, T(7), T(-1)) == T(0));
    CHECK(set.clear_length_m(ray<T>{vec3<T>{T(0), T(0), T(50)}, vec3<T>{T(1), T(0), T(0)}}, T(7), std::numeric_limits<T>::quiet_NaN()) == T(0));
}

TEST_CASE_TEMPLATE("No object lies above a descending ray's lower bound within the object set's clear range beside a "
                   "neighbour",
                   T, float, double) {
    const object_set<T> set(random_objects<T>(200, 5));
    std::mt19937_64 g(37);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t short_of_limit = 0, to_limit = 0;
    const T high = set.top_m() + T(1);
    for (int k = 0; k < 2000; ++k) {
        const double az = 6.283 * u(g);
        sss::scene::beside_rays<T> b;
        b.origin = vec3<T>{T(120 * u(g) - 60), T(120 * u(g) - 60), T(3 + 4 * u(g))};
        // Along the axes now and then: the horizontal ray's slabs with a zero component.
        b.heading_r = k % 10 == 0 ? sss::vec2<T>{T(0), T(k % 20 == 0 ? 1 : -1)}
                      : k % 10 == 1 ? sss::vec2<T>{T(1), T(0)}
                                    : sss::vec2<T>{T(std::cos(az)), T(std::sin(az))};
        b.slope_r = T(k % 50 == 0 ? 0.0 : 0.02 + 0.4 * u(g));
        b.margin_m = T(0.2 * u(g));
        const T limit = T(60);
        const T d = set.clear_range_beside_m(b, limit);
        REQUIRE(d >= T(0));
        REQUIRE(d <= limit);
        (d < limit ? short_of_limit : to_limit)++;
        // Vertical probes every 5 cm short of d, from above every object down to the lower bound, meet nothing.
        for (int s = 0; s * 0.05 < double(d); ++s) {
            const T rho = T(0.05 * s);
            const T low = b.origin.z - b.slope_r * rho - b.margin_m;
            if (!(high > low)) continue;
            const ray<T> probe{vec3<T>{b.origin.x + b.heading_r.x * rho, b.origin.y + b.heading_r.y * rho, high},
                               vec3<T>{T(0), T(0), T(-1)}};
            if (set.intersect(probe, high - low)) {
                FAIL_CHECK("ray " << k << ": an object above the bound at " << rho << " m of a clear range " << d);
                break;
            }
        }
    }
    MESSAGE(short_of_limit << " stopped short by an object's box, " << to_limit << " clear to the limit");
    CHECK(short_of_limit > 100);
    CHECK(to_limit > 100);
    CHECK(object_set<T>{}.clear_range_beside_m(sss::scene::beside_rays<T>{}, T(7)) == T(7));
    // A negative or NaN slope promises nothing.
    sss::scene::beside_rays<T> bad{.origin = {T(0), T(0), T(50)}, .heading_r = {T(1), T(0)}, .slope_r = T(-1)};
    CHECK(set.clear_range_beside_m(bad, T(7)) == T(0));
    bad.slope_r = std::numeric_limits<T>::quiet_NaN();
    CHECK(set.clear_range_beside_m(bad, T(7)) == T(0));
}
