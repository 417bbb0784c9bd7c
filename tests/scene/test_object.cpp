// Composite objects: the placement is a proper rotation with the documented axes, a placed object is hit
// exactly where its local primitives are hit by the ray carried into the object's frame, and its bounds
// contain it.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/matrix.hpp>

#include <sss/scene/object.hpp>

namespace {

using sss::ray;
using sss::vec3;
using sss::scene::cylinder;
using sss::scene::object;
using sss::scene::placement;
using sss::scene::sphere;
using sss::scene::surface_ids;

// A buoy-like object in its own frame: a sphere on a post on a disc, plus a horizontal bar.
template <class T> object<T> sample_object(const sss::scene::rigid_transform<T>& where) {
    const std::vector<sphere<T>> s{sphere<T>(vec3<T>{T(0), T(0), T(2)}, T(0.5), surface_ids{1, 9, 3})};
    const std::vector<cylinder<T>> c{
        cylinder<T>(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(0), T(0), T(2)}, T(0.05), surface_ids{2, 9, 3}),
        cylinder<T>(vec3<T>{T(0), T(0), T(0)}, vec3<T>{T(0), T(0), T(0.2)}, T(0.6), surface_ids{3, 9, 3}),
        cylinder<T>(vec3<T>{T(-1), T(0), T(1)}, vec3<T>{T(1), T(0), T(1)}, T(0.1), surface_ids{4, 9, 3})};
    return object<T>(s, c, where);
}

} // namespace

TEST_CASE_TEMPLATE("placement() is a proper rotation: heading turns +x clockwise from north, pitch raises the +x end, roll lowers the right side",
                   T, float, double) {
    // Heading 50 deg clockwise from north is 0.7 rad counter-clockwise from east... to float rounding.
    const T h = T(90.0 - sss::rad_to_deg(0.7)), p = T(sss::rad_to_deg(0.3)), r = T(sss::rad_to_deg(-1.1));
    const auto x = placement<T>({.position_m = vec3<T>{T(1), T(2), T(3)}, .heading_deg = h, .pitch_deg = p, .roll_deg = r});
    CHECK(glm::determinant(x.rotation) == doctest::Approx(1.0));
    const auto g = glm::transpose(x.rotation) * x.rotation;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) CHECK(g[i][j] == doctest::Approx(i == j ? 1.0 : 0.0));
    const vec3<T> ex = x.vector(vec3<T>{T(1), T(0), T(0)});
    CHECK(ex.x == doctest::Approx(std::cos(0.7) * std::cos(0.3)).epsilon(1e-5));
    CHECK(ex.y == doctest::Approx(std::sin(0.7) * std::cos(0.3)).epsilon(1e-5));
    // Heading 0: +x points north; heading 90 (the default): east.
    const vec3<T> north = placement<T>({.heading_deg = T(0)}).vector(vec3<T>{T(1), T(0), T(0)});
    CHECK(north.y == doctest::Approx(1.0));
    CHECK(std::abs(double(north.x)) < 1e-6);
    const vec3<T> east = placement<T>({}).vector(vec3<T>{T(1), T(0), T(0)});
    CHECK(east.x == doctest::Approx(1.0));
    CHECK(ex.z == doctest::Approx(std::sin(0.3)));
    // Roll turns local +y about local +x, right-handed: with heading = pitch = 0, +y goes to (0, cos r, sin r).
    const auto rolled = placement<T>({.roll_deg = T(sss::rad_to_deg(0.4))});
    const vec3<T> ey = rolled.vector(vec3<T>{T(0), T(1), T(0)});
    CHECK(ey.y == doctest::Approx(std::cos(0.4)));
    CHECK(ey.z == doctest::Approx(std::sin(0.4)));
    CHECK(x.point(vec3<T>{}).z == doctest::Approx(3.0));
}

