// The top of a scene over a rectangle of the plane bounds every piece of geometry there and nothing more than the
// whole scene's top; an area view answers every query as its scene does, with that top, and leaves out objects
// that reach nowhere over its rectangle.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/area_view.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/targets.hpp>

#include "support/grid_relief.hpp"

namespace {

using sss::vec2;
using sss::vec3;
constexpr double inf = std::numeric_limits<double>::infinity();

// 301 x 201 vertices at 0.5 m from (-50, 20): a slope of 5 cm per metre eastwards with +-0.4 m of noise.
sss::scene::height_field<double> sloped_field() {
    std::mt19937_64 g(11);
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    auto h = sss_test::sample_heights<double>(301, 201, 0.5, [&](double x, double) { return 0.05 * x + u(g); });
    return sss::scene::height_field<double>({.nx = 301, .ny = 201, .cell_m = 0.5, .origin_m = {-50.0, 20.0}, .heights_m = std::move(h)});
}

// The highest vertex of every cell that holds part of the rectangle: a bound the surface over it reaches.
double highest_under(const sss::scene::height_field<double>& f, vec2<double> lo, vec2<double> hi) {
    const double c = f.cell_m();
    const auto clamp_cell = [](double v, std::size_t n) { return std::clamp(v, 0.0, double(n - 2)); };
    const double u0 = clamp_cell(std::floor((lo.x - f.origin_m().x) / c), f.nx()), u1 = clamp_cell(std::floor((hi.x - f.origin_m().x) / c), f.nx());
    const double v0 = clamp_cell(std::floor((lo.y - f.origin_m().y) / c), f.ny()), v1 = clamp_cell(std::floor((hi.y - f.origin_m().y) / c), f.ny());
    double m = -inf;
    for (auto iy = std::size_t(v0); iy <= std::size_t(v1) + 1; ++iy)
        for (auto ix = std::size_t(u0); ix <= std::size_t(u1) + 1; ++ix) m = std::max(m, f.height_m(ix, iy));
    return m;
}

} // namespace

TEST_CASE("a height field's top over a rectangle bounds every cell there and never exceeds its top") {
    const auto f = sloped_field();
    std::mt19937_64 g(3);
    std::uniform_real_distribution<double> x(-60.0, 110.0), y(10.0, 130.0), size(0.0, 40.0);
    int tighter = 0;
    for (int k = 0; k < 2000; ++k) {
        const double x0 = x(g), y0 = y(g);
        const vec2<double> lo{x0, y0}, hi{x0 + (k % 7 == 0 ? 0.0 : size(g)), y0 + (k % 11 == 0 ? 0.0 : size(g))};
        const double top = f.top_m(lo, hi);
        const bool off = hi.x < -50.0 || lo.x > 100.0 || hi.y < 20.0 || lo.y > 120.0;
        if (off) {
            CHECK(top == -inf);
            continue;
        }
        CHECK(top >= highest_under(f, lo, hi));
        CHECK(top <= f.top_m());
        if (hi.x < 0.0 && top < f.top_m() - 2.0) ++tighter;
    }
    // The bound is local: west of x = 0 the slope keeps it metres below the field's top.
    CHECK(tighter > 100);
    CHECK(f.top_m({-1000.0, -1000.0}, {1000.0, 1000.0}) == f.top_m());
    // A rectangle on a vertex line, and one a single point wide.
    CHECK(f.top_m({0.0, 40.0}, {0.0, 40.0}) >= highest_under(f, {0.0, 40.0}, {0.0, 40.0}));
}

