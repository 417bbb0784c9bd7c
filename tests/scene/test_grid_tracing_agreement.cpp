// Agreement of the accelerated traversal and of the fan sweep (intersect_many) with the reference
// traversal, on a rough surface with plateaus (exact ties), a trench and white noise.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

#include "sss/scene/height_field.hpp"
#include "support/grid_relief.hpp"

using sss::ray;
using sss::vec3;
using sss::scene::height_field;
using sss_test::make_ray;
using sss_test::rng;
using sss_test::rough_field;

namespace {

constexpr double deg = 3.141592653589793 / 180;

// intersect() against the reference traversal: the same hit or miss, and for a hit the same cell and the same
// distance to the last bit. True for a hit.
template <class T> bool same_as_reference(const height_field<T>& hf, const ray<T>& r, T t_max) {
    const auto a = hf.intersect(r, t_max);
    const auto b = hf.intersect_reference(r, t_max);
    REQUIRE(bool(a) == bool(b));
    if (!a) return false;
    REQUIRE(a->label == b->label);
    REQUIRE(a->distance_m == b->distance_m);
    return true;
}

} // namespace

TEST_CASE_TEMPLATE("The accelerated and the reference traversal find the same cell and distance, to the last bit, for a million rays", T,
                   float, double) {
    // A 601 x 411 rough field (600 x 410 cells: partial pyramid blocks), random rays of every kind and
    // sidescan fans. The region id of a hit is its cell index, so equal labels mean equal cells.
    const auto hf = rough_field<T>(601, 411, 0.25, {-20, 10}, 42);
    rng gen{17};
    const long n = std::is_same_v<T, double> ? 600000 : 150000;
    long hits = 0, compared = 0;
    auto compare = [&](const ray<T>& r, T t_max) {
        ++compared;
        hits += same_as_reference(hf, r, t_max);
    };
    // Random rays: origins over and around the footprint, some under the surface; all directions.
    for (long k = 0; k < n; ++k) {
        const vec3<double> o{gen.uniform(-40, 150), gen.uniform(-10, 130), gen.uniform(-2, 15)};
        compare(make_ray<T>(o, gen.direction()), T(gen.uniform() < 0.2 ? gen.uniform(0.5, 20) : 80));
    }
    // Sidescan fans: towfish 2..15 m above the top, 8 along-track angles, 2 x 256 depressions per ping.
    const long pings = n / 4096;
    for (long p = 0; p < pings; ++p) {
        const vec3<double> fish{gen.uniform(-10, 140), gen.uniform(0, 120), double(hf.top_m()) + gen.uniform(2, 15)};
        const double heading = gen.uniform(0, 6.283185307179586);
        for (int side = -1; side <= 1; side += 2)
            for (int a = 0; a < 8; ++a) {
                const double along = (-0.5 + a / 7.0) * deg;
                for (int i = 0; i < 256; ++i) {
                    const double dep = (1 + 59 * i / 255.0) * deg;
                    const double az = heading + side * (90 * deg - along);
                    compare(
                        make_ray<T>(fish, {std::cos(dep) * std::cos(az), std::cos(dep) * std::sin(az), -std::sin(dep)}),
                        T(150));
                }
            }
    }
    CHECK(compared >= (std::is_same_v<T, double> ? 1000000 : 250000) * 9 / 10);
    CHECK(hits > compared / 3);
    MESSAGE(compared << " rays compared, " << hits << " hits");
}

