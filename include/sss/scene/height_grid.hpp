#pragma once
/// \file
/// The vertex grid of a height field and its triangulated surface: the grid view, the triangle of a point, heights,
/// gradients and normals. Part of scene/height_field_surface.hpp (see its file comment for the surface), which
/// includes it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "sss/core/types.hpp"
#include "sss/scene/detail/grid_cell.hpp"

namespace sss::scene {

/// Which half of a cell: `lower` holds vertex (ix+1, iy) and the points with a >= b, `upper` holds
/// vertex (ix, iy+1) and the points with a < b.
enum class cell_triangle : unsigned char { lower = 0, upper = 1 };

/// A non-owning view of an nx x ny vertex grid: heights[iy * nx + ix] is the height (world z, m) of
/// vertex (ix, iy) at world (origin_m.x + ix cell_m, origin_m.y + iy cell_m).
template <Real T> struct height_grid_view {
    const T* heights = nullptr; ///< nx * ny vertex heights (m), row-major, south row first
    std::int32_t nx = 0;        ///< vertices along x (>= 2)
    std::int32_t ny = 0;        ///< vertices along y (>= 2)
    T cell_m{};                 ///< vertex spacing (m)
    T inv_cell_m{};             ///< 1 / cell_m (1/m)
    vec2<T> origin_m{};         ///< world (x, y) of vertex (0, 0) (m)

    /// Height of vertex (ix, iy) (m); no bounds check.
    [[nodiscard]] T at(std::int32_t ix, std::int32_t iy) const noexcept {
        return heights[static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ix)];
    }
    /// Row-major index of cell (ix, iy) among the (nx - 1) x (ny - 1) cells.
    [[nodiscard]] std::size_t cell_index(std::int32_t ix, std::int32_t iy) const noexcept {
        return static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx - 1) + static_cast<std::size_t>(ix);
    }
};

/// The triangle of a cell holding local coordinates (a, b): lower when a >= b.
template <Real T> [[nodiscard]] constexpr cell_triangle triangle_of(T a, T b) noexcept {
    return a >= b ? cell_triangle::lower : cell_triangle::upper;
}

/// Height (m) of the surface at local coordinates (a, b) of cell (ix, iy), by the triangle rule above.
template <Real T> [[nodiscard]] inline T height_in_cell(const height_grid_view<T>& g, std::int32_t ix, std::int32_t iy,
                                                        T a, T b) noexcept {
    const T h00 = g.at(ix, iy);
    const T h11 = g.at(ix + 1, iy + 1);
    if (a >= b) {
        const T h10 = g.at(ix + 1, iy);
        return h00 + a * (h10 - h00) + b * (h11 - h10);
    }
    const T h01 = g.at(ix, iy + 1);
    return h00 + b * (h01 - h00) + a * (h11 - h01);
}

/// Height (m) of the surface at grid coordinates (u, v); points outside the grid are first clamped to its
/// nearest boundary point, so the surface is continued outside by its edge values.
template <Real T> [[nodiscard]] inline T height_at_grid(const height_grid_view<T>& g, T u, T v) noexcept {
    u = std::clamp(u, T(0), static_cast<T>(g.nx - 1));
    v = std::clamp(v, T(0), static_cast<T>(g.ny - 1));
    const std::int32_t ix = detail::cell_of(u, g.nx - 2);
    const std::int32_t iy = detail::cell_of(v, g.ny - 2);
    return height_in_cell(g, ix, iy, u - static_cast<T>(ix), v - static_cast<T>(iy));
}

/// Height gradient (dh/dx, dh/dy) of one triangle (dimensionless: m per m).
template <Real T> [[nodiscard]] inline vec2<T> triangle_gradient(const height_grid_view<T>& g, std::int32_t ix,
                                                                 std::int32_t iy, cell_triangle tri) noexcept {
    const T inv_c = g.inv_cell_m;
    const T h00 = g.at(ix, iy);
    const T h11 = g.at(ix + 1, iy + 1);
    if (tri == cell_triangle::lower) {
        const T h10 = g.at(ix + 1, iy);
        return vec2<T>{(h10 - h00) * inv_c, (h11 - h10) * inv_c};
    }
    const T h01 = g.at(ix, iy + 1);
    return vec2<T>{(h11 - h01) * inv_c, (h01 - h00) * inv_c};
}

