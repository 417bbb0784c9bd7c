#pragma once
/// \file
/// The surface a height field stands for: a non-owning view of the vertex grid, the triangulation of
/// each cell, the interpolated height and the geometric and smooth normals. Both the scene class
/// (`height_field.hpp`) and the tracers (`height_field_tracer.hpp`) use these, so "the surface" is
/// defined in exactly one place.
///
/// Grid units: u = (x - origin.x) / cell, v = (y - origin.y) / cell, so vertex (ix, iy) sits at (u, v) = (ix, iy).
/// Cell (ix, iy) spans [ix, ix+1] x [iy, iy+1]; inside it, a = u - ix and b = v - iy lie in [0, 1].
///
/// Triangulation: every cell is split by the diagonal from vertex (ix, iy) to vertex (ix+1, iy+1), the
/// line a = b (in the world: from the south-west to the north-east corner). The same diagonal in every
/// cell makes the diagonals of all cells lie on the lines u - v = k (k integer), so a ray crosses three
/// families of straight lines (u = i, v = j, u - v = k) and nothing else. The two triangles are
///   lower (a >= b): vertices (0,0), (1,0), (1,1);  h = h00 + a (h10 - h00) + b (h11 - h10)
///   upper (a <  b): vertices (0,0), (0,1), (1,1);  h = h00 + b (h01 - h00) + a (h11 - h01)
/// Points on the diagonal belong to both, and both formulas give h00 + a (h11 - h00) there.
///
/// Why triangles and not bilinear patches: the surface along any straight ray is then piecewise linear
/// in the distance, with breakpoints only where the ray crosses those lines, so the hit is the root of
/// a linear function (exact, no quadratic and no discriminant), normals are constant per triangle, and
/// the tracer's watertightness argument (see height_field_tracer.hpp) is one line long. Bilinear patches
/// would need a quadratic per cell and can be crossed twice inside one cell.
///
/// Smooth normals: each vertex gets the gradient of the heights by central differences (one-sided at the
/// border of the grid); the gradient is interpolated with the hit's barycentric coordinates in its
/// triangle and the normal is normalize(-gx, -gy, 1). Nothing is stored per vertex beyond the heights.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "sss/core/detail/force_inline.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/detail/border_gradients.hpp"
#include "sss/scene/height_grid.hpp"

namespace sss::scene {

/// The gradients of a hit at local coordinates (a, b) of cell (ix, iy) in triangle `tri` (see hit_gradients). Always
/// inlined: the batched hit builders read the heights of many hits in one loop.
template <Real T>
[[nodiscard]] SSS_FORCE_INLINE hit_gradients<T> gradients_at(const height_grid_view<T>& g, std::int32_t ix,
                                                             std::int32_t iy, cell_triangle tri, T a, T b) noexcept {
    if (!(ix >= 1 && iy >= 1 && ix + 2 <= g.nx - 1 && iy + 2 <= g.ny - 1))
        return detail::gradients_at_border(g, ix, iy, tri, a, b);
    const std::ptrdiff_t nx = g.nx;
    const std::ptrdiff_t lower = tri == cell_triangle::lower ? 1 : 0;
    const T* p = g.heights + static_cast<std::ptrdiff_t>(iy) * nx + ix; // vertex (ix, iy)
    const T inv_c = g.inv_cell_m;
    // The triangle: lower (h10 - h00, h11 - h10), upper (h11 - h01, h01 - h00).
    const T* px = p + (1 - lower) * nx; // lower: h00, h10; upper: h01, h11
    const T* py = p + lower;            // lower: h10, h11; upper: h00, h01
    const vec2<T> gt{(px[1] - px[0]) * inv_c, (py[nx] - py[0]) * inv_c};
    // The smooth gradient, as in smooth_gradient: weights of (0,0), the own corner and (1,1).
    a = std::clamp(a, T(0), T(1));
    b = std::clamp(b, T(0), T(1));
    const T ab[2] = {b, a};
    const T lo = std::min(a, b), hi = ab[lower];
    const T w00 = T(1) - hi, w_side = hi - lo, w11 = lo;
    const T* ps = p + lower + (1 - lower) * nx; // the own corner: (1, 0) or (0, 1)
    const vec2<T> d00{p[1] - p[-1], p[nx] - p[-nx]};
    const vec2<T> ds{ps[1] - ps[-1], ps[nx] - ps[-nx]};
    const vec2<T> d11{p[nx + 2] - p[nx], p[2 * nx + 1] - p[1]};
    return {gt, (d00 * w00 + ds * w_side + d11 * w11) * (T(0.5) * inv_c)};
}

} // namespace sss::scene
