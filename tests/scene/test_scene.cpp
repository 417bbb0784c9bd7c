// A scene of seabed and objects returns the nearest hit over both, with the labels of what was hit; its top
// includes the objects; it works over a flat seabed and over a height field.

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>

namespace {

using sss::ray;
using sss::vec2;
using sss::vec3;
using sss::scene::cylinder;
using sss::scene::flat_seabed;
using sss::scene::height_field;
using sss::scene::object;
using sss::scene::object_set;
using sss::scene::sphere;
using sss::scene::surface_ids;

template <class T> object<T> ball(vec3<T> c, T r, std::uint32_t id, std::uint32_t cls) {
    return object<T>({sphere<T>(c, r, surface_ids{5, id, cls})}, {});
}

} // namespace

static_assert(sss::Scene<sss::scene::scene<flat_seabed<float>>>);
static_assert(sss::Scene<sss::scene::scene<flat_seabed<double>>>);
static_assert(sss::Scene<sss::scene::scene<height_field<float>>>);
static_assert(sss::Scene<sss::scene::scene<height_field<double>>>);

TEST_CASE_TEMPLATE("A ray meets an object above the seabed first, and the seabed beside it; labels say which", T, float,
                   double) {
    std::vector<object<T>> objs{ball<T>({T(0), T(0), T(-18)}, T(1), 42, 7)};
    const sss::scene::scene sc(flat_seabed<T>(T(-20), 3, 9), object_set<T>(std::move(objs)));
    const vec3<T> down{T(0), T(0), T(-1)};
    auto h = sc.intersect(ray<T>{vec3<T>{T(0), T(0), T(0)}, down}, T(100));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(17.0));
    CHECK(h->object == 42u);
    CHECK(h->label == 7u);
    CHECK(h->material == 5u);
    h = sc.intersect(ray<T>{vec3<T>{T(1.5), T(0), T(0)}, down}, T(100));
    REQUIRE(h);
    CHECK(h->distance_m == doctest::Approx(20.0));
    CHECK(h->object == sss::no_object);
    CHECK(h->label == 9u);
    CHECK(h->material == 3u);
    CHECK_FALSE(sc.intersect(ray<T>{vec3<T>{T(0), T(0), T(0)}, down}, T(16.9)));
}

