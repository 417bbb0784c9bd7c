#pragma once
// Seeded random numbers, rays and rough height fields for the grid-tracing tests: surfaces built to catch a
// height-field traversal out (exact ties, steep walls, noise), and random rays to throw at them.
// Independent of the library's own random numbers, so a change there cannot move these surfaces.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sss/scene/height_field.hpp"

namespace sss_test {

/// splitmix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators", OOPSLA; Vigna's
/// splitmix64.c): a 64-bit state advanced by the golden-ratio increment and mixed. Fully determined by the
/// seed `s`, so a test draws the same rays and heights on every platform and compiler. Every function
/// below states how many draws it takes, since the order of draws is part of what a test's inputs are.
struct rng {
    std::uint64_t s;

    /// One draw: the next 64-bit output.
    std::uint64_t next() noexcept {
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform on [0, 1) on a grid of 2^-53 (the top 53 bits of one draw).
    double uniform() noexcept { return double(next() >> 11) * 0x1.0p-53; }
    /// Uniform on [a, b): one draw.
    double uniform(double a, double b) noexcept { return a + (b - a) * uniform(); }
    /// A unit vector uniform on the sphere (Archimedes: z uniform on [-1, 1], azimuth uniform on
    /// [0, 2 pi)): two draws, z first.
    sss::vec3<double> direction() noexcept {
        const double z = uniform(-1, 1), phi = uniform(0, 6.283185307179586), r = std::sqrt(1 - z * z);
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
};

/// A ray in precision T from an origin and a direction of any length given in double: the direction is
/// normalised in double, then both are rounded to T.
template <class T> sss::ray<T> make_ray(sss::vec3<double> origin, sss::vec3<double> direction) {
    return sss::ray<T>{sss::vec3<T>(origin), sss::vec3<T>(glm::normalize(direction))};
}

/// Heights of an nx x ny vertex grid of spacing `cell_m` (m): vertex (ix, iy) gets T(z(x, y)) with x = ix cell_m
/// and y = iy cell_m (m, from the grid's corner), row by row (iy outer, ix inner), so a `z` that draws random
/// numbers draws them in that order. Stored row-major, as height_field takes them.
template <class T, class Height>
std::vector<T> sample_heights(std::size_t nx, std::size_t ny, double cell_m, Height&& z) {
    std::vector<T> h(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double x = double(ix) * cell_m, y = double(iy) * cell_m;
            h[iy * nx + ix] = T(z(x, y));
        }
    return h;
}

/// Ids 0, 1, 2, ... for the (nx - 1) x (ny - 1) cells of an nx x ny vertex grid, in height_field's cell
/// order: used as region ids, a hit's label names the cell it landed in, so two traversals can be checked
/// to agree on the cell and not only on the distance.
inline std::vector<std::uint32_t> cell_ids(std::size_t nx, std::size_t ny) {
    std::vector<std::uint32_t> ids((nx - 1) * (ny - 1));
    for (std::size_t c = 0; c < ids.size(); ++c) ids[c] = std::uint32_t(c);
    return ids;
}

/// Rough relief with a plateau, a trench and white noise, over an nx x ny grid of spacing `cell_m` (m)
/// whose corner is at `origin` (m). With x, y (m) from the corner and u uniform on [0, 1) from rng{seed}
/// (one draw per vertex, row by row):
///   z = 1.2 sin(0.11 x + 0.05 y) + 0.35 sin(0.9 x - 0.6 y + 1) + 0.12 sin(2.1 y + 0.4 x) + 0.1 (u - 0.5),
/// then clipped at 1.1 m and lowered by 1.5 m where 60 < x + y/2 < 75 (m).
/// - The plateau at 1.1 m puts many vertices at exactly the same height: exact ties between neighbouring
///   cells and between a coarse level's bound and the fine heights under it.
/// - The trench's walls drop 1.5 m within one cell: steep faces a traversal must not step over, and rays
///   that enter and leave it within a cell or two.
/// - The noise (0.1 m) makes every cell's triangles different, so a hit in the wrong cell shows.
/// Every cell's region id is its index (cell_ids), so a hit's label names its cell.
template <class T>
sss::scene::height_field<T> rough_field(std::size_t nx, std::size_t ny, double cell_m, sss::vec2<double> origin, std::uint64_t seed) {
    rng noise{seed};
    auto h = sample_heights<T>(nx, ny, cell_m, [&noise](double x, double y) {
        double z = 1.2 * std::sin(0.11 * x + 0.05 * y) + 0.35 * std::sin(0.9 * x - 0.6 * y + 1) +
                   0.12 * std::sin(2.1 * y + 0.4 * x) + 0.1 * (noise.uniform() - 0.5);
        z = std::min(z, 1.1);                               // plateau: many vertices at exactly 1.1
        if (x + 0.5 * y > 60 && x + 0.5 * y < 75) z -= 1.5; // a trench with near-vertical walls
        return z;
    });
    return sss::scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = T(cell_m), .origin_m = sss::vec2<T>(origin), .heights_m = std::move(h), .regions = cell_ids(nx, ny)});
}

/// Rolling relief with white noise and a material per cell, over an nx x ny grid of spacing `cell_m` (m)
/// whose corner is at `origin` (m). With x, y (m) from the corner and u uniform on [0, 1) from rng{seed}
/// (one draw per vertex, row by row):
///   z = 1.1 sin(0.13 x + 0.04 y) + 0.3 sin(0.8 x - 0.7 y + 1) + 0.1 (u - 0.5).
/// No plateau or trench: smooth hills (wavelengths of about 6 to 50 m, slopes below 0.5) under noise (0.1 m)
/// that makes every cell's triangles and normals different. Cell c has region c and material c % 5, so a
/// hit's label names its cell and its material can be checked against that label.
template <class T>
sss::scene::height_field<T> rolling_field(std::size_t nx, std::size_t ny, double cell_m, sss::vec2<double> origin, std::uint64_t seed) {
    rng noise{seed};
    auto h = sample_heights<T>(nx, ny, cell_m, [&noise](double x, double y) {
        return 1.1 * std::sin(0.13 * x + 0.04 * y) + 0.3 * std::sin(0.8 * x - 0.7 * y + 1) +
               0.1 * (noise.uniform() - 0.5);
    });
    std::vector<std::uint32_t> regions = cell_ids(nx, ny), materials(regions.size());
    for (std::size_t c = 0; c < materials.size(); ++c) materials[c] = std::uint32_t(c % 5);
    return sss::scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = T(cell_m), .origin_m = sss::vec2<T>(origin), .heights_m = std::move(h), .materials = std::move(materials), .regions = std::move(regions)});
}

} // namespace sss_test
