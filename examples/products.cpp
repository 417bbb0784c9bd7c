// One scene, every product: a lying cylinder, a tethered mine and a pipeline on a rough sandy seabed, rendered and
// written as the files sonar tools and learning pipelines read. Output directory argv[1] (default sss_products):
//   products.xtf                  XTF, two sidescan channels, float samples, latitude/longitude (origin 57.7 N 11.9 E)
//   products.png                  the waterfall, 8 bits, range-compensated display over a 40 dB window
//   products.npy, products.json   the waterfall as float32 for numpy.load, and its sidecar (dt, c, range, poses)
//   products_coco.json            COCO boxes (highlight + shadow) with RLE masks; products_highlight_coco.json
//   products.txt, classes.txt     YOLO boxes (highlight + shadow) and the class names
//   products_labels_class.png     per-sample class (0 no coverage, 1 water, 2 seabed, 3 highlight, 4 shadow,
//                                 5 seabed shadow),
//   products_labels_instance.png  object id + 1 on highlight and shadow (16 bits), products_labels_legend.json
//   products_labels_view.png      the class image spread over the grey range, to look at
//   products_ground_labels_*      the labels on a 5 cm ground-range grid (flat-bottom mapping), same three files
// No dependency beyond the library (its PNG writer needs no libpng).

#include <sss/sss.hpp>
#include <sss/io/labels.hpp>
#include <sss/io/npy.hpp>
#include <sss/io/png.hpp>
#include <sss/io/xtf.hpp>
#include <sss/labels/ground_truth.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/targets.hpp>

#include "common/display.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

