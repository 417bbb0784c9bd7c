#pragma once
/// \file
/// Plain regular rasters: what the seabed generators produce (heights, region ids).
///
/// Layout: row-major, `values[iy * nx + ix]`. Sample (ix, iy) lies at raster-local position
/// x = ix cell_m (east), y = iy cell_m (north); a raster covers [0, (nx - 1) cell_m] x [0, (ny - 1) cell_m]
/// with samples on the nodes. Placing it in the world (an origin, a rotation) is the scene's business.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/core/types.hpp"

namespace sss::seabed {

/// A raster of `Value` samples on a square grid of spacing `cell_m` (metres, of type T).
template <class Value, Real T> struct basic_raster {
    using value_type = Value;
    using length_type = T;

    std::size_t nx = 0;        ///< samples along x (east)
    std::size_t ny = 0;        ///< samples along y (north)
    T cell_m = T(1);           ///< sample spacing (m)
    std::vector<Value> values; ///< nx * ny samples, row-major: values[iy * nx + ix]

    [[nodiscard]] Value& operator()(std::size_t ix, std::size_t iy) noexcept { return values[iy * nx + ix]; }
    [[nodiscard]] const Value& operator()(std::size_t ix, std::size_t iy) const noexcept {
        return values[iy * nx + ix];
    }
    [[nodiscard]] std::size_t size() const noexcept { return values.size(); }
    /// Raster-local x of column ix (m).
    [[nodiscard]] T x_m(std::size_t ix) const noexcept { return static_cast<T>(ix) * cell_m; }
    /// Raster-local y of row iy (m).
    [[nodiscard]] T y_m(std::size_t iy) const noexcept { return static_cast<T>(iy) * cell_m; }
};

/// Heights (m, world z) on a grid.
template <Real T> using raster = basic_raster<T, T>;

/// Region ids (material / ground-truth label) on a grid.
template <Real T> using region_raster = basic_raster<std::uint32_t, T>;

/// Throws unless nx, ny >= 1, nx * ny <= sss::max_elements and cell_m is finite and > 0; `who` prefixes the
/// parameter names.
template <Real T> void require_grid(std::size_t nx, std::size_t ny, T cell_m, const std::string& who) {
    sss::require(nx >= 1, who + ".nx", "must be >= 1");
    sss::require(ny >= 1, who + ".ny", "must be >= 1");
    (void)checked_elements(nx, ny, who + ".nx * ny");
    sss::require_positive(cell_m, who + ".cell_m");
}

/// A raster of nx x ny samples of spacing cell_m, every sample set to `fill`. Validates the grid.
template <class Value, Real T>
[[nodiscard]] basic_raster<Value, T> make_raster(std::size_t nx, std::size_t ny, T cell_m, Value fill = Value{}) {
    require_grid(nx, ny, cell_m, "make_raster");
    return basic_raster<Value, T>{nx, ny, cell_m, std::vector<Value>(nx * ny, fill)};
}

} // namespace sss::seabed
