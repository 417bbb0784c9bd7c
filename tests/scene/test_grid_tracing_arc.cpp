// A circular arc in a vertical plane met by a height field (height_field_arc.hpp, intersect_arc): the path of a ray
// through a layer of water whose sound speed changes linearly with depth, met exactly rather than through chords.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "sss/scene/height_field.hpp"
#include "support/fused.hpp"
#include "support/grid_relief.hpp"

using sss::vec2;
using sss::vec3;
using sss::scene::height_field;
using sss::scene::vertical_arc;
using sss_test::rng;
using sss_test::rough_field;

namespace {

// A random arc over the field: from 0.3 to 3 m above the surface at a random point of the inner part, any heading,
// inclination from 3 degrees up to 17 degrees down, curvature up to 3e-3 1/m either way (bending up or down: a
// 1500 m/s ray under a gradient of 4.5 1/s, far beyond any ocean's, so that arcs turn within the field).
template <class T> vertical_arc<T> random_arc(const height_field<T>& hf, rng& r, double lo_m, double hi_m) {
    const double x = r.uniform(lo_m, hi_m), y = r.uniform(lo_m, hi_m), az = r.uniform(0, 6.283185307179586);
    const double phi = r.uniform(-0.05, 0.3), above = r.uniform(0.3, 3.0), kappa = r.uniform(-3e-3, 3e-3);
    vertical_arc<T> a;
    a.start = vec3<T>{T(x), T(y), T(double(hf.seabed_height_m(T(x), T(y))) + above)};
    a.heading = vec2<T>{T(std::cos(az)), T(std::sin(az))};
    a.sin_phi0 = T(std::sin(phi));
    a.cos_phi0 = T(std::cos(phi));
    a.kappa_per_m = T(kappa);
    return a;
}

// The arc's height above the surface (m) at horizontal distance x (m), in double, from the arc's own formula.
template <class T> double above_surface(const height_field<T>& hf, const vertical_arc<T>& a, double x) {
    const vec3<T> p = a.at(T(x));
    return double(p.z) - double(hf.seabed_height_m(p.x, p.y));
}

// Whether (x, y) lies over the field's footprint [0, extent]^2.
bool over(double x, double y, double extent) { return x >= 0 && y >= 0 && x <= extent && y <= extent; }

template <class T> void check_first_crossing() {
    const std::size_t n = 321;
    const double cell = 0.25, extent = double(n - 1) * cell;
    const auto hf = rough_field<T>(n, n, cell, {0, 0}, 7);
    rng r{42};
    const double step = 2e-3, on_surface = sizeof(T) == 4 ? 2e-4 : 1e-9;
    int hits = 0, misses = 0, turning = 0;
    for (int k = 0; k < 400; ++k) {
        const auto a = random_arc(hf, r, 5.0, extent - 5.0);
        const T x_end = T(60);
        const auto h = hf.intersect_arc(a, T(0), x_end);
        // Arcs going down that bend up and turn within their length (f convex: the dip check's case).
        turning += a.sin_phi0 > T(0) && a.kappa_per_m > T(0) && double(a.sin_phi0 / a.kappa_per_m) < double(x_end);
        // Nothing before the hit: the arc is above the surface at every sample short of it (or of its end, or of
        // where it leaves the footprint).
        const double stop = h ? double(h->x_m) - step : double(x_end);
        bool clear = true;
        for (double x = 0; x < stop; x += step) {
            const vec3<T> p = a.at(T(x));
            if (!over(double(p.x), double(p.y), extent)) break;
            if (!(above_surface(hf, a, x) > 0)) {
                clear = false;
                break;
            }
        }
        CHECK_MESSAGE(clear, "arc " << k << ": below the surface before the reported " << (h ? "hit" : "end"));
        if (!h) {
            ++misses;
            continue;
        }
        ++hits;
        // The hit lies on the surface.
        CHECK(std::abs(above_surface(hf, a, double(h->x_m))) <= on_surface);
        CHECK(h->surface.normal.z > T(0));
    }
    MESSAGE(hits << " hits, " << misses << " arcs leave the field or end first; " << turning << " turn up within their length");
    CHECK(hits > 300);
    CHECK(turning > 30);
}

} // namespace

TEST_CASE_TEMPLATE("An arc's first crossing of rough relief lies on the surface, with the arc above it all the way "
                   "there",
                   T, float, double) {
    check_first_crossing<T>();
}

