#pragma once
/// \file
/// One sediment description for a region's geometry and its scattering.
///
/// A `sediment_region` names its sediment once (a TR 9407 Table 2 name, a mean grain size in phi, or explicit
/// parameters; APL-UW TR 9407, 1994, D. R. Jackson): its roughness spectrum for the composite seabed is that
/// sediment's W(K) = w2 / (h0 K)^gamma (seabed/power_law_spectrum.hpp), and its scattering is Jackson's model with
/// the same parameters (scattering/jackson.hpp), so the relief and the backscatter of a region can never disagree.
///
///     std::vector<sss::seabed::sediment_region<float>> regions{
///         {.id = 0, .sediment = sss::seabed::sediment_named<float>("medium_sand"), .ripples = {...}},
///         {.id = 1, .sediment = sss::seabed::sediment_named<float>("sandy_gravel"), .mean_height_m = 0.2f}};
///     const auto bed = sss::seabed::compose(index, sss::seabed::textures(regions), 0.5f, 11);
///     const auto scattering = sss::seabed::jackson_for(regions, {.frequency_hz = 100e3f, .sound_speed_mps = 1500.f});

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/scattering/jackson.hpp"
#include "sss/scattering/sediments.hpp"
#include "sss/seabed/composite.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/ripples.hpp"

namespace sss::seabed {

/// The Table 2 sediment of that name (canonical or alias).
template <Real T> [[nodiscard]] scattering::sediment_params<T> sediment_named(std::string_view name) {
    return scattering::sediment_preset<T>(name);
}

/// The sediment of mean grain size mz_phi (phi), by the TR 9407 regressions.
template <Real T> [[nodiscard]] scattering::sediment_params<T> sediment_of_grain_size(T mz_phi) {
    return scattering::sediment_from_grain_size<T>(mz_phi);
}

template <Real T> struct sediment_region {
    std::uint32_t id = 0;                                 ///< region id = material id (0, 1, ... without gaps)
    scattering::sediment_params<T> sediment{};            ///< the sediment: sets roughness and scattering
    T mean_height_m = T(0);                               ///< mean height of the region (m)
    T outer_scale_m = T(20);                              ///< outer scale of its roughness spectrum (m), >= 0
    std::vector<ripple_params<T>> ripples{};              ///< ripple sets on top (geometry only)
};

/// The composite-seabed texture of a region: its sediment's roughness spectrum, its height and ripples.
template <Real T> [[nodiscard]] region_texture<T> texture(const sediment_region<T>& r) {
    scattering::validate(r.sediment, "sediment_region.sediment");
    sss::require_non_negative(r.outer_scale_m, "sediment_region.outer_scale_m");
    region_texture<T> t;
    t.id = r.id;
    t.mean_height_m = r.mean_height_m;
    t.roughness.spectrum = jackson_spectrum(r.sediment.w2_cm4, r.sediment.gamma, r.outer_scale_m);
    t.ripples = r.ripples;
    return t;
}

/// The textures of every region, in order (for `compose`).
template <Real T> [[nodiscard]] std::vector<region_texture<T>> textures(const std::vector<sediment_region<T>>& regions) {
    std::vector<region_texture<T>> out;
    out.reserve(regions.size());
    for (const auto& r : regions) out.push_back(texture(r));
    return out;
}

/// The sediments indexed by region id; the ids must be 0 .. n-1, each once.
template <Real T>
[[nodiscard]] std::vector<scattering::sediment_params<T>> sediments_by_id(const std::vector<sediment_region<T>>& regions) {
    sss::require(!regions.empty(), "sediment_regions", "needs at least one region");
    std::vector<scattering::sediment_params<T>> out(regions.size());
    std::vector<bool> seen(regions.size(), false);
    for (const auto& r : regions) {
        sss::require(r.id < regions.size() && !seen[r.id], "sediment_regions.id",
                             "ids must be 0 .. " + std::to_string(regions.size() - 1) + ", each once; got " + std::to_string(r.id));
        seen[r.id] = true;
        out[r.id] = r.sediment;
    }
    return out;
}

/// Jackson's scattering with one material per region id; `settings` gives the frequency and sound speed (its
/// `materials` are replaced by the regions' sediments).
template <Real T>
[[nodiscard]] scattering::jackson<T> jackson_for(const std::vector<sediment_region<T>>& regions,
                                                 scattering::jackson_params<T> settings = {}) {
    settings.materials = sediments_by_id(regions);
    return scattering::jackson<T>(settings);
}

} // namespace sss::seabed
