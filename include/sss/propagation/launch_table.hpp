#pragma once
/// \file
/// A table of the rays launched down from one depth, where they first reach a deeper one, indexed by launch angle.
///
/// Every ray of a ping starts at the same point, and by the water's cylindrical symmetry a ray's path down to a
/// depth z_H (the depth from which the scene's geometry begins) depends on its launch inclination phi0 alone. The
/// table holds, for phi0 on a grid, the ray's state at z_H on its way down: horizontal range, time, path length,
/// absorption (dB) and the two ray-tube sums (ray_tube.hpp); the inclination there follows exactly from Snell's
/// law, cos(phi_H) = c(z_H) cos(phi0) / c(z_A). A ray looks its state up by six-point Lagrange interpolation and
/// is traced exactly from z_H on; what the table replaces is the stepping through the layers above the geometry.
///
/// The grid is uniform in w = ln tan(phi0 / 2), so that nodes crowd towards grazing launches, where range changes
/// fastest (in uniform water range ~ 1/phi0 ~ e^-w, and the tube sum K ~ e^-2w: the interpolation error is then
/// the same fraction of each everywhere, about 5e-3 (r h)^6 relative for grid step h and growth rate r, below
/// 1e-11 here); tan(phi0/2) = sin(phi0) / (1 + cos(phi0)) needs no trigonometry from a ray direction.
/// It spans phi0 from 1e-3 rad to the vertical with 64 nodes per unit of w (about 490), plus two nodes beyond each
/// end (beyond the vertical by symmetry: range is odd in w there, everything else even). Each interval is validated
/// when the table is built: the interpolation at its midpoint is compared with an exact trace, and an interval
/// where any quantity is off by more than the tolerance (relative to its size, and for range also to the path
/// length) is marked for exact tracing. That catches the places where the ray family is not smooth: launches
/// close to the critical one below which rays turn before z_H, and rays grazing a knot. The interpolation error
/// peaks near the interval's middle, so the check bounds it; tests/propagation/test_layered_table.cpp measures it
/// against exact tracing over many rays.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "sss/core/types.hpp"

