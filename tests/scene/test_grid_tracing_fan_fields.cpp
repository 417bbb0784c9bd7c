// Every field of a hit found by the fan sweep (intersect_many) against the same ray traced alone
// (intersect): distance, point, both normals, material, label and object, on a rough surface whose cells
// all carry their own material and region, for fans longer than one sweep takes, in both orders.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "sss/scene/height_field.hpp"
#include "support/grid_relief.hpp"

using sss::ray;
using sss::vec3;
using sss::scene::height_field;
using sss_test::rng;
using sss_test::rolling_field;

namespace {

constexpr double deg = 3.141592653589793 / 180;

} // namespace

TEST_CASE_TEMPLATE("Every field of a fan-swept hit is the hit of the same ray traced alone, to rounding", T, float,
                   double) {
    const auto hf = rolling_field<T>(801, 801, 0.25, {-10, -5}, 7);
    constexpr bool is_double = std::is_same_v<T, double>;
    const double rel = is_double ? 1e-9 : 2e-4; // distance and point, relative to the distance
    const double smooth_tol = is_double ? 1e-7 : 2e-3;
    rng gen{11};
    long compared = 0, hits = 0, edge = 0, diagonal = 0, grazing = 0;
    for (int p = 0; p < 14; ++p) {
        const vec3<double> fish{gen.uniform(60, 140), gen.uniform(60, 140), double(hf.top_m()) + gen.uniform(2, 12)};
        const double heading = gen.uniform(0, 6.283185307179586);
        std::vector<ray<T>> rays;
        // Starboard: one fan of 5000 rays (longer than one sweep takes), steep first; port: 2500, shallow first.
        for (int side = -1; side <= 1; side += 2) {
            const int n = side > 0 ? 5000 : 2500;
            for (int i = 0; i < n; ++i) {
                const int ii = side > 0 ? i : n - 1 - i;
                const double dep = (70 - 68.0 * ii / (n - 1)) * deg, az = heading + side * 90 * deg;
                const vec3<double> d{std::cos(dep) * std::cos(az), std::cos(dep) * std::sin(az), -std::sin(dep)};
                rays.push_back(ray<T>{vec3<T>(fish), vec3<T>(d)});
            }
        }
        const T t_max = T(p % 3 == 0 ? 60 : 150); // some rays end before they come down
        std::vector<std::optional<sss::hit<T>>> got(rays.size());
        hf.intersect_many(rays, t_max, got);
        for (std::size_t k = 0; k < rays.size(); ++k) {
            const auto want = hf.intersect(rays[k], t_max);
            ++compared;
            if (bool(got[k]) != bool(want)) {
                // Only a ray that grazes the surface within rounding, or ends on it at t_max, may differ.
                const auto& h = got[k] ? got[k] : want;
                const vec3<double> q = vec3<double>(rays[k].at(h->distance_m));
                const double f = q.z - double(hf.seabed_height_m(T(q.x), T(q.y)));
                CHECK((std::abs(f) < (is_double ? 1e-9 : 1e-4) ||
                       std::abs(double(h->distance_m) - double(t_max)) < rel * double(t_max) * 10));
                ++grazing;
                continue;
            }
            if (!want) continue;
            ++hits;
            const auto& a = *got[k];
            const auto& b = *want;
            const double d = double(b.distance_m);
            CHECK(std::abs(double(a.distance_m) - d) <= rel * d);
            CHECK(glm::length(vec3<double>(a.point) - vec3<double>(b.point)) <= rel * d);
            CHECK(a.object == sss::no_object);
            CHECK(a.object == b.object);
            const double u = (double(b.point.x) + 10) / 0.25, v = (double(b.point.y) + 5) / 0.25;
            if (a.label != b.label) {
                // Allowed only for a hit on a cell boundary, where either cell is right.
                CHECK((std::abs(u - std::round(u)) < rel * d * 4 / 0.25 || std::abs(v - std::round(v)) < rel * d * 4 / 0.25));
                ++edge;
                continue;
            }
            CHECK(a.material == b.material);
            CHECK(a.material == a.label % 5);
            // The geometric normal is the triangle's (its rounding shares a division with the smooth one).
            const double eps = double(std::numeric_limits<T>::epsilon());
            if (glm::length(vec3<double>(a.normal) - vec3<double>(b.normal)) > 8 * eps) {
                // Same cell, other triangle: only on the cell's diagonal.
                CHECK(std::abs((u - std::floor(u)) - (v - std::floor(v))) < rel * d * 4 / 0.25);
                ++diagonal;
            }
            CHECK(glm::length(vec3<double>(a.shading_normal) - vec3<double>(b.shading_normal)) <= smooth_tol);
            CHECK(std::abs(glm::length(vec3<double>(a.normal)) - 1) < (is_double ? 1e-12 : 1e-6));
            CHECK(std::abs(glm::length(vec3<double>(a.shading_normal)) - 1) < (is_double ? 1e-12 : 1e-6));
        }
    }
    CHECK(compared == 14 * 7500);
    CHECK(hits > compared / 2);
    CHECK(grazing <= compared / 10000);
    CHECK(edge + diagonal <= hits / 1000);
    MESSAGE(compared << " rays, " << hits << " hits, " << edge << " on cell edges, " << diagonal << " on diagonals, "
                     << grazing << " grazing");
}

