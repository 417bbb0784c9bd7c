#pragma once
/// \file
/// Counter-based random numbers: every variate is a pure function of a 64-bit key (seed and what the variate is
/// attached to), so a result never depends on thread, call order or how a job is split.
///
/// - `mix`: the SplitMix64 finaliser (Steele, Lea & Flood, "Fast splittable pseudorandom number generators",
///   OOPSLA 2014), a bijective avalanche hash of 64 bits.
/// - Gaussian variates by table: 2^13 half-normal magnitudes at stratified quantiles Phi^-1(1/2 + (i + 1/2)/2^14),
///   rescaled to unit second moment, each picked by 13 hash bits and given a sign by another: zero mean and unit
///   variance exactly, the normal distribution to within its 2^-14 quantile spacing (tails to 4 sigma), for the
///   price of one hash. Speckle sums many of them, so its field is circular Gaussian to well within any test.
/// - `gaussian_exact` (Box-Muller, Box & Muller, Ann. Math. Stat. 29, 1958) and `gamma_unit_mean`
///   (Marsaglia & Tsang, ACM TOMS 26(3), 2000) where exactness matters more than speed.

#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>

#include "sss/core/constants.hpp"

namespace sss::detail {

/// SplitMix64 finaliser.
[[nodiscard]] constexpr std::uint64_t mix(std::uint64_t x) noexcept {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

/// A key from a running key and one more coordinate.
[[nodiscard]] constexpr std::uint64_t mix(std::uint64_t key, std::uint64_t value) noexcept {
    return mix(key ^ (value * 0xD6E8FEB86659FD93ULL));
}

/// A cheaper hash of a well-mixed key and one more coordinate, for the innermost loops: two multiply-xorshift
/// rounds (the "moremur" constants of Evensen, 2019), enough to decorrelate neighbouring lattice cells.
[[nodiscard]] constexpr std::uint64_t mix_fast(std::uint64_t key, std::uint64_t value) noexcept {
    std::uint64_t x = key ^ (value * 0x9E3779B97F4A7C15ULL);
    x = (x ^ (x >> 27)) * 0x3C79AC492BA7B653ULL;
    x = (x ^ (x >> 33)) * 0x1C69B3F74AC4AE35ULL;
    return x ^ (x >> 27);
}

/// A signed coordinate as a key word.
[[nodiscard]] constexpr std::uint64_t key_word(std::int64_t v) noexcept { return static_cast<std::uint64_t>(v); }

/// floor(x) as an integer, without a library call (|x| < 2^63).
[[nodiscard]] inline std::int64_t floor_to_int(double x) noexcept {
    const auto i = static_cast<std::int64_t>(x);
    return static_cast<double>(i) > x ? i - 1 : i;
}

/// Uniform in (0, 1) from 53 bits of a hash.
[[nodiscard]] inline double uniform_open(std::uint64_t h) noexcept {
    return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

/// Upper-tail standard normal quantile x with Q(x) = q, 0 < q <= 1/2: the rational start of Abramowitz & Stegun
/// (1964) 26.2.23 polished by Newton steps on erfc.
[[nodiscard]] inline double normal_upper_quantile(double q) noexcept {
    const double t = std::sqrt(-2.0 * std::log(q));
    double x = t - (2.515517 + 0.802853 * t + 0.010328 * t * t) / (1.0 + 1.432788 * t + 0.189269 * t * t + 0.001308 * t * t * t);
    for (int it = 0; it < 3; ++it) {
        const double f = 0.5 * std::erfc(x / std::sqrt(2.0)) - q;
        const double pdf = std::exp(-0.5 * x * x) / std::sqrt(2.0 * pi_v<double>);
        x += f / pdf;
    }
    return x;
}

inline constexpr std::size_t gaussian_table_bits = 13;
inline constexpr std::size_t gaussian_table_size = std::size_t(1) << gaussian_table_bits;

/// The half-normal magnitudes, scaled to a second moment of 1/2 (one component of a unit-power complex variate).
[[nodiscard]] inline const std::array<float, gaussian_table_size>& half_normal_table() {
    static const std::array<float, gaussian_table_size> table = [] {
        std::array<double, gaussian_table_size> m{};
        double second = 0.0;
        for (std::size_t i = 0; i < gaussian_table_size; ++i) {
            const double q = 0.5 - (double(i) + 0.5) / double(2 * gaussian_table_size);
            m[i] = normal_upper_quantile(q);
            second += m[i] * m[i];
        }
        const double scale = std::sqrt(0.5 * double(gaussian_table_size) / second);
        std::array<float, gaussian_table_size> out{};
        for (std::size_t i = 0; i < gaussian_table_size; ++i) out[i] = static_cast<float>(m[i] * scale);
        return out;
    }();
    return table;
}

/// Circular complex Gaussian of unit mean power (E|z|^2 = 1) from one hash value (signs set without branches).
[[nodiscard]] inline std::complex<float> complex_gaussian(std::uint64_t h, const std::array<float, gaussian_table_size>& table) noexcept {
    constexpr std::uint64_t mask = gaussian_table_size - 1;
    const auto re = std::bit_cast<std::uint32_t>(table[h & mask]) ^ (static_cast<std::uint32_t>(h >> 13) & 1U) << 31;
    const auto im = std::bit_cast<std::uint32_t>(table[(h >> 14) & mask]) ^ (static_cast<std::uint32_t>(h >> 27) & 1U) << 31;
    return {std::bit_cast<float>(re), std::bit_cast<float>(im)};
}

/// Standard normal by Box-Muller from two hash values.
[[nodiscard]] inline double gaussian_exact(std::uint64_t h1, std::uint64_t h2) noexcept {
    return std::sqrt(-2.0 * std::log(uniform_open(h1))) * std::cos(2.0 * pi_v<double> * uniform_open(h2));
}

/// Gamma(shape nu, scale 1/nu): unit mean, variance 1/nu (Marsaglia & Tsang 2000; for nu < 1 their boost
/// Gamma(nu) = Gamma(nu + 1) U^(1/nu)). The variates are drawn from the counter stream mix(key, 0, 1, 2, ...).
[[nodiscard]] inline double gamma_unit_mean(double nu, std::uint64_t key) noexcept {
    std::uint64_t counter = 0;
    auto next = [&] { return mix(key, counter++); };
    const double shape = nu < 1.0 ? nu + 1.0 : nu;
    const double d = shape - 1.0 / 3.0;
    const double c = 1.0 / std::sqrt(9.0 * d);
    double g = d;
    for (int attempt = 0; attempt < 64; ++attempt) {
        const double x = gaussian_exact(next(), next());
        double v = 1.0 + c * x;
        if (v <= 0.0) continue;
        v = v * v * v;
        const double u = uniform_open(next());
        if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) {
            g = d * v;
            break;
        }
    }
    if (nu < 1.0) g *= std::pow(uniform_open(next()), 1.0 / nu);
    return g / nu;
}

} // namespace sss::detail