TEST_CASE_TEMPLATE("Rays nearly along a grid axis, passing a hair from a block-edge vertex, get the reference hits to the last bit",
                   T, float, double) {
    // A ray turned a hair from a grid axis crosses that axis's lines far apart, at ill-conditioned distances. Where
    // a skipped block ends (on a line of the other axis) within rounding of such a crossing, the exit point's own
    // coordinate can round into the next cell while the reference walk, comparing the two lines' crossings, has not
    // entered it; resumed there, the walk would miss that line's breakpoint and interpolate the hit over a longer
    // segment. Each ray here passes a vertex (on a block's edge) a hair to one side (down to float's or double's
    // rounding), 2 to 30 cm above the surface and coming down, and hits the surface a few cells on.
    const auto hf = rough_field<T>(601, 411, 0.25, {-20, 10}, 42);
    rng gen{29};
    const long n = 40000;
    long hits = 0;
    for (long k = 0; k < n; ++k) {
        const int axis = int(gen.next() % 4); // heading along +u, +v, -u or -v, turned a hair
        const double turn = (gen.uniform() < 0.5 ? -1 : 1) * std::pow(10.0, gen.uniform(-5, -1.5));
        const double az = axis * 90 * deg + turn, dep = gen.uniform(3, 30) * deg;
        const vec3<double> d{std::cos(dep) * std::cos(az), std::cos(dep) * std::sin(az), -std::sin(dep)};
        // The vertex: on a line of the axis the ray runs across (a multiple of 4: a block edge at levels 1 and 2),
        // the point beside it a hair along the other axis.
        const double i = double(8 + gen.next() % 584), j = double(8 + gen.next() % 394);
        const bool along_v = axis % 2 == 1;
        const double hair =
            (gen.uniform() < 0.5 ? -1 : 1) * std::pow(10.0, gen.uniform(std::is_same_v<T, float> ? -6 : -14, -2));
        const double u = along_v ? i + hair : std::round(i / 4) * 4, v = along_v ? std::round(j / 4) * 4 : j + hair;
        const double x = -20 + 0.25 * u, y = 10 + 0.25 * v;
        const vec3<double> p{x, y, double(hf.seabed_height_m(T(x), T(y))) + gen.uniform(0.02, 0.3)};
        hits += same_as_reference(hf, make_ray<T>(p - gen.uniform(5, 40) * d, d), T(150));
    }
    CHECK(hits > n / 2);
}

TEST_CASE_TEMPLATE("Rays through the grid's vertices (u and v lines crossed at once) get the reference hits to the last bit",
                   T, float, double) {
    // Headings at 45 degrees to the axes from a point on a vertex's diagonal line: the ray meets every vertex on its
    // path, where it crosses a u line and a v line at the same distance (exactly, where the rounding of the two
    // coordinates agrees), and block exits tie. Both tracers must settle each tie the same way.
    const auto hf = rough_field<T>(601, 411, 0.25, {-20, 10}, 42);
    rng gen{37};
    long hits = 0;
    const long n = 20000;
    for (long k = 0; k < n; ++k) {
        const double f = gen.uniform() < 0.5 ? 0.0 : gen.uniform(), along = gen.uniform(-40, 40);
        const double i = double(20 + gen.next() % 560), j = double(20 + gen.next() % 370);
        const int sx = gen.next() % 2 ? 1 : -1, sy = gen.next() % 2 ? 1 : -1;
        const double x = -20 + 0.25 * (i + f) + along * sx * 0.25, y = 10 + 0.25 * (j + f) + along * sy * 0.25;
        const double h = std::sqrt(0.5) * std::cos(gen.uniform(3, 40) * deg), dz = -std::sqrt(1 - 2 * h * h);
        hits += same_as_reference(hf, make_ray<T>({x, y, double(hf.top_m()) + gen.uniform(0.1, 6)}, {sx * h, sy * h, dz}), T(150));
    }
    CHECK(hits > n / 2);
}