int main(int argc, char** argv) try {
    using T = float;
    namespace sb = sss::seabed;
    using namespace sss;
    const std::string dir = argc > 1 ? argv[1] : "sss_products";
    std::filesystem::create_directories(dir);
    const std::string stem = dir + "/products";
    const auto t0 = std::chrono::steady_clock::now();

    // Seabed: 102.4 m across x 51.2 m along at 10 cm, medium sand roughness; x east (across track), y north.
    const std::size_t nx = 1024, ny = 512;
    const T cell = T(0.1);
    sb::fractal_params<T> rough;
    rough.spectrum = sb::jackson_spectrum(T(0.004446), T(3.25), T(20));
    const auto bed = sb::fractal_surface<T>(nx, ny, cell, rough, 11);
    const scene::height_field<T> seabed({.nx = nx, .ny = ny, .cell_m = cell, .heights_m = bed.values});
    const auto h = sb::seabed_height_of(seabed);

    // Targets, starboard of a track at x = 30 m: a 2 m cylinder at 15 m ground range, a moored mine at 25 m, a
    // pipeline at 38 m; on port, a second cylinder at 20 m. Class ids 1 cylinder, 2 mine, 3 pipeline.
    const T track_x = T(30);
    std::vector<scene::object<T>> objects;
    objects.push_back(sb::lying_cylinder(sb::lying_cylinder_params<T>{.center_m = {track_x + 15, T(20)}, .heading_deg = T(21.25),
                                                                      .length_m = T(2), .radius_m = T(0.3), .ids = {.material = 1, .object = 1, .label = 1}},
                                         h));
    objects.push_back(sb::lying_cylinder(sb::lying_cylinder_params<T>{.center_m = {track_x - 20, T(30)}, .heading_deg = T(78.54),
                                                                      .length_m = T(1.5), .radius_m = T(0.25), .ids = {.material = 1, .object = 4, .label = 1}},
                                         h));
    sb::tethered_mine_params<T> mine;
    mine.anchor_m = {track_x + 25, T(26)};
    mine.case_height_m = T(3);
    mine.object_id = 2;
    mine.class_id = 2;
    objects.push_back(sb::tethered_mine(mine, h));
    sb::pipeline_params<T> pipe;
    pipe.route_m = {{track_x + 38, T(1)}, {track_x + 39, T(50)}};
    pipe.radius_m = T(0.3);
    pipe.ids = {.material = 1, .object = 3, .label = 3};
    objects.push_back(sb::pipeline(pipe, h));
    const scene::scene world(seabed, scene::object_set<T>(std::move(objects)));
    const std::vector<io::label_class> classes{{1, "cylinder"}, {2, "mine"}, {3, "pipeline"}};

    // Sonar: Lambertian (-27 dB sand, -8 dB targets), 30 dB/km absorption, 1 x 50 deg fan tilted 20 deg down,
    // 20 kHz sampling to 50 m; the towfish 10 m above the seabed, north at 2 m/s, 10 pings a second.
    const scattering::lambertian<T> scatter({.mu_db = {T(-27), T(-8)}});
    const propagation::straight<T> water({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)});
    const beam::ideal_fan<T> fan({.along_width_deg = T(1), .vertical_width_deg = T(50), .depression_deg = T(20)});
    const T altitude = T(10), ground = seabed.seabed_height_m(track_x, T(25));
    const motion::straight_line<T> tow(
        {.start_m = {track_x, T(12)}, .heading_deg = T(0), .speed_mps = T(2), .altitude_m = ground + altitude, .ping_interval_s = T(0.1)});
    receiver_params rx;
    rx.max_range_m = 50;
    const simulator<scattering::lambertian<T>, propagation::straight<T>, beam::ideal_fan<T>, motion::straight_line<T>> sim(
        scatter, water, fan, tow, rx);
    const std::size_t pings = 150; // 30 m of track
    const auto t1 = std::chrono::steady_clock::now();
    // The waterfall and its labels from one trace per side (plus the bare seabed's for the shadows).
    const auto [w, labels] = render_labelled(sim, world, 0, pings, {.threads = 2});
    const auto t3 = std::chrono::steady_clock::now();

    std::vector<pose<T>> poses;
    std::vector<double> alt;
    for (std::size_t i = 0; i < pings; ++i) {
        poses.push_back(sim.motion().pose_at(i));
        alt.push_back(double(poses.back().position.z - seabed.seabed_height_m(poses.back().position.x, poses.back().position.y)));
    }
    // XTF: UTC 2026-06-01 12:00:00 for ping 0.
    io::xtf_render_params xp{.start_unix_s = 1'780'315'200.0, .ping_interval_s = 0.1, .first_ping_number = 1,
                             .sound_speed_mps = 1500.0, .origin = {.latitude_deg = 57.7, .longitude_deg = 11.9}};
    xp.header.port = {.frequency_khz = 400.0, .horizontal_beam_angle_deg = 1.0, .beam_width_deg = 50.0, .tilt_deg = 20.0};
    xp.header.starboard = xp.header.port;
    io::write_xtf(stem + ".xtf", io::make_xtf<T>(w, poses, xp, alt));
    // PNG: range-compensated power over a 40 dB window.
    const std::vector<double> shown = sss_examples::range_compensated(w, 1500.0, 30.0);
    io::write_png_grey8(stem + ".png", w.width(), w.pings, io::to_grey_db<std::uint8_t>(std::span<const double>(shown), {.dynamic_range_db = 40.0}));
    // NumPy array and sidecar.
    io::write_npy(stem + ".npy", w);
    io::write_render_sidecar<T>(stem + ".json", w, poses, {.array_file = "products.npy", .sound_speed_mps = 1500.0});
    // Labels.
    const std::vector<io::coco_image> set{{"products.png", &labels}};
    io::write_text(stem + "_coco.json", io::coco_json(set, classes, io::box_extent::highlight_and_shadow));
    io::write_text(stem + "_highlight_coco.json", io::coco_json(set, classes, io::box_extent::highlight));
    io::write_text(stem + ".txt", io::yolo_txt(labels, classes, io::box_extent::highlight_and_shadow));
    io::write_text(dir + "/classes.txt", io::yolo_classes_txt(classes));
    io::write_label_images(stem + "_labels", labels, classes);
    std::vector<std::uint8_t> view = io::class_pixels(labels);
    for (auto& v : view) v = static_cast<std::uint8_t>(v * 51); // classes 0 to 5 over 0 to 255
    io::write_png_grey8(stem + "_labels_view.png", labels.width(), labels.pings, view);
    // The same labels on a 5 cm ground-range grid (flat-bottom mapping at each ping's altitude).
    const label_image ground_labels = ground_range_labels(labels, alt, {.cell_m = 0.05, .cells = 0, .sound_speed_mps = 1500.0});
    io::write_label_images(stem + "_ground_labels", ground_labels, classes);
    const auto t4 = std::chrono::steady_clock::now();

    auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("sss products: %zu pings x 2 x %zu samples -> %s/products.{xtf,png,npy,json,txt}, labels and COCO\n"
                "  scene %.0f ms, render with labels %.0f ms, files %.0f ms\n",
                w.pings, w.samples, dir.c_str(), ms(t0, t1), ms(t1, t3), ms(t3, t4));
    for (const auto& b : io::object_boxes(labels, io::box_extent::highlight_and_shadow))
        std::printf("  object %u (class %u): box x %zu..%zu, pings %zu..%zu, %zu samples\n", b.object, b.class_id, b.x,
                    b.x + b.width - 1, b.y, b.y + b.height - 1, b.area);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_products: %s\n", e.what());
    return 1;
}
