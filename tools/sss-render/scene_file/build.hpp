#pragma once
/// \file
/// From a resolved `description` to the library's objects: the seabed (generated or loaded), the objects laid
/// on it, and the simulator, chosen among the compiled instantiations listed once in `with_simulator`.

#include "error.hpp"
#include "policies.hpp"
#include "scene.hpp"

#include <sss/io/height_field_io.hpp>
#include <sss/io/sound_speed_profile.hpp>
#include <sss/io/trajectory_csv.hpp>
#include <sss/policies.hpp>
#include <sss/receiver/echo_statistics.hpp>
#include <sss/receiver/tvg.hpp>
#include <sss/scattering/by_material.hpp>
#include <sss/scattering/hard_target.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/composite.hpp>
#include <sss/seabed/sediment_region.hpp>
#include <sss/seabed/stamps.hpp>
#include <sss/seabed/targets.hpp>

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sss::scene_file {

/// The scene of scalar T: float (half the memory, and the precision of most data), or double where the
/// coordinates are large (render.precision; the instantiations compiled are listed above `with_simulator`).
template <Real T> using world = sss::scene::scene<sss::scene::height_field<T>>;

/// The seabed's regions as the library's sediment regions (a flat or loaded seabed: one default region).
template <Real T = float> [[nodiscard]] std::vector<sss::seabed::sediment_region<T>> sediment_regions(const description& d) {
    std::vector<region> regions = d.bed.regions;
    if (regions.empty()) regions.push_back(region{});
    std::vector<sss::seabed::sediment_region<T>> out;
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const auto& g = regions[i];
        sss::seabed::sediment_region<T> r{.id = std::uint32_t(i), .sediment = sss::seabed::sediment_named<T>(g.sediment),
                                          .mean_height_m = T(g.mean_height_m), .outer_scale_m = T(g.outer_scale_m)};
        for (const auto& p : g.ripple_sets)
            r.ripples.push_back({.wavelength_m = T(p.wavelength_m), .height_m = T(p.height_m),
                                 .crest_heading_deg = T(p.crest_heading_deg), .symmetry_index = T(p.symmetry_index),
                                 .sinuosity_m = T(p.sinuosity_m), .sinuosity_wavelength_m = T(p.sinuosity_wavelength_m),
                                 .perturbation_m = T(p.perturbation_m), .height_variation = T(p.height_variation)});
        out.push_back(std::move(r));
    }
    return out;
}

/// Stamps the scene's features on raster h (raster-local coordinates: world minus origin_m, so float even
/// for a double scene: make_seabed).
template <Real T> void apply_stamps(const description& d, sss::seabed::raster<T>& h) {
    namespace sb = sss::seabed;
    const double x0 = d.bed.origin_m[0], y0 = d.bed.origin_m[1];
    for (const auto& p : d.bed.stamps) {
        const T cx = T(p.center_m[0] - x0), cy = T(p.center_m[1] - y0);
        if (p.type == "plate")
            sb::stamp(h, sb::plate<T>{.center_x_m = cx, .center_y_m = cy, .length_m = T(p.length_m), .width_m = T(p.width_m),
                                      .heading_deg = T(p.heading_deg), .top_m = T(p.top_m)});
        else if (p.type == "mound")
            sb::stamp(h, sb::mound<T>{.center_x_m = cx, .center_y_m = cy, .radius_u_m = T(p.radius_u_m),
                                      .radius_v_m = T(p.radius_v_m), .heading_deg = T(p.heading_deg), .height_m = T(p.height_m)});
        else if (p.type == "scour")
            sb::stamp(h, sb::scour<T>{.center_x_m = cx, .center_y_m = cy, .radius_u_m = T(p.radius_u_m),
                                      .radius_v_m = T(p.radius_v_m), .heading_deg = T(p.heading_deg), .depth_m = T(p.depth_m),
                                      .rim_height_m = T(p.rim_height_m), .rim_width_m = T(p.rim_width_m)});
        else
            sb::stamp(h, sb::trench<T>{.x0_m = T(p.start_m[0] - x0), .y0_m = T(p.start_m[1] - y0), .x1_m = T(p.end_m[0] - x0),
                                       .y1_m = T(p.end_m[1] - y0), .width_m = T(p.width_m), .floor_width_m = T(p.floor_width_m),
                                       .depth_m = T(p.depth_m), .berm_height_m = T(p.berm_height_m),
                                       .berm_width_m = T(p.berm_width_m)});
    }
}