namespace sss::propagation {

/// A ray where it reaches the table's depth. Plain data.
template <Real T> struct descent_state {
    T range_m{};       ///< horizontal range from the source (m)
    T time_s{};        ///< one-way time (s)
    T path_m{};        ///< arc length (m)
    T absorption_db{}; ///< one-way absorption so far (dB)
    T q_sum{};         ///< ray-tube sum Q (m^2/s), see ray_tube.hpp
    T k_sum{};         ///< ray-tube sum K (m^2/s)
};

template <Real T> class launch_table {
public:
    static constexpr T min_launch_rad = T(1e-3); ///< shallowest launch the table covers (rad)
    static constexpr int nodes_per_unit = 64;     ///< grid nodes per unit of w = ln tan(phi0 / 2)

    /// Builds the table. `exact(sin_phi0, cos_phi0)` returns the exact std::optional<descent_state<T>> of the ray
    /// launched down at inclination phi0, nullopt when it does not reach the table's depth going down all the way.
    /// tolerance: largest relative interpolation error accepted in an interval.
    template <class Exact> launch_table(Exact&& exact, T tolerance) {
        const T w_lo = std::log(std::tan(min_launch_rad / T(2)));
        intervals_ = static_cast<std::size_t>(std::ceil(-w_lo * T(nodes_per_unit)));
        h_ = -w_lo / static_cast<T>(intervals_);
        w0_ = w_lo;
        inv_h_ = T(1) / h_;
        const std::size_t nodes = intervals_ + 1 + 2 * pad; // w0 - 2h ... 0 + 2h
        values_.assign(nodes * fields, T(0));
        std::vector<unsigned char> have(nodes, 0);
        const std::size_t vertical = pad + intervals_; // the node at w = 0
        for (std::size_t k = 0; k <= vertical; ++k) {
            if (const auto s = at(exact, w0_ + h_ * (static_cast<T>(k) - T(pad)))) {
                store(k, *s);
                have[k] = 1;
            }
        }
        for (std::size_t m = 1; m <= pad; ++m) { // beyond the vertical: the mirror images
            const std::size_t from = vertical - m, to = vertical + m;
            if (!have[from]) continue;
            for (std::size_t f = 0; f < fields; ++f) values_[to * fields + f] = values_[from * fields + f];
            values_[to * fields] = -values_[from * fields]; // range is odd about the vertical
            have[to] = 1;
        }
        ok_.assign(intervals_, 0);
        for (std::size_t j = 0; j < intervals_; ++j) {
            if (!std::all_of(have.begin() + static_cast<std::ptrdiff_t>(j),
                             have.begin() + static_cast<std::ptrdiff_t>(j + 2 * pad + 2), [](unsigned char c) { return c != 0; }))
                continue;
            const auto mid = at(exact, w0_ + h_ * (static_cast<T>(j) + T(0.5)));
            if (!mid) continue;
            const descent_state<T> got = interpolate(j, T(0.5));
            bool good = true;
            const T want[fields] = {mid->range_m, mid->time_s, mid->path_m, mid->absorption_db, mid->q_sum, mid->k_sum};
            const T have_v[fields] = {got.range_m, got.time_s, got.path_m, got.absorption_db, got.q_sum, got.k_sum};
            for (std::size_t f = 0; f < fields; ++f) {
                const T scale = f == 0 ? std::max(std::abs(want[f]), mid->path_m) : std::abs(want[f]);
                if (!(std::abs(have_v[f] - want[f]) <= tolerance * scale)) good = false;
            }
            ok_[j] = good ? 1 : 0;
            if (good) ++usable_;
        }
    }

    /// Intervals of the grid, and how many passed validation.
    [[nodiscard]] std::size_t intervals() const noexcept { return intervals_; }
    [[nodiscard]] std::size_t usable_intervals() const noexcept { return usable_; }

    /// The state of the ray launched down at inclination phi0, given as sin_phi0 (> 0) and cos_phi0; nullopt where the
    /// table does not cover it (trace it exactly).
    [[nodiscard]] std::optional<descent_state<T>> lookup(T sin_phi0, T cos_phi0) const noexcept {
        if (!(sin_phi0 > T(0))) return std::nullopt;
        const T w = std::log(sin_phi0 / (T(1) + cos_phi0));
        const T pos = (w - w0_) * inv_h_;
        if (!(pos >= T(0))) return std::nullopt;
        std::size_t j = static_cast<std::size_t>(pos);
        T t = pos - static_cast<T>(j);
        if (j >= intervals_) { j = intervals_ - 1; t = T(1); }
        if (!ok_[j]) return std::nullopt;
        return interpolate(j, t);
    }

private:
    static constexpr std::size_t fields = 6;
    static constexpr std::size_t pad = 2; ///< nodes beyond each end of the grid

    template <class Exact> static std::optional<descent_state<T>> at(Exact& exact, T w) {
        const T u = std::exp(w); // tan(phi0 / 2)
        const T d = T(1) + u * u;
        return exact(T(2) * u / d, (T(1) - u) * (T(1) + u) / d);
    }

    void store(std::size_t k, const descent_state<T>& s) {
        T* v = values_.data() + k * fields;
        v[0] = s.range_m; v[1] = s.time_s; v[2] = s.path_m; v[3] = s.absorption_db; v[4] = s.q_sum; v[5] = s.k_sum;
    }

    /// Six-point Lagrange interpolation in interval j (storage nodes j .. j + 5; the storage starts two nodes early)
    /// at fraction t: weights prod_{m != k} (t - m) / (k - m) over the nodes m = -2 .. 3 around the interval [0, 1].
    [[nodiscard]] descent_state<T> interpolate(std::size_t j, T t) const noexcept {
        T d[6];
        for (int m = 0; m < 6; ++m) d[m] = t - static_cast<T>(m - 2);
        T prefix[7], suffix[7];
        prefix[0] = T(1);
        suffix[6] = T(1);
        for (int m = 0; m < 6; ++m) prefix[m + 1] = prefix[m] * d[m];
        for (int m = 5; m >= 0; --m) suffix[m] = suffix[m + 1] * d[m];
        static constexpr T inverse_denominator[6] = {T(-1.0 / 120), T(1.0 / 24), T(-1.0 / 12), T(1.0 / 12), T(-1.0 / 24),
                                                     T(1.0 / 120)};
        T weight[6];
        for (int m = 0; m < 6; ++m) weight[m] = prefix[m] * suffix[m + 1] * inverse_denominator[m];
        const T* v = values_.data() + j * fields;
        T r[fields] = {};
        for (std::size_t m = 0; m < 6; ++m)
            for (std::size_t f = 0; f < fields; ++f) r[f] += weight[m] * v[m * fields + f];
        return {r[0], r[1], r[2], r[3], r[4], r[5]};
    }

    std::size_t intervals_{};
    std::size_t usable_{};
    T w0_{}, h_{}, inv_h_{};
    std::vector<T> values_;
    std::vector<unsigned char> ok_;
};

} // namespace sss::propagation
