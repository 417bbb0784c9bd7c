#pragma once
/// \file
/// Sand ripples: periodic crests with a stoss/lee profile, crest sinuosity and fractal perturbation;
/// several sets (e.g. small ripples on large ones) superpose.
///
/// Geometry. Crests run along `crest_heading_deg` (clockwise from north, docs/conventions.md; 0: crests run
/// north-south), i.e. along c = (cos theta, sin theta) with theta = 90 deg - crest_heading_deg the angle
/// counter-clockwise from +x (east). The ripples migrate along the normal n = (sin theta, -cos theta) (c turned clockwise by
/// 90 degrees): the gentle stoss side faces -n (upstream), the steep lee side faces +n. At raster-local
/// position x the phase is
///   s(x) = [x . n + d(x)] / lambda + phase_rad / (2 pi),
///   d(x) = sinuosity_m sin(2 pi (x . c) / sinuosity_wavelength_m) + perturbation_m g1(x)   (m)
/// and the height is z(x) = height_m [1 + height_variation g2(x)]_+ p(frac(s)), where g1, g2 are
/// independent fractal fields of unit RMS (power law, exponent perturbation_gamma, outer scale
/// perturbation_scale_m; see fractal.hpp) and p is the unit profile below.
///
/// Profile and asymmetry. The ripple symmetry index RSI = L_stoss / L_lee, the ratio of the horizontal
/// lengths of the stoss and lee sides (Tanner, 1967, Sedimentology 9, 89-104: RSI near 1 for wave
/// ripples, about 2 to 4 or more for current ripples), fixes the stoss fraction f = RSI / (1 + RSI) of a
/// wavelength. With q = frac(s) in [0, 1):
///   p(q) = -cos(pi q / f) / 2             for q < f      (stoss: trough at q = 0 up to the crest at q = f)
///   p(q) = +cos(pi (q - f) / (1 - f)) / 2 for q >= f     (lee: crest down to the next trough)
/// p is continuous with continuous slope, has zero mean, crest-to-trough height 1 and RMS 1/(2 sqrt 2);
/// the mean stoss and lee slopes are H / (f lambda) and H / ((1 - f) lambda), whose ratio is RSI, and the
/// fraction of the plan area where the surface rises along n is f.

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/thread_pool.hpp"
#include "sss/seabed/detail/cosine.hpp"
#include "sss/seabed/detail/unit_fractal.hpp"
#include "sss/seabed/fractal.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"