/// The seabed in `seabed.file`, by its extension: ESRI ASCII (.asc), raw float32 with its sidecar (.raw), or
/// binary PGM (.pgm, 8- or 16-bit samples) placed by cell_m and origin_m with heights pgm_offset_m + pgm_scale_m x sample.
template <Real T = float> [[nodiscard]] sss::scene::height_field<T> load_seabed(const description& d) {
    const auto& b = d.bed;
    try {
        const seabed_format format = seabed_format_of(b.file);
        if (format == seabed_format::raw_f32) return sss::io::read_raw_f32<T>(b.file);
        if (format == seabed_format::pgm)
            return sss::io::read_pgm16<T>(b.file, T(b.cell_m), {T(b.origin_m[0]), T(b.origin_m[1])},
                                          {.scale_m = T(b.pgm_scale_m), .offset_m = T(b.pgm_offset_m)});
        return sss::io::read_esri_ascii<T>(b.file);
    } catch (const sss::error& e) { // the file's own message (with its line or byte), under the scene's key
        std::string what = e.what();
        if (what.rfind("sss: ", 0) == 0) what = what.substr(5);
        throw scene_error(d.path + ": seabed.file: " + what);
    }
}

/// A generated seabed's heights (m, raster-local: world minus origin_m) and the region of each vertex, synthesised
/// in scalar S: flat at z = 0 without regions (its region raster left empty), else composed from the regions,
/// the stamps on top. make_seabed asks for float whatever the scene's precision.
template <Real S> [[nodiscard]] sss::seabed::composite_seabed<S> synthesise_seabed(const description& d) {
    namespace sb = sss::seabed;
    const auto& b = d.bed;
    const auto nx = std::size_t(b.nx), ny = std::size_t(b.ny);
    const S cell = S(b.cell_m);
    if (b.regions.empty()) {
        sb::composite_seabed<S> flat{.height = sb::make_raster<S>(nx, ny, cell, S(0)), .regions = {}};
        apply_stamps(d, flat.height);
        return flat;
    }
    sb::voronoi_partition<S> part{.sites = {}, .warp_m = S(b.warp_m), .warp_scale_m = S(b.warp_scale_m)};
    for (const auto& s : b.sites)
        part.sites.push_back({.x_m = S(s.x_m - b.origin_m[0]), .y_m = S(s.y_m - b.origin_m[1]), .texture = std::size_t(s.region)});
    if (part.sites.empty()) part.sites.push_back({.x_m = S(0), .y_m = S(0), .texture = 0});
    auto bed = sb::compose(sb::partition(nx, ny, cell, part, std::uint64_t(b.partition_seed)), sb::textures(sediment_regions<S>(d)),
                           S(b.blend_m), std::uint64_t(b.seed));
    apply_stamps(d, bed.height);
    return bed;
}

/// The seabed: loaded from `file` (in T), else generated (synthesise_seabed).
/// A generated seabed's heights are synthesised in float whatever T, on the raster's own grid (relative to
/// origin_m, where float holds them to well under a micrometre), then widened to T: a scene's seabed is the
/// same in both precisions, and double pays for its coordinates (origin, objects, track, rays), not for a
/// second synthesis (partition, fractal, ripples, stamps) compiled in double.
template <Real T = float> [[nodiscard]] sss::scene::height_field<T> make_seabed(const description& d) {
    const auto& b = d.bed;
    if (!b.file.empty()) return load_seabed<T>(d);
    const auto nx = std::size_t(b.nx), ny = std::size_t(b.ny);
    const auto bed = synthesise_seabed<float>(d);
    sss::scene::height_field_params<T> p{.nx = nx, .ny = ny, .cell_m = T(b.cell_m), .origin_m = {T(b.origin_m[0]), T(b.origin_m[1])},
                                         .heights_m = std::vector<T>(bed.height.values.begin(), bed.height.values.end())};
    if (!b.regions.empty()) {
        std::vector<std::uint32_t> material((nx - 1) * (ny - 1));
        for (std::size_t iy = 0; iy + 1 < ny; ++iy)
            for (std::size_t ix = 0; ix + 1 < nx; ++ix) material[iy * (nx - 1) + ix] = bed.regions.values[iy * nx + ix];
        p.materials = material;
        p.regions = std::move(material);
    }
    return sss::scene::height_field<T>(std::move(p));
}

