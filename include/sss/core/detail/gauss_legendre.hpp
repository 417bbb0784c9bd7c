#pragma once
/// \file
/// Internal: the 8-point Gauss-Legendre rule on [0, 1] (nodes and weights of Abramowitz & Stegun, 1964, Table 25.4,
/// mapped from [-1, 1]), exact for polynomials up to degree 15.

#include <array>

namespace sss::detail {

inline constexpr std::array<double, 8> gauss_legendre8_x{0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                                                         0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                                                         0.8983332387068134, 0.9801449282487681};
inline constexpr std::array<double, 8> gauss_legendre8_w{0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                                                         0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                                                         0.1111905172266872, 0.0506142681451881};

} // namespace sss::detail
