#pragma once
/// \file
/// What the target builders (seabed/targets.hpp) read the seabed through: a height function h(x_m, y_m) -> world z
/// (m), and the height function of a scene.

#include <concepts>
#include <type_traits>

#include "sss/core/types.hpp"
#include "sss/scene/concept.hpp"

namespace sss::seabed {

/// A seabed height function: h(x_m, y_m) gives the seabed's world z (m) below (x, y).
template <class F, class T>
concept HeightFunction = Real<T> && std::invocable<const F&, T, T> && std::convertible_to<std::invoke_result_t<const F&, T, T>, T>;

/// The height function of a scene (holds a reference: the scene must outlive it).
template <Scene S> [[nodiscard]] auto seabed_height_of(const S& s) {
    using T = typename S::value_type;
    return [&s](T x_m, T y_m) { return s.seabed_height_m(x_m, y_m); };
}

} // namespace sss::seabed
