#pragma once
/// \file
/// Two scattering models in one simulator, chosen by material id: the seabed's materials under one (e.g.
/// Jackson's sediments), the targets' under another (e.g. hard_target's facets).
///
/// `by_material<Seabed, Targets>(seabed, targets)`: material ids below `seabed.material_count()` go to the seabed
/// model unchanged; id m at or beyond it goes to the target model as id m - seabed.material_count(). So a scene
/// keeps its seabed ids and numbers its targets' materials after them. A scene with one model does not use this
/// wrapper and pays nothing; with it, each evaluation costs one comparison. The coherent reflection of the
/// specular bounce is forwarded when both models have one.

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "sss/scattering/concept.hpp"
#include "sss/scattering/specular_bounce.hpp"

namespace sss::scattering {

template <Scattering Seabed, Scattering Targets> class by_material {
public:
    using value_type = typename Seabed::value_type;
    using T = value_type;
    static_assert(std::is_same_v<T, typename Targets::value_type>, "by_material: both models must share one scalar type");

    by_material(Seabed seabed, Targets targets)
        : seabed_(std::move(seabed)), targets_(std::move(targets)),
          first_target_(static_cast<std::uint32_t>(seabed_.material_count())) {}

    [[nodiscard]] const Seabed& seabed() const noexcept { return seabed_; }
    [[nodiscard]] const Targets& targets() const noexcept { return targets_; }
    /// The first material id that belongs to the target model.
    [[nodiscard]] std::uint32_t first_target_material() const noexcept { return first_target_; }

    [[nodiscard]] T backscatter(T graze_rad, std::uint32_t material) const noexcept {
        return material < first_target_ ? seabed_.backscatter(graze_rad, material)
                                        : targets_.backscatter(graze_rad, material - first_target_);
    }
    [[nodiscard]] T bistatic(T gi_rad, T gs_rad, T phi_rad, std::uint32_t material) const noexcept {
        return material < first_target_ ? seabed_.bistatic(gi_rad, gs_rad, phi_rad, material)
                                        : targets_.bistatic(gi_rad, gs_rad, phi_rad, material - first_target_);
    }
    [[nodiscard]] std::size_t material_count() const noexcept { return seabed_.material_count() + targets_.material_count(); }

    [[nodiscard]] T reflection(T graze_rad, std::uint32_t material, T patch_m) const noexcept
        requires Reflecting<Seabed> && Reflecting<Targets>
    {
        return material < first_target_ ? seabed_.reflection(graze_rad, material, patch_m)
                                        : targets_.reflection(graze_rad, material - first_target_, patch_m);
    }

private:
    Seabed seabed_;
    Targets targets_;
    std::uint32_t first_target_;
};

} // namespace sss::scattering
