// The height field as a surface: construction checks, the triangle rule of interpolation, clamping
// outside the footprint, extreme heights, per-cell ids, normals, and the maximum pyramid.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "sss/scene/concept.hpp"
#include "sss/scene/height_field.hpp"

using sss::vec2;
using sss::vec3;
using sss::scene::height_field;

namespace {

// Heights of a function sampled at the vertices of an nx x ny grid.
template <class T, class F> std::vector<T> sample(std::size_t nx, std::size_t ny, double cell, vec2<double> o, F f) {
    std::vector<T> h(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            h[iy * nx + ix] = static_cast<T>(f(o.x + double(ix) * cell, o.y + double(iy) * cell));
    return h;
}

bool throws_naming(auto&& f, const std::string& what) {
    try {
        f();
    } catch (const sss::invalid_parameter& e) {
        return std::string(e.what()).find(what) != std::string::npos;
    }
    return false;
}

} // namespace

static_assert(sss::Scene<height_field<float>> && sss::Scene<height_field<double>>);

TEST_CASE_TEMPLATE("A height field rejects bad sizes, spacing and origins, and non-finite heights by vertex", T, float,
                   double) {
    const std::vector<T> four(4, T(1));
    CHECK(throws_naming([&] { height_field<T>({.nx = 1, .ny = 4, .cell_m = T(1), .heights_m = four}); }, "height_field.nx"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 4, .ny = 1, .cell_m = T(1), .heights_m = four}); }, "height_field.ny"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 2, .ny = 2, .cell_m = T(0), .heights_m = four}); }, "height_field.cell_m"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 2, .ny = 2, .cell_m = T(-1), .heights_m = four}); }, "height_field.cell_m"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 2, .ny = 2, .cell_m = std::numeric_limits<T>::infinity(), .heights_m = four}); },
                           "height_field.cell_m"));
    CHECK(throws_naming(
        [&] {
            height_field<T>({.nx = 2, .ny = 2, .cell_m = T(1), .origin_m = vec2<T>{std::numeric_limits<T>::quiet_NaN(), T(0)}, .heights_m = four});
        },
        "height_field.origin_m.x"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 2, .ny = 3, .cell_m = T(1), .heights_m = four}); }, "height_field.heights_m"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 2, .ny = 2, .cell_m = T(1), .heights_m = four, .materials = std::vector<std::uint32_t>(2)}); },
                           "height_field.materials"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 2, .ny = 2, .cell_m = T(1), .heights_m = four, .regions = std::vector<std::uint32_t>(3)}); },
                           "height_field.regions"));

    std::vector<T> h(12, T(0));
    h[7] = std::numeric_limits<T>::quiet_NaN(); // vertex (ix 3, iy 1) of a 4 x 3 grid
    CHECK(throws_naming([&] { height_field<T>({.nx = 4, .ny = 3, .cell_m = T(1), .heights_m = h}); }, "heights_m[7]"));
    CHECK(throws_naming([&] { height_field<T>({.nx = 4, .ny = 3, .cell_m = T(1), .heights_m = h}); }, "(ix 3, iy 1)"));
    h[7] = -std::numeric_limits<T>::infinity();
    CHECK(throws_naming([&] { height_field<T>({.nx = 4, .ny = 3, .cell_m = T(1), .heights_m = h}); }, "heights_m[7]"));
}

TEST_CASE_TEMPLATE("Inside a cell the surface is the two triangles split by the south-west to north-east diagonal", T,
                   float, double) {
    // One cell with corners h00 = 0, h10 = 1, h01 = 2, h11 = 0.5, 2 m cells, origin (10, 20).
    const height_field<T> hf({.nx = 2, .ny = 2, .cell_m = T(2), .origin_m = vec2<T>{T(10), T(20)}, .heights_m = {T(0), T(1), T(2), T(0.5)}});
    const double tol = 4 * std::numeric_limits<T>::epsilon() * 4;
    // Corners.
    CHECK(hf.seabed_height_m(T(10), T(20)) == doctest::Approx(0.0).epsilon(tol));
    CHECK(hf.seabed_height_m(T(12), T(20)) == doctest::Approx(1.0).epsilon(tol));
    CHECK(hf.seabed_height_m(T(10), T(22)) == doctest::Approx(2.0).epsilon(tol));
    CHECK(hf.seabed_height_m(T(12), T(22)) == doctest::Approx(0.5).epsilon(tol));
    // Lower triangle (a >= b): h = h00 + a (h10 - h00) + b (h11 - h10); at a = 0.75, b = 0.25: 0.75 - 0.125.
    CHECK(double(hf.seabed_height_m(T(11.5), T(20.5))) == doctest::Approx(0.625).epsilon(tol));
    // Upper triangle (a < b): h = h00 + b (h01 - h00) + a (h11 - h01); at a = 0.25, b = 0.75: 1.5 - 0.375.
    CHECK(double(hf.seabed_height_m(T(10.5), T(21.5))) == doctest::Approx(1.125).epsilon(tol));
    // On the diagonal both give h00 + a (h11 - h00): 0.25 at a = b = 0.5. Bilinear would give 0.875.
    CHECK(double(hf.seabed_height_m(T(11), T(21))) == doctest::Approx(0.25).epsilon(tol));
}