TEST_CASE_TEMPLATE("A straight arc meets the height field where the straight-ray tracer does", T, float, double) {
    const std::size_t n = 321;
    const double cell = 0.25;
    const auto hf = rough_field<T>(n, n, cell, {-40, -40}, 3);
    rng r{9};
    int compared = 0;
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
        auto a = random_arc(hf, r, -35.0, 35.0);
        a.kappa_per_m = T(0);
        if (!(a.sin_phi0 > T(0.01))) continue;
        const auto h = hf.intersect_arc(a, T(0), T(60));
        const sss::ray<T> ray{a.start, vec3<T>{a.heading.x * a.cos_phi0, a.heading.y * a.cos_phi0, -a.sin_phi0}};
        const auto s = hf.intersect(ray, T(60) / a.cos_phi0);
        REQUIRE(bool(h) == bool(s));
        if (!h) continue;
        ++compared;
        // The same crossing; the two walks compute it by different formulas (in x, in distance along the ray).
        const double d = double(glm::length(h->surface.point - s->point));
        worst = std::max(worst, d);
        CHECK(d <= (sizeof(T) == 4 ? 2e-4 : 1e-9) * (1 + double(s->distance_m)));
        CHECK(h->surface.label == s->label);
    }
    MESSAGE(compared << " hits, worst distance between them " << worst << " m");
    CHECK(compared > 1000);
}

TEST_CASE_TEMPLATE("Any start before its crossing that the arc is above gives the same hit, to the last bit", T, float,
                   double) {
    const std::size_t n = 321;
    const double cell = 0.25, extent = double(n - 1) * cell;
    const auto hf = rough_field<T>(n, n, cell, {0, 0}, 11);
    rng r{5};
    int arcs = 0, starts = 0, moved = 0;
    double worst = 0;
    for (int k = 0; k < 600; ++k) {
        auto a = random_arc(hf, r, 5.0, extent - 5.0);
        // Some along the grid's axes and diagonals (no diagonal crossings, or crossings at vertices), some from a vertex.
        if (k % 5 == 1) a.heading = vec2<T>{T(k % 10 == 1 ? 1 : -1), T(0)};
        if (k % 5 == 2) a.heading = vec2<T>{T(0), T(k % 10 == 2 ? 1 : -1)};
        if (k % 5 == 3) a.heading = vec2<T>{T(std::sqrt(0.5)), T(k % 10 == 3 ? std::sqrt(0.5) : -std::sqrt(0.5))};
        if (k % 7 == 0) {
            a.start.x = T(std::round(double(a.start.x) / cell) * cell);
            a.start.y = T(std::round(double(a.start.y) / cell) * cell);
            a.start.z = T(double(hf.seabed_height_m(a.start.x, a.start.y)) + 1.0);
        }
        const auto h = hf.intersect_arc(a, T(0), T(60));
        if (!h) continue;
        ++arcs;
        // Starts spread over the way there, some a hair before the hit, and some on the grid's lines (a cell edge
        // crossed: x where u or v is a whole number of cells).
        std::vector<T> clears;
        for (const double f : {0.05, 0.3, 0.6, 0.9, 0.99, 0.999, 0.99999}) clears.push_back(T(f * double(h->x_m)));
        const T u0 = a.start.x / T(cell), v0 = a.start.y / T(cell);
        for (int line = -3; line <= 3; ++line) {
            const T du = a.heading.x / T(cell);
            if (du != T(0)) clears.push_back((std::floor(u0) + T(line) - u0) * (T(1) / du));
            const T dv = a.heading.y / T(cell);
            if (dv != T(0)) clears.push_back((std::floor(v0) + T(line) - v0) * (T(1) / dv));
        }
        for (const T c : clears) {
            if (!(c > T(0) && c < h->x_m)) continue;
            ++starts;
            const auto g = hf.intersect_arc(a, c, T(60));
            REQUIRE(g);
            // Where multiply-adds are fused, to the rounding of the arc's place (the start's and the distance's).
            const double reach = double(glm::length(a.start)) + double(h->x_m);
            CHECK(sss_test::same_to_rounding(g->x_m, h->x_m, reach));
            CHECK(sss_test::same_to_rounding(g->surface.point, h->surface.point, reach));
            CHECK(sss_test::same_to_rounding(g->surface.normal, h->surface.normal, 1.0));
            CHECK(g->surface.label == h->surface.label);
            if constexpr (sss_test::fused)
                worst = std::max(worst, std::abs(double(g->x_m) - double(h->x_m)) /
                                            (double(std::numeric_limits<T>::epsilon()) * reach));
        }
        // The start is used: one past the crossing (a promise broken) finds a later crossing, or none.
        const auto past = hf.intersect_arc(a, h->x_m + T(0.5), T(60));
        if (past) CHECK(past->x_m > h->x_m);
        moved += !past || past->x_m > h->x_m;
    }
    MESSAGE(arcs << " arcs, " << starts << " guided starts");
    if constexpr (sss_test::fused) MESSAGE("fused: worst x_m " << worst << " epsilons of the reach");
    CHECK(starts > 3000);
    CHECK(moved == arcs);
}

