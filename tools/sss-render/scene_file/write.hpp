#pragma once
/// \file
/// Writing a resolved `description` back as a scene file (TOML): every key it uses, every default filled in, numbers
/// in their shortest round-trip form, so that reading the text again gives the same description.

#include "scene.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>

namespace sss::scene_file {

namespace detail {

inline std::string num(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    std::string s(buf, r.ptr);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0"; // stays a TOML float
    return s;
}
/// A TOML basic string: quotes and backslashes escaped, control characters as \uXXXX (TOML allows none raw).
inline std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) {
            char buf[16];
            std::snprintf(buf, sizeof buf, "\\u%04X", unsigned(u));
            out += buf;
            continue;
        }
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}
inline std::string pt(const xy& p) {
    // Appended piece by piece: GCC 12 at -O3 warns (falsely) of an overflow in "[" + std::string.
    std::string s = "[";
    s += num(p[0]);
    s += ", ";
    s += num(p[1]);
    s += ']';
    return s;
}

struct toml_out {
    std::string text;
    void header(const std::string& h) { text += (text.empty() ? "" : "\n") + h + "\n"; }
    void kv(const char* k, double v) { text += std::string(k) + " = " + num(v) + "\n"; }
    void kv(const char* k, std::int64_t v) { text += std::string(k) + " = " + std::to_string(v) + "\n"; }
    void kv(const char* k, bool v) { text += std::string(k) + " = " + (v ? "true" : "false") + "\n"; }
    void kv(const char* k, const std::string& v) { text += std::string(k) + " = " + quoted(v) + "\n"; }
    void kv(const char* k, const xy& v) { text += std::string(k) + " = " + pt(v) + "\n"; }
};

} // namespace detail

