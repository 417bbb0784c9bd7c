#pragma once
/// \file
/// Composite seabeds: the plane partitioned into regions with fractal boundaries, each region with its
/// own texture (fractal roughness, ripples, mean height) and its own id in a region raster.
///
/// Two partitions, both giving a raster of texture indices:
/// - `level_partition`: thresholds of a low-pass fractal field F (power law of exponent
///   `boundary_gamma` with outer scale `patch_scale_m`, see fractal.hpp). Texture k takes the samples whose
///   F lies between the quantiles of the cumulative fractions, so it covers its requested fraction of the
///   area exactly (to one sample). The boundaries are level sets of a fractional Brownian surface of
///   Hurst exponent H = boundary_gamma/2 - 1, whose fractal dimension is 2 - H below the patch scale
///   (Mandelbrot, 1982, The Fractal Geometry of Nature, ch. 28): 1.25 for the default gamma = 3.5.
///   Textures are ordered by level: texture k borders only k - 1 and k + 1.
/// - `voronoi_partition`: each sample goes to the nearest site after displacing the sample by a 2D
///   fractal field d(x) (each component of RMS `warp_m`, exponent `warp_gamma`, outer scale
///   `warp_scale_m`): region(x) = site nearest to x + d(x). Straight Voronoi edges become fractal
///   curves, each displaced by the component of d normal to it (RMS warp_m while warp_m is well below
///   warp_scale_m; larger warps fold the map and the boundaries move less than warp_m, with islands).
///   Any adjacency; several sites may share a texture.
/// The fractal fields are periodic over the raster (fractal.hpp), so the partitions tile.
///
/// `compose` fills each region from its texture: height = mean_height_m + fractal roughness + ripple
/// sets, each texture drawn over the whole raster from its own seed stream, then selected by region.
/// With blend_m > 0 the textures are mixed across boundaries with weights equal to the region indicators
/// smoothed by a Gaussian of standard deviation blend_m (edges clamped), so heights change smoothly over
/// a band of a few blend_m; the region raster stays sharp.

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/seabed/detail/gaussian_smoothing.hpp"
#include "sss/seabed/detail/unit_fractal.hpp"
#include "sss/seabed/fractal.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"
#include "sss/seabed/ripples.hpp"