TEST_CASE_TEMPLATE("a rectangle on the grid's last vertex line has the top of its cells, also in float at survey coordinates",
                   T, float, double) {
    // A point on the east or north edge line, computed as origin + (n - 1) cell, rounds a few cells' worth of eps past
    // the line in float at coordinates of 10^5 m: it was taken for off the grid, and its top was -infinity.
    std::mt19937 g(1);
    std::uniform_real_distribution<double> coordinate(-5e5, 5e5), cell(0.01, 3.0);
    int no_top = 0, beyond_has_top = 0, checked_beyond = 0, points = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const T c = T(cell(g));
        const vec2<T> origin{T(coordinate(g)), T(coordinate(g))};
        const std::size_t n = 5 + std::size_t(trial % 37);
        const sss::scene::height_field<T> f(
            {.nx = n, .ny = n, .cell_m = c, .origin_m = origin, .heights_m = std::vector<T>(n * n, T(-10))});
        const T east = origin.x + T(n - 1) * c, north = origin.y + T(n - 1) * c;
        for (std::size_t i = 0; i < n; ++i, ++points) {
            const T x = origin.x + T(i) * c, y = origin.y + T(i) * c;
            no_top += !(f.top_m({east, y}, {east, y}) == T(-10)) + !(f.top_m({x, north}, {x, north}) == T(-10));
            // Half a cell beyond the edge lines is off the grid, where the scalar resolves an eighth of a cell there.
            const T east_out = origin.x + (T(n) - T(0.5)) * c, north_out = origin.y + (T(n) - T(0.5)) * c;
            const auto resolved = [&](T a, T b) {
                return std::numeric_limits<T>::epsilon() * (std::abs(a) + std::abs(b)) < c / T(8);
            };
            if (resolved(east_out, origin.x)) {
                ++checked_beyond;
                beyond_has_top += std::isfinite(f.top_m({east_out, y}, {east_out, y}));
            }
            if (resolved(north_out, origin.y)) {
                ++checked_beyond;
                beyond_has_top += std::isfinite(f.top_m({x, north_out}, {x, north_out}));
            }
        }
    }
    CHECK(points > 5000);
    CHECK(no_top == 0);
    // A point at infinity is off the grid; a rectangle from -infinity to +infinity covers it.
    constexpr T big = std::numeric_limits<T>::infinity();
    const sss::scene::height_field<T> f({.nx = 5, .ny = 5, .cell_m = T(1), .heights_m = std::vector<T>(25, T(-10))});
    CHECK(f.top_m({big, T(2)}, {big, T(2)}) == -big);
    CHECK(f.top_m({-big, T(2)}, {-big, T(2)}) == -big);
    CHECK(f.top_m({T(2), big}, {T(2), big}) == -big);
    CHECK(f.top_m({-big, -big}, {big, big}) == T(-10));
    CHECK(checked_beyond > 2000);
    CHECK(beyond_has_top == 0);
}

TEST_CASE("objects count over a rectangle only where their boxes reach over it") {
    auto seabed = [](double, double) { return 0.0; };
    std::vector<sss::scene::object<double>> objs;
    objs.push_back(sss::seabed::tethered_mine<double>({.anchor_m = {0.0, 0.0}, .case_height_m = 5.0, .object_id = 1}, seabed));
    objs.push_back(sss::seabed::tethered_mine<double>({.anchor_m = {200.0, 0.0}, .case_height_m = 2.0, .object_id = 2}, seabed));
    const sss::scene::object_set<double> set(std::move(objs));
    CHECK(set.top_m({-10.0, -10.0}, {10.0, 10.0}) == doctest::Approx(5.5));
    CHECK(set.top_m({190.0, -10.0}, {210.0, 10.0}) == doctest::Approx(2.5));
    CHECK(set.top_m({50.0, -10.0}, {150.0, 10.0}) == -inf);
    CHECK(set.top_m({-10.0, -10.0}, {210.0, 10.0}) == set.top_m());
    CHECK(sss::scene::object_set<double>().top_m({0.0, 0.0}, {1.0, 1.0}) == -inf);
    CHECK(sss::scene::flat_seabed<double>(-3.0).top_m({0.0, 0.0}, {1.0, 1.0}) == -3.0);
}