/// The material id of every object: the first after the seabed's regions.
[[nodiscard]] inline std::uint32_t object_material(const description& d) {
    return std::uint32_t(std::max<std::size_t>(1, d.bed.regions.size()));
}

/// The scene: the seabed and the objects laid on it; object k has object id k + 1.
template <Real T = float> [[nodiscard]] world<T> make_world(const description& d) {
    namespace sb = sss::seabed;
    auto seabed = make_seabed<T>(d);
    const auto h = sb::seabed_height_of(seabed);
    const std::uint32_t material = object_material(d);
    std::vector<sss::scene::object<T>> objects;
    for (std::size_t k = 0; k < d.objects.size(); ++k) try {
        const auto& o = d.objects[k];
        const auto id = std::uint32_t(k + 1), label = std::uint32_t(o.class_id);
        if (o.type == "lying_cylinder") {
            objects.push_back(sb::lying_cylinder(
                sb::lying_cylinder_params<T>{.center_m = {T(o.center_m[0]), T(o.center_m[1])},
                                             .heading_deg = T(o.heading_deg), .length_m = T(o.length_m),
                                             .radius_m = T(o.radius_m), .ids = {.material = material, .object = id, .label = label}},
                h));
        } else if (o.type == "sphere" || o.type == "cylinder") {
            const sss::scene::surface_ids ids{.material = material, .object = id, .label = label};
            const auto at = [&](const xy& p, double above) {
                return sss::vec3<T>{T(p[0]), T(p[1]), h(T(p[0]), T(p[1])) + T(above)};
            };
            if (o.type == "sphere")
                objects.push_back(sss::scene::object<T>({sss::scene::sphere<T>(at(o.center_m, o.height_m), T(o.radius_m), ids)}, {}));
            else
                objects.push_back(sss::scene::object<T>(
                    {}, {sss::scene::cylinder<T>(at(o.center_m, o.end0_height_m), at(o.end_m, o.end1_height_m), T(o.radius_m), ids)}));
        } else if (o.type == "tethered_mine") {
            objects.push_back(sb::tethered_mine(
                sb::tethered_mine_params<T>{.anchor_m = {T(o.anchor_m[0]), T(o.anchor_m[1])},
                                            .case_height_m = T(o.case_height_m),
                                            .shape = o.case_shape == "sphere" ? sb::mine_case::sphere : sb::mine_case::cylinder,
                                            .case_radius_m = T(o.case_radius_m), .case_length_m = T(o.case_length_m),
                                            .case_heading_deg = T(o.case_heading_deg), .object_id = id, .class_id = label,
                                            .case_material = material, .tether_material = material, .anchor_material = material},
                h));
        } else {
            sb::pipeline_params<T> p{.route_m = {}, .radius_m = T(o.radius_m), .ids = {.material = material, .object = id, .label = label}};
            for (const auto& q : o.route_m) p.route_m.push_back({T(q[0]), T(q[1])});
            if (o.max_span_m > 0) p.max_span_m = T(o.max_span_m);
            objects.push_back(sb::pipeline(p, h));
        }
    } catch (const sss::error& e) { // laid on the seabed (a mine's case below it): the object's table and line
        std::string what = e.what();
        if (what.rfind("sss: ", 0) == 0) what = what.substr(5);
        throw scene_error((d.objects[k].origin.empty() ? d.path + ": object[" + std::to_string(k) + "]" : d.objects[k].origin) +
                          ": " + what);
    }
    return world<T>(std::move(seabed), sss::scene::object_set<T>(std::move(objects)));
}