TEST_CASE_TEMPLATE("An arc bending up that dips under a facet between two points above it meets it, where the closed "
                   "form says",
                   T, float, double) {
    // A flat seabed at z = 0 in cells of 40 m: the arc turns up at x_t = sin phi0 / kappa, at depth
    // sin^2 phi0 / (kappa (1 + cos phi0)) below its start, well inside one piece of a cell.
    const auto hf = height_field<T>({.nx = 5, .ny = 5, .cell_m = T(40), .origin_m = {T(0), T(0)},
                                     .heights_m = std::vector<T>(25, T(0))});
    const double phi = 0.05, kappa = 2e-3;
    const double bottom = std::sin(phi) * std::sin(phi) / (kappa * (1 + std::cos(phi))); // 0.625 m
    for (const double miss : {1e-3, -1e-3, 0.1, -0.1}) {
        vertical_arc<T> a;
        a.start = vec3<T>{T(5), T(83), T(bottom + miss)}; // the turn at x = 25 m: (30, 83), inside cell (0, 2)
        a.heading = vec2<T>{T(1), T(0)};
        a.sin_phi0 = T(std::sin(phi));
        a.cos_phi0 = T(std::cos(phi));
        a.kappa_per_m = T(kappa);
        const auto h = hf.intersect_arc(a, T(0), T(60));
        if (miss > 0) {
            CHECK_FALSE(h);
            continue;
        }
        REQUIRE(h);
        // Depth d reached first where cos phi = cos phi0 + kappa d, going down: x = (sin phi0 - sin phi) / kappa.
        const double cos_hit = std::cos(phi) + kappa * (bottom + miss), x = (std::sin(phi) - std::sqrt(1 - cos_hit * cos_hit)) / kappa;
        CHECK(double(h->x_m) == doctest::Approx(x).epsilon(sizeof(T) == 4 ? 1e-3 : 1e-7));
        CHECK(double(h->x_m) < std::sin(phi) / kappa); // before the turn
    }
}

TEST_CASE_TEMPLATE("An arc that starts under the surface, or comes over the field's side below it, is not stopped until "
                   "it has come out",
                   T, float, double) {
    // Flat seabed at z = 0 over [0, 100]^2; an arc going up from 0.5 m under it, bending down (kappa < 0): it comes out,
    // rises, turns and comes back down, meeting z = 0 again where the closed form says.
    const auto hf = height_field<T>({.nx = 11, .ny = 11, .cell_m = T(10), .origin_m = {T(0), T(0)},
                                     .heights_m = std::vector<T>(121, T(0))});
    const double phi = -0.1, kappa = -4e-3; // sin phi = sin phi0 - kappa x: rises to the turn at x = 25 m
    for (const double x0 : {20.0, -3.0}) { // inside the footprint, and 3 m outside its west side (still under at 0)
        vertical_arc<T> a;
        a.start = vec3<T>{T(x0), T(50), T(-0.5)};
        a.heading = vec2<T>{T(1), T(0)};
        a.sin_phi0 = T(std::sin(phi));
        a.cos_phi0 = T(std::cos(phi));
        a.kappa_per_m = T(kappa);
        const auto h = hf.intersect_arc(a, T(0), T(80));
        REQUIRE(h);
        // Depth below the start -0.5 m again (height 0), on the way down: cos phi = cos phi0 + kappa d, d = -0.5.
        const double cos_hit = std::cos(phi) + kappa * -0.5;
        const double x = (std::sin(phi) - std::sqrt(1 - cos_hit * cos_hit)) / kappa; // sin phi > 0 (descending)
        CHECK(double(h->x_m) == doctest::Approx(x).epsilon(sizeof(T) == 4 ? 1e-4 : 1e-9));
        CHECK(double(h->x_m) > std::sin(phi) / kappa); // after the turn
    }
}

