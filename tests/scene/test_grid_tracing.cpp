// Ray tracing of height fields: exact distances and normals on planes, and the hard cases (rays from
// outside the footprint, from below the surface, vertical, along grid lines and diagonals, grazing at
// 0.01 deg, grids of one and two cells) with brute force over all triangles on small grids.
// (Agreement of the traversals: test_grid_tracing_agreement.cpp; no leaks: test_grid_tracing_leaks.cpp.)
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "sss/scene/height_field.hpp"
#include "support/grid_relief.hpp"

using sss::ray;
using sss::vec2;
using sss::vec3;
using lvec3 = glm::vec<3, long double>;
using sss::scene::height_field;
using sss_test::make_ray;
using sss_test::rng;
using sss_test::rough_field;

namespace {

constexpr double deg = 3.141592653589793 / 180;

// A plane z = a + bx x + by y sampled on a grid.
struct plane {
    double a, bx, by;
    double at(double x, double y) const { return a + bx * x + by * y; }
    vec3<double> normal() const { return glm::normalize(vec3<double>{-bx, -by, 1}); }
};

template <class T> height_field<T> plane_field(std::size_t nx, std::size_t ny, double cell, vec2<double> o, plane p) {
    std::vector<T> h(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            h[iy * nx + ix] = T(p.at(o.x + double(ix) * cell, o.y + double(iy) * cell));
    return height_field<T>({.nx = nx, .ny = ny, .cell_m = T(cell), .origin_m = vec2<T>(o), .heights_m = std::move(h)});
}

template <class T> double eps() { return double(std::numeric_limits<T>::epsilon()); }

} // namespace

TEST_CASE_TEMPLATE("A tilted plane is hit at the exact distance with the plane's normal", T, float, double) {
    const plane p{1.5, 0.3, -0.2};
    const vec2<double> o{-7, 3};
    const auto hf = plane_field<T>(41, 23, 0.5, o, p); // footprint x in [-7, 13], y in [3, 14]
    rng g{7};
    int hits = 0, misses = 0;
    double worst = 0;
    for (int k = 0; k < 20000; ++k) {
        const vec3<double> org{g.uniform(-10, 16), g.uniform(0, 17), 0};
        const vec3<double> origin{org.x, org.y, p.at(org.x, org.y) + g.uniform(0.05, 20)};
        vec3<double> d = g.direction();
        if (g.uniform() < 0.7) d.z = -std::abs(d.z); // mostly downwards
        const ray<T> r = make_ray<T>(origin, d);
        const vec3<double> dd(r.direction), oo(r.origin);
        // f(s) = z0 + dz s - plane(x0 + dx s, y0 + dy s) = f0 - rate s.
        const double f0 = oo.z - p.at(oo.x, oo.y), rate = p.bx * dd.x + p.by * dd.y - dd.z;
        const double s = f0 / rate;
        const vec3<double> at = oo + dd * s;
        const bool inside = at.x > -7 && at.x < 13 && at.y > 3 && at.y < 14;
        const bool near_edge = std::abs(at.x + 7) < 1e-3 || std::abs(at.x - 13) < 1e-3 || std::abs(at.y - 3) < 1e-3 ||
                               std::abs(at.y - 14) < 1e-3;
        if (near_edge) continue;
        const bool expect = rate > 0 && inside && s <= 100;
        for (const auto& got : {hf.intersect(r, T(100)), hf.intersect_reference(r, T(100))}) {
            REQUIRE(bool(got) == expect);
            if (!got) continue;
            // f is known to a few ulps of the magnitudes involved; the distance to that over the rate.
            const double tol = 64 * eps<T>() *
                               (1 + std::abs(oo.z) + std::abs(p.a) + 0.3 * std::abs(oo.x) + 0.2 * std::abs(oo.y) + s) /
                               rate;
            CHECK(std::abs(double(got->distance_m) - s) <= tol);
            worst = std::max(worst, std::abs(double(got->distance_m) - s) / tol);
            CHECK(glm::length(vec3<double>(got->normal) - p.normal()) < 64 * eps<T>() * 10);
            CHECK(glm::length(vec3<double>(got->shading_normal) - p.normal()) < 64 * eps<T>() * 10);
        }
        (expect ? hits : misses)++;
    }
    CHECK(hits > 2500);
    CHECK(misses > 2500);
    MESSAGE("worst distance error / tolerance: " << worst);
}

TEST_CASE_TEMPLATE("Grazing rays at 0.01 degrees hit a tilted plane and a flat bottom at the exact distance", T, float,
                   double) {
    const double graze = 0.01 * deg;
    {
        // Flat bottom at z = 0, rays from 0.01 m up at 0.01 deg below horizontal: s = 0.01 / sin(0.01 deg) = 57.3 m.
        const auto hf = plane_field<T>(321, 321, 0.25, {0, 0}, plane{0, 0, 0}); // 80 m x 80 m
        for (double azimuth : {0.0, 0.3, -0.2, 0.05, 0.785}) {
            const vec3<double> d{std::cos(graze) * std::cos(azimuth), std::cos(graze) * std::sin(azimuth),
                                 -std::sin(graze)};
            const ray<T> r = make_ray<T>({0.5, 30.0, 0.01}, d);
            const double s = 0.01 / -double(r.direction.z);
            for (const auto& got : {hf.intersect(r, T(200)), hf.intersect_reference(r, T(200))}) {
                REQUIRE(got);
                CHECK(std::abs(double(got->distance_m) - s) <= 16 * eps<T>() * s);
            }
        }
    }
    {
        // Tilted plane; rays meeting it at 0.01 deg, aimed at random points of the plane from 30 m away.
        const plane p{-2.0, 0.15, 0.25};
        const auto hf = plane_field<T>(161, 161, 0.25, {0, 0}, p);
        rng g{11};
        const vec3<double> n = p.normal();
        for (int k = 0; k < 2000; ++k) {
            const double x = g.uniform(5, 35), y = g.uniform(5, 35);
            const vec3<double> target{x, y, p.at(x, y)};
            const double phi = g.uniform(0, 6.283185307179586);
            vec3<double> t = glm::cross(n, vec3<double>{std::cos(phi), std::sin(phi), 0}); // in the plane
            t = glm::normalize(t);
            const vec3<double> d = t * std::cos(graze) - n * std::sin(graze);
            const ray<T> r = make_ray<T>(target - d * 30.0, d);
            const vec3<double> dd(r.direction), oo(r.origin);
            const double rate = -glm::dot(dd, n) * glm::length(vec3<double>{-p.bx, -p.by, 1});
            const double s = (oo.z - p.at(oo.x, oo.y)) / rate;
            for (const auto& got : {hf.intersect(r, T(100)), hf.intersect_reference(r, T(100))}) {
                REQUIRE(got); // never slips under at 0.01 deg, in float too
                const double tol = 64 * eps<T>() * (1 + std::abs(oo.z) + 0.15 * oo.x + 0.25 * oo.y + s) / rate;
                CHECK(std::abs(double(got->distance_m) - s) <= tol);
            }
        }
    }
}

TEST_CASE_TEMPLATE("Rays from outside the footprint enter it and hit; rays passing beside it miss", T, float, double) {
    const plane p{0.5, 0.1, 0.05};
    const auto hf = plane_field<T>(17, 9, 1.0, {0, 0}, p); // x in [0, 16], y in [0, 8]
    rng g{3};
    for (int k = 0; k < 1000; ++k) {
        const vec3<double> target{g.uniform(0.5, 15.5), g.uniform(0.5, 7.5), 0};
        const vec3<double> tp{target.x, target.y, p.at(target.x, target.y)};
        const double phi = g.uniform(0, 6.283185307179586), dep = g.uniform(10, 80) * deg;
        const vec3<double> d{std::cos(dep) * std::cos(phi), std::cos(dep) * std::sin(phi), -std::sin(dep)};
        // Back off until the origin is outside the footprint.
        double back = 1;
        while (true) {
            const vec3<double> q = tp - d * back;
            if (q.x < 0 || q.x > 16 || q.y < 0 || q.y > 8) break;
            back += 1;
        }
        const ray<T> r = make_ray<T>(tp - d * back, d);
        for (const auto& got : {hf.intersect(r, T(1000)), hf.intersect_reference(r, T(1000))}) {
            REQUIRE(got);
            CHECK(double(got->distance_m) == doctest::Approx(back).epsilon(1e-4));
        }
        // The same ray shifted 20 m sideways passes beside the grid.
        const vec3<double> side = glm::normalize(vec3<double>{-d.y, d.x, 0}) * 20.0;
        const ray<T> beside = make_ray<T>(tp - d * back + side, d);
        CHECK_FALSE(hf.intersect(beside, T(1000)));
        CHECK_FALSE(hf.intersect_reference(beside, T(1000)));
    }
}

TEST_CASE_TEMPLATE("A ray from below the surface is not stopped on its way out, and hits where it comes down again", T,
                   float, double) {
    // V-shaped valley h = |x - 5| on 0.5 m cells, x in [0, 10], y in [0, 2].
    std::vector<T> h(21 * 5);
    for (std::size_t iy = 0; iy < 5; ++iy)
        for (std::size_t ix = 0; ix < 21; ++ix) h[iy * 21 + ix] = T(std::abs(double(ix) * 0.5 - 5));
    const height_field<T> hf({.nx = 21, .ny = 5, .cell_m = T(0.5), .heights_m = h});
    // From (1, 1, 3.5), 0.5 m under the west slope, along (1, 0, 0.1): it leaves the west slope at
    // x = 16/11 and meets the east slope h = x - 5 where 3.4 + 0.1 x = x - 5: x = 28/3.
    const vec3<double> d = glm::normalize(vec3<double>{1, 0, 0.1});
    const ray<T> r = make_ray<T>({1, 1, 3.5}, d);
    const double s = (28.0 / 3.0 - 1) * std::sqrt(1.01);
    for (const auto& got : {hf.intersect(r, T(100)), hf.intersect_reference(r, T(100))}) {
        REQUIRE(got);
        CHECK(double(got->distance_m) == doctest::Approx(s).epsilon(1e-5));
        CHECK(double(got->normal.x) ==
              doctest::Approx(-std::sqrt(0.5)).epsilon(1e-5)); // east slope, facing west and up
    }
    // Straight up from under the surface: nothing.
    const ray<T> up = make_ray<T>({3, 1, 1}, {0.1, 0.05, 1});
    CHECK_FALSE(hf.intersect(up, T(100)));
    CHECK_FALSE(hf.intersect_reference(up, T(100)));
    // A ray starting exactly on the surface does not hit its own starting point.
    const ray<T> on = make_ray<T>({7, 1, 2}, {0, 0.3, -1});
    CHECK_FALSE(hf.intersect(on, T(100)));
}

TEST_CASE_TEMPLATE("A vertical ray hits at the surface's height, on vertices, edges and inside triangles", T, float,
                   double) {
    const auto hf = rough_field<T>(130, 97, 0.25, {-3, 4}, 42);
    const auto& g = hf.grid();
    rng gen{5};
    for (int k = 0; k < 20000; ++k) {
        // Grid coordinates: a vertex, a point on an edge or a diagonal, or anywhere.
        const double i = double(gen.next() % 129), j = double(gen.next() % 96), t = gen.uniform();
        const int kind = int(gen.next() % 5);
        const double u = kind == 0 ? i : kind == 1 ? i + t : kind == 2 ? i : kind == 3 ? i + t : i + gen.uniform();
        const double v = kind == 0 ? j : kind == 1 ? j : kind == 2 ? j + t : kind == 3 ? j + t : j + gen.uniform();
        if (u > 129 || v > 96) continue;
        // The height by the triangle rule, in long double, from the vertex heights.
        const int ix = std::min(int(u), 128), iy = std::min(int(v), 95);
        const long double a = u - ix, b = v - iy;
        const long double h00 = g.at(ix, iy), h10 = g.at(ix + 1, iy), h01 = g.at(ix, iy + 1),
                          h11 = g.at(ix + 1, iy + 1);
        const long double hz =
            a >= b ? h00 + a * (h10 - h00) + b * (h11 - h10) : h00 + b * (h01 - h00) + a * (h11 - h01);
        const double x = -3 + u * 0.25, y = 4 + v * 0.25;
        const ray<T> down{vec3<T>{T(x), T(y), T(10)}, vec3<T>{T(0), T(0), T(-1)}};
        for (const auto& got : {hf.intersect(down, T(100)), hf.intersect_reference(down, T(100))}) {
            REQUIRE(got);
            CHECK(std::abs(double(got->distance_m) - double(10 - hz)) <= 64 * eps<T>() * 12);
            CHECK(got->normal.z > T(0));
        }
        const ray<T> up{vec3<T>{T(x), T(y), T(-10)}, vec3<T>{T(0), T(0), T(1)}};
        CHECK_FALSE(hf.intersect(up, T(100)));
        CHECK_FALSE(hf.intersect_reference(up, T(100)));
    }
    // Vertical rays beside the footprint miss.
    CHECK_FALSE(hf.intersect(ray<T>{vec3<T>{T(-3.01), T(5), T(10)}, vec3<T>{T(0), T(0), T(-1)}}, T(100)));
    CHECK_FALSE(hf.intersect(ray<T>{vec3<T>{T(0), T(3.99), T(10)}, vec3<T>{T(0), T(0), T(-1)}}, T(100)));
}

TEST_CASE_TEMPLATE("Rays along grid lines and diagonals find the first crossing of the edge profile under them", T,
                   float, double) {
    // Along a grid line or a diagonal the surface is linear between consecutive vertices; the expected
    // hit comes from walking those vertices in long double.
    const auto hf = rough_field<T>(161, 121, 0.25, {0, 0}, 42);
    const auto& g = hf.grid();
    rng gen{9};
    int checked = 0;
    for (int k = 0; k < 6000; ++k) {
        const int kind = int(gen.next() % 3); // 0: along x (v = j), 1: along y (u = i), 2: along the diagonal
        const int sgn = gen.next() % 2 ? 1 : -1;
        const int i0 = 20 + int(gen.next() % 120), j0 = 20 + int(gen.next() % 80);
        const int du = kind == 1 ? 0 : sgn, dv = kind == 0 ? 0 : sgn;
        const double dep = gen.uniform(1, 89) * deg;
        const double h_len = std::cos(dep) / std::sqrt(double(du * du + dv * dv)); // horizontal speed per axis step
        const vec3<T> d{T(du * h_len), T(dv * h_len), T(-std::sin(dep))};
        const double z0 = double(hf.top_m()) + gen.uniform(0.01, 3);
        const ray<T> r{vec3<T>{T(i0 * 0.25), T(j0 * 0.25), T(z0)}, d};
        // Expected: in steps of one vertex along the line, f = z_ray - h is linear between vertices.
        const long double step_s = 0.25L / (long double)(du != 0 ? std::abs(double(d.x)) : std::abs(double(d.y)));
        std::optional<long double> expect;
        long double f_prev = (long double)r.origin.z - g.at(i0, j0);
        for (int m = 1;; ++m) {
            const int iu = i0 + m * du, jv = j0 + m * dv;
            if (iu < 0 || jv < 0 || iu >= g.nx || jv >= g.ny) break;
            const long double s = m * step_s;
            const long double f = (long double)r.origin.z + (long double)r.direction.z * s - g.at(iu, jv);
            if (f_prev > 0 && f <= 0) {
                expect = (m - 1) * step_s + step_s * f_prev / (f_prev - f);
                break;
            }
            f_prev = f;
        }
        for (const auto& got : {hf.intersect(r, T(1000)), hf.intersect_reference(r, T(1000))}) {
            REQUIRE(bool(got) == bool(expect));
            if (got)
                CHECK(std::abs(double(got->distance_m - T(0)) - double(*expect)) <=
                      1e3 * eps<T>() * (1 + double(*expect)));
        }
        checked += expect ? 1 : 0;
    }
    CHECK(checked > 3000);
}

TEST_CASE_TEMPLATE("On grids of 1 x 1, 2 x 2 and 5 x 3 cells the tracer agrees with brute force over all triangles", T,
                   float, double) {
    rng gen{13};
    for (const auto& dims : {std::pair<std::size_t, std::size_t>{2, 2}, {3, 3}, {6, 4}}) {
        const std::size_t nx = dims.first, ny = dims.second;
        std::vector<T> h(nx * ny);
        for (auto& v : h) v = T(gen.uniform(-1, 1));
        const double cell = 0.7;
        const height_field<T> hf({.nx = nx, .ny = ny, .cell_m = T(cell), .origin_m = vec2<T>{T(1), T(-2)}, .heights_m = h});
        // All triangles in world coordinates.
        std::vector<std::array<lvec3, 3>> tris;
        auto V = [&](std::size_t ix, std::size_t iy) {
            return lvec3{1 + (long double)ix * (long double)T(cell), -2 + (long double)iy * (long double)T(cell),
                         (long double)h[iy * nx + ix]};
        };
        for (std::size_t iy = 0; iy + 1 < ny; ++iy)
            for (std::size_t ix = 0; ix + 1 < nx; ++ix) {
                tris.push_back({V(ix, iy), V(ix + 1, iy), V(ix + 1, iy + 1)});
                tris.push_back({V(ix, iy), V(ix + 1, iy + 1), V(ix, iy + 1)});
            }
        int compared = 0;
        for (int k = 0; k < 20000; ++k) {
            const vec3<double> o{gen.uniform(-1, 6), gen.uniform(-4, 3), gen.uniform(-1.5, 4)};
            const ray<T> r = make_ray<T>(o, gen.direction());
            // Moller-Trumbore on every triangle, culling triangles seen from below; long double.
            const lvec3 ro(r.origin), rd(r.direction);
            std::optional<long double> best;
            long double best_cos = 1;
            bool ambiguous = false;
            for (const auto& t : tris) {
                const lvec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
                const lvec3 n = glm::cross(e1, e2); // upward (counter-clockwise from above)
                if (glm::dot(n, rd) >= 0) continue;
                const lvec3 pv = glm::cross(rd, e2);
                const long double det = glm::dot(e1, pv), inv = 1 / det;
                const lvec3 tv = ro - t[0];
                const long double bu = glm::dot(tv, pv) * inv;
                const lvec3 qv = glm::cross(tv, e1);
                const long double bv = glm::dot(rd, qv) * inv;
                const long double s = glm::dot(e2, qv) * inv;
                const long double margin = 1e-4L;
                if (bu < -margin || bv < -margin || bu + bv > 1 + margin || s <= 0 || s > 50) continue;
                const bool inside = bu > margin && bv > margin && bu + bv < 1 - margin;
                if (!best || s < *best) {
                    best = s;
                    best_cos = -glm::dot(n, rd) / glm::length(n);
                    ambiguous = !inside;
                } else if (!inside && std::abs(s - *best) < 1e-3L) {
                    ambiguous = true;
                }
            }
            // Does the ray start below the surface? Then brute force culling and the tracer's rule differ
            // only in rays that cross a triangle from below first: both leave those out, so no special case.
            if (ambiguous || (best && best_cos < 1e-3L)) continue;
            ++compared;
            for (const auto& got : {hf.intersect(r, T(50)), hf.intersect_reference(r, T(50))}) {
                REQUIRE(bool(got) == bool(best));
                if (got)
                    CHECK(std::abs(double(got->distance_m) - double(*best)) <= 64 * eps<T>() * 20 / double(best_cos));
            }
        }
        CHECK(compared > 15000);
    }
}