TEST_CASE("Fans traced together give the one-by-one hits, to rounding") {
    using T = double;
    const auto hf = rough_field<T>(601, 411, 0.25, {-20, 10}, 42);
    rng gen{23};
    long compared = 0, boundary = 0;
    for (int p = 0; p < 40; ++p) {
        const vec3<double> fish{gen.uniform(-10, 140), gen.uniform(0, 120), double(hf.top_m()) + gen.uniform(-0.5, 15)};
        const double heading = gen.uniform(0, 6.283185307179586);
        std::vector<ray<T>> rays;
        for (int side = -1; side <= 1; side += 2)
            for (int a = 0; a < 4; ++a) {
                const double along = (-0.5 + a / 3.0) * deg;
                const bool reverse = gen.next() % 2;
                for (int i = 0; i < 400; ++i) {
                    const int ii = reverse ? 399 - i : i;
                    const double dep = (-5 + 65 * ii / 399.0) * deg; // a few rays point up
                    const double az = heading + side * (90 * deg - along);
                    rays.push_back(make_ray<T>(
                        fish, {std::cos(dep) * std::cos(az), std::cos(dep) * std::sin(az), -std::sin(dep)}));
                }
            }
        // A few odd rays between fans: vertical, and one that breaks the order.
        rays.push_back(make_ray<T>(fish, {0, 0, -1}));
        std::vector<std::optional<sss::hit<T>>> got(rays.size());
        const T t_max = T(gen.uniform() < 0.3 ? 40 : 200);
        hf.intersect_many(rays, t_max, got);
        for (std::size_t k = 0; k < rays.size(); ++k) {
            const auto want = hf.intersect_reference(rays[k], t_max);
            ++compared;
            REQUIRE(bool(got[k]) == bool(want));
            if (!want) continue;
            CHECK(std::abs(got[k]->distance_m - want->distance_m) <= 1e-9 * want->distance_m);
            if (got[k]->label != want->label) {
                // Allowed only for a hit on a cell boundary, where either cell is right.
                const double u = (want->point.x + 20) / 0.25, v = (want->point.y - 10) / 0.25;
                const bool on_edge = std::abs(u - std::round(u)) < 1e-7 || std::abs(v - std::round(v)) < 1e-7;
                CHECK(on_edge);
                ++boundary;
            }
        }
    }
    std::vector<std::optional<sss::hit<T>>> two(2);
    CHECK_THROWS_AS(hf.intersect_many(std::vector<ray<T>>(3), T(1), two), sss::invalid_parameter);
    MESSAGE(compared << " rays compared, " << boundary << " on cell boundaries");
}

TEST_CASE("In float, fans and single rays differ only where a ray grazes the surface within float rounding") {
    // Float rounding decides near-tangent touches differently in the two formulations; any difference
    // must be such a touch, as judged in double on the same heights.
    const auto hf = rough_field<float>(601, 411, 0.25, {-20, 10}, 42);
    const height_field<double> hd({.nx = 601, .ny = 411, .cell_m = 0.25, .origin_m = {-20, 10}, .heights_m = std::vector<double>(hf.heights_m().begin(), hf.heights_m().end())});
    rng gen{29};
    long compared = 0, differ = 0;
    for (int p = 0; p < 20; ++p) {
        const vec3<double> fish{gen.uniform(-10, 140), gen.uniform(0, 120), double(hf.top_m()) + gen.uniform(1, 12)};
        const double heading = gen.uniform(0, 6.283185307179586);
        std::vector<ray<float>> rays;
        for (int side = -1; side <= 1; side += 2)
            for (int i = 0; i < 2048; ++i) {
                const double dep = (1 + 59 * i / 2047.0) * deg, az = heading + side * 90 * deg;
                rays.push_back(make_ray<float>(
                    fish, {std::cos(dep) * std::cos(az), std::cos(dep) * std::sin(az), -std::sin(dep)}));
            }
        std::vector<std::optional<sss::hit<float>>> got(rays.size());
        hf.intersect_many(rays, 200.f, got);
        for (std::size_t k = 0; k < rays.size(); ++k) {
            const auto one = hf.intersect(rays[k], 200.f);
            ++compared;
            const bool same =
                bool(one) == bool(got[k]) &&
                (!one || std::abs(double(one->distance_m - got[k]->distance_m)) <= 1e-4 * double(one->distance_m));
            if (same) continue;
            ++differ;
            // Height of the ray above the double surface at both candidate hits: the earlier one must be
            // a touch within float rounding (|f| below 1e-4 m here), the later one a real crossing.
            const ray<double> rd{vec3<double>(rays[k].origin), vec3<double>(rays[k].direction)};
            auto f_at = [&](double s) {
                const auto q = rd.at(s);
                return q.z - hd.seabed_height_m(q.x, q.y);
            };
            const double s1 = one ? double(one->distance_m) : 1e9, s2 = got[k] ? double(got[k]->distance_m) : 1e9;
            CHECK(std::abs(f_at(std::min(s1, s2))) < 1e-4);
        }
    }
    CHECK(differ < compared / 1000);
    MESSAGE(compared << " rays compared, " << differ << " differ");
}
