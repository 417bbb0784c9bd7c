#pragma once
/// \file
/// How deep the along-track check may divide each column of a side, given the beam's weight on each column: the
/// division shared among the columns by weight, normalised to the cost of dividing every column alike, with a floor
/// set by the heaviest column.
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
///
/// That sum is the error of the line where every column sees the same scene. Where the heavier columns are in
/// shadow (behind a ripple's crest or a target) and a lighter one is not, the lighter one carries the line alone,
/// and its own staircase is that sample's whole error in dB. Rounding to the nearest level is relative to the
/// columns' mean, so a column with a fifth of the heaviest's weight can land a whole level below it although the
/// rule's slope is one level per factor 9. So the depths also keep a floor set by the heaviest column: no column is
/// divided less than the heaviest until its weight is a full factor 9 below it, and one level less per further factor
/// 9, d_j >= d_max - floor(log9(w_max / w_j)). Under an ideal fan that changes nothing; under the survey's 100 kHz
/// array (bench/bench_survey.cpp) the two columns beside the axis, at a fifth of its weight, go with the axis
/// columns to one level past L. The floor at most raises every column to the heaviest's depth, at most 3 times the
/// cost of even division. On the 256 m copy of the survey (bench/bench_survey_accuracy.cpp) it takes 1.2 to 1.3
/// times the time of the budget alone and lowers the worst line's 99th percentile error by about a third; on the
/// 1 km survey, 1.3 times the time for a tenth (docs/design/along-track.md).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

namespace sss {

/// depths[j]: how many times column j may be divided into thirds, for columns with along-track weights
/// `weights` (any common scale; a weight that is not a finite positive number counts as zero) and `levels` (L) for
/// a column of even weight (file comment): between 1 and L + 1, never more than a level below the heaviest column's
/// per whole factor 9 of weight below it, and 1 for a column of zero weight. Every depth is `levels` when levels is
/// 0 or when no weight counts. `depths` must hold at least weights.size() slots.
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
    // The floor set by the heaviest column (the first of equals): one level less per whole factor 9 below it. A factor
    // that is a power of 9 to within rounding counts as that power.
    std::size_t heaviest = n;
    for (std::size_t j = 0; j < n; ++j)
        if (counts(weights[j]) && (heaviest == n || weights[j] > weights[heaviest])) heaviest = j;
    if (heaviest == n) return;
    const double w_max = weights[heaviest];
    const std::size_t d_max = depths[heaviest];
    for (std::size_t j = 0; j < n; ++j) {
        if (!counts(weights[j])) continue;
        const double below = std::floor(std::log(w_max / weights[j]) / std::log(9.0) + 1e-9);
        const std::size_t down = below >= 64.0 ? 64 : static_cast<std::size_t>(below);
        depths[j] = std::max(depths[j], d_max > down ? d_max - down : std::size_t(1));
    }
}

} // namespace sss
