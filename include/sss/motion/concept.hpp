#pragma once
/// \file
/// The Motion concept: where the towfish is, and how it is oriented, at each ping.
///
/// | expression        | type       | meaning                                                          |
/// |-------------------|------------|------------------------------------------------------------------|
/// | `M::value_type`   | T          | float or double                                                  |
/// | `m.pose_at(i)`       | `pose<T>`  | pose at ping `i` (std::size_t): time, world position, attitude  |
///
/// `pose_at` is const and deterministic, so pings can be rendered in any order and in parallel.

#include <concepts>
#include <cstddef>

#include "sss/core/pose.hpp"

namespace sss {

template <class M>
concept Motion = Real<typename M::value_type> && requires(const M& m, std::size_t i) {
    { m.pose_at(i) } -> std::same_as<pose<typename M::value_type>>;
};

} // namespace sss