TEST_CASE_TEMPLATE("An object casts a shadow: the seabed point behind it is not reached", T, float, double) {
    // Sphere of radius 1 centred 2 m above a seabed at z = 0, 10 m from a transducer 10 m up.
    std::vector<object<T>> objs{ball<T>({T(10), T(0), T(2)}, T(1), 1, 1)};
    const sss::scene::scene sc(flat_seabed<T>(T(0)), object_set<T>(std::move(objs)));
    const vec3<T> o{T(0), T(0), T(10)};
    // The seabed point on the line through the sphere's centre: x = 10 * 10 / 8 = 12.5.
    const vec3<T> d = glm::normalize(vec3<T>{T(12.5), T(0), T(0)} - o);
    const auto h = sc.intersect(ray<T>{o, d}, T(100));
    REQUIRE(h);
    CHECK(h->object == 1u);
    CHECK(h->distance_m == doctest::Approx(std::sqrt(164.0) - 1.0).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("Buried parts of objects are hidden by the seabed, exposed parts are hit", T, float, double) {
    std::vector<object<T>> objs{ball<T>({T(0), T(0), T(0)}, T(1), 1, 1), ball<T>({T(5), T(0), T(-3)}, T(1), 2, 1)};
    const sss::scene::scene sc(flat_seabed<T>(T(0)), object_set<T>(std::move(objs)));
    const vec3<T> down{T(0), T(0), T(-1)};
    auto h = sc.intersect(ray<T>{vec3<T>{T(0.5), T(0), T(10)}, down}, T(100));
    REQUIRE(h);
    CHECK(h->object == 1u);
    CHECK(h->point.z == doctest::Approx(std::sqrt(0.75)));
    h = sc.intersect(ray<T>{vec3<T>{T(5), T(0), T(10)}, down}, T(100)); // wholly buried
    REQUIRE(h);
    CHECK(h->object == sss::no_object);
    CHECK(h->distance_m == doctest::Approx(10.0));
}

TEST_CASE_TEMPLATE("The scene's top includes the objects; its seabed height is the seabed's", T, float, double) {
    const sss::scene::scene bare(flat_seabed<T>(T(-20)));
    CHECK(bare.top_m() == doctest::Approx(-20.0));
    std::vector<object<T>> objs{ball<T>({T(3), T(4), T(-12)}, T(0.5), 1, 1)};
    const sss::scene::scene sc(flat_seabed<T>(T(-20)), object_set<T>(std::move(objs)));
    CHECK(sc.top_m() == doctest::Approx(-11.5));
    CHECK(sc.seabed_height_m(T(3), T(4)) == doctest::Approx(-20.0));
    std::vector<object<T>> buried{ball<T>({T(3), T(4), T(-30)}, T(0.5), 1, 1)};
    const sss::scene::scene low(flat_seabed<T>(T(-20)), object_set<T>(std::move(buried)));
    CHECK(low.top_m() == doctest::Approx(-20.0));
}

TEST_CASE_TEMPLATE("Over a height field the scene's hit is the nearer of the seabed's and the objects' hits", T, float,
                   double) {
    // A 64 m square, 0.5 m cells, gently undulating; objects scattered on and above it.
    const std::size_t n = 129;
    std::vector<T> hts(n * n);
    for (std::size_t iy = 0; iy < n; ++iy)
        for (std::size_t ix = 0; ix < n; ++ix)
            hts[iy * n + ix] = T(0.8 * std::sin(0.2 * double(ix)) * std::cos(0.13 * double(iy)));
    const height_field<T> hf({.nx = n, .ny = n, .cell_m = T(0.5), .origin_m = vec2<T>{T(0), T(0)}, .heights_m = hts});
    std::mt19937_64 g(4);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<object<T>> objs;
    for (std::uint32_t k = 0; k < 60; ++k) {
        const T x = T(4 + 56 * u(g)), y = T(4 + 56 * u(g));
        const T z = hf.seabed_height_m(x, y);
        if (k % 2) objs.push_back(ball<T>({x, y, z + T(2 * u(g))}, T(0.2 + 0.8 * u(g)), k, 2));
        else objs.emplace_back(std::vector<sphere<T>>{},
                               std::vector<cylinder<T>>{cylinder<T>({x, y, z + T(0.2)}, {x + T(3), y + T(1), z + T(0.4)}, T(0.3),
                                                                    surface_ids{1, k, 3})});
    }
    const object_set<T> set(objs);
    const sss::scene::scene sc(hf, set);
    int object_hits = 0, seabed_hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const vec3<T> o{T(64 * u(g)), T(64 * u(g)), T(6)};
        const double az = 6.2831853 * u(g), dep = 0.05 + 1.5 * u(g);
        const ray<T> r{o, vec3<T>{T(std::cos(dep) * std::cos(az)), T(std::cos(dep) * std::sin(az)), T(-std::sin(dep))}};
        const auto got = sc.intersect(r, T(80));
        const auto s = hf.intersect(r, T(80));
        const auto b = set.intersect_brute_force(r, T(80));
        std::optional<sss::hit<T>> want = s;
        if (b && (!s || b->distance_m <= s->distance_m)) want = b;
        REQUIRE(bool(got) == bool(want));
        if (!got) continue;
        CHECK(got->distance_m == doctest::Approx(double(want->distance_m)).epsilon(1e-6));
        CHECK(got->object == want->object);
        CHECK(got->label == want->label);
        (got->object == sss::no_object ? seabed_hits : object_hits)++;
    }
    CHECK(object_hits > 100);
    CHECK(seabed_hits > 1000);
}
