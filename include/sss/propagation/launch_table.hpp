#pragma once
/// \file
/// A table of the rays launched down from one depth, where they first reach a deeper one, indexed by launch angle.
///
/// Every ray of a ping starts at the same point, and by the water's cylindrical symmetry a ray's path down to a
/// depth z_H (the depth from which the scene's geometry begins) depends on its launch inclination phi0 alone. The
/// table holds, for phi0 on a grid, the ray's state at z_H on its way down: horizontal range, time, path length,
/// absorption (dB, and as an intensity ratio) and the two ray-tube sums (ray_tube.hpp); the inclination there
/// follows exactly from Snell's law, cos(phi_H) = c(z_H) cos(phi0) / c(z_A). A ray looks its state up by six-point
/// Lagrange interpolation and is traced exactly from z_H on; what the table replaces is the stepping through the
/// layers above the geometry.
///
/// The grid is uniform in w = ln tan(phi0 / 2), so that nodes crowd towards grazing launches, where range changes
/// fastest (in uniform water range ~ 1/phi0 ~ e^-w, and the tube sum K ~ e^-2w: the interpolation error is then
/// the same fraction of each everywhere, about 5e-3 (r h)^6 relative for grid step h and growth rate r, below
/// 1e-11 here); tan(phi0/2) = sin(phi0) / (1 + cos(phi0)) needs no trigonometry from a ray direction.
/// It spans phi0 from 1e-3 rad to the vertical with 64 nodes per unit of w (about 490), plus two nodes beyond each
/// end (beyond the vertical by symmetry: range is odd in w there, everything else even). The interpolating quintic
/// of each interval (through its six surrounding nodes) is stored as its power series in the interval's own
/// coordinate t in [0, 1), worked out in long double when the table is built, so that a lookup is one logarithm and
/// seven Horner evaluations of degree five (no weights to form, no search; 336 bytes an interval, 164 kB a table in
/// double). Grids that avoid the logarithm, read off the floating-point exponent and mantissa of u, were measured
/// on uniform water and lose: uniform in u within each octave (64 intervals an octave, 704 in all), worst errors
/// 4e-11 in range and 3e-10 in K against 7e-14 and 4.5e-12 here; u quadratic in t within each octave (48 an octave,
/// one square root a lookup), 5e-12 and 4e-11. 1/u and 1/u^2 are far smoother in ln u than in any such coordinate.
///
/// The absorption ratio 10^(-dB/10) is interpolated too, so that a ray resuming from the table needs no exponential;
/// an interval uses it only where, at its midpoint, it is within twice the error of the ratio of the interpolated dB
/// (and 64 roundings), else the lookup takes 10^(-dB/10) of the interpolated dB. Long grazing paths, where the ratio
/// is far less smooth than the dB, fall back so; the ratio plays no part in validation.
///
/// Each interval is validated when the table is built: the interpolation at its midpoint is compared with an exact
/// trace, and an interval where any quantity is off by more than the tolerance (relative to its size, and for range
/// also to the path length) is marked for exact tracing. That catches the places where the ray family is not
/// smooth: launches close to the critical one below which rays turn before z_H, and rays grazing a knot. The
/// interpolation error peaks near the interval's middle, so the check bounds it; tests/propagation/
/// test_layered_table.cpp measures it against exact tracing over many rays.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "sss/core/constants.hpp"
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
    T absorption{};    ///< absorption_db as an intensity ratio, 10^(-absorption_db / 10): set by the table's lookup
                       ///< (interpolated where that is about as accurate, else from absorption_db)
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
        std::vector<std::array<T, fields>> value(nodes);
        std::vector<unsigned char> have(nodes, 0);
        const std::size_t vertical = pad + intervals_; // the node at w = 0
        for (std::size_t k = 0; k <= vertical; ++k) {
            if (const auto s = at(exact, w0_ + h_ * (static_cast<T>(k) - T(pad)))) {
                value[k] = {s->range_m, s->time_s, s->path_m, s->absorption_db, s->q_sum, s->k_sum, ratio(s->absorption_db)};
                have[k] = 1;
            }
        }
        for (std::size_t m = 1; m <= pad; ++m) { // beyond the vertical: the mirror images
            const std::size_t from = vertical - m, to = vertical + m;
            if (!have[from]) continue;
            value[to] = value[from];
            value[to][0] = -value[from][0]; // range is odd about the vertical
            have[to] = 1;
        }
        const auto basis = lagrange_power_series();
        coefficients_.assign(intervals_ * fields * terms, T(0));
        ok_.assign(intervals_, 0);
        for (std::size_t j = 0; j < intervals_; ++j) {
            // Interval j (nodes j + pad, j + pad + 1 in storage) is interpolated through storage nodes j .. j + 5.
            if (!std::all_of(have.begin() + static_cast<std::ptrdiff_t>(j),
                             have.begin() + static_cast<std::ptrdiff_t>(j + terms), [](unsigned char c) { return c != 0; }))
                continue;
            T* c = coefficients_.data() + j * fields * terms;
            for (std::size_t d = 0; d < terms; ++d)
                for (std::size_t f = 0; f < fields; ++f) {
                    long double sum = 0;
                    for (std::size_t m = 0; m < terms; ++m) sum += basis[m][d] * static_cast<long double>(value[j + m][f]);
                    c[d * fields + f] = static_cast<T>(sum);
                }
            const auto mid = at(exact, w0_ + h_ * (static_cast<T>(j) + T(0.5)));
            if (!mid) continue;
            const descent_state<T> got = evaluate(j, T(0.5));
            bool good = true;
            const T want[fields] = {mid->range_m, mid->time_s, mid->path_m, mid->absorption_db, mid->q_sum, mid->k_sum,
                                    ratio(mid->absorption_db)};
            const T have_v[fields] = {got.range_m, got.time_s, got.path_m, got.absorption_db, got.q_sum, got.k_sum,
                                      got.absorption};
            for (std::size_t f = 0; f + 1 < fields; ++f) {
                const T scale = f == 0 ? std::max(std::abs(want[f]), mid->path_m) : std::abs(want[f]);
                if (!(std::abs(have_v[f] - want[f]) <= tolerance * scale)) good = false;
            }
            if (!good) continue;
            ++usable_;
            ok_[j] = usable;
            // The ratio's own interpolation only where it is about as accurate as 10^(-dB/10) of the interpolated dB
            // (within twice its error and 64 roundings, at the midpoint): not where absorption is large and changes
            // fast (long grazing paths), where the ratio is far less smooth than the dB.
            const T r_want = want[fields - 1];
            const T e_ratio = std::abs(have_v[fields - 1] - r_want), e_db = std::abs(ratio(got.absorption_db) - r_want);
            if (e_ratio <= T(2) * e_db + T(64) * std::numeric_limits<T>::epsilon() * r_want) ok_[j] |= ratio_usable;
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
        if (!(ok_[j] & usable)) return std::nullopt;
        descent_state<T> d = evaluate(j, t);
        if (!(ok_[j] & ratio_usable)) d.absorption = ratio(d.absorption_db);
        return d;
    }

