#pragma once
/// \file
/// The maximum pyramid of a height field: for every level L >= 1, the highest vertex of every block of
/// 2^L x 2^L cells (the block's closed vertex set, boundary vertices included, since the cells' triangles
/// use them). A ray that stays above a block's maximum while it crosses the block cannot hit anything in
/// it, so the tracer skips the block in one step. Level 0 (single cells) is not stored: the tracer tests
/// cells exactly instead. This is the "maximum mipmap" of Tevs, Ihrke & Seidel (2008), "Maximum mipmaps
/// for fast, accurate, and scalable dynamic height field rendering", Proc. ACM I3D, 183-190.
///
/// Memory: level L holds ceil((nx-1)/2^L) x ceil((ny-1)/2^L) values, so all levels together hold about a
/// third of the vertex count: 1/4 + 1/16 + ... = 1/3 of the heights' bytes (plus a few partial blocks).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sss/scene/height_field_surface.hpp"

namespace sss::scene {

template <Real T> class max_pyramid {
public:
    /// Largest level a grid can need (blocks of 2^30 cells cover any grid with int32 indices).
    static constexpr std::int32_t max_levels = 31;

    max_pyramid() = default;

    /// Builds every level from the vertex grid `g` (which must have nx, ny >= 2).
    explicit max_pyramid(const height_grid_view<T>& g) : max_pyramid(g, [](std::int32_t) {}) {}

    /// The same, reading the grid's rows in order, in one pass: rows_read(y) says that rows [0, y) will not be read
    /// again, so that heights held in a memory map can be dropped behind the pass (io/mapped_height_field.hpp).
    template <class RowsRead> max_pyramid(const height_grid_view<T>& g, RowsRead&& rows_read) {
        std::int32_t cx = g.nx - 1, cy = g.ny - 1; // cells at level 0
        std::size_t total = 0;
        levels_ = 0;
        while (cx > 1 || cy > 1) {
            cx = (cx + 1) / 2;
            cy = (cy + 1) / 2;
            ++levels_;
            width_[static_cast<std::size_t>(levels_)] = cx;
            height_[static_cast<std::size_t>(levels_)] = cy;
            offset_[static_cast<std::size_t>(levels_)] = total;
            total += static_cast<std::size_t>(cx) * static_cast<std::size_t>(cy);
        }
        data_.resize(total);
        max_step_m_ = T(0);
        for (std::int32_t y = 0; y < g.ny; ++y) {
            max_step_m_ = std::max(max_step_m_, largest_step(g, y));
            // Blocks of level one whose rows end at y (2 by + 2 = y, or the last row) are complete.
            if (y % 2 == 1) continue; // the blocks ending at y + 1 read row y - 1 again
            if (levels_ > 0 && y >= 2) build_level_one_row(g, y / 2 - 1);
            rows_read(y); // later steps and blocks start at row y
        }
        if (levels_ > 0 && ((g.ny - 1) % 2 == 1)) build_level_one_row(g, height_[1] - 1); // the odd last block row
        rows_read(g.ny);
        for (std::int32_t level = 2; level <= levels_; ++level) build_from_children(level);
    }

    /// Number of stored levels: blocks of 2^1 ... 2^levels() cells (0 for a grid of one cell).
    [[nodiscard]] std::int32_t levels() const noexcept { return levels_; }
    /// Blocks along x at `level` (1 <= level <= levels()).
    [[nodiscard]] std::int32_t width(std::int32_t level) const noexcept {
        return width_[static_cast<std::size_t>(level)];
    }
    /// Blocks along y at `level`.
    [[nodiscard]] std::int32_t height(std::int32_t level) const noexcept {
        return height_[static_cast<std::size_t>(level)];
    }

    /// Highest vertex (m) of block (bx, by) at `level`, covering cells [bx 2^level, (bx+1) 2^level) along x.
    [[nodiscard]] T max_m(std::int32_t level, std::int32_t bx, std::int32_t by) const noexcept {
        const auto l = static_cast<std::size_t>(level);
        return data_[offset_[l] + static_cast<std::size_t>(by) * static_cast<std::size_t>(width_[l]) +
                     static_cast<std::size_t>(bx)];
    }

    /// Largest height difference (m) between two vertices next to each other along x or along y. Every triangle's
    /// gradient has components of at most max_step_m() / cell (height_field_surface.hpp), so between two points
    /// (du, dv) cells apart the surface differs by at most max_step_m() (|du| + |dv|): a Lipschitz bound.
    [[nodiscard]] T max_step_m() const noexcept { return max_step_m_; }

    /// Bytes held by the pyramid's values.
    [[nodiscard]] std::size_t bytes() const noexcept { return data_.size() * sizeof(T); }

private:
    /// Largest step from row y's vertices to their neighbours along +x and to row y + 1.
    static T largest_step(const height_grid_view<T>& g, std::int32_t y) noexcept {
        const T* row = g.heights + static_cast<std::size_t>(y) * static_cast<std::size_t>(g.nx);
        const T* up = y + 1 < g.ny ? row + g.nx : row;
        T r = T(0);
        for (std::int32_t x = 0; x + 1 < g.nx; ++x)
            r = std::max(r, std::max(std::abs(row[x + 1] - row[x]), std::abs(up[x] - row[x])));
        return std::max(r, std::abs(up[g.nx - 1] - row[g.nx - 1]));
    }

    /// Row `by` of level one: the highest of the vertices y in [2 by, min(2 by + 2, ny - 1)] of each block.
    void build_level_one_row(const height_grid_view<T>& g, std::int32_t by) {
        const std::int32_t w = width_[1];
        T* out = data_.data() + offset_[1] + static_cast<std::size_t>(by) * static_cast<std::size_t>(w);
        const std::int32_t y0 = 2 * by, y1 = std::min(2 * by + 2, g.ny - 1);
        for (std::int32_t bx = 0; bx < w; ++bx) {
            const std::int32_t x0 = 2 * bx, x1 = std::min(2 * bx + 2, g.nx - 1);
            T m = g.at(x0, y0);
            for (std::int32_t y = y0; y <= y1; ++y)
                for (std::int32_t x = x0; x <= x1; ++x) m = std::max(m, g.at(x, y));
            out[static_cast<std::size_t>(bx)] = m;
        }
    }

    void build_from_children(std::int32_t level) {
        const std::int32_t w = width_[static_cast<std::size_t>(level)], h = height_[static_cast<std::size_t>(level)];
        const std::int32_t cw = width_[static_cast<std::size_t>(level - 1)],
                           ch = height_[static_cast<std::size_t>(level - 1)];
        T* out = data_.data() + offset_[static_cast<std::size_t>(level)];
        for (std::int32_t by = 0; by < h; ++by) {
            for (std::int32_t bx = 0; bx < w; ++bx) {
                const std::int32_t x0 = 2 * bx, x1 = std::min(2 * bx + 1, cw - 1);
                const std::int32_t y0 = 2 * by, y1 = std::min(2 * by + 1, ch - 1);
                const T m = std::max(std::max(max_m(level - 1, x0, y0), max_m(level - 1, x1, y0)),
                                     std::max(max_m(level - 1, x0, y1), max_m(level - 1, x1, y1)));
                out[static_cast<std::size_t>(by) * static_cast<std::size_t>(w) + static_cast<std::size_t>(bx)] = m;
            }
        }
    }

    std::vector<T> data_;
    std::array<std::size_t, max_levels + 1> offset_{};
    std::array<std::int32_t, max_levels + 1> width_{};
    std::array<std::int32_t, max_levels + 1> height_{};
    std::int32_t levels_ = 0;
    T max_step_m_{};
};

} // namespace sss::scene
