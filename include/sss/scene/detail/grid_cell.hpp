#pragma once
/// \file
/// Internal to the height-field surface and its tracers: the cell along one axis that holds a grid coordinate.
/// Not part of the API.

#include <cstdint>

#include "sss/core/types.hpp"

namespace sss::scene::detail {

/// The cell index along one axis holding grid coordinate x: floor(x) clamped to [0, last_cell].
/// NaN maps to 0.
template <Real T> [[nodiscard]] inline std::int32_t cell_of(T x, std::int32_t last_cell) noexcept {
    if (!(x > T(0))) return 0;
    if (x >= static_cast<T>(last_cell)) return last_cell;
    return static_cast<std::int32_t>(x); // truncation is floor for x > 0
}

} // namespace sss::scene::detail
