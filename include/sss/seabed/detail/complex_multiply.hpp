#pragma once
/// \file
/// Internal to seabed/fft.hpp: the complex product written out. Not part of the API.

#include <complex>

namespace sss::seabed::detail {
/// Complex product written out: std::complex's operator* checks for NaN and infinity (C99 Annex G) and is slow.
[[nodiscard]] inline std::complex<double> cmul(std::complex<double> a, std::complex<double> b) noexcept {
    return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}
} // namespace sss::seabed::detail
