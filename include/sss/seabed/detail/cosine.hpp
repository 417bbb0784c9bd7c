#pragma once
/// \file
/// Internal to the ripple synthesis: the cosine of an angle in [0, pi] inline, without a library call, for loops
/// that evaluate one per sample. Not part of the API.
///
/// Method: the angle is brought into [0, pi/4] by cos x = sin(pi/2 - x) on (pi/4, 3 pi/4] and
/// cos x = -cos(pi - x) on (3 pi/4, pi], with pi/2 and pi each split into a double and its remainder so that the
/// reduced angle keeps its accuracy (Cody & Waite, 1980, Software Manual for the Elementary Functions,
/// Prentice-Hall, chapters 8 and 9; the subtractions x' - x are exact by Sterbenz's lemma on these intervals).
/// On [0, pi/4] the Taylor series of cos to x^16 and of sin to x^17 are summed by Horner's rule; the first
/// neglected terms are below (pi/4)^18 / 18! < 3e-18. The result is within 3e-16 of the cosine (absolute),
/// about one rounding of a double: the std::cos it stands in for agrees to that, and a float computed from it
/// to the last bit but in the rare case of a tie.

namespace sss::seabed::detail {

/// cos x for x in [0, pi] (rad), within 3e-16 absolute (see the file comment).
[[nodiscard]] inline double cos_0_pi(double x) noexcept {
    constexpr double half_pi_hi = 1.5707963267948966;    // the double nearest pi/2
    constexpr double half_pi_lo = 6.123233995736766e-17; // pi/2 - half_pi_hi
    constexpr double pi_hi = 3.141592653589793;          // the double nearest pi
    constexpr double pi_lo = 1.2246467991473532e-16;     // pi - pi_hi
    // cos r = sum_k (-1)^k r^(2k) / (2k)!, sin r = r sum_k (-1)^k r^(2k) / (2k + 1)!, k = 0 .. 8.
    const auto cos_taylor = [](double r) {
        const double r2 = r * r;
        double p = 1.0 / 20922789888000.0; // 1/16!
        p = p * r2 - 1.0 / 87178291200.0;  // 1/14!
        p = p * r2 + 1.0 / 479001600.0;    // 1/12!
        p = p * r2 - 1.0 / 3628800.0;      // 1/10!
        p = p * r2 + 1.0 / 40320.0;        // 1/8!
        p = p * r2 - 1.0 / 720.0;          // 1/6!
        p = p * r2 + 1.0 / 24.0;           // 1/4!
        p = p * r2 - 0.5;                  // 1/2!
        return p * r2 + 1.0;
    };
    const auto sin_taylor = [](double r) {
        const double r2 = r * r;
        double p = 1.0 / 355687428096000.0; // 1/17!
        p = p * r2 - 1.0 / 1307674368000.0; // 1/15!
        p = p * r2 + 1.0 / 6227020800.0;    // 1/13!
        p = p * r2 - 1.0 / 39916800.0;      // 1/11!
        p = p * r2 + 1.0 / 362880.0;        // 1/9!
        p = p * r2 - 1.0 / 5040.0;          // 1/7!
        p = p * r2 + 1.0 / 120.0;           // 1/5!
        p = p * r2 - 1.0 / 6.0;             // 1/3!
        return r + r * (p * r2);
    };
    if (x <= 0.78539816339744831) return cos_taylor(x);                       // [0, pi/4]
    if (x <= 2.3561944901923448) return sin_taylor((half_pi_hi - x) + half_pi_lo); // (pi/4, 3 pi/4]
    return -cos_taylor((pi_hi - x) + pi_lo);                                  // (3 pi/4, pi]
}

} // namespace sss::seabed::detail