TEST_CASE_TEMPLATE("A placed object is hit where its local primitives are hit by the ray carried into its frame", T, float,
                   double) {
    const auto where = placement<T>({.position_m = vec3<T>{T(40), T(-12), T(-19)}, .heading_deg = T(90.0 - sss::rad_to_deg(2.1)), .pitch_deg = T(sss::rad_to_deg(0.4)), .roll_deg = T(sss::rad_to_deg(0.9))});
    const object<T> placed = sample_object<T>(where);
    const object<T> local = sample_object<T>({});
    const sss::mat3<T> Rt = glm::transpose(where.rotation);
    std::mt19937_64 g(3);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0, ties = 0;
    for (int i = 0; i < 5000; ++i) {
        const vec3<T> target = where.point(vec3<T>{T(1.2 * u(g)), T(1.2 * u(g)), T(1.3 + 1.4 * u(g))});
        const vec3<T> o = target + glm::normalize(vec3<T>{T(u(g)), T(u(g)), T(u(g))}) * T(15);
        const ray<T> r{o, glm::normalize(target - o)};
        const ray<T> rl{Rt * (r.origin - where.translation_m), Rt * r.direction};
        const auto hw = placed.intersect(r, T(40));
        const auto hl = local.intersect(rl, T(40));
        REQUIRE(bool(hw) == bool(hl));
        if (!hw) continue;
        ++hits;
        const double tol = sizeof(T) == 4 ? 1e-4 : 1e-9;
        CHECK(hw->distance_m == doctest::Approx(double(hl->distance_m)).epsilon(tol));
        if (hw->material != hl->material) {
            // Where two primitives meet (the post leaving the disc), both are hit at one distance, and the two
            // frames' rounding (or a compiler's fused multiply-adds) may pick either: the world's choice must
            // then be hit in the local frame as near as the local choice.
            ++ties;
            double d = std::numeric_limits<double>::infinity();
            const auto nearer = [&](const auto& primitive) {
                const auto h = primitive.intersect(rl, T(40));
                if (h && h->material == hw->material) d = std::min(d, double(h->distance_m));
            };
            for (const auto& s : local.spheres()) nearer(s);
            for (const auto& c : local.cylinders()) nearer(c);
            CHECK(d == doctest::Approx(double(hl->distance_m)).epsilon(tol));
        }
        CHECK(hw->object == 9u);
        CHECK(hw->label == 3u);
        CHECK(glm::dot(hw->normal, where.rotation * hl->normal) > T(0.9999));
        CHECK(placed.bounds().contains(hw->point - (hw->point - placed.bounds().center()) * T(1e-4)));
        CHECK(glm::length(hw->point - placed.bounding().center_m) <= placed.bounding().radius_m * T(1.0001));
    }
    CHECK(hits > 1000);
    CHECK(ties <= 5);
}

TEST_CASE_TEMPLATE("An object's box is the union of its primitives' boxes and its top is the highest point", T, float,
                   double) {
    const object<T> o = sample_object<T>(placement<T>({.position_m = vec3<T>{T(5), T(5), T(-10)}}));
    CHECK(o.bounds().lo.x == doctest::Approx(4.0));   // bar from -1 to 1, radius 0.1 caps
    CHECK(o.bounds().hi.x == doctest::Approx(6.0));
    CHECK(o.bounds().lo.y == doctest::Approx(4.4));   // disc radius 0.6
    CHECK(o.bounds().lo.z == doctest::Approx(-10.0));
    CHECK(o.top_m() == doctest::Approx(-7.5));        // sphere top at 2.5
    CHECK(o.primitive_count() == 4u);
}

TEST_CASE("Objects without primitives or with an improper placement are rejected, naming the parameter") {
    auto param = [](auto&& make) {
        try {
            make();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(none)");
    };
    CHECK(param([] { return object<double>({}, {}); }) == "object.primitives");
    sss::scene::rigid_transform<double> mirror;
    mirror.rotation[0][0] = -1.0; // a reflection: orthonormal, determinant -1
    CHECK(param([&] { return sample_object<double>(mirror); }) == "object.placement.rotation");
    sss::scene::rigid_transform<double> sheared;
    sheared.rotation[1][0] = 0.1;
    CHECK(param([&] { return sample_object<double>(sheared); }) == "object.placement.rotation");
    sss::scene::rigid_transform<double> far;
    far.translation_m.y = NAN;
    CHECK(param([&] { return sample_object<double>(far); }) == "object.placement.translation_m.y");
}