namespace sss::seabed {

/// What fills one region.
template <Real T> struct region_texture {
    std::uint32_t id = 0;                    ///< written to the region raster (material / ground-truth label)
    T mean_height_m = T(0);                  ///< mean height of the region (m)
    fractal_params<T> roughness{};           ///< fractal roughness; spectrum.w2_si = 0 for none
    std::vector<ripple_params<T>> ripples{}; ///< ripple sets added on top (none by default)
};

/// Partition by thresholds of a low-pass fractal field (see the file comment).
template <Real T> struct level_partition {
    std::vector<T> fractions;  ///< relative area of each texture (> 0; normalised by their sum)
    T patch_scale_m = T(10);   ///< outer scale of the partition field: typical patch size (m), > 0
    T boundary_gamma = T(3.5); ///< spectral exponent of the partition field, in (2, 4)
};

/// A Voronoi site: a point (m, raster-local) and the texture its region takes.
template <Real T> struct voronoi_site {
    T x_m = T(0), y_m = T(0);
    std::size_t texture = 0;
};

/// Partition into warped Voronoi cells (see the file comment).
template <Real T> struct voronoi_partition {
    std::vector<voronoi_site<T>> sites; ///< at least one
    T warp_m = T(0);                    ///< RMS of each component of the boundary displacement (m), >= 0
    T warp_scale_m = T(10);             ///< outer scale of the displacement field (m), > 0
    T warp_gamma = T(3.5);              ///< spectral exponent of the displacement field, in (2, 4)
};

/// A composite seabed: heights and the id of the region each sample belongs to.
template <Real T> struct composite_seabed {
    raster<T> height;         ///< heights (m)
    region_raster<T> regions; ///< region_texture::id of each sample
};

/// Texture indices (0 .. fractions.size() - 1) of an nx x ny raster partitioned by levels.
template <Real T> [[nodiscard]] region_raster<T> partition(std::size_t nx, std::size_t ny, T cell_m,
                                                           const level_partition<T>& p, std::uint64_t seed) {
    require_grid(nx, ny, cell_m, "partition");
    sss::require(!p.fractions.empty(), "partition.fractions", "needs at least one texture");
    double total = 0.0;
    for (std::size_t k = 0; k < p.fractions.size(); ++k) {
        sss::require_positive(p.fractions[k], "partition.fractions[" + std::to_string(k) + "]");
        total += static_cast<double>(p.fractions[k]);
    }
    sss::require_positive(p.patch_scale_m, "partition.patch_scale_m");
    sss::require_finite(p.boundary_gamma, "partition.boundary_gamma");
    sss::require(p.boundary_gamma > T(2) && p.boundary_gamma < T(4), "partition.boundary_gamma",
                    "must lie in (2, 4)");

    const raster<double> f = detail::unit_fractal_field(nx, ny, cell_m, p.boundary_gamma, p.patch_scale_m, seed);
    std::vector<double> sorted = f.values;
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> thresholds; // upper level of textures 0 .. K-2
    double cumulative = 0.0;
    for (std::size_t k = 0; k + 1 < p.fractions.size(); ++k) {
        cumulative += static_cast<double>(p.fractions[k]) / total;
        const auto idx = std::min(
            sorted.size() - 1, static_cast<std::size_t>(std::llround(cumulative * static_cast<double>(sorted.size()))));
        thresholds.push_back(sorted[idx]);
    }
    region_raster<T> out{nx, ny, cell_m, std::vector<std::uint32_t>(nx * ny)};
    for (std::size_t i = 0; i < f.values.size(); ++i) {
        const auto k = static_cast<std::size_t>(std::upper_bound(thresholds.begin(), thresholds.end(), f.values[i]) -
                                                thresholds.begin());
        // upper_bound puts values equal to a threshold above it: the threshold sample opens texture k + 1.
        out.values[i] = static_cast<std::uint32_t>(k);
    }
    return out;
}

/// Texture indices of an nx x ny raster partitioned into warped Voronoi cells.
template <Real T> [[nodiscard]] region_raster<T> partition(std::size_t nx, std::size_t ny, T cell_m,
                                                           const voronoi_partition<T>& p, std::uint64_t seed) {
    require_grid(nx, ny, cell_m, "partition");
    sss::require(!p.sites.empty(), "partition.sites", "needs at least one site");
    for (std::size_t k = 0; k < p.sites.size(); ++k) {
        sss::require_finite(p.sites[k].x_m, "partition.sites[" + std::to_string(k) + "].x_m");
        sss::require_finite(p.sites[k].y_m, "partition.sites[" + std::to_string(k) + "].y_m");
    }
    sss::require_non_negative(p.warp_m, "partition.warp_m");
    sss::require_positive(p.warp_scale_m, "partition.warp_scale_m");
    sss::require_finite(p.warp_gamma, "partition.warp_gamma");
    sss::require(p.warp_gamma > T(2) && p.warp_gamma < T(4), "partition.warp_gamma", "must lie in (2, 4)");

    // The warp's x and y fields, drawn in step: x in `a`, y in `b`.
    detail::fractal_pair<double> warp_xy;
    if (p.warp_m > T(0))
        warp_xy = detail::unit_fractal_pair<double>(nx, ny, cell_m, p.warp_gamma, p.warp_scale_m, derive_seed(seed, 1),
                                                    derive_seed(seed, 2), true);
    const double warp = static_cast<double>(p.warp_m), cell = static_cast<double>(cell_m);
    region_raster<T> out{nx, ny, cell_m, std::vector<std::uint32_t>(nx * ny)};
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const std::size_t i = iy * nx + ix;
            double x = static_cast<double>(ix) * cell, y = static_cast<double>(iy) * cell;
            if (warp > 0.0) {
                x += warp * warp_xy.a[i];
                y += warp * warp_xy.b[i];
            }
            std::size_t best = 0;
            double best_d2 = HUGE_VAL;
            for (std::size_t k = 0; k < p.sites.size(); ++k) {
                const double dx = x - static_cast<double>(p.sites[k].x_m), dy = y - static_cast<double>(p.sites[k].y_m);
                const double d2 = dx * dx + dy * dy;
                if (d2 < best_d2) {
                    best_d2 = d2;
                    best = k;
                }
            }
            out.values[i] = static_cast<std::uint32_t>(p.sites[best].texture);
        }
    return out;
}

/// The widest blend compose takes, in cells (blend_m over cell_m): its Gaussian reaches 4 blend_m either side of each
/// cell, summed cell by cell (a band of 2048 cells at this width).
inline constexpr double max_blend_cells = 256.0;

