#pragma once
/// \file
/// A sound-speed profile c(z): piecewise linear in depth between knots, constant beyond them.
///
/// Depth z is positive down, in metres (z = 0 at the sea surface); speeds are in m/s. Between two
/// knots (z_i, c_i) and (z_{i+1}, c_{i+1}) the speed is linear, c(z) = c_i + g_i (z - z_i) with the
/// layer gradient g_i = (c_{i+1} - c_i)/(z_{i+1} - z_i) (1/s). Above the first knot and below the last
/// the speed is held constant at the end value (zero gradient): a measured cast that stops short of
/// the surface or the seabed is extended by its end values, the usual practice in swath sonar
/// processing. In each such layer a ray path is an exact circular arc (see ray_arc.hpp).
///
/// Layers are numbered so that every depth belongs to exactly one of them. With n knots there are
/// n + 1 layers: layer 0 is the half-space above knot 0, layer i (1 <= i <= n - 1) spans
/// [z_{i-1}, z_i], and layer n is the half-space below knot n - 1. The half-spaces have infinite
/// outer bounds and zero gradient.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/propagation/sound_speed.hpp"

namespace sss::propagation {

/// Which way a ray travels in depth: `down` is increasing z.
enum class vertical_direction : unsigned char { down = 0, up = 1 };

/// One layer of constant sound-speed gradient: c(z) = c_ref + g (z - z_ref) for z_top <= z <= z_bottom.
/// Plain data. `z_top_m` may be -infinity and `z_bottom_m` +infinity (then the gradient is 0); the
/// reference depth is finite and normally one of the bounds.
template <Real T> struct gradient_layer {
    T z_top_m{};        ///< upper bound (m, positive down); z_top_m < z_bottom_m
    T z_bottom_m{};     ///< lower bound (m)
    T z_ref_m{};        ///< depth at which c_ref_mps is given (m)
    T c_ref_mps{};      ///< sound speed at z_ref_m (m/s)
    T gradient_per_s{}; ///< dc/dz (1/s); positive when speed increases with depth

    /// c(z) of this layer (m/s), evaluated without clamping z to the layer.
    [[nodiscard]] constexpr T speed_mps(T depth_m) const noexcept {
        return c_ref_mps + gradient_per_s * (depth_m - z_ref_m);
    }
};

template <Real T> class sound_speed_profile {
public:
    using value_type = T;

    /// Knots (depth_m[i], speed_mps[i]). Throws sss::invalid_parameter naming the offending entry
    /// (for example "depth_m[3]") unless: both lists have the same, non-zero length; depths are finite
    /// and strictly increasing; speeds are finite and positive.
    sound_speed_profile(std::vector<T> depth_m, std::vector<T> speed_mps)
        : depth_(std::move(depth_m)), speed_(std::move(speed_mps)) {
        sss::require(!depth_.empty(), "depth_m", "needs at least one knot");
        sss::require(speed_.size() == depth_.size(), "speed_mps",
                        [&] { return "must have as many entries as depth_m (" + std::to_string(depth_.size()) + "), has " +
                            std::to_string(speed_.size()); });
        for (std::size_t i = 0; i < depth_.size(); ++i) {
            sss::require_finite(depth_[i], knot_name("depth_m", i));
            sss::require_positive(speed_[i], knot_name("speed_mps", i));
            if (i > 0) {
                sss::require(depth_[i] > depth_[i - 1], knot_name("depth_m", i),
                                [&] { return "depths must increase strictly: " + std::to_string(depth_[i]) + " follows " +
                                    std::to_string(depth_[i - 1]); });
            }
        }
        gradient_.assign(depth_.size() + 1, T(0));
        for (std::size_t i = 1; i < depth_.size(); ++i) {
            const T g = (speed_[i] - speed_[i - 1]) / (depth_[i] - depth_[i - 1]);
            sss::require(std::isfinite(g), knot_name("depth_m", i),
                            "knots too close: the speed gradient to the previous knot overflows");
            gradient_[i] = g;
        }
    }

    /// A uniform profile: one knot, speed_mps everywhere.
    [[nodiscard]] static sound_speed_profile constant(T speed_mps) {
        return sound_speed_profile(std::vector<T>{T(0)}, std::vector<T>{speed_mps});
    }

    /// A profile from temperature (degC) and salinity (ppt) casts at the given depths (m), with the
    /// speed at each knot from Mackenzie (1981), see sound_speed.hpp. Errors as the main constructor;
    /// the three lists must have equal length.
    [[nodiscard]] static sound_speed_profile from_temperature_salinity(std::vector<T> depth_m,
                                                                       const std::vector<T>& temperature_c,
                                                                       const std::vector<T>& salinity_ppt) {
        sss::require(temperature_c.size() == depth_m.size(), "temperature_c",
                        [&] { return "must have as many entries as depth_m (" + std::to_string(depth_m.size()) + ")"; });
        sss::require(salinity_ppt.size() == depth_m.size(), "salinity_ppt",
                        [&] { return "must have as many entries as depth_m (" + std::to_string(depth_m.size()) + ")"; });
        std::vector<T> speed(depth_m.size());
        for (std::size_t i = 0; i < depth_m.size(); ++i) {
            sss::require_finite(temperature_c[i], knot_name("temperature_c", i));
            sss::require_finite(salinity_ppt[i], knot_name("salinity_ppt", i));
            sss::require(salinity_ppt[i] >= T(0), knot_name("salinity_ppt", i), "must be >= 0");
            sss::require_finite(depth_m[i], knot_name("depth_m", i));
            speed[i] = mackenzie_sound_speed_mps(temperature_c[i], salinity_ppt[i], depth_m[i]);
        }
        return sound_speed_profile(std::move(depth_m), std::move(speed));
    }

    [[nodiscard]] std::size_t knot_count() const noexcept { return depth_.size(); }
    [[nodiscard]] std::span<const T> depths_m() const noexcept { return depth_; }
    [[nodiscard]] std::span<const T> speeds_mps() const noexcept { return speed_; }

    /// Number of layers, knot_count() + 1 (the two outer ones are the constant half-spaces).
    [[nodiscard]] std::size_t layer_count() const noexcept { return depth_.size() + 1; }

    /// The layer holding depth_m, with z_top <= depth_m < z_bottom (binary search, O(log n)).
    [[nodiscard]] std::size_t layer_index(T depth_m) const noexcept {
        return static_cast<std::size_t>(std::upper_bound(depth_.begin(), depth_.end(), depth_m) - depth_.begin());
    }

    /// The layer a ray at depth_m moving in `heading` is in: as layer_index(depth_m), except that a ray
    /// exactly on a knot and moving up is in the layer above the knot.
    [[nodiscard]] std::size_t layer_index(T depth_m, vertical_direction heading) const noexcept {
        std::size_t i = layer_index(depth_m);
        if (heading == vertical_direction::up && i > 0 && depth_[i - 1] == depth_m) --i;
        return i;
    }

    /// Layer i (0 <= i < layer_count()) as a plain gradient_layer; its reference point is its upper knot
    /// (the lower one for the top half-space).
    [[nodiscard]] gradient_layer<T> layer(std::size_t i) const noexcept {
        constexpr T inf = std::numeric_limits<T>::infinity();
        const std::size_t n = depth_.size();
        if (i == 0) return {-inf, depth_[0], depth_[0], speed_[0], T(0)};
        if (i >= n) return {depth_[n - 1], inf, depth_[n - 1], speed_[n - 1], T(0)};
        return {depth_[i - 1], depth_[i], depth_[i - 1], speed_[i - 1], gradient_[i]};
    }

    /// dc/dz of layer i (1/s); 0 for the half-spaces.
    [[nodiscard]] T gradient_per_s(std::size_t layer_i) const noexcept {
        return gradient_[std::min(layer_i, gradient_.size() - 1)];
    }

    /// c(z) (m/s): linear between knots, constant beyond the first and last knot.
    [[nodiscard]] T speed_mps(T depth_m) const noexcept {
        const std::size_t i = layer_index(depth_m);
        if (i == 0) return speed_.front();
        if (i >= depth_.size()) return speed_.back();
        return speed_[i - 1] + gradient_[i] * (depth_m - depth_[i - 1]);
    }

    [[nodiscard]] T min_speed_mps() const noexcept { return *std::min_element(speed_.begin(), speed_.end()); }
    [[nodiscard]] T max_speed_mps() const noexcept { return *std::max_element(speed_.begin(), speed_.end()); }

private:
    static std::string knot_name(const char* list, std::size_t i) {
        return std::string(list) + "[" + std::to_string(i) + "]";
    }

    std::vector<T> depth_;
    std::vector<T> speed_;
    std::vector<T> gradient_; // per layer; entries 0 and n are the half-spaces (0)
};

} // namespace sss::propagation
