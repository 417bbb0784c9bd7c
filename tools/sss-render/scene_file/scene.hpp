#pragma once
/// \file
/// The resolved scene of a scene file: every setting, each default filled in. Plain data in the units and the
/// field names of the library's parameter structs (docs/scene-format.md lists each key). Angles are degrees,
/// headings clockwise from north, as everywhere at sss's public boundaries.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <system_error>
#include <string>
#include <string_view>
#include <vector>

namespace sss::scene_file {

using xy = std::array<double, 2>;

/// Most pings one run renders (`render.pings`, `--pings`): a day and more at 10 pings/s; a longer survey is
/// rendered in ping ranges.
inline constexpr std::int64_t max_pings = 10'000'000;
/// Most worker threads (`render.threads`, `--threads`).
inline constexpr std::int64_t max_threads = 1024;
/// The longest output.stem (bytes): with the longest suffix ("_ground_labels_instance.png"), the run's temporary
/// names (".STEM....partial-" and 16 hexadecimal digits) and the writer's own (".tmp-" and 16 more), a file name
/// of 255 bytes.
inline constexpr std::size_t max_stem_bytes = 180;

struct ripples {
    double wavelength_m = 0.5, height_m = 0.05, crest_heading_deg = 90, symmetry_index = 1;
    double sinuosity_m = 0, sinuosity_wavelength_m = 0, perturbation_m = 0, height_variation = 0;
};

struct region {
    std::string sediment = "medium_sand"; ///< a Table 2 sediment (APL-UW TR 9407) by name: roughness and Jackson scattering
    double mean_height_m = 0;
    double outer_scale_m = 20;
    double mu_db = -27; ///< Lambert strength under `scattering = "lambertian"`
    std::vector<ripples> ripple_sets;
};

struct site {
    double x_m = 0, y_m = 0;
    std::int64_t region = 0;
};

/// A feature stamped on the generated seabed (seabed/stamps.hpp), world coordinates.
struct stamp {
    std::string type = "mound"; ///< plate, mound, scour or trench
    xy center_m{0, 0};          ///< plate, mound, scour
    double heading_deg = 90;    ///< plate, mound, scour: the long axis
    double length_m = 1, width_m = 1, top_m = 0.1;                   // plate
    double radius_u_m = 1, radius_v_m = 1, height_m = 0.3;           // mound (and scour's radii)
    double depth_m = 0.3, rim_height_m = 0, rim_width_m = 0;         // scour (depth_m also trench)
    xy start_m{0, 0}, end_m{1, 0};                                   // trench
    double floor_width_m = 0, berm_height_m = 0, berm_width_m = 0;   // trench (width_m its top width)
};

struct seabed {
    std::string file;           ///< a height file to load instead of generating (.asc, .raw + .raw.txt, .pgm); "" generates
    double pgm_scale_m = 0.01, pgm_offset_m = 0; ///< a .pgm's heights: offset + scale x sample (m)
    std::int64_t nx = 512, ny = 512;
    double cell_m = 0.1;
    xy origin_m{0, 0};
    std::int64_t seed = 11;     ///< roughness and ripple seed
    double blend_m = 0.5;       ///< width of the blend between regions (m)
    double warp_m = 0;          ///< RMS displacement of the region boundaries (m): fractal boundaries
    double warp_scale_m = 10;
    std::int64_t partition_seed = 7;
    std::vector<region> regions; ///< empty: a flat seabed at z = 0 (generated) of material 0
    std::vector<site> sites;     ///< Voronoi sites; empty with one region: that region everywhere
    std::vector<stamp> stamps;   ///< features stamped on the generated heights, in order
};

/// The kind of seabed `seabed.file` names, by its extension; `generated` when it is empty.
enum class seabed_format { generated, esri_ascii, raw_f32, pgm, unknown };

/// The format of the seabed in `file` ("" generates one): ESRI ASCII (.asc), raw float32 with its .raw.txt sidecar
/// (.raw), binary PGM (.pgm), or a file sss does not read.
inline seabed_format seabed_format_of(std::string_view file) {
    if (file.empty()) return seabed_format::generated;
    if (file.ends_with(".asc")) return seabed_format::esri_ascii;
    if (file.ends_with(".raw")) return seabed_format::raw_f32;
    if (file.ends_with(".pgm")) return seabed_format::pgm;
    return seabed_format::unknown;
}

/// A [seabed] key that the seabed from `file` does not use, with why.
struct unused_seabed_key {
    const char* key;
    const char* why;
};

/// The [seabed] keys that a seabed from `file` ("" generates one from its `regions` [[seabed.region]] tables, flat
/// without any) does not use: a loaded seabed takes no generation keys and its size is the file's; a .asc or .raw also
/// brings its cell size and place (header or sidecar), a .pgm does not; only a .pgm has samples to scale; a generated
/// seabed without regions is flat, with nothing to seed, partition or blend, and one with a single region has no
/// boundary to place or blend. The reader refuses them, the writer leaves them out.
inline std::vector<unused_seabed_key> unused_seabed_keys(std::string_view file, std::size_t regions) {
    const seabed_format format = seabed_format_of(file);
    std::vector<unused_seabed_key> out;
    if (format != seabed_format::pgm)
        for (const char* k : {"pgm_scale_m", "pgm_offset_m"}) out.push_back({k, "applies only to a .pgm seabed.file (its samples' heights)"});
    constexpr std::array generation{"seed", "blend_m", "warp_m", "warp_scale_m", "partition_seed"};
    if (format == seabed_format::generated) {
        if (regions == 0)
            for (const char* k : generation)
                out.push_back({k, "applies only to a seabed generated from [[seabed.region]] tables (without them there is no roughness, ripple or region boundary to synthesise)"});
        else if (regions == 1)
            for (const char* k : {"blend_m", "warp_m", "warp_scale_m", "partition_seed"})
                out.push_back({k, "applies only where [[seabed.region]] tables meet (with one region there is no boundary to place or blend)"});
        return out;
    }
    for (const char* k : {"nx", "ny"}) out.push_back({k, "a loaded seabed's size is its file's"});
    if (format != seabed_format::pgm)
        for (const char* k : {"cell_m", "origin_m"})
            out.push_back({k, format == seabed_format::raw_f32 ? "a loaded .raw seabed is placed by its .raw.txt sidecar"
                                                                : "a loaded .asc seabed is placed by its header (cellsize, xllcorner, yllcorner)"});
    for (const char* k : generation) out.push_back({k, "sets the generated seabed, and seabed.file loads one"});
    return out;
}

struct object {
    std::string origin; ///< where the scene file defines it ("scene.toml:12:1: object[0]"), for errors of the built scene
    std::string type = "lying_cylinder"; ///< lying_cylinder, tethered_mine, pipeline, sphere, cylinder
    std::int64_t class_id = 1;
    std::string class_name; ///< the class's name in the label files; "" in a file: the type
    // lying_cylinder
    xy center_m{0, 0};
    double heading_deg = 90, length_m = 2, radius_m = 0.25;
    // tethered_mine
    xy anchor_m{0, 0};
    std::string case_shape = "sphere";
    double case_height_m = 5, case_radius_m = 0.5, case_length_m = 1.5, case_heading_deg = 90;
    // sphere (center_m, radius_m) and cylinder (center_m to end_m, radius_m): raw primitives, heights above the seabed
    double height_m = 1;   ///< sphere: centre above the seabed under center_m (m)
    xy end_m{1, 0};        ///< cylinder: the second end's plan position
    double end0_height_m = 0.5, end1_height_m = 0.5; ///< cylinder: each end above the seabed under it (m)
    // pipeline
    std::vector<xy> route_m;
    double max_span_m = 0; ///< 0: unlimited (the pipe follows the seabed only where it is taut)
};

struct water {
    std::string model = "straight"; ///< straight (isovelocity) or layered (refraction through a profile)
    double sound_speed_mps = 1500;  ///< straight: the speed; layered: the reference speed of the time axis
    double absorption_db_per_km = 30; ///< straight: the absorption (and the display's, both models)
    // layered
    std::string svp_file;           ///< a sound-speed CSV (depth_m, speed_mps); or the knots below
    std::vector<double> depth_m{0.0}, speed_mps{1500.0};
    double towfish_depth_m = 20;    ///< depth of the towfish below the surface (m)
    std::string absorption_model = "francois_garrison"; ///< or ainslie_mccolm, at sonar.frequency_hz
    double temperature_c = 10, salinity_ppt = 35, ph = 8;
};

/// One axis of a planar array's elements (beam/planar_array.hpp, array_axis).
struct array_axis {
    std::int64_t count = 1;      ///< elements along this axis, >= 1
    double element_m = 0.5;      ///< element length along this axis (m), > 0
    double pitch_m = 0.5;        ///< centre-to-centre spacing (m), >= element_m when count > 1 (default element_m)
    std::vector<double> shading; ///< amplitude weight per element (count of them); empty: uniform
};

/// The elements of a transmit or receive array: along track and in the tilted vertical plane.
struct array_layout {
    array_axis along{};
    array_axis vertical{.count = 1, .element_m = 0.02, .pitch_m = 0.02, .shading = {}};
};

struct sonar {
    std::string scattering = "lambertian"; ///< lambertian or jackson (seabed Jackson + targets hard_target)
    std::string beam = "ideal_fan";        ///< ideal_fan or planar_array
    double frequency_hz = 100000;
    double target_mu_db = -8; ///< Lambert strength of the objects under lambertian
    double along_width_deg = 1, vertical_width_deg = 50, depression_deg = 20;
    double sample_rate_hz = 20000, max_range_m = 50, source_level_db = 0;
    double pulse_length_s = 100e-6;
    std::string pulse_shape = "rectangular"; ///< rectangular, hann, lfm
    double pulse_bandwidth_hz = 0;
    // planar_array (frequency_hz, water.sound_speed_mps and depression_deg shared with the rest)
    double beam_threshold_db = -30;       ///< two-way level bounding the beam's extent (dB), < 0
    array_layout transmit{};              ///< the transmitting array
    std::optional<array_layout> receive;  ///< the receiving array; empty: the transmitting array receives
};

/// A periodic perturbation of the towfish: amplitude x sin(2 pi t / period + phase).
struct oscillation {
    double amplitude = 0, period_s = 1, phase_deg = 0;
};

struct motion {
    std::string model = "perturbed"; ///< perturbed (the keys below) or trajectory (a sampled track from a CSV file)
    // trajectory
    std::string trajectory_file;        ///< the CSV (io/trajectory_csv.hpp); relative: to the scene file's directory
    std::string interpolation = "cubic"; ///< cubic or linear
    std::optional<double> ping_zero_at;  ///< key (time in s, or ping number) of ping 0; empty: the first sample's
    bool roll_from_turn = false;         ///< without a roll column: the coordinated-turn bank angle instead of 0
    // perturbed (ping_interval_s: both)
    xy start_m{0, 0};
    double heading_deg = 0, speed_mps = 2;
    double altitude_m = 10; ///< above the seabed under start_m (m)
    double ping_interval_s = 0.1;
    std::string turn = "none"; ///< none, port or starboard: a constant turn from ping 0
    double turn_radius_m = 0, turn_rate_deg_s = 0;
    oscillation yaw_deg, sway_m, pitch_deg, heave_m, roll_deg;
};

/// The receiver's line stages (receiver/line_stage.hpp), each off unless asked for.
struct receiver {
    std::int64_t seed = 1; ///< speckle and noise seed
    bool speckle = false;
    double transducer_length_m = 0.5, k_shape = 0, texture_patch_m = 1;
    bool noise = false;
    double sea_state = 2, directivity_index_db = 20, noise_source_level_db = 210;
    bool volume = false;
    double sv_db = -80, psi_sr = 0; // psi_sr 0: the beam's own equivalent two-way solid angle
    bool tvg = false;
    double tvg_spreading_n = 30, tvg_gain_db = 0;
};

struct output {
    std::string stem = "sss";
    bool png = true;
    double png_dynamic_range_db = 40;
    std::string png_scale = "db"; ///< db: a dB window; quantised: 8-bit amplitude counts, the 95th percentile at 100
    bool ground_range = false;    ///< stem_ground.png: the PNG resampled to ground range (flat seabed at each ping's altitude)
    double ground_range_cell_m = 0.1;
    bool npy = false; ///< stem.npy and its sidecar stem.json
    bool xtf = false; ///< stem.xtf: two float channels, latitude/longitude from xtf_origin_*
    double xtf_origin_latitude_deg = 0, xtf_origin_longitude_deg = 0, xtf_start_unix_s = 0;
    std::int64_t xtf_utm_zone = 0;             ///< 1 to 60: world x, y are UTM easting, northing there; 0: a local plane
    std::string xtf_utm_hemisphere = "north"; ///< north or south, with xtf_utm_zone
    bool coco = false;         ///< stem_coco.json: boxes (highlight and shadow) and masks of the objects
    bool yolo = false;         ///< stem.txt and classes.txt
    bool label_images = false; ///< stem_labels_class.png, stem_labels_instance.png, stem_labels_legend.json
};

struct render {
    std::int64_t pings = 100;
    std::int64_t threads = 0; ///< 0: every core
    // The rays (sss::ray_density)
    std::int64_t rays_along = 8;             ///< along-track columns per side, at least (the beam may ask for more)
    double rays_per_sample = 1;              ///< rays per range sample in each column
    std::string seabed_edges_along = "auto"; ///< auto, on or off: the seabed's shadow edges in the along-track check
    std::int64_t along_split = 9;            ///< narrowest columns of that check, as a fraction of a column
    bool along_split_by_weight = true;       ///< that depth shared among the columns by the beam's weight on each
    bool refine_facets = true;               ///< refine across the seabed's facets' edges where the echo jumps
    bool bracket_facet_edges = true;         ///< there, the rays either side of where the edge lies (not halving)
    bool along_split_sparse = true;          ///< the narrowest columns at every other launch angle
    bool along_split_targets = true;         ///< small targets divide the columns over them along track
    bool along_split_nadir = true;           ///< near the first return, columns over a seabed not one plane divide,
                                             ///< and over a plane those across which the first return moves
    double along_split_echo = 0.1;           ///< columns divide where their echo departs from their neighbours' by
                                             ///< more than this fraction of the three columns' echo
    double along_onset = 1.0;                ///< how far (range samples) the first return may move across a column
    double max_launch_step_deg = 1.0;        ///< largest step between a column's launch angles across track (0: none)
    bool sloping_launch = true;              ///< launch for a plane fitted to a sloping seabed where that saves rays
    std::string precision = "float";         ///< float or double: the scalar of the world and the simulator (build.hpp)
};

struct description {
    std::string path; ///< the file it came from (for messages)
    render run;
    seabed bed;
    std::vector<object> objects;
    water sea;
    sonar sensor;
    motion tow;
    receiver rx;
    output out;
};

/// Where a file key's path (`seabed.file`, `water.svp_file`, `motion.trajectory_file`) leads from the scene file
/// `scene_path`: a relative path is taken from the scene file's directory, as an #include is, so that a scene and its
/// data files can be moved and run from anywhere together; an absolute path, or an empty one (no file), stays.
[[nodiscard]] inline std::string beside_scene(const std::string& scene_path, const std::string& key_path) {
    if (key_path.empty()) return key_path;
    const std::filesystem::path p(key_path);
    if (p.is_absolute()) return key_path;
    const std::filesystem::path dir = std::filesystem::path(scene_path).parent_path();
    return dir.empty() ? key_path : (dir / p).string();
}

/// A file key's path as a resolved scene writes it: absolute, so that the resolved scene reads the same files from
/// wherever it is saved (empty: no file; unchanged where the working directory is unknown).
[[nodiscard]] inline std::string absolute_path(const std::string& key_path) {
    if (key_path.empty()) return key_path;
    std::error_code ec;
    const std::filesystem::path a = std::filesystem::absolute(std::filesystem::path(key_path), ec);
    return ec ? key_path : a.string();
}

} // namespace sss::scene_file