/// Fills the regions of `texture_index` (values index `textures`) with their textures. Texture k draws
/// from streams 2k and 2k + 1 of `seed`. blend_m >= 0 (0: sharp changes of height at boundaries), at most max_blend_cells cells.
template <Real T> [[nodiscard]] composite_seabed<T> compose(const region_raster<T>& texture_index,
                                                            std::span<const region_texture<T>> textures, T blend_m,
                                                            std::uint64_t seed) {
    const std::size_t nx = texture_index.nx, ny = texture_index.ny;
    const T cell_m = texture_index.cell_m;
    require_grid(nx, ny, cell_m, "compose.texture_index");
    sss::require(texture_index.values.size() == nx * ny, "compose.texture_index.values",
                    "size differs from nx * ny");
    sss::require(!textures.empty(), "compose.textures", "needs at least one texture");
    sss::require_non_negative(blend_m, "compose.blend_m");
    sss::require(double(blend_m) <= max_blend_cells * double(cell_m), "compose.blend_m", [&] {
        return "must be at most " + std::to_string(int(max_blend_cells)) + " cells (" + std::to_string(max_blend_cells * double(cell_m)) +
               " m), got " + std::to_string(blend_m) + " m";
    });
    for (std::uint32_t k : texture_index.values)
        sss::require(k < textures.size(), "compose.texture_index",
                        [&] { return "holds texture " + std::to_string(k) + " but only " + std::to_string(textures.size()) +
                            " are given"; });
    for (std::size_t k = 0; k < textures.size(); ++k) {
        const std::string who = "compose.textures[" + std::to_string(k) + "]";
        sss::require_finite(textures[k].mean_height_m, who + ".mean_height_m");
        validate(textures[k].roughness, who + ".roughness");
        for (std::size_t r = 0; r < textures[k].ripples.size(); ++r)
            validate(textures[k].ripples[r], cell_m, who + ".ripples[" + std::to_string(r) + "]");
    }

    std::vector<bool> used(textures.size(), false);
    for (std::uint32_t k : texture_index.values) used[k] = true;

    composite_seabed<T> out{raster<T>{nx, ny, cell_m, std::vector<T>(nx * ny, T(0))},
                            region_raster<T>{nx, ny, cell_m, std::vector<std::uint32_t>(nx * ny)}};
    for (std::size_t i = 0; i < nx * ny; ++i) out.regions.values[i] = textures[texture_index.values[i]].id;

    const bool blend = blend_m > T(0);
    std::vector<double> acc(nx * ny, 0.0), weight_sum(blend ? nx * ny : 0, 0.0), weight;
    const double sigma_cells = static_cast<double>(blend_m) / static_cast<double>(cell_m);
    for (std::size_t k = 0; k < textures.size(); ++k) {
        if (!used[k]) continue;
        const region_texture<T>& t = textures[k];
        raster<T> h = t.roughness.spectrum.w2_si > T(0)
                          ? fractal_surface<T>(nx, ny, cell_m, t.roughness, derive_seed(seed, 2 * k))
                          : make_raster<T, T>(nx, ny, cell_m, T(0));
        for (std::size_t r = 0; r < t.ripples.size(); ++r)
            add_ripples(h, t.ripples[r], derive_seed(derive_seed(seed, 2 * k + 1), r));
        const double mean = static_cast<double>(t.mean_height_m);
        if (!blend) {
            for (std::size_t i = 0; i < nx * ny; ++i)
                if (texture_index.values[i] == k) acc[i] = mean + static_cast<double>(h.values[i]);
            continue;
        }
        weight.assign(nx * ny, 0.0);
        for (std::size_t i = 0; i < nx * ny; ++i) weight[i] = texture_index.values[i] == k ? 1.0 : 0.0;
        detail::gaussian_pass(weight, nx, ny, sigma_cells, true);
        detail::gaussian_pass(weight, nx, ny, sigma_cells, false);
        for (std::size_t i = 0; i < nx * ny; ++i) {
            acc[i] += weight[i] * (mean + static_cast<double>(h.values[i]));
            weight_sum[i] += weight[i];
        }
    }
    for (std::size_t i = 0; i < nx * ny; ++i)
        out.height.values[i] = static_cast<T>(blend ? acc[i] / weight_sum[i] : acc[i]);
    return out;
}

/// compose() for textures held in a vector.
template <Real T> [[nodiscard]] composite_seabed<T> compose(const region_raster<T>& texture_index,
                                                            const std::vector<region_texture<T>>& textures, T blend_m,
                                                            std::uint64_t seed) {
    return compose(texture_index, std::span<const region_texture<T>>(textures), blend_m, seed);
}

} // namespace sss::seabed
