#pragma once
/// \file
/// Internal to seabed/composite.hpp: separable Gaussian smoothing of a raster, one direction at a time.
/// Not part of the API.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sss::seabed::detail {

/// 1D Gaussian smoothing (standard deviation sigma cells, truncated at 4 sigma, edges clamped) of
/// each row (stride 1) or column (stride nx) of `v` in place.
inline void gaussian_pass(std::vector<double>& v, std::size_t nx, std::size_t ny, double sigma_cells, bool rows) {
    const auto radius = static_cast<std::ptrdiff_t>(std::ceil(4.0 * sigma_cells));
    std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
    double sum = 0.0;
    for (std::ptrdiff_t k = -radius; k <= radius; ++k) {
        const double x = static_cast<double>(k) / sigma_cells;
        sum += kernel[static_cast<std::size_t>(k + radius)] = std::exp(-0.5 * x * x);
    }
    for (double& k : kernel) k /= sum;
    const std::size_t lines = rows ? ny : nx, len = rows ? nx : ny;
    const std::size_t step = rows ? 1 : nx;
    std::vector<double> line(len);
    for (std::size_t l = 0; l < lines; ++l) {
        const std::size_t base = rows ? l * nx : l;
        for (std::size_t i = 0; i < len; ++i) line[i] = v[base + i * step];
        for (std::size_t i = 0; i < len; ++i) {
            double acc = 0.0;
            for (std::ptrdiff_t k = -radius; k <= radius; ++k) {
                const std::ptrdiff_t j = std::clamp<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(i) + k, 0,
                                                                    static_cast<std::ptrdiff_t>(len) - 1);
                acc += kernel[static_cast<std::size_t>(k + radius)] * line[static_cast<std::size_t>(j)];
            }
            v[base + i * step] = acc;
        }
    }
}

} // namespace sss::seabed::detail
