#pragma once
/// \file
/// What a height-field grid tracer returns (`grid_hit`) and the height slab it clips rays to (`height_bounds`);
/// the tracers are in height_field_tracer.hpp, height_field_fan.hpp and height_field_wedge.hpp.

#include <cstdint>

#include "sss/core/types.hpp"
#include "sss/scene/height_field_surface.hpp"

namespace sss::scene {

/// What a grid tracer found: the distance along the ray and the cell and triangle that hold the hit.
template <Real T> struct grid_hit {
    T distance_m{};                                ///< distance from the ray origin (m)
    std::int32_t ix = 0;                           ///< cell column
    std::int32_t iy = 0;                           ///< cell row
    cell_triangle triangle = cell_triangle::lower; ///< half of the cell
};

/// Height bounds of a grid: the tracers clip rays to the slab bottom_m <= z <= top_m.
template <Real T> struct height_bounds {
    T bottom_m{}; ///< lowest vertex (m)
    T top_m{};    ///< highest vertex (m)
};

} // namespace sss::scene