[[nodiscard]] inline sss::receiver_params receiver_of(const description& d) {
    const auto& s = d.sensor;
    const sss::pulse_shape shape = s.pulse_shape == "hann" ? sss::pulse_shape::hann
                                   : s.pulse_shape == "lfm" ? sss::pulse_shape::lfm
                                                            : sss::pulse_shape::rectangular;
    return {.sample_rate_hz = s.sample_rate_hz, .max_range_m = s.max_range_m,
            .pulse = {.length_s = s.pulse_length_s, .shape = shape, .bandwidth_hz = s.pulse_bandwidth_hz},
            .source_level_db = s.source_level_db};
}

/// World z of the perturbed motion's towfish: altitude_m above the seabed under start_m.
/// The rays of [render] (sss::ray_density).
[[nodiscard]] inline sss::ray_density rays_of(const description& d) {
    sss::ray_density r{.along = static_cast<std::size_t>(d.run.rays_along), .across = 0, .per_sample = d.run.rays_per_sample,
                       .along_split = static_cast<std::size_t>(d.run.along_split),
                       .along_split_by_weight = d.run.along_split_by_weight};
    r.refine_facets = d.run.refine_facets;
    r.bracket_facet_edges = d.run.bracket_facet_edges;
    r.along_split_sparse = d.run.along_split_sparse;
    r.along_split_targets = d.run.along_split_targets;
    r.along_split_nadir = d.run.along_split_nadir;
    r.along_split_echo = d.run.along_split_echo;
    r.along_onset = d.run.along_onset;
    r.max_launch_step_deg = d.run.max_launch_step_deg;
    r.sloping_launch = d.run.sloping_launch;
    if (d.run.seabed_edges_along != "auto") r.along_split_seabed = d.run.seabed_edges_along == "on";
    return r;
}

template <Real T> [[nodiscard]] T tow_z(const description& d, const world<T>& w) {
    return w.seabed().seabed_height_m(T(d.tow.start_m[0]), T(d.tow.start_m[1])) + T(d.tow.altitude_m);
}

/// The beam: the ideal fan, or the planar array of `[sonar.transmit]` (and `[sonar.receive]`) at the sonar's
/// frequency, the water's sound speed and the sonar's depression.
template <Real T = float> [[nodiscard]] scene_beam<T> beam_of(const description& d) {
    const auto& s = d.sensor;
    if (s.beam == "planar_array") {
        const auto axis = [](const array_axis& a) {
            return sss::beam::array_axis<T>{.count = std::size_t(a.count), .element_m = T(a.element_m), .pitch_m = T(a.pitch_m),
                                            .shading = std::vector<T>(a.shading.begin(), a.shading.end())};
        };
        const auto layout = [&](const array_layout& a) {
            return sss::beam::array_layout<T>{.along = axis(a.along), .vertical = axis(a.vertical)};
        };
        sss::beam::planar_array_params<T> p{.frequency_hz = T(s.frequency_hz), .sound_speed_mps = T(d.sea.sound_speed_mps),
                                            .depression_deg = T(s.depression_deg), .transmit = layout(s.transmit),
                                            .receive = std::nullopt, .threshold_db = T(s.beam_threshold_db)};
        if (s.receive) p.receive = layout(*s.receive);
        return scene_beam<T>(sss::beam::planar_array<T>(p));
    }
    return scene_beam<T>(sss::beam::ideal_fan<T>({.along_width_deg = T(s.along_width_deg),
                                                  .vertical_width_deg = T(s.vertical_width_deg),
                                                  .depression_deg = T(s.depression_deg)}));
}

