#pragma once
/// \file
/// The beam and the motion of sss-render's simulators, each a run-time choice among the library's policies of
/// its family: `scene_beam` holds an ideal fan or a planar array, `scene_motion` a perturbed track or a sampled
/// trajectory. Each satisfies its family's concept (beam/concept.hpp, motion/concept.hpp) by passing every call
/// to the policy it holds, so the whitelist in build.hpp stays at one instantiation per scattering x water
/// pair instead of multiplying by every beam and motion. The dispatch is a std::get_if per call (no std::visit,
/// which may throw std::bad_variant_access): `weight` stays noexcept, and a scene of the ideal fan and the
/// perturbed motion renders bit for bit what a simulator of those two policies renders.

#include <sss/beam/concept.hpp>
#include <sss/beam/ideal_fan.hpp>
#include <sss/beam/planar_array.hpp>
#include <sss/motion/concept.hpp>
#include <sss/motion/perturbed.hpp>
#include <sss/motion/trajectory.hpp>

#include <cstddef>
#include <limits>
#include <utility>
#include <variant>

namespace sss::scene_file {

/// The beam a scene asks for: an ideal fan or a planar array (float, like every compiled instantiation).
class scene_beam {
public:
    using value_type = float;
    using fan = sss::beam::ideal_fan<float>;
    using array = sss::beam::planar_array<float>;

    explicit scene_beam(fan b) : b_(std::move(b)) {}
    explicit scene_beam(array b) : b_(std::move(b)) {}

    [[nodiscard]] sss::beam_extent<float> extent(side s) const noexcept {
        if (const auto* a = std::get_if<array>(&b_)) return a->extent(s);
        return std::get_if<fan>(&b_)->extent(s);
    }
    [[nodiscard]] float weight(side s, float along_rad, float depression_rad) const noexcept {
        if (const auto* a = std::get_if<array>(&b_)) return a->weight(s, along_rad, depression_rad);
        return std::get_if<fan>(&b_)->weight(s, along_rad, depression_rad);
    }
    /// The planar array's along-track step; 0 for the ideal fan, which the simulator reads as "no columns beyond
    /// ray_density.along" (simulator::along_columns), what a fan without the member gets.
    [[nodiscard]] float along_resolution_rad(side s) const noexcept {
        if (const auto* a = std::get_if<array>(&b_)) return a->along_resolution_rad(s);
        return 0.0f;
    }
    /// The planar array held, or nullptr.
    [[nodiscard]] const array* planar() const noexcept { return std::get_if<array>(&b_); }

private:
    std::variant<fan, array> b_;
};

/// The towfish's motion a scene asks for: a perturbed track (straight line, turn, oscillations) or a trajectory
/// sampled in a file.
class scene_motion {
public:
    using value_type = float;
    using perturbed = sss::motion::perturbed<float>;
    using trajectory = sss::motion::trajectory<float>;

    explicit scene_motion(perturbed m) : m_(std::move(m)) {}
    explicit scene_motion(trajectory m) : m_(std::move(m)) {}

    /// The pose at ping i; a trajectory throws sss::invalid_parameter("ping") beyond its last ping.
    [[nodiscard]] sss::pose<float> pose_at(std::size_t ping) const {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->pose_at(ping);
        return std::get_if<perturbed>(&m_)->pose_at(ping);
    }
    /// The track without oscillations (perturbed), or the trajectory's pose: the swath geometry of coverage.hpp.
    [[nodiscard]] sss::pose<float> nominal_pose_at(std::size_t ping) const {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->pose_at(ping);
        return std::get_if<perturbed>(&m_)->nominal_pose_at(ping);
    }
    /// Pings 0 .. ping_count() - 1 have a pose: the trajectory's count, or no limit for a perturbed track.
    [[nodiscard]] std::size_t ping_count() const noexcept {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->ping_count();
        return std::numeric_limits<std::size_t>::max();
    }
    /// The trajectory held, or nullptr.
    [[nodiscard]] const trajectory* sampled() const noexcept { return std::get_if<trajectory>(&m_); }

private:
    std::variant<perturbed, trajectory> m_;
};

static_assert(AlongResolvedBeam<scene_beam> && Motion<scene_motion>);

} // namespace sss::scene_file
