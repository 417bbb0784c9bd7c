#pragma once
/// \file
/// A seeded random number generator whose output is the same on every platform and compiler.
///
/// The standard library's engines are portable but its distributions (`std::normal_distribution`,
/// `std::uniform_real_distribution`) are implementation-defined, so surfaces drawn with them differ
/// between libstdc++, libc++ and MSVC. Everything here is specified to the bit:
///
/// - integers: xoshiro256** (Blackman & Vigna, 2021, "Scrambled linear pseudorandom number generators",
///   ACM Trans. Math. Softw. 47(4) 36), its 256-bit state filled from the 64-bit seed by splitmix64
///   (Steele, Lea & Flood, 2014, "Fast splittable pseudorandom number generators", OOPSLA), as its
///   authors recommend;
/// - uniform doubles: the top 53 bits of one draw times 2^-53, in [0, 1);
/// - normal deviates: Marsaglia's polar method (Marsaglia & Bray, 1964, SIAM Review 6(3) 260-264),
///   whose only transcendental function is a logarithm; it is computed here (`portable_log`) from
///   frexp/ldexp, the four IEEE-754 operations, sqrt and explicit fma, all of which are correctly rounded
///   (and every multiply-add is written as std::fma, so compilers that fuse multiply-adds change nothing):
///   the deviates are bit-identical wherever doubles are IEEE-754 binary64.

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

namespace sss::seabed {

/// One step of splitmix64: advances `state` by the golden-ratio increment and returns a well-mixed
/// 64-bit value. Used to seed xoshiro256** and to derive independent sub-seeds.
[[nodiscard]] constexpr std::uint64_t splitmix64(std::uint64_t& state) noexcept {
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/// A seed for stream number `stream` derived from `seed`: distinct streams give unrelated sequences.
/// Generators inside the seabed synthesis use this so that, e.g., each region's texture and the
/// partition field draw from separate streams of one user seed.
[[nodiscard]] constexpr std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) noexcept {
    std::uint64_t s = seed ^ (0xD1B54A32D192ED03ULL * (stream + 1));
    (void)splitmix64(s);
    return splitmix64(s);
}

/// Natural logarithm of a positive finite double, computed with a fixed sequence of correctly rounded
/// operations so that its result does not depend on the platform's libm or on the compiler's choice to
/// fuse multiply-adds (every multiply-add is an explicit std::fma, itself correctly rounded).
/// x = m 2^e with m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(t), t = (m - 1)/(m + 1), |t| < 0.1716,
/// summed as the odd series t + t^3/3 + ... to t^25 (truncation below 1e-19).
/// Accurate to a few ulp (at most 3 seen over (0, 1]). Returns -inf for 0 and NaN for negative or NaN
/// input (callers pass values in (0, 1]).
[[nodiscard]] inline double portable_log(double x) noexcept {
    if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : std::numeric_limits<double>::quiet_NaN();
    if (x == HUGE_VAL) return x;
    int e = 0;
    double m = 0.0; // x = m 2^e, m in [0.5, 1): exact
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const auto biased = static_cast<int>(bits >> 52); // x > 0: no sign bit
    if (biased != 0) {                                 // a normal number: std::frexp's result, without the call
        m = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFULL) | 0x3FE0000000000000ULL);
        e = biased - 1022;
    } else {
        m = std::frexp(x, &e);
    }
    if (m < 0.70710678118654752440) {
        m *= 2.0; // exact
        e -= 1;
    }
    const double t = (m - 1.0) / (m + 1.0);
    const double t2 = t * t;
    // 1 / (2k + 1), k = 0 .. 12, each the correctly rounded quotient.
    constexpr double c[13] = {1.0 / 1,  1.0 / 3,  1.0 / 5,  1.0 / 7,  1.0 / 9,  1.0 / 11, 1.0 / 13,
                              1.0 / 15, 1.0 / 17, 1.0 / 19, 1.0 / 21, 1.0 / 23, 1.0 / 25};
    double series = c[12];
    for (int k = 11; k >= 0; --k) series = std::fma(t2, series, c[k]);
    // ln 2 split so that e * ln2_hi is exact for |e| < 2^11 (so fusing it with the sum changes nothing).
    constexpr double ln2_hi = 6.93147180369123816490e-01;
    constexpr double ln2_lo = 1.90821492927058770002e-10;
    const double de = static_cast<double>(e);
    return de * ln2_hi + std::fma(de, ln2_lo, 2.0 * t * series);
}

/// xoshiro256** with splitmix64 seeding; satisfies std::uniform_random_bit_generator.
class rng {
public:
    using result_type = std::uint64_t;

    /// Seeds the 256-bit state from a 64-bit seed with four splitmix64 steps (never all zero).
    explicit constexpr rng(std::uint64_t seed) noexcept {
        std::uint64_t s = seed;
        for (auto& w : s_) w = splitmix64(s);
    }

    /// A generator in the given 256-bit state (not all zero), for reproducing published test vectors.
    [[nodiscard]] static constexpr rng from_state(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2,
                                                  std::uint64_t s3) noexcept {
        rng g(0);
        g.s_[0] = s0;
        g.s_[1] = s1;
        g.s_[2] = s2;
        g.s_[3] = s3;
        return g;
    }