/// The trajectory of `motion.trajectory_file` (a relative path: from the scene file's directory). A file that cannot
/// be read is a scene_error naming the scene, the key and the file's own message (with its line).
template <Real T = float> [[nodiscard]] sss::motion::trajectory<T> load_trajectory(const description& d) {
    const auto& m = d.tow;
    sss::motion::trajectory_params<T> p{.ping_interval_s = T(m.ping_interval_s),
                                        .ping_zero_at = m.ping_zero_at.value_or(std::numeric_limits<double>::quiet_NaN()),
                                        .method = m.interpolation == "linear" ? sss::motion::interpolation::linear
                                                                              : sss::motion::interpolation::cubic,
                                        .roll_from_turn = m.roll_from_turn};
    const auto fail = [&](const sss::error& e) {
        std::string what = e.what();
        if (what.rfind("sss: ", 0) == 0) what = what.substr(5);
        return scene_error(d.path + ": motion.trajectory_file: " + what);
    };
    std::optional<sss::motion::trajectory_samples<T>> samples;
    try {
        samples.emplace(sss::io::read_trajectory_csv<T>(m.trajectory_file));
    } catch (const sss::error& e) {
        throw fail(e);
    }
    // Ping 0 among the file's keys: the scene's key, not the library's, in the message.
    const std::vector<double>& key = samples->ping.empty() ? samples->time_s : samples->ping;
    if (m.ping_zero_at && !key.empty() && !(*m.ping_zero_at >= key.front() && *m.ping_zero_at <= key.back()))
        throw scene_error(d.path + ": motion.ping_zero_at: " + detail::fmt(*m.ping_zero_at) + " lies outside motion.trajectory_file '" +
                          m.trajectory_file + "', whose " + (samples->ping.empty() ? "times run from " : "pings run from ") +
                          detail::fmt(key.front()) + " to " + detail::fmt(key.back()) + (samples->ping.empty() ? " s" : ""));
    try {
        return sss::motion::trajectory<T>(*samples, p);
    } catch (const sss::error& e) {
        throw fail(e);
    }
}

/// The towfish's motion: with model "trajectory" the file's (world z from the file; `z_m` unused), else
/// `perturbed` at world z `z_m` (a straight line, turns and oscillations all in one policy).
template <Real T> [[nodiscard]] scene_motion<T> motion_of(const description& d, T z_m) {
    const auto& m = d.tow;
    if (m.model == "trajectory") return scene_motion<T>(load_trajectory<T>(d));
    const auto wobble = [](const oscillation& o) {
        return sss::motion::oscillation<T>{.amplitude = T(o.amplitude), .period_s = T(o.period_s), .phase_deg = T(o.phase_deg)};
    };
    sss::motion::perturbed_params<T> p{.start_m = {T(m.start_m[0]), T(m.start_m[1])}, .heading_deg = T(m.heading_deg),
                                       .speed_mps = T(m.speed_mps), .altitude_m = z_m, .ping_interval_s = T(m.ping_interval_s),
                                       .turn = {}, .yaw_deg = wobble(m.yaw_deg), .sway_m = wobble(m.sway_m),
                                       .pitch_deg = wobble(m.pitch_deg), .heave_m = wobble(m.heave_m), .roll_deg = wobble(m.roll_deg)};
    if (m.turn != "none")
        p.turn = sss::motion::constant_turn<T>{.toward = m.turn == "port" ? sss::side::port : sss::side::starboard,
                                               .radius_m = T(m.turn_radius_m), .rate_deg_s = T(m.turn_rate_deg_s)};
    try {
        return scene_motion<T>(sss::motion::perturbed<T>(p));
    } catch (const sss::invalid_parameter& e) {
        // The policy's names as the scene's keys: perturbed.heave_m.amplitude is motion.heave_m.
        std::string key = e.parameter();
        if (key.rfind("perturbed.", 0) == 0) key = "motion." + key.substr(10);
        if (const auto dot = key.find('.', 7); dot != std::string::npos && key.rfind("motion.turn.", 0) != 0) key.resize(dot);
        if (key.rfind("motion.turn.", 0) == 0) key = "motion.turn_" + key.substr(12);
        std::string why = std::string(sss::message_body(e));
        if (const auto colon = why.find("': "); colon != std::string::npos) why = why.substr(colon + 3);
        throw scene_error(d.path + ": " + key + ": " + why);
    }
}

