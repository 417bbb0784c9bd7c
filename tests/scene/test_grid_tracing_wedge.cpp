// The wedge sweep (height_field_wedge.hpp): rays of one sidescan column, which share their origin but not their
// vertical plane (a cone about the array axis, tilted by roll and pitch), give the single-ray tracer's hits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "sss/core/pose.hpp"
#include "sss/scene/height_field.hpp"
#include "sss/scene/height_field_wedge.hpp"
#include "support/fused.hpp"
#include "support/grid_relief.hpp"

using sss::ray;
using sss::vec3;
using sss::scene::height_field;
using sss_test::rng;
using sss_test::rough_field;

namespace {

constexpr double deg = 3.141592653589793 / 180;

// One column of a sidescan beam from a towfish with the given attitude: body direction (sin a, s cos a cos e,
// cos a sin e) (FRD) for depressions e from e0 to e1, in that order.
template <class T>
std::vector<ray<T>> column(vec3<double> fish, double yaw, double pitch, double roll, int side, double along, double e0,
                           double e1, int count) {
    const auto p = sss::make_pose(0.0, fish, roll, pitch, yaw);
    std::vector<ray<T>> rays;
    for (int i = 0; i < count; ++i) {
        const double e = e0 + (e1 - e0) * i / (count - 1);
        const vec3<double> body{std::sin(along), side * std::cos(along) * std::cos(e), std::cos(along) * std::sin(e)};
        rays.push_back(ray<T>{vec3<T>(fish), vec3<T>(glm::normalize(p.to_world(body)))});
    }
    return rays;
}

// Traces `rays` as wedge runs where they form them, one by one elsewhere; hits as (distance, cell label).
template <class T>
std::vector<std::optional<sss::hit<T>>> trace_wedges(const height_field<T>& hf, std::span<const ray<T>> rays, T t_max,
                                                     long& in_runs) {
    std::vector<std::optional<sss::hit<T>>> out(rays.size());
    std::vector<sss::scene::detail::wedge_slope<T>> slopes(rays.size());
    std::size_t i = 0;
    while (i < rays.size()) {
        const auto run = sss::scene::detail::find_wedge_run(rays, i, std::span(slopes).subspan(i));
        if (run.count >= 8) {
            const auto part = rays.subspan(i, run.count);
            sss::scene::trace_wedge(hf.grid(), hf.pyramid(), sss::scene::height_bounds<T>{hf.bottom_m(), hf.top_m()},
                                    part, std::span<const sss::scene::detail::wedge_slope<T>>(slopes).subspan(i, run.count), run, t_max,
                                    [&](std::size_t k, const sss::scene::grid_hit<T>* g) {
                                        if (!g) return;
                                        sss::hit<T> h;
                                        h.distance_m = g->distance_m;
                                        h.label = hf.region(std::size_t(g->ix), std::size_t(g->iy));
                                        out[i + k] = h;
                                    });
            in_runs += long(run.count);
            i += run.count;
        } else {
            out[i] = hf.intersect(rays[i], t_max);
            ++i;
        }
    }
    return out;
}

} // namespace

TEST_CASE_TEMPLATE("Columns of a tilted cone traced as wedges give the reference hits to the last bit: same cell, same distance", T,
                   float, double) {
    const auto hf = rough_field<T>(401, 301, 0.25, {-20, 10}, 7);
    rng gen{31};
    long compared = 0, hits = 0, in_runs = 0;
    for (int p = 0; p < 24; ++p) {
        // Towfish over and around the footprint, from just above the top to 15 m above it; any heading, roll and
        // pitch up to 20 deg; a few pings start under the top (among the hills) or outside the grid.
        const vec3<double> fish{gen.uniform(-30, 110), gen.uniform(0, 90), double(hf.top_m()) + gen.uniform(-1, 15)};
        const double yaw = gen.uniform(0, 360) * deg, pitch = gen.uniform(-20, 20) * deg,
                     roll = gen.uniform(-20, 20) * deg;
        for (int side : {-1, 1})
            for (int a = 0; a < 6; ++a) {
                const double along = (-1.5 + 3.0 * a / 5.0) * deg;
                const bool steep_first = gen.next() % 2;
                const auto rays = steep_first ? column<T>(fish, yaw, pitch, roll, side, along, 88 * deg, -3 * deg, 700)
                                              : column<T>(fish, yaw, pitch, roll, side, along, -3 * deg, 88 * deg, 700);
                const T t_max = T(gen.uniform() < 0.3 ? gen.uniform(5, 40) : 150);
                const auto got = trace_wedges<T>(hf, rays, t_max, in_runs);
                for (std::size_t k = 0; k < rays.size(); ++k) {
                    const auto want = hf.intersect_reference(rays[k], t_max);
                    ++compared;
                    REQUIRE(bool(got[k]) == bool(want));
                    if (!want) continue;
                    ++hits;
                    REQUIRE(got[k]->distance_m == want->distance_m);
                    REQUIRE(got[k]->label == want->label);
                }
            }
    }
    MESSAGE(compared << " rays, " << hits << " hits, " << in_runs << " in wedge runs");
    CHECK(in_runs > compared / 2);
    CHECK(hits > compared / 3);
}