namespace {
// The highest rise of a vertex above `plane` over the vertices within the rectangle.
double highest_rise(const sss::scene::height_field<double>& f, vec2<double> lo, vec2<double> hi,
                    const sss::scene::sloping_plane& plane) {
    double m = -inf;
    for (std::size_t iy = 0; iy < f.ny(); ++iy)
        for (std::size_t ix = 0; ix < f.nx(); ++ix) {
            const double x = f.origin_m().x + f.cell_m() * double(ix), y = f.origin_m().y + f.cell_m() * double(iy);
            if (x >= lo.x && x <= hi.x && y >= lo.y && y <= hi.y) m = std::max(m, f.height_m(ix, iy) - plane.height_m(x, y));
        }
    return m;
}
} // namespace

TEST_CASE("how far a scene rises above a sloping plane over a rectangle bounds every vertex there, within the plane's "
          "change over a block of the maximum pyramid") {
    const auto f = sloped_field(); // 0.05 (x + 50) + -0.4 ... 0.4 m of noise
    std::mt19937_64 g(5);
    std::uniform_real_distribution<double> x(-60.0, 110.0), y(10.0, 130.0), size(0.0, 40.0), slope(-0.1, 0.1);
    for (int k = 0; k < 500; ++k) {
        const double x0 = x(g), y0 = y(g);
        const vec2<double> lo{x0, y0}, hi{x0 + size(g), y0 + size(g)};
        const sss::scene::sloping_plane plane{.at = {x(g), y(g)}, .z_m = slope(g) * 10.0, .gradient = {slope(g), slope(g)}};
        const double rise = f.rise_above_m(lo, hi, plane);
        if (hi.x < -50.0 || lo.x > 100.0 || hi.y < 20.0 || lo.y > 120.0) {
            CHECK(rise == -inf);
            continue;
        }
        CAPTURE(k);
        CHECK(rise >= highest_rise(f, lo, hi, plane));
        // Rectangles up to 40 m take blocks of at most 2 cells (1 m): the bound looks at most 2 m beyond the rectangle
        // and loses at most 0.1 m per metre of block to the plane's slope there.
        const vec2<double> margin{2.0, 2.0};
        CHECK(rise <= highest_rise(f, lo - margin, hi + margin, plane) + 0.2);
    }
    // Over the field's slope the rise is the noise; above the level plane through its low end, the slope's 2 m more.
    const vec2<double> lo{0.0, 40.0}, hi{40.0, 60.0};
    const sss::scene::sloping_plane along{.at = {-50.0, 0.0}, .z_m = 0.0, .gradient = {0.05, 0.0}};
    const sss::scene::sloping_plane level{.at = {0.0, 0.0}, .z_m = 2.5, .gradient = {0.0, 0.0}};
    CHECK(f.rise_above_m(lo, hi, along) == doctest::Approx(0.4).epsilon(0.15));
    CHECK(f.rise_above_m(lo, hi, level) >= 1.9);
    // A flat seabed: exactly, at the lowest corner of the plane.
    CHECK(sss::scene::flat_seabed<double>(1.0).rise_above_m({0.0, 0.0}, {10.0, 4.0}, along) == doctest::Approx(-1.5));
    // Objects: the top of each box reaching over the rectangle, above the plane's lowest point under the box there.
    auto seabed = [](double, double) { return 0.0; };
    std::vector<sss::scene::object<double>> objs;
    objs.push_back(sss::seabed::tethered_mine<double>({.anchor_m = {0.0, 0.0}, .case_height_m = 5.0, .object_id = 1}, seabed));
    const sss::scene::object_set<double> set(std::move(objs));
    const sss::scene::sloping_plane tilted{.at = {0.0, 0.0}, .z_m = 1.0, .gradient = {0.1, 0.0}};
    const auto& box = set.objects().front().bounds();
    CHECK(set.rise_above_m({-10.0, -10.0}, {10.0, 10.0}, tilted) == doctest::Approx(box.hi.z - (1.0 + 0.1 * box.lo.x)));
    CHECK(set.rise_above_m({50.0, -10.0}, {60.0, 10.0}, tilted) == -inf);
    // A scene: the higher of its seabed's and its objects'.
    const sss::scene::scene sc(sss::scene::flat_seabed<double>(0.0), set);
    CHECK(sc.rise_above_m({-10.0, -10.0}, {10.0, 10.0}, tilted) == set.rise_above_m({-10.0, -10.0}, {10.0, 10.0}, tilted));
    CHECK(sc.rise_above_m({50.0, -10.0}, {60.0, 10.0}, tilted) == doctest::Approx(-1.0 - 0.1 * 50.0));
}