/// The upward unit normal of a surface with height gradient `grad`: normalize(-gx, -gy, 1).
template <Real T> [[nodiscard]] inline vec3<T> normal_from_gradient(vec2<T> grad) noexcept {
    const T inv_len = T(1) / std::sqrt(grad.x * grad.x + grad.y * grad.y + T(1));
    return vec3<T>{-grad.x * inv_len, -grad.y * inv_len, inv_len};
}

/// Upward unit geometric normal of one triangle.
template <Real T> [[nodiscard]] inline vec3<T> triangle_normal(const height_grid_view<T>& g, std::int32_t ix,
                                                               std::int32_t iy, cell_triangle tri) noexcept {
    return normal_from_gradient(triangle_gradient(g, ix, iy, tri));
}

/// Height gradient at vertex (ix, iy) by central differences, one-sided at the border of the grid.
template <Real T>
[[nodiscard]] inline vec2<T> vertex_gradient(const height_grid_view<T>& g, std::int32_t ix, std::int32_t iy) noexcept {
    const std::int32_t x0 = std::max(ix - 1, 0), x1 = std::min(ix + 1, g.nx - 1);
    const std::int32_t y0 = std::max(iy - 1, 0), y1 = std::min(iy + 1, g.ny - 1);
    return vec2<T>{(g.at(x1, iy) - g.at(x0, iy)) / (static_cast<T>(x1 - x0) * g.cell_m),
                   (g.at(ix, y1) - g.at(ix, y0)) / (static_cast<T>(y1 - y0) * g.cell_m)};
}

/// The smooth gradient at local coordinates (a, b) of cell (ix, iy) in triangle `tri`: the vertex
/// gradients interpolated barycentrically. (a, b) are clamped into the triangle.
template <Real T> [[nodiscard]] inline vec2<T> smooth_gradient(const height_grid_view<T>& g, std::int32_t ix,
                                                               std::int32_t iy, cell_triangle tri, T a, T b) noexcept {
    a = std::clamp(a, T(0), T(1));
    b = std::clamp(b, T(0), T(1));
    // Weights of the corner (0,0), the triangle's own corner (1,0) or (0,1), and (1,1).
    T w00, w_side, w11;
    std::int32_t sx, sy; // the own corner's offset from (ix, iy)
    if (tri == cell_triangle::lower) {
        b = std::min(a, b);
        w00 = T(1) - a, w_side = a - b, w11 = b, sx = 1, sy = 0;
    } else {
        a = std::min(a, b);
        w00 = T(1) - b, w_side = b - a, w11 = a, sx = 0, sy = 1;
    }
    vec2<T> grad;
    if (ix >= 1 && iy >= 1 && ix + 2 <= g.nx - 1 && iy + 2 <= g.ny - 1) {
        // Interior: every central difference spans two cells, so scale once at the end.
        auto diff = [&](std::int32_t x, std::int32_t y) {
            return vec2<T>{g.at(x + 1, y) - g.at(x - 1, y), g.at(x, y + 1) - g.at(x, y - 1)};
        };
        grad = (diff(ix, iy) * w00 + diff(ix + sx, iy + sy) * w_side + diff(ix + 1, iy + 1) * w11) *
               (T(0.5) * g.inv_cell_m);
    } else {
        grad = vertex_gradient(g, ix, iy) * w00 + vertex_gradient(g, ix + sx, iy + sy) * w_side +
               vertex_gradient(g, ix + 1, iy + 1) * w11;
    }
    return grad;
}

/// Upward unit smooth normal at local coordinates (a, b) of cell (ix, iy) in triangle `tri`:
/// normal_from_gradient(smooth_gradient(...)).
template <Real T> [[nodiscard]] inline vec3<T> smooth_normal(const height_grid_view<T>& g, std::int32_t ix,
                                                             std::int32_t iy, cell_triangle tri, T a, T b) noexcept {
    return normal_from_gradient(smooth_gradient(g, ix, iy, tri, a, b));
}

/// Both gradients a hit needs (m per m): its triangle's (`triangle`) and the smooth one at its point
/// (`smooth`), equal to the last bit to triangle_gradient(g, ix, iy, tri) and smooth_gradient(g, ix, iy,
/// tri, a, b). Inside the grid the heights around the cell are loaded once for both, and the triangle
/// picks offsets rather than branches (which triangle a hit lands in is a coin toss, and a mispredicted
/// branch costs more than the whole computation).
template <Real T> struct hit_gradients {
    vec2<T> triangle; ///< gradient of the triangle (m per m)
    vec2<T> smooth;   ///< interpolated vertex gradient at the point (m per m)
};

} // namespace sss::scene
