#pragma once
/// \file
/// Where a side's along-track columns lie.
///
/// Each column is traced as one fan at its centre and carries the beam's weight over its whole width (simulator.hpp),
/// so everything the column sees arrives at the times its centre's rays see it. Along the beam's width the first
/// return moves: over a level seabed at altitude H, the nearest point the launch plane at along-track angle a reaches
/// lies at slant range H / cos(a - a_n), where a_n is the angle whose plane holds the vertical. Under a beam narrow
/// along track that moves by millimetres; under one wide along track (a short array, a single element) each column's
/// echo began at its centre's time, and the line stepped there: a 1 mm element at 100 kHz, 10 m above a level seabed,
/// in 8 columns of 22 degrees, was 8 dB above a quadrature of the beam past one column's onset and silent for the
/// first 5 samples after the nadir time. The columns are therefore no wider than the requested count makes them, and
/// narrower where the first return moves by more than a tolerance across them: there their density follows the
/// onset's slope and curvature. Where the onset moves by less than half the tolerance across every column of the
/// requested count, the columns are those, evenly wide, as before.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "sss/beam/concept.hpp"
#include "sss/core/constants.hpp"

namespace sss {

/// The slant range (m) of the nearest point of the plane with unit normal `up_normal` (world, pointing towards the
/// transducer) lying `distance_m` from it that a ray launched at along-track angle `along_rad` and any depression within
/// [depression_min_rad, depression_max_rad] meets along a straight path, the body rotated by R; infinity where no such
/// ray comes towards the plane. With g(e) = A + B cos e + C sin e the ray's component at depression e against the
/// normal (A, B, C from the body axes' components along it, R's columns), the range is distance_m / max g: over a
/// level seabed, the downward component of sampling/launch_angles.hpp.
template <Real T>
[[nodiscard]] double nearest_range_to_plane_m(side s, double along_rad, double depression_min_rad,
                                              double depression_max_rad, const mat3<T>& R, const vec3<double>& up_normal,
                                              double distance_m) noexcept {
    const double sa = std::sin(along_rad), ca = std::cos(along_rad);
    // The body axes' components along the normal (GLM stores columns: R[col] is body axis col in world).
    const auto along_normal = [&](int col) {
        return double(R[col][0]) * up_normal.x + double(R[col][1]) * up_normal.y + double(R[col][2]) * up_normal.z;
    };
    const double A = -along_normal(0) * sa;
    const double B = -along_normal(1) * double(side_sign<T>(s)) * ca;
    const double C = -along_normal(2) * ca;
    auto g = [&](double e) { return A + B * std::cos(e) + C * std::sin(e); };
    double best = std::max(g(depression_min_rad), g(depression_max_rad));
    const double phi = std::atan2(C, B); // where B cos e + C sin e peaks, modulo 2 pi
    for (int m = -1; m <= 1; ++m) {
        const double e = phi + double(m) * two_pi_v<double>;
        if (e > depression_min_rad && e < depression_max_rad) best = std::max(best, A + std::hypot(B, C));
    }
    if (!(distance_m > 0.0) || !(best > 0.0)) return std::numeric_limits<double>::infinity();
    return distance_m / best;
}

/// The slant range (m) of the nearest point of a level seabed `altitude_m` below the transducer that a ray launched
/// at along-track angle `along_rad` and any depression within [depression_min_rad, depression_max_rad] meets along a
/// straight path, the body rotated by R; infinity where no such ray descends (nearest_range_to_plane_m with the
/// vertical: the body axes' components along it are R's third row exactly).
template <Real T>
[[nodiscard]] double nearest_range_m(side s, double along_rad, double depression_min_rad, double depression_max_rad,
                                     const mat3<T>& R, double altitude_m) noexcept {
    return nearest_range_to_plane_m(s, along_rad, depression_min_rad, depression_max_rad, R, vec3<double>{0.0, 0.0, 1.0},
                                    altitude_m);
}

/// The edges of a side's along-track columns: `edges` receives the angles a0 = edges[0] < ... < edges[m] = a1 (rad)
/// of m >= n columns (m = n, evenly spaced, where the tolerance holds for those, or a1 <= a0).
/// \param n             columns asked for (ray_density::along, or more for the beam's pattern); at least 1
/// \param tolerance_m   how far (m of slant range) the first return may move across one column
/// \param max_range_m   the line's range: first returns beyond it are not seen and ask for nothing
/// \param nearest_m     nearest_m(a): the slant range (m) of the first return of the launch plane at angle a
///                      (nearest_range_m; infinity where none)
/// \param max_columns   at most this many columns; where the tolerance asks for more, the density it asks for
///                      beyond the even columns' is scaled down alike (no column is wider than the even ones)
template <class Nearest>
void column_edges(std::vector<double>& edges, double a0, double a1, std::size_t n, double tolerance_m,
                  double max_range_m, Nearest&& nearest_m, std::size_t max_columns = 4096) {
    n = std::max<std::size_t>(n, 1);
    auto even = [&](std::size_t m) {
        edges.resize(m + 1);
        for (std::size_t j = 0; j <= m; ++j) edges[j] = a0 + (a1 - a0) * double(j) / double(m);
    };
    even(n);
    if (!(a1 > a0) || !(tolerance_m > 0.0) || !(max_range_m > 0.0) || n >= max_columns) return;
    // The onset, clipped at the line's range (a first return beyond it is not seen, wherever it lies).
    auto onset = [&](double a) {
        const double r = nearest_m(a);
        return std::isfinite(r) ? std::min(r, max_range_m) : max_range_m;
    };
    // The tolerance where the first return lies at range r: tolerance_m near the nearest first return r_min, and
    // 8 (r - r_min) / r_min times it farther out. Near the first return the line is the sum of a few columns, each
    // with its own onset peak, and peaks a few samples apart make a comb; farther out a column is a small part of
    // the many columns that see the seabed, and its step is small against their sum. Where the onset turns within a
    // column (the column holding the vertical's plane), its centre's onset lags the true one, the line's first
    // samples: there a quarter of that. Measured against a quadrature of the beam over a level seabed 10 m down,
    // sampled at 20 kHz: under a 1 mm element at 100 kHz (60 m range) a fixed 8 samples left 8 dB peaks in the comb,
    // 1 sample growing so 0.1 dB near the first return and 0.3 dB beyond; under a 120 degree ideal fan the quarter
    // where the onset turns takes the first sample from 2 dB to 0.1 dB off.
    auto moving = [&](double r, double r_min) { return tolerance_m * std::max(1.0, 8.0 * (r - r_min) / r_min); };
    auto turning = [&](double r, double r_min) { return tolerance_m * std::max(0.25, 8.0 * (r - r_min) / r_min); };
    // The even columns stand where the onset moves across each by at most half the tolerance (its ends, quarters
    // and centre sampled: the onset is smooth and turns at most once within a column). The samples are kept in
    // `edges` meanwhile.
    std::vector<double>& sampled = edges;
    sampled.resize(4 * n + 1);
    for (std::size_t i = 0; i < sampled.size(); ++i) sampled[i] = onset(a0 + (a1 - a0) * double(i) / double(4 * n));
    const double sampled_min = *std::min_element(sampled.begin(), sampled.end());
    bool even_holds = true;
    for (std::size_t j = 0; j < n && even_holds; ++j) {
        const auto first = sampled.begin() + std::ptrdiff_t(4 * j), last = first + 5;
        const auto [lo, hi] = std::minmax_element(first, last);
        const bool turns = lo != first && lo != last - 1;
        even_holds = *hi - *lo <= 0.5 * (turns ? turning(*lo, sampled_min) : moving(*lo, sampled_min));
    }
    even(n);
    if (even_holds) return;
    // Density of columns (per rad) on a grid: 1 / the width w over which the onset, with its local slope r' and
    // curvature r'', moves by the tolerance (|r'| w / moving + |r''| w^2 / (8 turning) = 1), and at least
    // n / (a1 - a0): `extra` accumulates what it asks for beyond that floor.
    const std::size_t cells = std::clamp<std::size_t>(64 * n, 2048, 16384);
    const double h = (a1 - a0) / double(cells);
    std::vector<double> r(cells + 3);
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = onset(a0 + h * (double(i) - 1.0)); // r[i]: angle a0 + (i - 1) h
    const double base = double(n) / (a1 - a0);
    const double r_min = *std::min_element(r.begin(), r.end());
    const double most = double(max_columns) / h; // no cell needs more than every column
    std::vector<double> extra(cells + 1, 0.0);
    for (std::size_t i = 0; i < cells; ++i) {
        // the cell from a0 + i h to a0 + (i + 1) h, its ends r[i + 1] and r[i + 2]
        const double near = std::min(r[i + 1], r[i + 2]);
        const double b = std::abs(r[i + 2] - r[i + 1]) / h / moving(near, r_min);
        const double a = std::max(std::abs(r[i + 2] - 2.0 * r[i + 1] + r[i]),
                                  std::abs(r[i + 3] - 2.0 * r[i + 2] + r[i + 1])) / (h * h) / (8.0 * turning(near, r_min));
        // 1 / w, w the positive root of a w^2 + b w - 1 = 0
        const double per_rad = std::min(most, 0.5 * (b + std::sqrt(b * b + 4.0 * a)));
        extra[i + 1] = extra[i] + h * std::max(0.0, per_rad - base);
    }
    // m columns: what the density asks for, or at most max_columns, the extra density then scaled down alike (the
    // floor stays: no column wider than the even ones).
    const double asked = double(n) + extra.back();
    if (!(asked > double(n) + 1e-9)) return;
    const std::size_t m = asked >= double(max_columns) ? max_columns : static_cast<std::size_t>(std::ceil(asked - 1e-9));
    if (m <= n) return;
    const double scale = (double(m) - double(n)) / extra.back();
    // Edge j where the cumulative density, base h i + scale extra[i], reaches j (m columns of one each), linear
    // within a cell.
    auto cumulative = [&](std::size_t i) { return base * h * double(i) + scale * extra[i]; };
    edges.resize(m + 1);
    edges[0] = a0;
    std::size_t i = 0;
    for (std::size_t j = 1; j < m; ++j) {
        const double target = double(j);
        while (i + 1 < cells && cumulative(i + 1) < target) ++i;
        const double span = cumulative(i + 1) - cumulative(i);
        const double f = span > 0.0 ? std::clamp((target - cumulative(i)) / span, 0.0, 1.0) : 0.0;
        edges[j] = std::max(edges[j - 1], a0 + h * (double(i) + f));
    }
    edges[m] = a1;
}

} // namespace sss