TEST_CASE("an area view answers every ray over its rectangle as its scene does, with the top of what lies there") {
    auto field = sloped_field();
    std::vector<sss::scene::object<double>> objs;
    const auto ground = [&field](double x, double y) { return field.seabed_height_m(x, y); };
    objs.push_back(sss::seabed::tethered_mine<double>({.anchor_m = {-30.0, 70.0}, .case_height_m = 4.0, .object_id = 1}, ground));
    objs.push_back(sss::seabed::tethered_mine<double>({.anchor_m = {80.0, 70.0}, .case_height_m = 12.0, .object_id = 2}, ground));
    const sss::scene::scene sc(std::move(field), sss::scene::object_set<double>(std::move(objs)));

    const vec2<double> lo{-45.0, 50.0}, hi{-10.0, 90.0}; // the lower mine only
    const sss::scene::area_view view(sc, lo, hi);
    CHECK(view.objects_near());
    CHECK(view.top_m() >= sc.objects().top_m(lo, hi));
    CHECK(view.top_m() < sc.top_m() - 5.0);
    const sss::scene::area_view bare(sc, vec2<double>{10.0, 25.0}, vec2<double>{40.0, 45.0}); // no object
    CHECK_FALSE(bare.objects_near());

    std::mt19937_64 g(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int hits = 0, object_hits = 0;
    for (int k = 0; k < 4000; ++k) {
        // From above the rectangle down to a point in it: the whole ray stays over it.
        const vec3<double> from{lo.x + (hi.x - lo.x) * u(g), lo.y + (hi.y - lo.y) * u(g), 15.0};
        const vec3<double> to{lo.x + (hi.x - lo.x) * u(g), lo.y + (hi.y - lo.y) * u(g), -10.0};
        const sss::ray<double> r{from, glm::normalize(to - from)};
        const double t = glm::length(to - from);
        const auto a = view.intersect(r, t), b = sc.intersect(r, t);
        REQUIRE(bool(a) == bool(b));
        if (!a) continue;
        ++hits;
        if (a->object != sss::no_object) ++object_hits;
        CHECK(a->distance_m == b->distance_m);
        CHECK(a->object == b->object);
        CHECK(a->point.z <= view.top_m());
    }
    CHECK(hits > 3000);
    CHECK(object_hits > 0);
    // Batches too.
    std::vector<sss::ray<double>> rays;
    for (int k = 0; k < 64; ++k) {
        const double e = 0.2 + 1.2 * double(k) / 63.0;
        rays.push_back({vec3<double>{-44.0, 70.0, 12.0}, vec3<double>{std::cos(e), 0.0, -std::sin(e)}});
    }
    std::vector<std::optional<sss::hit<double>>> ha(rays.size()), hb(rays.size());
    view.intersect_many(rays, 30.0, ha);
    sc.intersect_many(rays, 30.0, hb);
    for (std::size_t k = 0; k < rays.size(); ++k) {
        REQUIRE(bool(ha[k]) == bool(hb[k]));
        if (ha[k]) CHECK(ha[k]->distance_m == hb[k]->distance_m);
    }
}

TEST_CASE("an area view over nothing keeps its scene's top") {
    const auto f = sloped_field();
    const sss::scene::area_view view(f, vec2<double>{500.0, 500.0}, vec2<double>{600.0, 600.0});
    CHECK(view.top_m() == f.top_m());
}

TEST_CASE("a view narrowed to a column's rectangle leaves out the objects that reach nowhere over it, and keeps its top") {
    auto field = sloped_field();
    std::vector<sss::scene::object<double>> objs;
    const auto ground = [&field](double x, double y) { return field.seabed_height_m(x, y); };
    objs.push_back(sss::seabed::tethered_mine<double>({.anchor_m = {-30.0, 70.0}, .case_height_m = 4.0, .object_id = 1}, ground));
    const sss::scene::scene sc(std::move(field), sss::scene::object_set<double>(std::move(objs)));
    const sss::scene::area_view view(sc, vec2<double>{-45.0, 50.0}, vec2<double>{40.0, 90.0});
    REQUIRE(view.objects_near());
    const auto beside = view.within({0.0, 50.0}, {40.0, 90.0}); // east of the mine
    const auto over = view.within({-35.0, 65.0}, {-25.0, 75.0});
    CHECK_FALSE(beside.objects_near());
    CHECK(over.objects_near());
    CHECK(beside.top_m() == view.top_m());
    // Narrowing a view that has no object near keeps it so.
    const sss::scene::area_view bare(sc, vec2<double>{10.0, 25.0}, vec2<double>{40.0, 45.0});
    CHECK_FALSE(bare.within({-35.0, 65.0}, {-25.0, 75.0}).objects_near());
    // Rays that stay over the narrowed rectangle meet what they meet through the whole scene.
    std::mt19937_64 g(9);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
        const vec3<double> from{40.0 * u(g), 50.0 + 40.0 * u(g), 15.0}, to{40.0 * u(g), 50.0 + 40.0 * u(g), -10.0};
        const sss::ray<double> r{from, glm::normalize(to - from)};
        const double t = glm::length(to - from);
        const auto a = beside.intersect(r, t), b = sc.intersect(r, t);
        REQUIRE(bool(a) == bool(b));
        if (a) CHECK(a->distance_m == b->distance_m);
    }
}