TEST_CASE_TEMPLATE("Outside its footprint the surface continues at the height of the nearest boundary point", T, float,
                   double) {
    const auto h = sample<T>(5, 4, 0.5, {-1.0, 2.0}, [](double x, double y) { return 0.3 * x - 0.2 * y + 1.0; });
    const height_field<T> hf({.nx = 5, .ny = 4, .cell_m = T(0.5), .origin_m = vec2<T>{T(-1), T(2)}, .heights_m = h});
    // Footprint: x in [-1, 1], y in [2, 3.5].
    CHECK(double(hf.seabed_height_m(T(-5), T(3))) == doctest::Approx(0.3 * -1 - 0.2 * 3 + 1).epsilon(1e-5));
    CHECK(double(hf.seabed_height_m(T(7), T(-9))) == doctest::Approx(0.3 * 1 - 0.2 * 2 + 1).epsilon(1e-5));
    CHECK(double(hf.seabed_height_m(T(0.25), T(100))) == doctest::Approx(0.3 * 0.25 - 0.2 * 3.5 + 1).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("top_m and bottom_m are the highest and lowest vertices", T, float, double) {
    std::vector<T> h(30, T(0.5));
    h[17] = T(3.25);
    h[4] = T(-7.5);
    const height_field<T> hf({.nx = 6, .ny = 5, .cell_m = T(1), .heights_m = h});
    CHECK(hf.top_m() == T(3.25));
    CHECK(hf.bottom_m() == T(-7.5));
}

TEST_CASE_TEMPLATE("A hit carries the material and region of the cell it lands in", T, float, double) {
    // 3 x 2 cells, flat at z = 0; cell (ix, iy) gets material 10 + index and region 100 + index.
    std::vector<std::uint32_t> mat(6), reg(6);
    for (std::uint32_t c = 0; c < 6; ++c) {
        mat[c] = 10 + c;
        reg[c] = 100 + c;
    }
    const height_field<T> hf({.nx = 4, .ny = 3, .cell_m = T(1), .heights_m = std::vector<T>(12, T(0)), .materials = mat, .regions = reg});
    for (std::uint32_t iy = 0; iy < 2; ++iy)
        for (std::uint32_t ix = 0; ix < 3; ++ix) {
            const sss::ray<T> r{vec3<T>{T(ix) + T(0.3), T(iy) + T(0.6), T(5)}, vec3<T>{T(0), T(0), T(-1)}};
            const auto hit = hf.intersect(r, T(10));
            REQUIRE(hit);
            CHECK(hit->material == 10 + iy * 3 + ix);
            CHECK(hit->label == 100 + iy * 3 + ix);
            CHECK(hit->object == sss::no_object);
            CHECK(hf.material(ix, iy) == 10 + iy * 3 + ix);
            CHECK(hf.region(ix, iy) == 100 + iy * 3 + ix);
        }
    const height_field<T> plain({.nx = 4, .ny = 3, .cell_m = T(1), .heights_m = std::vector<T>(12, T(0))});
    const auto hit = plain.intersect(sss::ray<T>{vec3<T>{T(1.5), T(1.5), T(1)}, vec3<T>{T(0), T(0), T(-1)}}, T(10));
    REQUIRE(hit);
    CHECK(hit->material == 0);
    CHECK(hit->label == 0);
}

TEST_CASE_TEMPLATE("Geometric normals are per triangle; smooth normals are continuous across shared edges", T, float,
                   double) {
    // A paraboloid z = 0.05 (x^2 + 2 y^2) on 0.5 m cells.
    const double c = 0.5;
    const auto f = [](double x, double y) { return 0.05 * (x * x + 2 * y * y); };
    const auto h = sample<T>(21, 17, c, {-5.0, -4.0}, f);
    const height_field<T> hf({.nx = 21, .ny = 17, .cell_m = T(c), .origin_m = vec2<T>{T(-5), T(-4)}, .heights_m = h});
    const auto& g = hf.grid();
    const double tol = std::is_same_v<T, float> ? 2e-5 : 1e-12;
    for (std::int32_t iy = 0; iy + 1 < g.ny; ++iy)
        for (std::int32_t ix = 0; ix + 1 < g.nx; ++ix) {
            // The lower triangle's plane through its three vertices, by cross product in double.
            const auto vtx = [&](int dx, int dy) {
                return vec3<double>{-5.0 + (ix + dx) * c, -4.0 + (iy + dy) * c, double(g.at(ix + dx, iy + dy))};
            };
            const vec3<double> n = glm::normalize(glm::cross(vtx(1, 0) - vtx(0, 0), vtx(1, 1) - vtx(0, 0)));
            const vec3<T> got = sss::scene::triangle_normal(g, ix, iy, sss::scene::cell_triangle::lower);
            CHECK(glm::length(vec3<double>(got) - n) < tol);
            const vec3<double> nu = glm::normalize(glm::cross(vtx(1, 1) - vtx(0, 0), vtx(0, 1) - vtx(0, 0)));
            const vec3<T> gotu = sss::scene::triangle_normal(g, ix, iy, sss::scene::cell_triangle::upper);
            CHECK(glm::length(vec3<double>(gotu) - nu) < tol);
            // Continuity: across the diagonal, and across the east edge into the next cell.
            const T a = T(0.37);
            const auto lo = sss::scene::smooth_normal(g, ix, iy, sss::scene::cell_triangle::lower, a, a);
            const auto up = sss::scene::smooth_normal(g, ix, iy, sss::scene::cell_triangle::upper, a, a);
            CHECK(glm::length(vec3<double>(lo) - vec3<double>(up)) < tol);
            if (ix + 2 < g.nx) {
                const auto west = sss::scene::smooth_normal(g, ix, iy, sss::scene::cell_triangle::lower, T(1), a);
                const auto east = sss::scene::smooth_normal(g, ix + 1, iy, sss::scene::cell_triangle::upper, T(0), a);
                CHECK(glm::length(vec3<double>(west) - vec3<double>(east)) < tol);
            }
        }
    // At an interior vertex the smooth normal is the central-difference normal, here exact for the
    // paraboloid: gradient (0.1 x, 0.2 y) at (1, -1.5) = vertex (12, 5).
    const vec3<T> nv = sss::scene::smooth_normal(g, 12, 5, sss::scene::cell_triangle::lower, T(0), T(0));
    const vec3<double> expect = glm::normalize(vec3<double>{-0.1 * 1.0, -0.2 * -1.5, 1.0});
    CHECK(glm::length(vec3<double>(nv) - expect) < 10 * tol);
}

TEST_CASE_TEMPLATE("The maximum pyramid holds every block's highest vertex, its step bound is the largest neighbour "
                   "difference, and it costs at most a third of the heights plus edge blocks",
                   T, float, double) {
    // Partial blocks at the edges of every level; an odd and an even number of cell rows; single-cell strips.
    struct shape {
        std::size_t nx, ny;
        std::int32_t levels;
    };
    for (const shape sh : {shape{37, 23, 6}, shape{37, 24, 6}, shape{40, 2, 6}, shape{2, 9, 3}, shape{2, 2, 0}}) {
        CAPTURE(sh.nx);
        CAPTURE(sh.ny);
        const auto h = sample<T>(sh.nx, sh.ny, 1.0, {0.0, 0.0},
                                 [](double x, double y) { return std::sin(1.3 * x) * std::cos(0.7 * y) + 0.01 * x * y; });
        const height_field<T> hf({.nx = sh.nx, .ny = sh.ny, .cell_m = T(1), .heights_m = h});
        const auto& p = hf.pyramid();
        const auto& g = hf.grid();
        REQUIRE(p.levels() == sh.levels); // 36 cells -> 18, 9, 5, 3, 2, 1
        for (std::int32_t level = 1; level <= p.levels(); ++level)
            for (std::int32_t by = 0; by < p.height(level); ++by)
                for (std::int32_t bx = 0; bx < p.width(level); ++bx) {
                    T m = -std::numeric_limits<T>::infinity();
                    const std::int32_t x0 = bx << level, y0 = by << level;
                    for (std::int32_t y = y0; y <= std::min(y0 + (1 << level), g.ny - 1); ++y)
                        for (std::int32_t x = x0; x <= std::min(x0 + (1 << level), g.nx - 1); ++x)
                            m = std::max(m, g.at(x, y));
                    CHECK(p.max_m(level, bx, by) == m);
                }
        T step = T(0);
        for (std::int32_t y = 0; y < g.ny; ++y)
            for (std::int32_t x = 0; x < g.nx; ++x) {
                if (x + 1 < g.nx) step = std::max(step, std::abs(g.at(x + 1, y) - g.at(x, y)));
                if (y + 1 < g.ny) step = std::max(step, std::abs(g.at(x, y + 1) - g.at(x, y)));
            }
        CHECK(p.max_step_m() == step);
        if (p.levels() > 0) CHECK(p.max_m(p.levels(), 0, 0) == hf.top_m());
        if (sh.nx > 2 && sh.ny > 2) CHECK(hf.acceleration_bytes() < hf.height_bytes() / 2); // strips hold half
    }
}

TEST_CASE_TEMPLATE("Building a height field over external heights never reads again what it has said it is done "
                   "with, and says so for every row in bands",
                   T, float, double) {
    // 150 rows: two full bands of 64 and the rest. Whatever the field has said it is done with is overwritten with
    // a height far above the rest until its pass ends; a second reading would show in the bounds or the pyramid.
    const std::size_t nx = 33, ny = 150, n = nx * ny;
    const auto h = sample<T>(nx, ny, 0.5, {0.0, 0.0}, [](double x, double y) { return std::sin(x) * std::cos(0.3 * y); });
    const height_field<T> reference({.nx = nx, .ny = ny, .cell_m = T(0.5), .heights_m = h});
    std::vector<T> values = h;
    std::vector<std::pair<std::size_t, std::size_t>> bands;
    const height_field<T> hf({.nx = nx, .ny = ny, .cell_m = T(0.5)},
                             sss::scene::external_heights<T>{
                                 .data = values.data(),
                                 .read_done = [&](std::size_t first, std::size_t count) {
                                     bands.emplace_back(first, count);
                                     if (first + count == n)
                                         values = h; // the pass is over; the next one reads the heights afresh
                                     else
                                         std::fill_n(values.begin() + std::ptrdiff_t(first), count, T(1e6));
                                 }});
    CHECK(hf.top_m() == reference.top_m());
    CHECK(hf.bottom_m() == reference.bottom_m());
    CHECK(hf.pyramid().max_step_m() == reference.pyramid().max_step_m());
    for (std::int32_t level = 1; level <= reference.pyramid().levels(); ++level)
        for (std::int32_t by = 0; by < reference.pyramid().height(level); ++by)
            for (std::int32_t bx = 0; bx < reference.pyramid().width(level); ++bx)
                CHECK(hf.pyramid().max_m(level, bx, by) == reference.pyramid().max_m(level, bx, by));
    // Two passes (checks and bounds, then the pyramid), each told in order, whole rows, bands of >= 64 rows but the
    // last, ending at the last vertex.
    std::size_t passes = 0, next = 0;
    for (const auto& [first, count] : bands) {
        CHECK(first == next);
        CHECK(first % nx == 0);
        CHECK(count % nx == 0);
        next = first + count;
        if (next == n) {
            ++passes;
            next = 0;
        } else {
            CHECK(count >= 64 * nx);
        }
    }
    CHECK(passes == 2);
    CHECK(next == 0);
}

TEST_CASE_TEMPLATE("A copied or moved height field traces its own heights", T, float, double) {
    height_field<T> a({.nx = 3, .ny = 3, .cell_m = T(1), .heights_m = std::vector<T>(9, T(2))});
    const height_field<T> b = a;
    height_field<T> c(std::move(a));
    a = height_field<T>({.nx = 2, .ny = 2, .cell_m = T(1), .heights_m = std::vector<T>(4, T(-1))});
    const sss::ray<T> down{vec3<T>{T(0.5), T(0.5), T(10)}, vec3<T>{T(0), T(0), T(-1)}};
    REQUIRE(b.intersect(down, T(100)));
    REQUIRE(c.intersect(down, T(100)));
    REQUIRE(a.intersect(down, T(100)));
    CHECK(b.intersect(down, T(100))->distance_m == doctest::Approx(8));
    CHECK(c.intersect(down, T(100))->distance_m == doctest::Approx(8));
    CHECK(a.intersect(down, T(100))->distance_m == doctest::Approx(11));
}

TEST_CASE_TEMPLATE("Over a height field's clear length the surface lies more than the band below the segment, and the "
                   "length ends where the lowered segment meets it",
                   T, float, double) {
    // 60 m x 60 m of bumps at 0.5 m.
    const std::size_t n = 121;
    std::vector<T> h(n * n);
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i)
            h[j * n + i] = T(0.8 * std::sin(0.9 * double(i) * 0.5) * std::cos(0.4 * double(j) * 0.5) +
                             0.3 * std::sin(2.3 * double(i + 2 * j) * 0.5));
    const height_field<T> hf({.nx = n, .ny = n, .cell_m = T(0.5), .origin_m = {T(-30), T(-30)}, .heights_m = h});
    static_assert(sss::ClearanceScene<height_field<T>>);
    std::size_t partly = 0, whole = 0, none = 0;
    for (int k = 0; k < 400; ++k) {
        const double az = 0.0157 * k, graze = (1 + 0.2 * (k % 50)) * 3.14159265358979 / 180, band = 0.05 * (k % 7);
        const sss::ray<T> r{vec3<T>{T(-25 + 0.1 * (k % 13)), T(-20 + 0.2 * (k % 11)), T(3.5)},
                            vec3<T>{T(std::cos(graze) * std::cos(az)), T(std::cos(graze) * std::sin(az)), T(-std::sin(graze))}};
        const T t_max = T(80);
        const T d = hf.clear_length_m(r, t_max, T(band));
        REQUIRE(d >= T(0));
        REQUIRE(d <= t_max);
        // Sampled every 2 cm: the lowered segment is on or above the surface (rounding aside) up to d.
        const int steps = int(double(d) / 0.02);
        for (int s = 0; s <= steps; ++s) {
            const sss::vec3<T> q = r.at(T(0.02 * s));
            if (std::abs(q.x) > T(30) || std::abs(q.y) > T(30)) break; // off the footprint: no surface
            if (!(q.z - T(band) >= hf.seabed_height_m(q.x, q.y) - T(1e-4))) {
                FAIL_CHECK("ray " << k << ": surface within the band at " << 0.02 * s << " m of a clear length " << d);
                break;
            }
        }
        // And it is no shorter than needed: where the lowered segment meets the surface, or the whole length.
        const auto lowered = hf.intersect(sss::ray<T>{r.origin - vec3<T>{T(0), T(0), T(band)}, r.direction}, t_max);
        if (lowered) {
            CHECK(d == lowered->distance_m);
            ++partly;
        } else {
            CHECK(d == t_max);
            ++whole;
        }
        none += d == T(0);
    }
    MESSAGE(partly << " segments cleared in part, " << whole << " whole, " << none << " not at all");
    CHECK(partly > 100);
    CHECK(whole > 10);
    // A segment starting within the band of the surface, or off the footprint, clears nothing.
    const T h0 = hf.seabed_height_m(T(0), T(0));
    CHECK(hf.clear_length_m(sss::ray<T>{vec3<T>{T(0), T(0), h0 + T(0.1)}, vec3<T>{T(1), T(0), T(0)}}, T(10), T(0.2)) == T(0));
    CHECK(hf.clear_length_m(sss::ray<T>{vec3<T>{T(40), T(0), T(5)}, vec3<T>{T(-1), T(0), T(0)}}, T(10), T(0.2)) == T(0));
    CHECK(hf.clear_length_m(sss::ray<T>{vec3<T>{T(0), T(0), T(5)}, vec3<T>{T(1), T(0), T(0)}}, T(10), T(-0.2)) == T(0));
}