/// World z of the towfish at ping 0, where the layered water's surface is placed from: tow_z, or with a
/// trajectory the z of its ping 0.
template <Real T> [[nodiscard]] T ping0_z(const description& d, const world<T>& w, const scene_motion<T>& tow) {
    if (d.tow.model == "trajectory") return tow.pose_at(0).position.z;
    return tow_z(d, w);
}

/// The pings [first, last) checked against the trajectory's pings; "" when they all have a pose, else the
/// sentence of the scene_error: `asked` names the setting that asked for them (render.pings or --pings A:B).
template <Real T>
[[nodiscard]] std::string pings_beyond(const description& d, const scene_motion<T>& tow, std::size_t last, const std::string& asked) {
    const std::size_t n = tow.ping_count();
    if (last <= n) return "";
    const bool by_time = tow.sampled() && !tow.sampled()->keyed_by_ping();
    return asked + " reaches ping " + std::to_string(last - 1) + ", but motion.trajectory_file '" + d.tow.trajectory_file + "' covers " +
           std::to_string(n) + " pings (0 to " + std::to_string(n - 1) + ")" +
           (by_time ? " at motion.ping_interval_s = " + detail::fmt(d.tow.ping_interval_s) + " s" : std::string());
}

/// UTC time (s since 1970) of ping `first` in the XTF file: output.xtf_start_unix_s, plus the trajectory's own
/// time of ping 0 when the motion is a trajectory (a CSV timed in Unix seconds then needs no offset), plus ping
/// `first`'s time since ping 0 (`first` ping intervals, or the trajectory's own times where it has them).
template <Real T> [[nodiscard]] double xtf_start_unix_s(const description& d, const scene_motion<T>& tow, std::size_t first) {
    const double ping0_s = tow.sampled() ? tow.sampled()->start_time_s() : 0.0;
    return d.out.xtf_start_unix_s + ping0_s + tow.time_since_ping0_s(first);
}

/// The receiver's stages a scene applies to the lines, in order, each with its parameters in words (the .npy
/// sidecar's receiver_stages): speckle, then noise and volume reverberation added, then the TVG.
[[nodiscard]] inline std::vector<std::pair<std::string, std::string>> receiver_stage_list(const description& d) {
    const auto& r = d.rx;
    std::vector<std::pair<std::string, std::string>> out;
    const std::string seed = ", seed " + std::to_string(r.seed);
    if (r.speckle)
        out.push_back({"speckle", (r.k_shape > 0 ? "K-distributed, shape " + detail::fmt(r.k_shape) + ", texture patch " +
                                                       detail::fmt(r.texture_patch_m) + " m"
                                                 : std::string("Rayleigh")) +
                                      ", transducer length " + detail::fmt(r.transducer_length_m) + " m" + seed});
    if (r.noise)
        out.push_back({"noise", "ambient noise at sea state " + detail::fmt(r.sea_state) + ", directivity index " +
                                    detail::fmt(r.directivity_index_db) + " dB, referred to a source level of " +
                                    detail::fmt(r.noise_source_level_db) + " dB" + seed});
    if (r.volume)
        out.push_back({"volume_reverberation", "Sv " + detail::fmt(r.sv_db) + " dB, equivalent beam angle " +
                                                   (r.psi_sr > 0 ? detail::fmt(r.psi_sr) + " sr" : std::string("the beam's own")) +
                                                   ", above the seabed" + seed});
    if (r.tvg)
        out.push_back({"tvg", "gain " + detail::fmt(r.tvg_spreading_n) + " log10(r) + 2 alpha r + " + detail::fmt(r.tvg_gain_db) +
                                  " dB, alpha " + detail::fmt(d.sea.absorption_db_per_km) + " dB/km"});
    return out;
}

