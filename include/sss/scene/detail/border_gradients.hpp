#pragma once
/// \file
/// Internal to scene/height_field_surface.hpp: the gradients of a hit on the border of the grid, where the fast
/// path's neighbours are missing. Not part of the API.

#include <cstdint>

#include "sss/core/types.hpp"
#include "sss/scene/height_grid.hpp"

namespace sss::scene::detail {

template <Real T> [[nodiscard]] hit_gradients<T> gradients_at_border(const height_grid_view<T>& g, std::int32_t ix,
                                                                     std::int32_t iy, cell_triangle tri, T a,
                                                                     T b) noexcept {
    return {triangle_gradient(g, ix, iy, tri), smooth_gradient(g, ix, iy, tri, a, b)};
}

} // namespace sss::scene::detail