    [[nodiscard]] static constexpr result_type min() noexcept { return 0; }
    [[nodiscard]] static constexpr result_type max() noexcept { return ~result_type{0}; }

    /// Next 64-bit output.
    constexpr result_type operator()() noexcept {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }

    /// Uniform double in [0, 1): top 53 bits of one output times 2^-53.
    [[nodiscard]] constexpr double uniform() noexcept { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }

    /// Uniform double in [lo, hi).
    [[nodiscard]] double uniform(double lo, double hi) noexcept { return std::fma(hi - lo, uniform(), lo); }

    /// Standard normal deviate (mean 0, variance 1) by Marsaglia's polar method: draw (u, v) uniform in
    /// the square (-1, 1)^2 until 0 < s = u^2 + v^2 < 1, then u f and v f with f = sqrt(-2 ln(s) / s)
    /// are two independent N(0, 1) deviates; the second is kept for the next call.
    [[nodiscard]] double normal() noexcept {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        double u = 0.0, v = 0.0;
        polar_pair(u, v);
        const double f = polar_factor(u, v);
        spare_ = v * f;
        has_spare_ = true;
        return u * f;
    }

    /// `out.size()` normal deviates: bit for bit those of as many calls of normal() (the spare included), in the
    /// two passes below.
    void normals(std::span<double> out) noexcept {
        const polar_span pairs = draw_polar_pairs(out);
        polar_normals(out.subspan(pairs.begin, pairs.end - pairs.begin));
    }

    /// Where draw_polar_pairs left accepted pairs: out[begin, end), (u, v) alternating, end - begin even.
    struct polar_span {
        std::size_t begin = 0;
        std::size_t end = 0;
    };

    /// The sequential pass of normals(out) (the generator and the rejection, no logarithm): out[0] takes the
    /// spare if there is one, out[begin, end) the accepted uniform pairs (u, v) whose deviates go there, and for
    /// an odd remainder out.size() - 1 its deviate (the pair's second becomes the spare). polar_normals on
    /// out[begin, end), on any number of threads in pieces of even length, then completes normals(out).
    [[nodiscard]] polar_span draw_polar_pairs(std::span<double> out) noexcept {
        const std::size_t n = out.size();
        std::size_t k = 0;
        if (n > 0 && has_spare_) {
            has_spare_ = false;
            out[k++] = spare_;
        }
        const polar_span pairs{k, k + (n - k) / 2 * 2};
        double u = 0.0, v = 0.0;
        for (; k < pairs.end; k += 2) {
            polar_pair(u, v);
            out[k] = u;
            out[k + 1] = v;
        }
        if (k < n) {
            polar_pair(u, v);
            const double f = polar_factor(u, v);
            out[k] = u * f;
            spare_ = v * f;
            has_spare_ = true;
        }
        return pairs;
    }

    /// The second pass of normals(): turns accepted pairs (u, v) (alternating, even length) into their two
    /// deviates (u f, v f) in place. The pairs are independent, so the processor overlaps their logarithms.
    /// Built with GCC or Clang for x86-64 without FMA instructions enabled, it runs a copy compiled for them
    /// when the processor has them: std::fma is correctly rounded in hardware as in the library, so the deviates
    /// are the same bits, only the library call for each multiply-add is saved.
    static void polar_normals(std::span<double> pairs) noexcept {
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(__FMA__)
        static const bool fma = [] {
            __builtin_cpu_init();
            return __builtin_cpu_supports("fma") != 0;
        }();
        if (fma) {
            polar_normals_fma(pairs);
            return;
        }
#endif
        polar_normals_loop(pairs);
    }

private:
    static constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }

    /// The polar method's next accepted pair: (u, v) uniform in (-1, 1)^2 until 0 < u^2 + v^2 < 1.
    void polar_pair(double& u, double& v) noexcept {
        double s = 0.0;
        do {
            u = 2.0 * uniform() - 1.0;
            v = 2.0 * uniform() - 1.0;
            s = std::fma(u, u, v * v);
        } while (!(s < 1.0) || s == 0.0);
    }

    static void polar_normals_loop(std::span<double> pairs) noexcept {
        for (std::size_t k = 0; k + 1 < pairs.size(); k += 2) {
            const double f = polar_factor(pairs[k], pairs[k + 1]);
            pairs[k] *= f;
            pairs[k + 1] *= f;
        }
    }

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(__FMA__)
    /// polar_normals_loop compiled for FMA instructions (its calls inlined here compile for them too).
    [[gnu::target("fma")]] static void polar_normals_fma(std::span<double> pairs) noexcept {
        for (std::size_t k = 0; k + 1 < pairs.size(); k += 2) {
            const double f = polar_factor(pairs[k], pairs[k + 1]);
            pairs[k] *= f;
            pairs[k + 1] *= f;
        }
    }
#endif

    /// The polar method's factor f = sqrt(-2 ln(s) / s), s = u^2 + v^2, of an accepted pair.
    [[nodiscard]] static double polar_factor(double u, double v) noexcept {
        const double s = std::fma(u, u, v * v);
        return std::sqrt(-2.0 * portable_log(s) / s);
    }

    std::uint64_t s_[4]{};
    double spare_ = 0.0;
    bool has_spare_ = false;
};

} // namespace sss::seabed
