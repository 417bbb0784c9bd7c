#pragma once
// The benchmarks' rough seabed: n x n vertex heights at `cell_m` spacing, the sum of four plane waves (swell 1.5 m
// at 180 m, dunes 0.6 m at 47 m, megaripples 0.25 m at 11 m, ripples 0.08 m at 1.3 m; various directions) plus
// white noise of +-0.05 m from a hash of the vertex index: +-2.5 m in all. Row-major from the south row.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sss_bench {

template <class T> std::vector<T> rough_heights(std::size_t n, double cell_m) {
    struct wave {
        double amplitude_m, wavelength_m, direction_deg, phase;
    };
    constexpr double pi = 3.141592653589793;
    const wave waves[] = {{1.5, 180, 20, 0.3}, {0.6, 47, 75, 1.1}, {0.25, 11, 140, 2.0}, {0.08, 1.3, 30, 0.5}};
    // Each wave evaluated separably: sin(a + b) = sin a cos b + cos a sin b.
    std::vector<double> z(n * n, 0.0), sx(n), cx(n), sy(n), cy(n);
    for (const wave& w : waves) {
        const double k = 2 * pi / w.wavelength_m, dir = w.direction_deg * pi / 180;
        for (std::size_t i = 0; i < n; ++i) {
            const double a = k * std::cos(dir) * double(i) * cell_m, b = k * std::sin(dir) * double(i) * cell_m + w.phase;
            sx[i] = std::sin(a);
            cx[i] = std::cos(a);
            sy[i] = std::sin(b);
            cy[i] = std::cos(b);
        }
        for (std::size_t iy = 0; iy < n; ++iy)
            for (std::size_t ix = 0; ix < n; ++ix) z[iy * n + ix] += w.amplitude_m * (sx[ix] * cy[iy] + cx[ix] * sy[iy]);
    }
    std::vector<T> h(n * n);
    for (std::size_t i = 0; i < h.size(); ++i) {
        std::uint64_t k = (i + 1) * 0x9E3779B97F4A7C15ull;
        k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ull;
        k = (k ^ (k >> 27)) * 0x94D049BB133111EBull;
        k ^= k >> 31;
        h[i] = T(z[i] + 0.1 * (double(k >> 11) * 0x1.0p-53 - 0.5));
    }
    return h;
}

} // namespace sss_bench
