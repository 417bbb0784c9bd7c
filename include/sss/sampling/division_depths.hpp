#pragma once
/// \file
/// How deep the along-track check may divide each column of a side, given the beam's weight on each column: the
/// division shared among the columns by weight, at about the cost of dividing every column alike.
///
/// A column whose located edges disagree with a neighbour's is traced again as thirds, and thirds that still
/// disagree again, down to 3^-d of the column (simulator.hpp, ray_density::along_split). What is left of the
/// staircase the columns draw where an edge crosses the beam obliquely is a misplacement of that edge by up to half
/// the narrowest column, so column j leaves an error about proportional to its share of the echo, w_j (its two-way
/// beam weight), times 3^-d_j; dividing it costs about 3^d_j column traces (where nearly every stretch disagrees, as
/// over ripples, each level traces twice as many thirds as the one before, and the middle thirds come free). The
/// depths that minimise sum_j w_j 3^-d_j for a given cost sum_j 3^d_j satisfy 3^(2 d_j) proportional to w_j
/// (Lagrange), i.e. one level more per factor 9 of weight; with the cost of dividing every column to depth L,
///     3^d_j = n 3^L sqrt(w_j) / sum_i sqrt(w_i),
/// rounded to the nearest level. Under a beam that weights every column alike (an ideal fan) that is L for every
/// column; under a real array's along-track pattern the few columns near its axis, which carry most of the echo,
/// go a level deeper and those near the edges of the extent a level or two shallower. Depths are kept between 1
/// (a disagreeing stretch is always traced again in thirds: even a faint column can fill another's shadow) and
/// L + 1.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace sss {

/// depths[j]: how many times column j may be divided into thirds, for columns with along-track weights
/// `weights` (any common scale; a weight that is not a finite positive number counts as zero) and `levels` (L) for
/// a column of even weight (file comment): between 1 and L + 1, and 1 for a column of zero weight. Every depth is
/// `levels` when levels is 0 or when no weight counts. `depths` must hold at least weights.size() slots.
inline void division_depths(std::span<const double> weights, std::size_t levels, std::span<std::size_t> depths) noexcept {
    const std::size_t n = weights.size();
    const auto counts = [](double w) { return w > 0.0 && w <= std::numeric_limits<double>::max(); };
    double sum_sqrt = 0.0;
    for (const double w : weights)
        if (counts(w)) sum_sqrt += std::sqrt(w);
    if (levels == 0 || !(sum_sqrt > 0.0)) {
        std::fill(depths.begin(), depths.begin() + static_cast<std::ptrdiff_t>(n), levels);
        return;
    }
    const std::size_t deepest = levels < std::numeric_limits<std::size_t>::max() ? levels + 1 : levels;
    for (std::size_t j = 0; j < n; ++j) {
        const double w = weights[j];
        if (!counts(w)) {
            depths[j] = 1;
            continue;
        }
        // log3(n sqrt(w) / sum sqrt(w)) levels from L, rounded; in whole levels from here on, so that any L is exact.
        const double shift = std::round(std::log(static_cast<double>(n) * std::sqrt(w) / sum_sqrt) / std::log(3.0));
        if (shift >= 1.0) {
            depths[j] = deepest;
        } else if (shift <= -1.0) {
            const std::size_t down = shift <= -64.0 ? 64 : static_cast<std::size_t>(-shift);
            depths[j] = levels > down ? levels - down : 1;
        } else {
            depths[j] = levels;
        }
    }
}

} // namespace sss