TEST_CASE_TEMPLATE("An arc bending down that rises out of the surface and falls back within one facet meets it on the "
                   "way down, where the closed form says",
                   T, float, double) {
    // Flat seabed at z = 0 in cells of 40 m; from 0.2 m under it, going up at 0.05 rad with kappa = -4e-3 1/m: it turns
    // at x = 12.5 m, 0.11 m above the seabed, and is under again at both ends of its one piece.
    const auto hf = height_field<T>({.nx = 5, .ny = 5, .cell_m = T(40), .origin_m = {T(0), T(0)},
                                     .heights_m = std::vector<T>(25, T(0))});
    const double phi = -0.05, kappa = -4e-3, z0 = -0.2;
    vertical_arc<T> a;
    a.start = vec3<T>{T(5), T(83), T(z0)};
    a.heading = vec2<T>{T(1), T(0)};
    a.sin_phi0 = T(std::sin(phi));
    a.cos_phi0 = T(std::cos(phi));
    a.kappa_per_m = T(kappa);
    REQUIRE(double(a.at(T(35)).z) < 0); // under at the piece's end (the cell's edge at x = 40 m)
    const auto h = hf.intersect_arc(a, T(0), T(35));
    REQUIRE(h);
    // Depth z0 below the start on the way down: cos phi = cos phi0 + kappa z0, sin phi > 0.
    const double cos_hit = std::cos(phi) + kappa * z0, x = (std::sin(phi) - std::sqrt(1 - cos_hit * cos_hit)) / kappa;
    CHECK(double(h->x_m) == doctest::Approx(x).epsilon(sizeof(T) == 4 ? 1e-4 : 1e-9));
}

TEST_CASE_TEMPLATE("An arc that would turn vertical before x_end_m meets the surface it comes down on first, as with a "
                   "shorter x_end_m",
                   T, float, double) {
    // Flat seabed at z = 0; from 1 m above it, 36.9 degrees down and bending down (kappa = -0.1 1/m): vertical at
    // x_v = (1 - sin phi0) / -kappa = 4 m, but it meets the seabed at x = 1.141 m. That hit stands whatever x_end_m;
    // beyond x_v it was dropped with the whole arc.
    const auto hf = height_field<T>({.nx = 11, .ny = 11, .cell_m = T(1), .origin_m = {T(0), T(0)},
                                     .heights_m = std::vector<T>(121, T(0))});
    vertical_arc<T> a;
    a.start = vec3<T>{T(5), T(5), T(1)};
    a.heading = vec2<T>{T(1), T(0)};
    a.sin_phi0 = T(0.6);
    a.cos_phi0 = T(0.8);
    a.kappa_per_m = T(-0.1);
    // Depth 1 m first where cos phi = cos phi0 + kappa d: x = (sin phi - sin phi0) / -kappa.
    const double x = (std::sqrt(1 - 0.7 * 0.7) - 0.6) / 0.1;
    for (const double x_end : {2.0, 3.9, 4.1, 5.0, 1e6}) {
        CAPTURE(x_end);
        const auto h = hf.intersect_arc(a, T(0), T(x_end));
        REQUIRE(h);
        CHECK(double(h->x_m) == doctest::Approx(x).epsilon(sizeof(T) == 4 ? 1e-5 : 1e-12));
    }
    // A seabed it would meet only beyond x_v (10 m down from 1 m up: it turns vertical 4 m out, 8 m down) is not met.
    const auto deep = height_field<T>({.nx = 11, .ny = 11, .cell_m = T(1), .origin_m = {T(0), T(0)},
                                       .heights_m = std::vector<T>(121, T(-9))});
    CHECK_FALSE(deep.intersect_arc(a, T(0), T(1e6)));
    // Steep and bending fast: sin phi0 = 0.99, kappa = -1 1/m (vertical 1 cm out). Stepping back a fixed fraction of
    // x_v left sin phi rounded to 1, and the arc was dropped whole; it meets the seabed 10 cm down before that.
    vertical_arc<T> steep;
    steep.start = vec3<T>{T(5), T(5), T(0.1)};
    steep.heading = vec2<T>{T(1), T(0)};
    steep.sin_phi0 = T(0.99);
    steep.cos_phi0 = T(std::sqrt(1.0 - 0.99 * 0.99));
    steep.kappa_per_m = T(-1);
    const auto h = hf.intersect_arc(steep, T(0), T(1));
    REQUIRE(h);
    CHECK(double(h->x_m) < 0.01);
    CHECK(std::abs(double(h->surface.point.z)) < 1e-4);
}