/// The scene file text of d (its `path` is not written; its file keys are written as absolute paths).
[[nodiscard]] inline std::string to_toml(const description& d) {
    detail::toml_out o;
    o.header("[render]");
    o.kv("pings", d.run.pings);
    o.kv("threads", d.run.threads);
    o.kv("rays_along", d.run.rays_along);
    o.kv("rays_per_sample", d.run.rays_per_sample);
    o.kv("seabed_edges_along", d.run.seabed_edges_along);
    o.kv("along_split", d.run.along_split);
    o.kv("along_split_by_weight", d.run.along_split_by_weight);
    o.kv("refine_facets", d.run.refine_facets);
    o.kv("bracket_facet_edges", d.run.bracket_facet_edges);
    o.kv("along_split_sparse", d.run.along_split_sparse);
    o.kv("along_split_targets", d.run.along_split_targets);
    o.kv("along_split_nadir", d.run.along_split_nadir);
    o.kv("along_split_echo", d.run.along_split_echo);
    o.kv("along_onset", d.run.along_onset);
    o.kv("max_launch_step_deg", d.run.max_launch_step_deg);
    o.kv("sloping_launch", d.run.sloping_launch);
    o.kv("precision", d.run.precision);

    const auto& b = d.bed;
    o.header("[seabed]");
    o.kv("file", absolute_path(b.file));
    // The keys this seabed does not use are left out (the reader refuses them).
    const auto unused = unused_seabed_keys(b.file, b.regions.size());
    const auto used = [&](std::string_view key) {
        return std::none_of(unused.begin(), unused.end(), [&](const unused_seabed_key& u) { return key == u.key; });
    };
    if (used("pgm_scale_m")) o.kv("pgm_scale_m", b.pgm_scale_m);
    if (used("pgm_offset_m")) o.kv("pgm_offset_m", b.pgm_offset_m);
    if (used("nx")) o.kv("nx", b.nx);
    if (used("ny")) o.kv("ny", b.ny);
    if (used("cell_m")) o.kv("cell_m", b.cell_m);
    if (used("origin_m")) o.kv("origin_m", b.origin_m);
    if (used("seed")) o.kv("seed", b.seed);
    if (used("blend_m")) o.kv("blend_m", b.blend_m);
    if (used("warp_m")) o.kv("warp_m", b.warp_m);
    if (used("warp_scale_m")) o.kv("warp_scale_m", b.warp_scale_m);
    if (used("partition_seed")) o.kv("partition_seed", b.partition_seed);
    for (const auto& g : b.regions) {
        o.header("[[seabed.region]]");
        o.kv("sediment", g.sediment);
        o.kv("mean_height_m", g.mean_height_m);
        o.kv("outer_scale_m", g.outer_scale_m);
        o.kv("mu_db", g.mu_db);
        for (const auto& p : g.ripple_sets) {
            o.header("[[seabed.region.ripples]]");
            o.kv("wavelength_m", p.wavelength_m);
            o.kv("height_m", p.height_m);
            o.kv("crest_heading_deg", p.crest_heading_deg);
            o.kv("symmetry_index", p.symmetry_index);
            o.kv("sinuosity_m", p.sinuosity_m);
            o.kv("sinuosity_wavelength_m", p.sinuosity_wavelength_m);
            o.kv("perturbation_m", p.perturbation_m);
            o.kv("height_variation", p.height_variation);
        }
    }
    for (const auto& s : b.sites) {
        o.header("[[seabed.site]]");
        o.kv("x_m", s.x_m);
        o.kv("y_m", s.y_m);
        o.kv("region", s.region);
    }
    for (const auto& p : b.stamps) {
        o.header("[[seabed.stamp]]");
        o.kv("type", p.type);
        if (p.type == "trench") {
            o.kv("start_m", p.start_m);
            o.kv("end_m", p.end_m);
            o.kv("width_m", p.width_m);
            o.kv("floor_width_m", p.floor_width_m);
            o.kv("depth_m", p.depth_m);
            o.kv("berm_height_m", p.berm_height_m);
            o.kv("berm_width_m", p.berm_width_m);
            continue;
        }
        o.kv("center_m", p.center_m);
        o.kv("heading_deg", p.heading_deg);
        if (p.type == "plate") {
            o.kv("length_m", p.length_m);
            o.kv("width_m", p.width_m);
            o.kv("top_m", p.top_m);
            continue;
        }
        o.kv("radius_u_m", p.radius_u_m);
        o.kv("radius_v_m", p.radius_v_m);
        if (p.type == "mound") {
            o.kv("height_m", p.height_m);
        } else {
            o.kv("depth_m", p.depth_m);
            o.kv("rim_height_m", p.rim_height_m);
            o.kv("rim_width_m", p.rim_width_m);
        }
    }
    for (const auto& ob : d.objects) {
        o.header("[[object]]");
        o.kv("type", ob.type);
        o.kv("class_id", ob.class_id);
        o.kv("class_name", ob.class_name);
        if (ob.type == "lying_cylinder") {
            o.kv("center_m", ob.center_m);
            o.kv("heading_deg", ob.heading_deg);
            o.kv("length_m", ob.length_m);
            o.kv("radius_m", ob.radius_m);
        } else if (ob.type == "sphere") {
            o.kv("center_m", ob.center_m);
            o.kv("height_m", ob.height_m);
            o.kv("radius_m", ob.radius_m);
        } else if (ob.type == "cylinder") {
            o.kv("center_m", ob.center_m);
            o.kv("end_m", ob.end_m);
            o.kv("end0_height_m", ob.end0_height_m);
            o.kv("end1_height_m", ob.end1_height_m);
            o.kv("radius_m", ob.radius_m);
        } else if (ob.type == "tethered_mine") {
            o.kv("anchor_m", ob.anchor_m);
            o.kv("case_shape", ob.case_shape);
            o.kv("case_height_m", ob.case_height_m);
            o.kv("case_radius_m", ob.case_radius_m);
            o.kv("case_length_m", ob.case_length_m);
            o.kv("case_heading_deg", ob.case_heading_deg);
        } else {
            std::string r = "route_m = [";
            for (std::size_t i = 0; i < ob.route_m.size(); ++i) r += (i ? ", " : "") + detail::pt(ob.route_m[i]);
            o.text += r + "]\n";
            o.kv("radius_m", ob.radius_m);
            o.kv("max_span_m", ob.max_span_m);
        }
    }
    o.header("[water]");
    o.kv("sound_speed_mps", d.sea.sound_speed_mps);
    o.kv("absorption_db_per_km", d.sea.absorption_db_per_km);
    o.kv("model", d.sea.model);
    if (d.sea.model == "layered") {
        o.kv("svp_file", absolute_path(d.sea.svp_file));
        std::string dl = "depth_m = [", sl = "speed_mps = [";
        for (std::size_t i = 0; i < d.sea.depth_m.size(); ++i) {
            dl += (i ? ", " : "") + detail::num(d.sea.depth_m[i]);
            sl += (i ? ", " : "") + detail::num(d.sea.speed_mps[i]);
        }
        o.text += dl + "]\n" + sl + "]\n";
        o.kv("towfish_depth_m", d.sea.towfish_depth_m);
        o.kv("absorption_model", d.sea.absorption_model);
        o.kv("temperature_c", d.sea.temperature_c);
        o.kv("salinity_ppt", d.sea.salinity_ppt);
        o.kv("ph", d.sea.ph);
    }

    const auto& s = d.sensor;
    o.header("[sonar]");
    o.kv("scattering", s.scattering);
    o.kv("beam", s.beam);
    o.kv("frequency_hz", s.frequency_hz);
    o.kv("target_mu_db", s.target_mu_db);
    o.kv("along_width_deg", s.along_width_deg);
    o.kv("vertical_width_deg", s.vertical_width_deg);
    o.kv("depression_deg", s.depression_deg);
    o.kv("sample_rate_hz", s.sample_rate_hz);
    o.kv("max_range_m", s.max_range_m);
    o.kv("source_level_db", s.source_level_db);
    o.kv("pulse_length_s", s.pulse_length_s);
    o.kv("pulse_shape", s.pulse_shape);
    o.kv("pulse_bandwidth_hz", s.pulse_bandwidth_hz);
    if (s.beam == "planar_array") {
        o.kv("beam_threshold_db", s.beam_threshold_db);
        const auto layout = [&](const char* header, const array_layout& a) {
            o.header(header);
            for (const auto& [name, x] : {std::pair<std::string, const array_axis*>{"along", &a.along}, {"vertical", &a.vertical}}) {
                o.kv((name + "_count").c_str(), x->count);
                o.kv((name + "_element_m").c_str(), x->element_m);
                o.kv((name + "_pitch_m").c_str(), x->pitch_m);
                std::string list = name + "_shading = [";
                for (std::size_t i = 0; i < x->shading.size(); ++i) list += (i ? ", " : "") + detail::num(x->shading[i]);
                o.text += list + "]\n";
            }
        };
        layout("[sonar.transmit]", s.transmit);
        if (s.receive) layout("[sonar.receive]", *s.receive);
    }

    o.header("[motion]");
    o.kv("model", d.tow.model);
    o.kv("ping_interval_s", d.tow.ping_interval_s);
    if (d.tow.model == "trajectory") {
        // The perturbed motion's keys are not used by a trajectory: not written.
        o.kv("trajectory_file", absolute_path(d.tow.trajectory_file));
        o.kv("interpolation", d.tow.interpolation);
        if (d.tow.ping_zero_at) o.kv("ping_zero_at", *d.tow.ping_zero_at);
        o.kv("roll_from_turn", d.tow.roll_from_turn);
    } else {
        o.kv("start_m", d.tow.start_m);
        o.kv("heading_deg", d.tow.heading_deg);
        o.kv("speed_mps", d.tow.speed_mps);
        o.kv("altitude_m", d.tow.altitude_m);
        o.kv("turn", d.tow.turn);
        o.kv("turn_radius_m", d.tow.turn_radius_m);
        o.kv("turn_rate_deg_s", d.tow.turn_rate_deg_s);
        const std::pair<const char*, const oscillation*> wobbles[] = {{"yaw_deg", &d.tow.yaw_deg}, {"sway_m", &d.tow.sway_m},
            {"pitch_deg", &d.tow.pitch_deg}, {"heave_m", &d.tow.heave_m}, {"roll_deg", &d.tow.roll_deg}};
        for (const auto& [name, w] : wobbles) {
            o.header(std::string("[motion.") + name + "]");
            o.kv("amplitude", w->amplitude);
            o.kv("period_s", w->period_s);
            o.kv("phase_deg", w->phase_deg);
        }
    }

    const auto& r = d.rx;
    o.header("[receiver]");
    o.kv("seed", r.seed);
    o.kv("speckle", r.speckle);
    o.kv("transducer_length_m", r.transducer_length_m);
    o.kv("k_shape", r.k_shape);
    o.kv("texture_patch_m", r.texture_patch_m);
    o.kv("noise", r.noise);
    o.kv("sea_state", r.sea_state);
    o.kv("directivity_index_db", r.directivity_index_db);
    o.kv("noise_source_level_db", r.noise_source_level_db);
    o.kv("volume", r.volume);
    o.kv("sv_db", r.sv_db);
    o.kv("psi_sr", r.psi_sr);
    o.kv("tvg", r.tvg);
    o.kv("tvg_spreading_n", r.tvg_spreading_n);
    o.kv("tvg_gain_db", r.tvg_gain_db);

    o.header("[output]");
    o.kv("stem", d.out.stem);
    o.kv("png", d.out.png);
    o.kv("png_dynamic_range_db", d.out.png_dynamic_range_db);
    o.kv("png_scale", d.out.png_scale);
    o.kv("ground_range", d.out.ground_range);
    o.kv("ground_range_cell_m", d.out.ground_range_cell_m);
    o.kv("npy", d.out.npy);
    o.kv("xtf", d.out.xtf);
    if (d.out.xtf_utm_zone == 0) { // a local plane about the origin; in a UTM zone the origin keys are not used
        o.kv("xtf_origin_latitude_deg", d.out.xtf_origin_latitude_deg);
        o.kv("xtf_origin_longitude_deg", d.out.xtf_origin_longitude_deg);
    }
    o.kv("xtf_utm_zone", d.out.xtf_utm_zone);
    if (d.out.xtf_utm_zone > 0) o.kv("xtf_utm_hemisphere", d.out.xtf_utm_hemisphere);
    o.kv("xtf_start_unix_s", d.out.xtf_start_unix_s);
    o.kv("coco", d.out.coco);
    o.kv("yolo", d.out.yolo);
    o.kv("label_images", d.out.label_images);
    return o.text;
}

} // namespace sss::scene_file
