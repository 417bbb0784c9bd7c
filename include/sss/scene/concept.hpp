#pragma once
/// \file
/// The Scene concept: geometry only (it knows nothing of sound).
///
/// | expression                      | type                       | meaning                                              |
/// |---------------------------------|----------------------------|------------------------------------------------------|
/// | `S::value_type`                 | float or double            | scalar type of the geometry                          |
/// | `s.intersect(r, t_max_m)`       | `std::optional<hit<T>>`    | nearest hit along `r` with 0 < distance <= t_max_m   |
/// | `s.seabed_height_m(x_m, y_m)`   | `T`                        | world z of the seabed below (x, y) (m)               |
/// | `s.top_m()`                     | `T`                        | world z above which no geometry exists (m)           |
///
/// `r` is a `ray<T>` with unit direction. `intersect` must be watertight: a ray never slips between two
/// pieces of one surface. `seabed_height_m` and `top_m` only steer ray sampling (they never decide a hit).

#include <concepts>
#include <optional>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"

namespace sss {

template <class S>
concept Scene = Real<typename S::value_type> &&
    requires(const S& s, const ray<typename S::value_type>& r, typename S::value_type t) {
        { s.intersect(r, t) } -> std::same_as<std::optional<hit<typename S::value_type>>>;
        { s.seabed_height_m(t, t) } -> std::same_as<typename S::value_type>;
        { s.top_m() } -> std::same_as<typename S::value_type>;
    };

} // namespace sss