TEST_CASE("A wedge run ends where the rays leave the origin, turn the other way in depression or spread too wide") {
    using T = double;
    const vec3<double> fish{0, 0, 10};
    auto rays = column<T>(fish, 0, 0, 0, 1, 0.5 * deg, 80 * deg, 5 * deg, 100);
    std::vector<sss::scene::detail::wedge_slope<T>> taus(rays.size() + 20);
    auto run = sss::scene::detail::find_wedge_run(std::span<const ray<T>>(rays), 0, std::span(taus));
    // Near nadir a cone's heading swings fast: from 80 deg the first 0.01 rad of spread ends the run early.
    CHECK(run.count < 100);
    CHECK(run.steep_first);
    const auto far = column<T>(fish, 0, 0, 0, 1, 0.5 * deg, 40 * deg, 5 * deg, 100);
    run = sss::scene::detail::find_wedge_run(std::span<const ray<T>>(far), 0, std::span(taus));
    CHECK(run.count == 100);
    auto broken = far;
    broken[50].origin.x += 1e-9;
    run = sss::scene::detail::find_wedge_run(std::span<const ray<T>>(broken), 0, std::span(taus));
    CHECK(run.count == 50);
    auto turned = far;
    std::swap(turned[60], turned[61]);
    run = sss::scene::detail::find_wedge_run(std::span<const ray<T>>(turned), 0, std::span(taus));
    CHECK(run.count == 61);
}

TEST_CASE_TEMPLATE("intersect_many on columns of a rolled, pitched towfish gives intersect's hits, every field to the last bit", T, float,
                   double) {
    const auto hf = rough_field<T>(401, 301, 0.25, {-20, 10}, 7);
    rng gen{5};
    long compared = 0, hits = 0;
    double worst_distance = 0, worst_shading = 0;
    for (int p = 0; p < 12; ++p) {
        const vec3<double> fish{gen.uniform(0, 80), gen.uniform(10, 60), double(hf.top_m()) + gen.uniform(1, 12)};
        const double yaw = gen.uniform(0, 360) * deg, pitch = gen.uniform(-10, 10) * deg,
                     roll = gen.uniform(-10, 10) * deg;
        std::vector<ray<T>> rays;
        for (int side : {-1, 1})
            for (int a = 0; a < 4; ++a) {
                const auto c = column<T>(fish, yaw, pitch, roll, side, (-0.5 + a / 3.0) * deg, 80 * deg, 2 * deg, 600);
                rays.insert(rays.end(), c.begin(), c.end());
            }
        std::vector<std::optional<sss::hit<T>>> got(rays.size());
        hf.intersect_many(rays, T(120), got);
        for (std::size_t k = 0; k < rays.size(); ++k) {
            const auto want = hf.intersect(rays[k], T(120));
            ++compared;
            REQUIRE(bool(got[k]) == bool(want));
            if (!want) continue;
            ++hits;
            // Where multiply-adds are fused, to rounding: the shading normal interpolates within the cell, so its
            // rounding is that of the hit's place in the cell, |point| / cell_m epsilons.
            const double reach = double(glm::length(want->point)) + double(want->distance_m);
            REQUIRE(sss_test::same_to_rounding(got[k]->distance_m, want->distance_m, double(want->distance_m)));
            REQUIRE(got[k]->label == want->label);
            REQUIRE(got[k]->object == want->object);
            REQUIRE(sss_test::same_to_rounding(got[k]->point, want->point, reach));
            REQUIRE(sss_test::same_to_rounding(got[k]->normal, want->normal, 1.0));
            REQUIRE(sss_test::same_to_rounding(got[k]->shading_normal, want->shading_normal, reach / 0.25));
            if constexpr (sss_test::fused) {
                const double eps = double(std::numeric_limits<T>::epsilon());
                worst_distance = std::max(worst_distance, std::abs(double(got[k]->distance_m - want->distance_m)) /
                                                              (eps * double(want->distance_m)));
                worst_shading = std::max(worst_shading,
                                         double(glm::length(got[k]->shading_normal - want->shading_normal)) /
                                             (eps * reach / 0.25));
            }
        }
    }
    if constexpr (sss_test::fused)
        MESSAGE("fused: worst distance " << worst_distance << ", shading normal " << worst_shading
                                         << " epsilons of their scales");
    CHECK(hits > compared / 2);
}
