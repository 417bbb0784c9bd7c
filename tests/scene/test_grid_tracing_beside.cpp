// A ray traced beside a steeper neighbour from the same origin (height_field_beside.hpp, intersect_beside): its walk
// starts about where the neighbour's first hit is, and it gets the single-ray tracer's hit to the last bit. So does a
// ray resumed past a distance it is known clear for (intersect_after).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "sss/core/pose.hpp"
#include "sss/scene/height_field.hpp"
#include "sss/scene/height_field_beside.hpp"
#include "support/grid_relief.hpp"

using sss::ray;
using sss::vec3;
using sss::scene::height_field;
using sss_test::rng;
using sss_test::rough_field;

namespace {

constexpr double deg = 3.141592653589793 / 180;

// The unit direction of a sidescan beam's ray at along-track angle `along` and depression e from a towfish with the
// given attitude: body direction (sin a, s cos a cos e, cos a sin e) (FRD).
vec3<double> beam_ray(const sss::pose<double>& p, int side, double along, double e) {
    return glm::normalize(p.to_world(vec3<double>{std::sin(along), side * std::cos(along) * std::cos(e),
                                                  std::cos(along) * std::sin(e)}));
}

template <class T> bool same_hit(const std::optional<sss::hit<T>>& a, const std::optional<sss::hit<T>>& b) {
    if (bool(a) != bool(b)) return false;
    if (!a) return true;
    return a->distance_m == b->distance_m && a->point == b->point && a->normal == b->normal &&
           a->shading_normal == b->shading_normal && a->label == b->label && a->material == b->material;
}

} // namespace

TEST_CASE_TEMPLATE("A ray traced beside a steeper neighbour's first hit gets the plain tracer's hit to the last bit", T,
                   float, double) {
    const auto hf = rough_field<T>(401, 301, 0.25, {-20, 10}, 7);
    rng gen{41};
    long compared = 0, guided = 0, hits = 0;
    for (int p = 0; p < 16; ++p) {
        // Towfish over the footprint from 1 m to 15 m above the top, a few among the hills (under the top) and a few
        // outside the footprint; any heading, roll and pitch up to 20 deg.
        const bool outside = p % 8 == 7;
        const vec3<double> fish{outside ? -25.0 : gen.uniform(0, 80), gen.uniform(15, 75),
                                double(hf.top_m()) + (p % 8 == 3 ? -0.3 : gen.uniform(1, 15))};
        const auto pose = sss::make_pose(0.0, fish, gen.uniform(-20, 20) * deg, gen.uniform(-20, 20) * deg,
                                         gen.uniform(0, 360) * deg);
        for (int side : {-1, 1})
            for (int a = 0; a < 3; ++a) {
                const double along = (-1.5 + 1.5 * a) * deg;
                // Neighbours as a refinement meets them: a ray and the midpoint between it and the next one, ever
                // closer (down to 2^-12 of the spacing, the refinement's deepest); and, across
                // columns, rays whose headings differ by far more than their depressions.
                for (int i = 0; i < 300; ++i) {
                    const double e = 80 * deg - i * 0.27 * deg;
                    const double de = 0.27 * deg * std::ldexp(1.0, -int(gen.next() % 13));
                    const double other_along = gen.uniform() < 0.2 ? along + gen.uniform(-0.5, 0.5) * deg : along;
                    const ray<T> steep{vec3<T>(fish), vec3<T>(beam_ray(pose, side, along, e))};
                    const ray<T> r{vec3<T>(fish), vec3<T>(beam_ray(pose, side, other_along, e - de))};
                    const T t_max = T(gen.uniform() < 0.2 ? gen.uniform(5, 40) : 150);
                    const auto first = hf.intersect(steep, T(150));
                    const auto want = hf.intersect(r, t_max);
                    const T clear = first ? first->distance_m : T(150);
                    if (sss::scene::clear_beside_m(hf.grid(), hf.pyramid(),
                                                   sss::scene::height_bounds<T>{hf.bottom_m(), hf.top_m()}, r, steep,
                                                   clear) > T(0))
                        ++guided;
                    ++compared;
                    hits += want.has_value();
                    REQUIRE(same_hit(hf.intersect_beside(r, t_max, steep, clear), want));
                    // The wrong way round (the shallower ray as the guide) is refused, not trusted.
                    if (want)
                        REQUIRE(same_hit(hf.intersect_beside(steep, T(150), r, want->distance_m), first));
                }
            }
    }
    MESSAGE(compared << " rays, " << hits << " hits, " << guided << " guided");
    CHECK(hits > compared / 2);
    CHECK(guided > compared / 20);
}

