#pragma once
/// \file
/// Conversions between linear power (intensity) ratios and decibels.

#include <cmath>

#include "sss/core/types.hpp"

namespace sss {

/// 10 log10(x) for a power ratio x (dB). Returns -inf for 0 and NaN for negative input.
template <Real T> [[nodiscard]] inline T power_to_db(T ratio) noexcept { return T(10) * std::log10(ratio); }

/// 10^(db/10): the power ratio of a level in dB.
template <Real T> [[nodiscard]] inline T db_to_power(T db) noexcept { return std::pow(T(10), db / T(10)); }

} // namespace sss