TEST_CASE("the object hierarchy reaches over a rectangle wherever a vertical ray through it meets an object") {
    std::mt19937_64 g(21);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<sss::scene::object<double>> objs;
    for (std::uint32_t k = 0; k < 120; ++k) {
        const vec2<double> at{200.0 * u(g) - 100.0, 200.0 * u(g) - 100.0};
        objs.push_back(sss::seabed::tethered_mine<double>(
            {.anchor_m = at, .case_height_m = 1.0 + 4.0 * u(g), .object_id = k + 1}, [](double, double) { return 0.0; }));
    }
    const sss::scene::object_set<double> set(std::move(objs));
    int empty = 0, reached = 0;
    for (int k = 0; k < 3000; ++k) {
        const vec2<double> lo{220.0 * u(g) - 110.0, 220.0 * u(g) - 110.0};
        const vec2<double> hi = lo + vec2<double>{0.2 + 8.0 * u(g), 0.2 + 8.0 * u(g)};
        const bool over = set.reaches_over(lo, hi);
        (over ? reached : empty)++;
        if (over) continue;
        // Vertical probes on a 10 cm grid over the rectangle meet nothing.
        for (double x = lo.x; x <= hi.x; x += 0.1)
            for (double y = lo.y; y <= hi.y; y += 0.1)
                if (set.intersect(sss::ray<double>{{x, y, 20.0}, {0.0, 0.0, -1.0}}, 40.0)) {
                    FAIL_CHECK("an object under (" << x << ", " << y << ") where none reaches over the rectangle");
                    x = hi.x + 1;
                    break;
                }
    }
    MESSAGE(reached << " rectangles reached, " << empty << " clear");
    CHECK(empty > 1000);
    CHECK(reached > 150);
    CHECK_FALSE(sss::scene::object_set<double>().reaches_over({0.0, 0.0}, {1.0, 1.0}));
}