TEST_CASE_TEMPLATE("trace_fan reports the distances and cells intersect_many turns into hits", T, float, double) {
    const auto hf = rolling_field<T>(401, 401, 0.25, {-10, -5}, 7);
    const vec3<double> fish{50, 40, double(hf.top_m()) + 6};
    std::vector<ray<T>> rays;
    for (int i = 0; i < 3000; ++i) {
        const double dep = (60 - 57.0 * i / 2999) * deg;
        rays.push_back(ray<T>{vec3<T>(fish), vec3<T>(vec3<double>{0.6 * std::cos(dep), 0.8 * std::cos(dep), -std::sin(dep)})});
    }
    std::vector<std::optional<sss::hit<T>>> many(rays.size());
    hf.intersect_many(rays, T(120), many);

    std::vector<sss::scene::detail::fan_slope<T>> slopes(rays.size());
    const auto run = sss::scene::detail::find_fan_run(std::span<const ray<T>>(rays), 0, std::span(slopes));
    REQUIRE(run.count == rays.size());
    CHECK(run.steep_first);
    std::vector<int> seen(rays.size(), 0);
    long hits = 0;
    const bool swept = sss::scene::trace_fan(
        hf.grid(), sss::scene::height_bounds<T>{hf.bottom_m(), hf.top_m()}, std::span<const ray<T>>(rays),
        std::span<const sss::scene::detail::fan_slope<T>>(slopes), run.steep_first, T(120),
        [&](std::size_t k, const sss::scene::grid_hit<T>* g) {
            ++seen[k];
            REQUIRE(bool(g) == bool(many[k]));
            if (!g) return;
            ++hits;
            CHECK(g->distance_m == many[k]->distance_m);
            CHECK(hf.region(std::size_t(g->ix), std::size_t(g->iy)) == many[k]->label);
        });
    REQUIRE(swept);
    for (int s : seen) CHECK(s == 1);
    CHECK(hits > 2000);
}

TEST_CASE_TEMPLATE("A fan ray whose f rounds to zero at both ends of its segment meets the segment at its start", T,
                   float, double) {
    // A compiler fusing multiply-adds may evaluate f = g - tau rho at the segment's ends otherwise than the sweep
    // did; where both come out 0 the linear root is 0/0. The ray lies on the segment there, and the hit is at
    // its start, not lost.
    using sss::scene::detail::fan_distance;
    using sss::scene::detail::fan_segment;
    using sss::scene::detail::fan_slope;
    const fan_slope<T> sl{.tau = T(0.5), .inv_h = T(1.25)};
    const fan_segment<T> on{.rho_a = T(2), .g_a = T(1), .rho_b = T(4), .g_b = T(2), .ix = 0, .iy = 0, .triangle = {}};
    CHECK(fan_distance(on, sl, T(100)) == T(2) * T(1.25));
    // Below at both ends (fa < fb = 0 is as possible): the start too.
    const fan_segment<T> below{.rho_a = T(2), .g_a = T(0.5), .rho_b = T(4), .g_b = T(2), .ix = 0, .iy = 0,
                               .triangle = {}};
    CHECK(fan_distance(below, sl, T(100)) == T(2) * T(1.25));
    // An ordinary crossing keeps its linear root: f goes from 1 to -1, so rho = 3.
    const fan_segment<T> crossing{.rho_a = T(2), .g_a = T(2), .rho_b = T(4), .g_b = T(1), .ix = 0, .iy = 0,
                                  .triangle = {}};
    CHECK(fan_distance(crossing, sl, T(100)) == T(3) * T(1.25));
}