/// The receiver's stages chosen at run time: echo statistics (speckle, noise, volume reverberation), then TVG,
/// each only when the scene asks. With neither, the lines pass through untouched (bit for bit), so one type
/// serves scenes with and without a receiver chain.
class receiver_stages {
public:
    receiver_stages() = default;
    explicit receiver_stages(const description& d) {
        const auto& r = d.rx;
        if (r.speckle || r.noise || r.volume) {
            sss::echo_statistics_params p{.seed = std::uint64_t(r.seed), .speckle = std::nullopt, .noise = std::nullopt, .volume = std::nullopt};
            if (r.speckle)
                p.speckle = sss::speckle_params{.transducer_length_m = r.transducer_length_m, .k_shape = r.k_shape,
                                                .texture_patch_m = r.texture_patch_m};
            if (r.noise)
                p.noise = sss::noise_params{.frequency_hz = d.sensor.frequency_hz, .sea_state = r.sea_state,
                                            .directivity_index_db = r.directivity_index_db, .source_level_db = r.noise_source_level_db};
            if (r.volume)
                p.volume = sss::volume_params{.sv_db = r.sv_db, .psi_sr = r.psi_sr, .absorption_db_per_m = d.sea.absorption_db_per_km / 1e3};
            statistics_.emplace(p);
        }
        if (r.tvg)
            gain_.emplace(sss::tvg_params{.spreading_n = r.tvg_spreading_n, .absorption_db_per_km = d.sea.absorption_db_per_km,
                                          .gain_db = r.tvg_gain_db});
    }
    [[nodiscard]] bool needs_materials() const noexcept { return statistics_ && statistics_->needs_materials(); }
    [[nodiscard]] bool needs_beam() const noexcept { return statistics_ && statistics_->needs_beam(); }
    template <Real T> void process(std::vector<T>& line, const sss::line_context<T>& ctx) const {
        if (statistics_) statistics_->process(line, ctx);
        if (gain_) gain_->process(line, ctx);
    }

private:
    std::optional<sss::echo_statistics> statistics_;
    std::optional<sss::tvg> gain_;
};

// ---------------------------------------------------------------------------------------------
// The whitelist: the simulator types sss-render is compiled with, listed here and nowhere else.
//   {float, double} x {lambertian, jackson seabed + hard_target objects} x {straight, layered} water
// each x scene_beam<T> x scene_motion<T> x receiver_stages. The beam and the motion are run-time choices
// (policies.hpp): scene_beam holds the ideal fan or the planar array, scene_motion the perturbed track (a
// straight line, a turn, oscillations) or a sampled trajectory, so they add no instantiation: eight simulator
// types serve every beam and motion. The scalar is render.precision; with_simulator<T> instantiates only T's,
// so sss-render compiles each scalar in its own translation unit (render_float.cpp, render_double.cpp).
// Double is for coordinates float cannot hold to a centimetre (a georeferenced seabed, UTM eastings and
// northings, a long track), with every scattering and water a survey there may need: a bathymetry in UTM
// coordinates with a measured sound-speed profile is the case double exists for. Each simulator type costs about
// 6 s of compile time per build; the other policies are run-time choices, so the product stays at eight.

template <Real T> using policy = sss::policies<T>;
template <Real T, class Scattering, class Propagation>
using simulator_of = sss::simulator<Scattering, Propagation, scene_beam<T>, scene_motion<T>, receiver_stages>;
template <Real T> using jackson_scattering = sss::scattering::by_material<typename policy<T>::jackson, sss::scattering::hard_target<T>>;

/// The sound-speed file of a layered scene (water.svp_file), read and held to the scene's own rule for its knots:
/// every speed in [1300, 1700] m/s. Its errors name the key and the file.
template <Real T> [[nodiscard]] sss::propagation::sound_speed_profile<T> load_sound_speed_file(const description& d) {
    std::optional<sss::propagation::sound_speed_profile<T>> profile;
    try {
        profile.emplace(sss::io::read_sound_speed_csv<T>(d.sea.svp_file));
    } catch (const sss::error& e) {
        std::string what = e.what();
        if (what.rfind("sss: ", 0) == 0) what = what.substr(5);
        throw scene_error(d.path + ": water.svp_file: " + what);
    }
    for (std::size_t i = 0; i < profile->speeds_mps().size(); ++i) {
        const double c = double(profile->speeds_mps()[i]);
        if (!(c >= 1300 && c <= 1700))
            throw scene_error(d.path + ": water.svp_file: " + d.sea.svp_file + ": knot " + std::to_string(i + 1) + " (depth " +
                              detail::fmt(double(profile->depths_m()[i])) + " m): speed " + detail::fmt(c) +
                              " m/s is outside [1300, 1700] m/s");
    }
    return std::move(*profile);
}