namespace sss::seabed {

/// One set of ripples (see the file comment for the geometry).
template <Real T> struct ripple_params {
    T wavelength_m = T(0.5);         ///< crest-to-crest spacing lambda (m), >= 2 cells
    T height_m = T(0.05);            ///< crest-to-trough height H (m), >= 0
    T crest_heading_deg = T(90);     ///< direction along the crests, clockwise from north (deg); 90: crests run east
    T symmetry_index = T(1);         ///< RSI = stoss length / lee length, > 0 (1: symmetric)
    T phase_rad = T(0);              ///< phase added to s (rad): the crests move by lambda phase / (2 pi) against n
    T sinuosity_m = T(0);            ///< amplitude of the regular crest meander along n (m), >= 0
    T sinuosity_wavelength_m = T(0); ///< along-crest wavelength of the meander (m), > 0 if sinuosity_m > 0
    T perturbation_m = T(0);         ///< RMS fractal displacement of the crests along n (m), >= 0
    T height_variation = T(0);       ///< RMS relative fractal variation of the height, in [0, 1]
    T perturbation_scale_m = T(0);   ///< outer scale of the fractal fields (m); 0: 4 wavelengths
    T perturbation_gamma = T(3.5);   ///< spectral exponent of the fractal fields, in (2, 4)
};

/// Throws invalid_parameter naming the offending field (prefixed by `who`) for a grid spacing cell_m.
template <Real T> void validate(const ripple_params<T>& p, T cell_m, const std::string& who) {
    sss::require_positive(p.wavelength_m, who + ".wavelength_m");
    sss::require(p.wavelength_m >= T(2) * cell_m, who + ".wavelength_m",
                    [&] { return "must be at least 2 cells (" + std::to_string(T(2) * cell_m) + " m) to be resolved, got " +
                        std::to_string(p.wavelength_m); });
    sss::require_non_negative(p.height_m, who + ".height_m");
    sss::require_finite(p.crest_heading_deg, who + ".crest_heading_deg");
    sss::require_positive(p.symmetry_index, who + ".symmetry_index");
    sss::require_finite(p.phase_rad, who + ".phase_rad");
    sss::require_non_negative(p.sinuosity_m, who + ".sinuosity_m");
    sss::require_non_negative(p.sinuosity_wavelength_m, who + ".sinuosity_wavelength_m");
    sss::require_positive_when(p.sinuosity_m != T(0), p.sinuosity_wavelength_m, who + ".sinuosity_wavelength_m",
                               "sinuosity_m > 0");
    sss::require_non_negative(p.perturbation_m, who + ".perturbation_m");
    sss::require_in_range(p.height_variation, T(0), T(1), who + ".height_variation");
    sss::require_non_negative(p.perturbation_scale_m, who + ".perturbation_scale_m");
    sss::require_finite(p.perturbation_gamma, who + ".perturbation_gamma");
    sss::require(p.perturbation_gamma > T(2) && p.perturbation_gamma < T(4), who + ".perturbation_gamma",
                    "must lie in (2, 4)");
}

/// The unit ripple profile p(q) (crest-to-trough 1, zero mean) at phase fraction q in [0, 1) for stoss
/// fraction f = RSI / (1 + RSI) (see the file comment).
template <Real T> [[nodiscard]] inline T ripple_profile(T q, T stoss_fraction) noexcept {
    if (q < stoss_fraction) return -T(0.5) * std::cos(pi_v<T> * q / stoss_fraction);
    return T(0.5) * std::cos(pi_v<T> * (q - stoss_fraction) / (T(1) - stoss_fraction));
}

/// Adds one set of ripples to `h` (heights in m). Same (h, p, seed), same result.
template <Real T> void add_ripples(raster<T>& h, const ripple_params<T>& p, std::uint64_t seed) {
    require_grid(h.nx, h.ny, h.cell_m, "add_ripples.h");
    sss::require(h.values.size() == h.nx * h.ny, "add_ripples.h.values", "size differs from nx * ny");
    validate(p, h.cell_m, "add_ripples.params");
    const double lambda = static_cast<double>(p.wavelength_m);
    const double theta = heading_to_ccw_from_east_rad(static_cast<double>(p.crest_heading_deg));
    const double cx = std::cos(theta), cy = std::sin(theta); // along the crests
    const double mx = cy, my = -cx;                          // migration direction n
    const double rsi = static_cast<double>(p.symmetry_index);
    const double f = rsi / (1.0 + rsi);
    const double sin_amp = static_cast<double>(p.sinuosity_m);
    const double sin_k = sin_amp > 0.0 ? two_pi_v<double> / static_cast<double>(p.sinuosity_wavelength_m) : 0.0;
    const double l0 = p.perturbation_scale_m > T(0) ? static_cast<double>(p.perturbation_scale_m) : 4.0 * lambda;

    // The crest displacement g1 and the height variation g2, drawn in step (detail::unit_fractal_pair), stored as T:
    // g1 in `a`, g2 in `b` (or g2 alone in `a`).
    const bool shifted = p.perturbation_m > T(0), modulated = p.height_variation > T(0);
    detail::fractal_pair<T> fields;
    if (shifted || modulated)
        fields = detail::unit_fractal_pair<T>(h.nx, h.ny, h.cell_m, p.perturbation_gamma, static_cast<T>(l0),
                                              derive_seed(seed, shifted ? 1 : 2), derive_seed(seed, 2),
                                              shifted && modulated);
    const T* shift = shifted ? fields.a.data() : nullptr;
    const T* modulation = modulated ? (shifted ? fields.b.data() : fields.a.data()) : nullptr;

    // The profile of ripple_profile in double, its cosine inline (detail::cos_0_pi: within a rounding of std::cos;
    // the library call would take most of the time).
    const auto profile = [f](double q) {
        if (q < f) return -0.5 * detail::cos_0_pi(pi_v<double> * q / f);
        return 0.5 * detail::cos_0_pi(pi_v<double> * (q - f) / (1.0 - f));
    };
    // Each sample on its own: rows are shared among the threads of shared_thread_pool().
    const double dx = static_cast<double>(h.cell_m);
    const double phase0 = static_cast<double>(p.phase_rad) / two_pi_v<double>;
    const double height = static_cast<double>(p.height_m), perturbation = static_cast<double>(p.perturbation_m);
    const double variation = static_cast<double>(p.height_variation);
    constexpr std::size_t rows_per_task = 16;
    shared_thread_pool().for_each(
        (h.ny + rows_per_task - 1) / rows_per_task,
        [&](std::size_t task) {
            const std::size_t y1 = std::min(h.ny, (task + 1) * rows_per_task);
            for (std::size_t iy = task * rows_per_task; iy < y1; ++iy) {
                const double y = static_cast<double>(iy) * dx;
                for (std::size_t ix = 0; ix < h.nx; ++ix) {
                    const double x = static_cast<double>(ix) * dx;
                    const std::size_t k = iy * h.nx + ix;
                    double d = 0.0;
                    if (sin_amp > 0.0) d += sin_amp * std::sin(sin_k * (x * cx + y * cy));
                    if (shift) d += perturbation * static_cast<double>(shift[k]);
                    const double s = (x * mx + y * my + d) / lambda + phase0;
                    const double q = s - std::floor(s);
                    double amp = height;
                    if (modulation) amp *= std::max(0.0, 1.0 + variation * static_cast<double>(modulation[k]));
                    h.values[k] += static_cast<T>(amp * profile(q));
                }
            }
        },
        h.nx * h.ny >= (std::size_t(1) << 16) ? 0u : 1u);
}

/// A raster of nx x ny samples holding the sum of the given ripple sets (set i uses stream i of `seed`).
template <Real T> [[nodiscard]] raster<T> ripple_field(std::size_t nx, std::size_t ny, T cell_m,
                                                       std::span<const ripple_params<T>> sets, std::uint64_t seed) {
    raster<T> h = make_raster<T, T>(nx, ny, cell_m, T(0));
    for (std::size_t i = 0; i < sets.size(); ++i) add_ripples(h, sets[i], derive_seed(seed, 100 + i));
    return h;
}

/// ripple_field() for ripple sets held in a vector.
template <Real T> [[nodiscard]] raster<T> ripple_field(std::size_t nx, std::size_t ny, T cell_m,
                                                       const std::vector<ripple_params<T>>& sets, std::uint64_t seed) {
    return ripple_field<T>(nx, ny, cell_m, std::span<const ripple_params<T>>(sets), seed);
}

/// A raster of nx x ny samples holding one set of ripples.
template <Real T> [[nodiscard]] raster<T> ripple_field(std::size_t nx, std::size_t ny, T cell_m,
                                                       const ripple_params<T>& p, std::uint64_t seed) {
    return ripple_field<T>(nx, ny, cell_m, std::span<const ripple_params<T>>(&p, 1), seed);
}

} // namespace sss::seabed
