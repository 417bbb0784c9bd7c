#pragma once
/// \file
/// Internal to scene/height_field_wedge.hpp: the rings of a wedge from a grid point and the highest vertex under
/// each, evaluated on demand from the grid or its maximum pyramid. Not part of the API.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "sss/core/types.hpp"
#include "sss/scene/detail/grid_cell.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_grid.hpp"

namespace sss::scene::detail {

/// The rings of a wedge and their envelopes, evaluated on demand.
template <Real T> class wedge_rings {
public:
    /// The wedge from grid point (u0, v0) between unit headings e_lo and e_hi (grid axes; the angle from e_lo to
    /// e_hi at most wedge_max_spread_rad plus rounding), rings from `first_ring` on.
    wedge_rings(const height_grid_view<T>& g, const max_pyramid<T>& p, T u0, T v0, vec2<T> e_lo, vec2<T> e_hi,
                T spread_rad, std::int32_t first_ring)
        : g_(g), p_(p), u0_(u0), v0_(v0), e_lo_(e_lo), e_hi_(e_hi), first_(first_ring) {
        // The arc of a ring lies within its sagitta, r (1 - cos(spread / 2)) <= r spread^2 / 8, of the chord
        // between the corners; 1e-3 cells more covers rounding of the corners themselves.
        sagitta_per_cell_ = spread_rad * spread_rad / T(8) + T(1e-6);
        // Beyond the farthest corner of the grid's footprint no ring meets a cell (one cell more for rounding).
        const T nu = static_cast<T>(g.nx - 1), nv = static_cast<T>(g.ny - 1);
        const T du = std::max(std::abs(u0), std::abs(nu - u0)), dv = std::max(std::abs(v0), std::abs(nv - v0));
        end_ = std::floor(std::sqrt(du * du + dv * dv) + T(2));
    }

    /// Rho (cells) beyond which the wedge meets no cell of the grid.
    [[nodiscard]] T end_cells() const noexcept { return end_; }

    /// Envelope of ring i (m): the highest vertex under it, or -infinity where it lies outside the grid. Each ring is
    /// evaluated the first time it is asked for, and only then: the walks of a column ask for a few rings far apart.
    [[nodiscard]] T envelope(std::int32_t i) {
        const std::size_t k = static_cast<std::size_t>(i - first_);
        if (values_.size() <= k) values_.resize(std::max(k + 1, 2 * values_.size()), unknown);
        T& v = values_[k];
        if (v == unknown) v = compute(i);
        return v;
    }

private:
    [[nodiscard]] T compute(std::int32_t i) const noexcept {
        const T r0 = static_cast<T>(i), r1 = r0 + T(1);
        const T m = r1 * sagitta_per_cell_ + T(1e-3) + (std::abs(u0_) + std::abs(v0_) + r1) * T(1e-6);
        const T ua = u0_ + r0 * e_lo_.x, ub = u0_ + r0 * e_hi_.x, uc = u0_ + r1 * e_lo_.x, ud = u0_ + r1 * e_hi_.x;
        const T va = v0_ + r0 * e_lo_.y, vb = v0_ + r0 * e_hi_.y, vc = v0_ + r1 * e_lo_.y, vd = v0_ + r1 * e_hi_.y;
        const T u_min = std::min(std::min(ua, ub), std::min(uc, ud)) - m;
        const T u_max = std::max(std::max(ua, ub), std::max(uc, ud)) + m;
        const T v_min = std::min(std::min(va, vb), std::min(vc, vd)) - m;
        const T v_max = std::max(std::max(va, vb), std::max(vc, vd)) + m;
        constexpr T lowest = -std::numeric_limits<T>::infinity();
        const T nu = static_cast<T>(g_.nx - 1), nv = static_cast<T>(g_.ny - 1);
        if (!(u_max >= T(0) && v_max >= T(0) && u_min <= nu && v_min <= nv)) return lowest;
        const std::int32_t cx0 = cell_of(u_min, g_.nx - 2), cx1 = cell_of(u_max, g_.nx - 2);
        const std::int32_t cy0 = cell_of(v_min, g_.ny - 2), cy1 = cell_of(v_max, g_.ny - 2);
        const std::int32_t span = std::max(cx1 - cx0, cy1 - cy0);
        T top = lowest;
        if (span < 4) {
            for (std::int32_t y = cy0; y <= cy1 + 1; ++y)
                for (std::int32_t x = cx0; x <= cx1 + 1; ++x) top = std::max(top, g_.at(x, y));
            return top;
        }
        // A wide ring: blocks of the maximum pyramid at least as wide as the ring, two or three per axis.
        const std::int32_t level = std::min(p_.levels(), static_cast<std::int32_t>(std::bit_width(static_cast<std::uint32_t>(span))));
        for (std::int32_t by = cy0 >> level; by <= (cy1 >> level); ++by)
            for (std::int32_t bx = cx0 >> level; bx <= (cx1 >> level); ++bx) top = std::max(top, p_.max_m(level, bx, by));
        return top;
    }

    const height_grid_view<T>& g_;
    const max_pyramid<T>& p_;
    T u0_, v0_;
    vec2<T> e_lo_, e_hi_;
    std::int32_t first_;
    T sagitta_per_cell_{};
    T end_{};
    std::vector<T> values_; // by ring from first_; `unknown` where not evaluated yet
    static constexpr T unknown = std::numeric_limits<T>::max(); // a ring with this envelope is only evaluated again
};

} // namespace sss::scene::detail