/// The checks of load_sound_speed_file, for --dry-run; nothing without a file.
inline void check_sound_speed_file(const description& d) {
    if (d.sea.model == "layered" && !d.sea.svp_file.empty()) (void)load_sound_speed_file<double>(d);
}

/// The layered water of scene d: its profile, the surface ping0_z + towfish_depth_m above, its absorption.
template <Real T>
[[nodiscard]] sss::propagation::layered<T> layered_water(const description& d, const world<T>& w, const scene_motion<T>& tow) {
    auto profile = d.sea.svp_file.empty()
                       ? sss::propagation::sound_speed_profile<T>(std::vector<T>(d.sea.depth_m.begin(), d.sea.depth_m.end()),
                                                                  std::vector<T>(d.sea.speed_mps.begin(), d.sea.speed_mps.end()))
                       : load_sound_speed_file<T>(d);
    return sss::propagation::layered<T>(
        std::move(profile),
        {.surface_z_m = ping0_z(d, w, tow) + T(d.sea.towfish_depth_m), .frequency_hz = T(d.sensor.frequency_hz),
         .water = {.temperature_c = T(d.sea.temperature_c), .salinity_ppt = T(d.sea.salinity_ppt), .ph = T(d.sea.ph)},
         .absorption = d.sea.absorption_model == "ainslie_mccolm" ? sss::propagation::absorption_formula::ainslie_mccolm
                                                                  : sss::propagation::absorption_formula::francois_garrison,
         .reference_speed_mps = T(d.sea.sound_speed_mps)});
}

template <Real T, class Water, class F>
decltype(auto) with_water(const description& d, const scene_motion<T>& tow, const Water& water, F&& f);

/// Calls f(simulator) with the whitelisted simulator the scene asks for, of the world's scalar T; the scene's
/// own words name it.
template <Real T, class F> decltype(auto) with_simulator(const description& d, const world<T>& w, F&& f) {
    const scene_motion<T> tow = motion_of(d, tow_z(d, w));
    if (d.sea.model == "layered") return with_water(d, tow, layered_water(d, w, tow), std::forward<F>(f));
    const sss::propagation::straight<T> water(
        {.sound_speed_mps = T(d.sea.sound_speed_mps), .absorption_db_per_km = T(d.sea.absorption_db_per_km)});
    return with_water(d, tow, water, std::forward<F>(f));
}

/// with_simulator's second step: the scattering, for the water already chosen.
template <Real T, class Water, class F>
decltype(auto) with_water(const description& d, const scene_motion<T>& tow, const Water& water, F&& f) {
    const scene_beam<T> beam = beam_of<T>(d);
    const auto rx = receiver_of(d);
    const auto regions = sediment_regions<T>(d);
    if (d.sensor.scattering == "jackson") {
        const jackson_scattering<T> scatter(
            sss::seabed::jackson_for(regions, {.frequency_hz = T(d.sensor.frequency_hz), .sound_speed_mps = T(d.sea.sound_speed_mps)}),
            sss::scattering::hard_target<T>{});
        return f(simulator_of<T, jackson_scattering<T>, Water>(scatter, water, beam, tow, rx, rays_of(d), receiver_stages(d)));
    }
    std::vector<T> mu;
    if (d.bed.regions.empty()) mu.push_back(T(region{}.mu_db));
    for (const auto& g : d.bed.regions) mu.push_back(T(g.mu_db));
    mu.push_back(T(d.sensor.target_mu_db));
    using lambertian = typename policy<T>::lambertian;
    return f(simulator_of<T, lambertian, Water>(lambertian({.mu_db = mu}), water, beam, tow, rx, rays_of(d), receiver_stages(d)));
}

} // namespace sss::scene_file