TEST_CASE_TEMPLATE("A ray resumed past a distance it is known to stay above the surface for gets the plain tracer's hit "
                   "to the last bit",
                   T, float, double) {
    // intersect_after: what bent rays hand the height field for the chord that reaches past what a neighbour vouches
    // for. Rays from 0.5 to 15 m above the top, 2 to 80 degrees down, any heading; the clear distance anywhere from 0
    // to just short of the plain hit (or of t_max for a miss). The promise is that the ray is above the surface before
    // that distance: origins over the footprint and above its top keep it (from beside the footprint a ray can enter
    // it through its side below the surface, where no walk reports a crossing, and the promise would be broken).
    const auto hf = rough_field<T>(401, 301, 0.25, {-20, 10}, 7);
    rng gen{43};
    long hits = 0, resumed_far = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const vec3<double> o{gen.uniform(-15, 75), gen.uniform(15, 80), double(hf.top_m()) + gen.uniform(0.5, 15)};
        const double e = gen.uniform(2, 80) * deg, h = gen.uniform(0, 360) * deg;
        const ray<T> r{vec3<T>(o), vec3<T>(vec3<double>{std::cos(e) * std::sin(h), std::cos(e) * std::cos(h), -std::sin(e)})};
        const T t_max = T(gen.uniform() < 0.2 ? gen.uniform(5, 40) : 150);
        const auto want = hf.intersect(r, t_max);
        const double u = i % 4 == 0 ? 1.0 - std::ldexp(1.0, -int(10 + gen.next() % 12)) : gen.uniform();
        const T clear = T(u * double(want ? want->distance_m : t_max));
        hits += want.has_value();
        resumed_far += want && clear > T(0.9) * want->distance_m;
        REQUIRE(same_hit(hf.intersect_after(r, t_max, clear), want));
        // It trusts the caller: told clear to 4 m past the hit (at least 0.69 m on horizontally at 80 degrees down, so
        // past a grid line of the 0.25 m cells), it does not look there.
        if (want) {
            const auto past = hf.intersect_after(r, t_max, want->distance_m + T(4));
            REQUIRE((!past || past->distance_m > want->distance_m));
        }
    }
    MESSAGE(n << " rays, " << hits << " hits, " << resumed_far << " resumed within a tenth of their hit");
    CHECK(hits > n / 2);
    CHECK(resumed_far > n / 5);
}

TEST_CASE_TEMPLATE("The clear distance beside a neighbour is never past the ray's own first hit, and is 0 where the "
                   "neighbour cannot vouch for it",
                   T, float, double) {
    const auto hf = rough_field<T>(401, 301, 0.25, {-20, 10}, 7);
    const sss::scene::height_bounds<T> hb{hf.bottom_m(), hf.top_m()};
    const vec3<double> fish{40, 40, double(hf.top_m()) + 8};
    const auto pose = sss::make_pose(0.0, fish, 0.0, 0.0, 0.0);
    const auto clear = [&](const ray<T>& r, const ray<T>& a, T a_clear) {
        return sss::scene::clear_beside_m(hf.grid(), hf.pyramid(), hb, r, a, a_clear);
    };
    long vouched = 0;
    for (int i = 0; i < 160; ++i) {
        const double e = 60 * deg - i * 0.25 * deg;
        const ray<T> a{vec3<T>(fish), vec3<T>(beam_ray(pose, 1, 0.0, e))};
        const ray<T> r{vec3<T>(fish), vec3<T>(beam_ray(pose, 1, 0.0, e - 0.01 * deg))};
        const auto ha = hf.intersect(a, T(200));
        const auto hr = hf.intersect(r, T(200));
        REQUIRE(ha);
        REQUIRE(hr);
        const T s = clear(r, a, ha->distance_m);
        CHECK(s <= hr->distance_m);
        vouched += s > T(0);
        // A shallower guide, another origin, a guide turned 2 degrees away, one whose path leaves the footprint:
        // nothing is vouched for.
        CHECK(clear(a, r, hr->distance_m) == T(0));
        ray<T> moved = a;
        moved.origin.x += T(0.5);
        CHECK(clear(r, moved, ha->distance_m) == T(0));
        const ray<T> turned{vec3<T>(fish), vec3<T>(beam_ray(pose, 1, 2 * deg, e))};
        CHECK(clear(r, turned, ha->distance_m) == T(0));
        CHECK(clear(r, a, T(1000)) == T(0));
    }
    MESSAGE(vouched << " of 160 vouched for");
    CHECK(vouched > 120);
    // Headings 50 degrees apart over a plane rising 0.1 m per metre along x and y: the points under the two rays at
    // horizontal distance rho are 2 rho sin(25 deg) apart, more than rho sin(50 deg), and a guide steeper by just
    // over the slope times the latter would vouch for a ray past its own hit. Such a turn is refused.
    {
        const std::size_t n = 1001;
        std::vector<T> plane(n * n);
        for (std::size_t iy = 0; iy < n; ++iy)
            for (std::size_t ix = 0; ix < n; ++ix) plane[iy * n + ix] = T(0.01 * double(ix + iy));
        const height_field<T> slope({.nx = n, .ny = n, .cell_m = T(0.1), .origin_m = {T(0), T(0)}, .heights_m = std::move(plane)});
        const auto toward = [](double heading_deg, double tau) {
            const double h = heading_deg * deg;
            return vec3<T>(glm::normalize(vec3<double>{std::sin(h), std::cos(h), -tau}));
        };
        const double lip = std::sqrt(2.0) * 0.1;
        const vec3<T> o{T(50), T(50), T(12)};
        const ray<T> r2{o, toward(-20, 0.3)}, a2{o, toward(-70, 0.3 + 0.8 * lip)};
        const auto ha2 = slope.intersect(a2, T(100));
        REQUIRE(ha2);
        const T a_clear = ha2->distance_m * T(0.9999);
        CHECK(sss::scene::clear_beside_m(slope.grid(), slope.pyramid(), {slope.bottom_m(), slope.top_m()}, r2, a2, a_clear) ==
              T(0));
        CHECK(same_hit(slope.intersect_beside(r2, T(100), a2, a_clear), slope.intersect(r2, T(100))));
    }
    // From under the surface (inside the sediment) nothing is vouched for.
    const vec3<double> buried{40, 40, double(hf.seabed_height_m(T(40), T(40))) - 0.2};
    const ray<T> a{vec3<T>(buried), vec3<T>(beam_ray(pose, 1, 0.0, 30 * deg))};
    const ray<T> r{vec3<T>(buried), vec3<T>(beam_ray(pose, 1, 0.0, 29 * deg))};
    CHECK(clear(r, a, T(5)) == T(0));
}