private:
    static constexpr std::size_t fields = 7; ///< the six of descent_state, and absorption as a ratio
    static constexpr std::size_t terms = 6; ///< nodes of each interval's quintic, and its coefficients
    static constexpr std::size_t pad = 2;   ///< nodes beyond each end of the grid
    static constexpr unsigned char usable = 1, ratio_usable = 2; ///< interval flags: passed validation, and the ratio too

    /// 10^(-db / 10).
    static T ratio(T db) noexcept { return std::exp(T(-0.1) * ln10_v<T> * db); }

    template <class Exact> static std::optional<descent_state<T>> at(Exact& exact, T w) {
        const T u = std::exp(w); // tan(phi0 / 2)
        const T d = T(1) + u * u;
        return exact(T(2) * u / d, (T(1) - u) * (T(1) + u) / d);
    }

    /// basis[m][d]: the coefficient of t^d in the Lagrange polynomial of node m - 2 among the nodes -2 .. 3,
    /// prod_{n != m} (t - (n - 2)) / ((m - 2) - (n - 2)).
    static std::array<std::array<long double, terms>, terms> lagrange_power_series() {
        std::array<std::array<long double, terms>, terms> basis{};
        for (std::size_t m = 0; m < terms; ++m) {
            std::array<long double, terms> p{};
            p[0] = 1;
            std::size_t degree = 0;
            for (std::size_t n = 0; n < terms; ++n) {
                if (n == m) continue;
                const long double node = static_cast<long double>(n) - 2, inv = 1.0L / (static_cast<long double>(m) - static_cast<long double>(n));
                ++degree;
                for (std::size_t d = degree + 1; d-- > 0;) p[d] = ((d > 0 ? p[d - 1] : 0.0L) - node * p[d]) * inv;
            }
            basis[m] = p;
        }
        return basis;
    }

    /// The quintic of interval j at t in [0, 1], by Horner's rule.
    [[nodiscard]] descent_state<T> evaluate(std::size_t j, T t) const noexcept {
        const T* c = coefficients_.data() + j * fields * terms;
        // One quantity at a time, written out, so that the seven chains stay in registers and interleave.
        const auto horner = [c, t](std::size_t f) {
            T v = c[5 * fields + f];
            v = v * t + c[4 * fields + f];
            v = v * t + c[3 * fields + f];
            v = v * t + c[2 * fields + f];
            v = v * t + c[fields + f];
            return v * t + c[f];
        };
        static_assert(terms == 6);
        return {horner(0), horner(1), horner(2), horner(3), horner(4), horner(5), horner(6)};
    }

    std::size_t intervals_{};
    std::size_t usable_{};
    T w0_{}, h_{}, inv_h_{};
    std::vector<T> coefficients_; ///< per interval, per power of t, per quantity
    std::vector<unsigned char> ok_;
};

} // namespace sss::propagation
