#pragma once
/// \file
/// Internal to labels/ground_truth.hpp: echo energy per sample, kept apart by where it came from.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace sss::detail {

/// Energy per sample, kept apart by source.
struct label_accumulator {
    std::size_t n = 0;
    double dt = 1.0;
    std::vector<double> seabed, bare;           ///< seabed echo in the scene; the bare seabed's echo
    std::vector<double> seabed_best;            ///< largest single seabed contribution, with its ids:
    std::vector<std::uint32_t> seabed_region, seabed_material;
    std::vector<double> bare_best;
    std::vector<std::uint32_t> bare_region, bare_material;
    std::vector<std::uint32_t> ids;             ///< objects met on this line
    std::vector<std::uint32_t> classes;         ///< their class ids
    std::vector<std::vector<double>> echo, blocked, best_echo;
    std::vector<std::vector<std::uint32_t>> echo_material;
    double first_bare_s = std::numeric_limits<double>::infinity();   ///< the bare seabed's first echo (s)
    double last_bare_s = -std::numeric_limits<double>::infinity();   ///< the bare seabed's last direct echo (s)
    double first_seabed_s = std::numeric_limits<double>::infinity(); ///< the scene's first seabed echo (s)
    double last_seabed_s = -std::numeric_limits<double>::infinity(); ///< the scene's last direct seabed echo (s)
    bool met_object = false; ///< some ray of the scene's pass met an object (with or without echo power)

    explicit label_accumulator(std::size_t samples, double dt_s)
        : n(samples), dt(dt_s), seabed(samples), bare(samples), seabed_best(samples), seabed_region(samples),
          seabed_material(samples), bare_best(samples), bare_region(samples), bare_material(samples) {}

    std::size_t slot(std::uint32_t id, std::uint32_t cls) {
        for (std::size_t i = 0; i < ids.size(); ++i)
            if (ids[i] == id) return i;
        ids.push_back(id);
        classes.push_back(cls);
        echo.emplace_back(n, 0.0);
        blocked.emplace_back(n, 0.0);
        best_echo.emplace_back(n, 0.0);
        echo_material.emplace_back(n, 0u);
        return ids.size() - 1;
    }

    /// Adds the share w to total[k]; true when w is the largest single share at k yet (then kept in best[k]), for
    /// the caller to record its ids.
    static bool add(std::vector<double>& total, std::vector<double>& best, std::size_t k, double w) {
        total[k] += w;
        if (!(w > best[k])) return false;
        best[k] = w;
        return true;
    }

    /// Calls f(k, share) for every sample k that [t0, t1] covers, share: the fraction of the span in it.
    template <class F> void spread(double t0, double t1, F&& f) const {
        if (t1 < t0) std::swap(t0, t1);
        const double a = t0 / dt, b = t1 / dt;
        if (!(a < double(n)) || !(b >= 0.0)) return;
        if (b - a <= 0.0) {
            f(static_cast<std::size_t>(a), 1.0);
            return;
        }
        const auto k0 = static_cast<std::size_t>(std::max(0.0, a));
        const std::size_t k1 = std::min(n - 1, static_cast<std::size_t>(b));
        for (std::size_t k = k0; k <= k1; ++k) {
            const double lo = std::max(a, double(k)), hi = std::min(b, double(k + 1));
            if (hi > lo) f(k, (hi - lo) / (b - a));
        }
    }
};

} // namespace sss::detail
