#pragma once
/// \file
/// How a beam's two-way pattern divides in depression, for the water column's echo.
///
/// The equivalent two-way beam solid angle (Urick, "Principles of Underwater Sound", 3rd ed., 1983, ch. 8) is
///
///     Psi = int w(along, depression) dOmega   (sr),   dOmega = cos(along) d(along) d(depression),
///
/// w the beam's two-way weight (Beam concept: 1 on the maximum axis). Volume reverberation at slant range r comes
/// from the spherical shell of radius r within the beam; over a flat seabed at altitude H < r, the directions
/// deeper than asin(H / r) meet the seabed before r, so only the share of Psi at shallower depressions
/// insonifies water there. `elevation_share` tabulates that share against the body-frame depression.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sss/beam/concept.hpp"
#include "sss/core/error.hpp"

namespace sss {

/// Psi and its share at body depressions shallower than a given one, for one side of a beam.
struct elevation_share {
    double psi_sr = 0.0;            ///< int w dOmega over the beam's extent (sr)
    double depression_lo_rad = 0.0; ///< the extent's shallowest depression (rad)
    double step_rad = 0.0;          ///< the table's step in depression (rad)
    std::vector<double> shallower{}; ///< shallower[i]: share of Psi at depressions below lo + i step (0 to 1)

    /// The share of Psi at body depressions shallower than depression_rad (0 to 1), linear between the table's
    /// points; 1 where nothing is tabulated.
    [[nodiscard]] double at(double depression_rad) const noexcept {
        if (shallower.size() < 2 || !(step_rad > 0.0)) return 1.0;
        if (std::isnan(depression_rad)) return 1.0;
        const double x = (depression_rad - depression_lo_rad) / step_rad;
        if (!(x > 0.0)) return 0.0;
        const double last = double(shallower.size() - 1);
        if (!(x < last)) return 1.0;
        const auto i = static_cast<std::size_t>(x);
        const double f = x - double(i);
        return shallower[i] + f * (shallower[i + 1] - shallower[i]);
    }
};

/// The elevation share of `beam` on side `s`: midpoint quadrature of w cos(along) over its extent, `depressions`
/// cells in depression and `alongs` along track (the defaults resolve a planar array's main lobe and first
/// sidelobes to well under 1 % of Psi).
template <Beam B>
[[nodiscard]] elevation_share elevation_share_of(const B& beam, side s, std::size_t depressions = 512, std::size_t alongs = 128) {
    using T = typename B::value_type;
    sss::require(depressions >= 1 && alongs >= 1, "elevation_share_of", "needs at least one cell each way");
    const beam_extent<T> e = beam.extent(s);
    const double a0 = double(e.along_min_rad), a1 = double(e.along_max_rad);
    const double d0 = double(e.depression_min_rad), d1 = double(e.depression_max_rad);
    elevation_share out;
    if (!(a1 > a0) || !(d1 > d0)) return out;
    const double da = (a1 - a0) / double(alongs), dd = (d1 - d0) / double(depressions);
    out.depression_lo_rad = d0;
    out.step_rad = dd;
    out.shallower.assign(depressions + 1, 0.0);
    double sum = 0.0;
    for (std::size_t i = 0; i < depressions; ++i) {
        const double d = d0 + (double(i) + 0.5) * dd;
        double row = 0.0;
        for (std::size_t j = 0; j < alongs; ++j) {
            const double a = a0 + (double(j) + 0.5) * da;
            row += double(beam.weight(s, T(a), T(d))) * std::cos(a);
        }
        sum += row * da * dd;
        out.shallower[i + 1] = sum;
    }
    out.psi_sr = sum;
    if (sum > 0.0)
        for (double& v : out.shallower) v = std::min(1.0, v / sum);
    return out;
}

} // namespace sss
