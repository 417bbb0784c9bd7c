// Ground-truth labels: the shadows they mark agree with the geometry of the shadow to within one sample (a cylinder
// lying on a flat seabed, a sphere in the water column, the same sphere in refracting water); on rough relief with a
// lying cylinder, a tethered mine and a pipeline span, every box encloses the samples its object's echo dominates; the label image, the COCO file
// and the YOLO file agree; the COCO file has every field the format requires, consistent; an image without an
// object gets empty label files.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sss/io/labels.hpp"
#include "sss/propagation/layered.hpp"
#include "sss/receiver/ground_range.hpp"
#include "sss/scattering/jackson.hpp"
#include "sss/scattering/sediments.hpp"
#include "sss/scattering/specular_bounce.hpp"
#include "sss/scene/flat_seabed.hpp"
#include "sss/scene/height_field.hpp"
#include "sss/scene/scene.hpp"
#include "sss/seabed/targets.hpp"
#include "sss/simulator.hpp"
#include "support/grid_relief.hpp"

namespace {

using namespace sss;
using scene::cylinder;
using scene::object;
using scene::object_set;
using scene::sphere;

constexpr double c_mps = 1500.0, fs_hz = 20000.0, dt_s = 1.0 / fs_hz, H = 10.0;
// A burst a fifth of a sample long: the receiver smears an echo over at most the next sample (a tenth of its energy),
// so the labels lie where the geometry puts them. How a longer pulse moves them has its own test.
constexpr double short_pulse_s = 10e-6;

using sim_t = simulator<scattering::lambertian<double>, propagation::straight<double>, beam::ideal_fan<double>, motion::straight_line<double>>;

sim_t make_simulator(double max_range_m, double per_sample, motion::straight_line_params<double> tow = {}) {
    receiver_params rp;
    rp.sample_rate_hz = fs_hz;
    rp.max_range_m = max_range_m;
    rp.pulse.length_s = short_pulse_s;
    beam::ideal_fan_params<double> fan;
    fan.along_width_deg = 1.0;
    fan.vertical_width_deg = 90.0;
    fan.depression_deg = 45.0;
    return sim_t(scattering::lambertian<double>({.mu_db = {-27.0, -10.0}}), propagation::straight<double>(), beam::ideal_fan<double>(fan),
                 motion::straight_line<double>(tow), rp, ray_density{.along = 4, .across = 0, .per_sample = per_sample});
}

// An ideal fan from depression lo_deg to hi_deg, 1 deg along track, over ranges up to max_range_m.
sim_t fan_simulator(double lo_deg, double hi_deg, double max_range_m) {
    receiver_params rp;
    rp.sample_rate_hz = fs_hz;
    rp.max_range_m = max_range_m;
    rp.pulse.length_s = short_pulse_s;
    return sim_t(scattering::lambertian<double>({.mu_db = {-27.0}}), propagation::straight<double>(),
                 beam::ideal_fan<double>({.along_width_deg = 1.0, .vertical_width_deg = hi_deg - lo_deg, .depression_deg = 0.5 * (lo_deg + hi_deg)}),
                 motion::straight_line<double>(motion::straight_line_params<double>{}), rp,
                 ray_density{.along = 4, .across = 0, .per_sample = 4.0});
}

pose<double> towfish() { return make_pose<double>(0.0, vec3<double>{0, 0, H}, 0, 0, 0); }

double sample_of(double range_m) { return 2 * range_m / c_mps / dt_s; }

// Depression of the ray from (0, H) grazing the circle of radius a at (x0, cz): far (-1) or near (+1) side.
double tangent_depression(double x0, double cz, double a, int side) {
    return std::atan2(H - cz, x0) + side * std::asin(a / std::hypot(x0, H - cz));
}

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The rough-relief survey: a lying cylinder, a tethered mine and a pipeline over rough_field, 40 pings north.
struct survey {
    scene::scene<scene::height_field<double>> world;
    sim_t sim;
    std::size_t pings;
};

survey rough_survey() {
    namespace sb = sss::seabed;
    auto bed = sss_test::rough_field<double>(161, 121, 0.25, {0.0, 0.0}, 7); // 40 m x 30 m
    const auto h = sb::seabed_height_of(bed);
    std::vector<object<double>> objs;
    objs.push_back(sb::lying_cylinder(sb::lying_cylinder_params<double>{.center_m = {16.0, 12.0}, .heading_deg = 72.81, .length_m = 2.0,
                                                                        .radius_m = 0.3, .profile_step_m = 0.05, .ids = {.material = 1, .object = 1, .label = 1}},
                                      h));
    sb::tethered_mine_params<double> mine;
    mine.anchor_m = {24.0, 17.0};
    mine.case_height_m = 3.0;
    mine.object_id = 2;
    mine.class_id = 2;
    objs.push_back(sb::tethered_mine(mine, h));
    sb::pipeline_params<double> pipe;
    pipe.route_m = {{31.0, 1.0}, {33.0, 29.0}};
    pipe.radius_m = 0.25;
    pipe.ids = {.material = 1, .object = 3, .label = 3};
    objs.push_back(sb::pipeline(pipe, h));
    const double z0 = bed.seabed_height_m(4.0, 10.0);
    scene::scene world(std::move(bed), object_set<double>(std::move(objs)));
    motion::straight_line_params<double> tow{.start_m = {4.0, 5.0}, .heading_deg = 0.0, .speed_mps = 2.5, .altitude_m = z0 + 9.0,
                                             .ping_interval_s = 0.2};
    return {std::move(world), make_simulator(35.0, 1.0, tow), 40};
}

} // namespace

TEST_CASE("The shadow label of a cylinder lying along the track ends where the ray grazing its top meets the seabed") {
    const double a = 0.5, x0 = 20.0;
    std::vector<object<double>> objs{object<double>({}, {cylinder<double>({x0, -15, a}, {x0, 15, a}, a, {1, 5, 3})})};
    const scene::scene sc(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
    const auto sim = make_simulator(40.0, 4.0);
    const auto l = label_line(sim, sc, towfish(), side::starboard);
    const double k_end = sample_of(H / std::sin(tangent_depression(x0, a, a, -1)));
    const double k_near = sample_of(std::hypot(x0, H - a) - a);
    const double k_top = sample_of(std::sqrt(x0 * x0 + (H - a) * (H - a) - a * a)); // far tangent point
    std::size_t first_hl = l.size(), last_hl = 0, first_sh = l.size(), last_sh = 0;
    for (std::size_t k = 0; k < l.size(); ++k) {
        if (l[k].kind == sample_class::highlight) first_hl = std::min(first_hl, k), last_hl = k;
        if (l[k].kind == sample_class::shadow) first_sh = std::min(first_sh, k), last_sh = k;
    }
    MESSAGE("highlight " << first_hl << "-" << last_hl << " (geometry " << k_near << "-" << k_top << "), shadow " << first_sh << "-"
                         << last_sh << " (ends at " << k_end << ")");
    CHECK(std::abs(double(first_hl) - k_near) <= 1.0);
    CHECK(std::abs(double(last_hl + 1) - k_top) <= 1.0);
    CHECK(std::abs(double(last_sh + 1) - k_end) <= 1.0);
    // The shadow starts where the ray grazing the cylinder's near side meets the seabed: the seabed in front of the
    // cylinder is lit up to there, its echo arriving just after the highlight's.
    const double k_front = sample_of(H / std::sin(tangent_depression(x0, a, a, +1)));
    CHECK(std::abs(double(first_sh) - k_front) <= 1.0);
    for (std::size_t k = last_hl + 1; k < first_sh; ++k) CHECK(l[k].kind == sample_class::seabed);
    for (std::size_t k = first_sh; k <= last_sh; ++k) {
        CHECK(l[k].kind == sample_class::shadow);
        CHECK(l[k].object == 5u);
        CHECK(l[k].label == 3u);
    }
    for (std::size_t k = first_hl; k <= last_hl; ++k) CHECK(l[k].object == 5u);
    // Before the first bottom return: water column; lit seabed carries its region; port sees no object.
    CHECK(l[std::size_t(sample_of(H)) - 2].kind == sample_class::water_column);
    CHECK(l[std::size_t(k_end) + 3].kind == sample_class::seabed);
    CHECK(l[std::size_t(k_end) + 3].label == 2u);
    const auto port = label_line(sim, sc, towfish(), side::port);
    CHECK(std::none_of(port.begin(), port.end(), [](const sample_label& s) { return s.object != no_object; }));
}

TEST_CASE("In ground range, the flat-bottom mapping puts the lying cylinder's shadow between its tangent rays' landing points") {
    const double a = 0.5, x0 = 20.0;
    std::vector<object<double>> objs{object<double>({}, {cylinder<double>({x0, -15, a}, {x0, 15, a}, a, {1, 5, 3})})};
    const scene::scene sc(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
    const auto sim = make_simulator(40.0, 4.0); // towfish at (0, 0, H) heading north: starboard is +x
    const label_image slant = label_render(sim, sc, 0, 1);
    const double cell = 0.05;
    const label_image g = ground_range_labels(slant, {H}, {.cell_m = cell, .cells = 0, .sound_speed_mps = c_mps});
    const double x_front = H / std::tan(tangent_depression(x0, a, a, +1)), x_end = H / std::tan(tangent_depression(x0, a, a, -1));
    std::size_t first = g.samples, last = 0;
    for (std::size_t j = 0; j < g.samples; ++j)
        if (g.at(0, g.samples + j).kind == sample_class::shadow) first = std::min(first, j), last = j;
    MESSAGE("ground-range shadow " << double(first) * cell << "-" << double(last + 1) * cell << " m, geometry " << x_front << "-" << x_end << " m");
    // One slant sample (c dt / 2 = 3.75 cm) spans about 4.2 cm of ground here: within two 5 cm cells.
    CHECK(std::abs(double(first) * cell - x_front) <= 2 * cell);
    CHECK(std::abs(double(last + 1) * cell - x_end) <= 2 * cell);
    // The mapping starts at the first bottom return (r = H): no ground cell is water column.
    CHECK(std::none_of(g.values.begin(), g.values.end(), [](const sample_label& l) { return l.kind == sample_class::water_column; }));
    // Port mirrors: the same cell mapping on the left, seabed only.
    CHECK(g.at(0, g.samples - 1 - std::size_t(x_end / cell) - 3).kind == sample_class::seabed);
}

TEST_CASE("Behind a ridge the seabed hides itself: seabed shadow from the ridge's last lit range to where its grazing ray lands") {
    // A ridge along the track, 2 m high, its crest at x = 15 m, flanks 1 m wide, on a flat seabed of region 4;
    // the towfish 10 m up at x = 0, its fan from 20 to 60 deg depression (the swath ends at 10 / sin 20 = 29.2 m). The front flank faces the sonar: its ranges run from hypot(14, 10) = 17.20 m at
    // its foot to hypot(15, 8) = 17.00 m at the crest, so the last lit range before the shadow is 17.20 m. The ray
    // grazing the crest lands at x = 15 x 10 / 8 = 18.75 m, range 21.25 m. The back flank (slope 2) and the seabed
    // up to there are hidden: labelled seabed shadow, with the region of the lit seabed before them.
    const std::size_t nx = 161, ny = 161;
    const double cell = 0.25;
    scene::height_field_params<double> hp{.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {-5.0, -20.0}, .heights_m = {}, .materials = {},
                                          .regions = std::vector<std::uint32_t>((nx - 1) * (ny - 1), 4u)};
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double x = -5.0 + double(ix) * cell;
            hp.heights_m.push_back(std::max(0.0, 2.0 * (1.0 - std::abs(x - 15.0))));
        }
    const scene::scene sc(scene::height_field<double>(std::move(hp)), object_set<double>{});
    const auto sim = fan_simulator(20.0, 60.0, 40.0);
    const auto l = label_line(sim, sc, towfish(), side::starboard);
    const double k_lit = sample_of(std::hypot(14.0, H)), k_land = sample_of(std::hypot(18.75, H));
    std::size_t first = l.size(), last = 0, shadows = 0;
    for (std::size_t k = 0; k < l.size(); ++k)
        if (l[k].kind == sample_class::seabed_shadow) {
            first = std::min(first, k), last = k, ++shadows;
            CHECK(l[k].label == 4u);
            CHECK(l[k].object == no_object);
        }
    MESSAGE("seabed shadow " << first << "-" << last << " (geometry " << k_lit << "-" << k_land << ")");
    CHECK(std::abs(double(first) - k_lit) <= 1.0);
    CHECK(std::abs(double(last + 1) - k_land) <= 1.0);
    CHECK(shadows == last - first + 1);
    // Lit seabed on either side; nothing inside the swath is "no coverage", nothing after it a seabed shadow.
    CHECK(l[first - 3].kind == sample_class::seabed);
    CHECK(l[last + 3].kind == sample_class::seabed);
    std::size_t k_first = 0, k_last = 0;
    for (std::size_t k = 0; k < l.size(); ++k)
        if (l[k].kind == sample_class::seabed) k_last = k, k_first = k_first ? k_first : k;
    for (std::size_t k = k_first; k <= k_last; ++k) CHECK(l[k].kind != sample_class::no_coverage);
    CHECK(std::abs(double(k_last + 1) - sample_of(H / std::sin(20.0 * std::numbers::pi / 180))) <= 1.0);
    for (std::size_t k = k_last + 1; k < l.size(); ++k) CHECK(l[k].kind == sample_class::no_coverage);
    // A flat seabed has none.
    const scene::scene flat(scene::flat_seabed<double>(0.0, 0, 4), object_set<double>{});
    const auto f = label_line(sim, flat, towfish(), side::starboard);
    CHECK(std::none_of(f.begin(), f.end(), [](const sample_label& s) { return s.kind == sample_class::seabed_shadow; }));
}

TEST_CASE("A bounced echo from beyond the swath is seabed, and the gap before it no coverage, not a seabed shadow") {
    // A fan from 20 to 60 deg depression, 10 m up: the direct swath ends at 10 / sin 20 = 29.2 m. A bank rises at
    // 3 m/m from x = 34 m to 8 m, out of the fan's direct reach; rays launched at 20 to 26 deg bounce off the flat
    // seabed (x = 27.5 to 20.5 m) up onto its face and come back the same way, at ranges of about 37 to 41 m.
    using jackson_bounce = scattering::specular_bounce<scattering::jackson<double>>;
    using bounce_sim = simulator<jackson_bounce, propagation::straight<double>, beam::ideal_fan<double>, motion::straight_line<double>>;
    const scattering::jackson<double> sand({.frequency_hz = 100000.0, .sound_speed_mps = c_mps,
                                            .materials = {scattering::sediment_preset<double>(scattering::sediment::medium_sand)}});
    receiver_params rp;
    rp.sample_rate_hz = fs_hz;
    rp.max_range_m = 50.0;
    rp.pulse.length_s = short_pulse_s;
    const bounce_sim sim(jackson_bounce(sand), propagation::straight<double>(),
                         beam::ideal_fan<double>({.along_width_deg = 1.0, .vertical_width_deg = 40.0, .depression_deg = 40.0}),
                         motion::straight_line<double>(motion::straight_line_params<double>{}), rp,
                         ray_density{.along = 4, .across = 0, .per_sample = 4.0});
    const std::size_t nx = 301, ny = 161;
    const double cell = 0.25;
    scene::height_field_params<double> hp{.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {-5.0, -20.0}, .heights_m = {}, .materials = {},
                                          .regions = {}};
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) hp.heights_m.push_back(std::clamp(3.0 * (-5.0 + double(ix) * cell - 34.0), 0.0, 8.0));
    const scene::scene sc(scene::height_field<double>(std::move(hp)), object_set<double>{});
    const auto l = label_line(sim, sc, towfish(), side::starboard);
    const std::size_t k_swath = std::size_t(sample_of(H / std::sin(20.0 * std::numbers::pi / 180)));
    std::size_t late_seabed = 0, shadows = 0;
    for (std::size_t k = k_swath + 2; k < l.size(); ++k) {
        late_seabed += l[k].kind == sample_class::seabed;
        shadows += l[k].kind == sample_class::seabed_shadow;
    }
    MESSAGE("beyond the direct swath (sample " << k_swath << "): " << late_seabed << " samples of bounced seabed echo, " << shadows
                                                << " of seabed shadow");
    CHECK(late_seabed > 0u); // the bounce is there
    CHECK(shadows == 0u);
    for (std::size_t k = k_swath + 2; k < std::size_t(sample_of(34.0)); ++k) CHECK(l[k].kind == sample_class::no_coverage);
}

TEST_CASE("In ground range the seabed a beam does not reach near nadir is no coverage, not water column") {
    // A fan from 30 to 60 deg depression, 10 m up: the first return is at 10 / sin 60 = 11.55 m, ground range
    // 5.77 m. The cells nearer than that are seabed the beam never lit.
    const auto sim = fan_simulator(30.0, 60.0, 30.0);
    const scene::scene flat(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>{});
    const label_image slant = label_render(sim, flat, 0, 1);
    CHECK(slant.at(0, slant.samples + std::size_t(sample_of(H / std::sin(std::numbers::pi / 3))) - 2).kind == sample_class::water_column);
    const double cell = 0.05;
    const label_image g = ground_range_labels(slant, {H}, {.cell_m = cell, .cells = 0, .sound_speed_mps = c_mps});
    CHECK(std::none_of(g.values.begin(), g.values.end(), [](const sample_label& l) { return l.kind == sample_class::water_column; }));
    const double near_m = H / std::tan(std::numbers::pi / 3);
    for (const std::size_t j : {std::size_t(0), std::size_t(near_m / cell) - 3})
        for (const std::size_t col : {g.samples + j, g.samples - 1 - j}) CHECK(g.at(0, col).kind == sample_class::no_coverage);
    CHECK(g.at(0, g.samples + std::size_t(near_m / cell) + 3).kind == sample_class::seabed);
}

TEST_CASE("A sphere in the water column: its highlight before the first bottom return, its shadow between its tangent rays") {
    const double a = 0.5, x0 = 5.0, cz = 6.0;
    std::vector<object<double>> objs{object<double>({sphere<double>({x0, 0, cz}, a, {1, 8, 4})}, {})};
    const scene::scene sc(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
    const auto sim = make_simulator(40.0, 4.0);
    const auto l = label_line(sim, sc, towfish(), side::starboard);
    const double k_hl = sample_of(std::hypot(x0, H - cz) - a);
    const double k1 = sample_of(H / std::sin(tangent_depression(x0, cz, a, +1)));
    const double k2 = sample_of(H / std::sin(tangent_depression(x0, cz, a, -1)));
    std::size_t first_hl = l.size(), first_sh = l.size(), last_sh = 0;
    for (std::size_t k = 0; k < l.size(); ++k) {
        if (l[k].kind == sample_class::highlight) first_hl = std::min(first_hl, k);
        if (l[k].kind == sample_class::shadow) first_sh = std::min(first_sh, k), last_sh = k;
    }
    MESSAGE("highlight from " << first_hl << " (geometry " << k_hl << "), shadow " << first_sh << "-" << last_sh << " (geometry " << k1
                              << "-" << k2 << ")");
    CHECK(std::abs(double(first_hl) - k_hl) <= 1.0);
    CHECK(l[first_hl].object == 8u);
    CHECK(std::abs(double(first_sh) - k1) <= 1.0);
    CHECK(std::abs(double(last_sh + 1) - k2) <= 1.0);
    for (std::size_t k = first_sh; k <= last_sh; ++k) CHECK(l[k].kind == sample_class::shadow);
    // Between the sphere's echo and the seabed: water column.
    CHECK(l[std::size_t(sample_of(H)) - 2].kind == sample_class::water_column);
}

TEST_CASE("A highlight covers the samples its echo shows in, as the pulse smears it: rectangular, Hann, long and chirped") {
    // A small sphere in the water column (5 cm, 6.4 m away): its echo in the image is the pulse's envelope. A Hann
    // burst of 1 ms peaks 0.5 ms (10 samples) after the echo arrives, a rectangular one lasts 20 samples: the labels
    // at the arrival alone missed the first's echo altogether and the second's but its first two samples.
    struct case_ {
        pulse_shape shape;
        double length_s, bandwidth_hz;
    };
    for (const case_ c : {case_{pulse_shape::rectangular, 100e-6, 0.0}, case_{pulse_shape::hann, 100e-6, 0.0},
                          case_{pulse_shape::rectangular, 1e-3, 0.0}, case_{pulse_shape::hann, 1e-3, 0.0},
                          case_{pulse_shape::lfm, 1e-3, 20000.0}}) {
        CAPTURE(int(c.shape));
        CAPTURE(c.length_s);
        receiver_params rp;
        rp.sample_rate_hz = fs_hz;
        rp.max_range_m = 20.0;
        rp.pulse = {.length_s = c.length_s, .shape = c.shape, .bandwidth_hz = c.bandwidth_hz};
        const sim_t sim(scattering::lambertian<double>({.mu_db = {-27.0, -10.0}}), propagation::straight<double>(),
                        beam::ideal_fan<double>({.along_width_deg = 1.0, .vertical_width_deg = 90.0, .depression_deg = 45.0}),
                        motion::straight_line<double>(motion::straight_line_params<double>{}), rp,
                        ray_density{.along = 4, .across = 0, .per_sample = 4.0});
        std::vector<object<double>> objs{object<double>({sphere<double>({5.0, 0, 6.0}, 0.05, {1, 8, 4})}, {})};
        const scene::scene sc(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
        const auto both = render_labelled(sim, sc, 0, 1);
        const std::size_t n = both.image.samples, before_seabed = std::size_t(sample_of(H)) - 1;
        double peak = 0.0;
        for (std::size_t k = 0; k < before_seabed; ++k) peak = std::max(peak, double(both.image.at(0, n + k)));
        REQUIRE(peak > 0.0);
        std::size_t shown = 0, labelled = 0;
        for (std::size_t k = 0; k < before_seabed; ++k) {
            const double v = double(both.image.at(0, n + k));
            const sample_label& l = both.labels.at(0, n + k);
            CAPTURE(k);
            if (v >= 0.1 * peak) { // within 10 dB of the echo's peak: the sphere's highlight
                ++shown;
                CHECK(l.kind == sample_class::highlight);
                CHECK(l.object == 8u);
            }
            if (l.kind == sample_class::highlight) { // and no highlight where the image shows no echo
                ++labelled;
                CHECK(v > 0.0);
            }
        }
        MESSAGE(shown << " samples within 10 dB of the echo's peak, " << labelled << " labelled highlight");
        CHECK(shown >= 2);
    }
}

TEST_CASE("A label deposit shows wholly in the line, on a sample's boundary too, whatever the pulse") {
    // Arrival 0.01 s at dt = 1e-5 s: t / dt rounds to 999.99999999999989, and the last sample the deposit reaches was
    // cut at 999. Under a pulse too short to hold (a subnormal length) the smear's tables were NaN and every deposit
    // vanished.
    const double dt = 1e-5;
    for (const double length_s : {5e-324, 1e-9, 100e-6}) {
        CAPTURE(length_s);
        const detail::echo_smear shown(pulse{.length_s = length_s, .shape = pulse_shape::rectangular});
        const detail::label_accumulator acc(4000, dt, &shown);
        for (const auto& [t0, t1] : {std::array<double, 2>{0.01, 0.01}, {0.01, 0.0100123}, {0.0031, 0.0095}}) {
            CAPTURE(t0);
            CAPTURE(t1);
            double total = 0.0;
            std::size_t first = 4000;
            acc.spread(t0, t1, [&](std::size_t k, double share) {
                total += share;
                first = std::min(first, k);
            });
            CHECK(total == doctest::Approx(1.0).scale(0).epsilon(1e-12));
            CHECK(std::abs(double(first) - t0 / dt) <= 1.0); // the arrival's sample, or the one before by rounding
        }
    }
    // A pulse just long enough for the table (its step's inverse near 1e308): a deposit spread over 3 to 3.01 s shows
    // evenly in the 100 samples of its arrivals. Scaling x and t by the inverse step apart overflowed there (x / step
    // beyond 1.8 s), and the whole deposit landed in its last sample.
    const detail::echo_smear tiny(pulse{.length_s = 1e-305, .shape = pulse_shape::rectangular});
    const detail::label_accumulator long_line(40000, 1e-4, &tiny);
    std::size_t samples = 0;
    double most = 0.0;
    long_line.spread(3.0, 3.01, [&](std::size_t, double share) {
        ++samples;
        most = std::max(most, share);
    });
    CHECK(samples >= 100u);
    CHECK(samples <= 102u);
    CHECK(most == doctest::Approx(0.01).scale(0).epsilon(1e-6));
}

TEST_CASE("Ground-range labels of a ping with no seabed under it (altitude +infinity) are no coverage, as its image") {
    label_image slant;
    slant.pings = 2;
    slant.samples = 400; // 15 m of slant range
    slant.dt_s = dt_s;
    slant.values.assign(2 * 800, sample_label{sample_class::seabed, no_object, 1, 0});
    const label_image g = ground_range_labels(slant, {10.0, std::numeric_limits<double>::infinity()}, {.cell_m = 0.05});
    CHECK(g.at(0, g.samples + 5).kind == sample_class::seabed);
    for (std::size_t c = 0; c < g.width(); ++c) CHECK(g.at(1, c).kind == sample_class::no_coverage);
    CHECK_THROWS_AS((void)ground_range_labels(slant, {10.0, -1.0}, {.cell_m = 0.05}), invalid_parameter);
    CHECK_THROWS_AS((void)ground_range_labels(slant, {10.0, std::numeric_limits<double>::quiet_NaN()}, {.cell_m = 0.05}),
                    invalid_parameter);
}

TEST_CASE("In refracting water a sphere's shadow lies between the landings of its tangent bent rays, not its straight ones") {
    // Sound slows by 60 m/s over the 10 m between the towfish (depth 20 m) and the seabed (depth 30 m): the rays
    // bend down with a radius of about 250 m, and sag 0.3 to 0.5 m below their chords over the 30 m to the shadow.
    using layered_sim = simulator<scattering::lambertian<double>, propagation::layered<double>, beam::ideal_fan<double>,
                                  motion::straight_line<double>>;
    const propagation::layered<double> water(propagation::sound_speed_profile<double>({0, 20, 30, 100}, {1500, 1500, 1440, 1440}),
                                             {.surface_z_m = H + 20.0});
    receiver_params rp;
    rp.sample_rate_hz = fs_hz;
    rp.max_range_m = 45.0;
    rp.pulse.length_s = short_pulse_s;
    // A narrow beam along track (0.25 deg, 5 cm at the sphere) keeps the rays near the oracle's plane below: off it
    // the sphere's section, and so its shadow, is shorter.
    beam::ideal_fan_params<double> fan;
    fan.along_width_deg = 0.25;
    fan.vertical_width_deg = 90.0;
    fan.depression_deg = 45.0;
    const layered_sim sim(scattering::lambertian<double>({.mu_db = {-27.0, -10.0}}), water, beam::ideal_fan<double>(fan),
                          motion::straight_line<double>(motion::straight_line_params<double>{}), rp,
                          ray_density{.along = 4, .across = 0, .per_sample = 4.0});
    const double a = 0.5, x0 = 12.0, cz = 6.0;
    std::vector<object<double>> objs{object<double>({sphere<double>({x0, 0, cz}, a, {1, 8, 4})}, {})};
    const scene::scene sc(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
    const scene::flat_seabed<double> bare(0.0, 0, 2);
    const auto l = label_line(sim, sc, towfish(), side::starboard);

    // The oracle: bent rays in the plane of the sphere's centre, launched at depression e from the towfish. Those
    // that meet the sphere before the seabed span [e_near, e_far]; their two-way times to the bare seabed bound the
    // shadow.
    const double t_max = 1.0;
    const auto ray_at = [&](double e) { return ray<double>{vec3<double>{0, 0, H}, vec3<double>{std::cos(e), 0.0, -std::sin(e)}}; };
    const auto blocked = [&](double e) {
        const auto p = water.trace(ray_at(e), sc, t_max);
        return p && p->surface.object == 8u;
    };
    const double e_centre = std::atan2(H - cz, x0);
    REQUIRE(blocked(e_centre + 0.01));
    const auto edge = [&](double inside, double outside) { // bisection to 1e-12 rad
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (inside + outside);
            (blocked(mid) ? inside : outside) = mid;
        }
        return 0.5 * (inside + outside);
    };
    const double e_far = edge(e_centre + 0.01, e_centre - 0.2), e_near = edge(e_centre + 0.01, e_centre + 0.2);
    const auto sample_of_launch = [&](double e) { return 2.0 * water.trace(ray_at(e), bare, t_max)->time_s / dt_s; };
    const double k1 = sample_of_launch(e_near), k2 = sample_of_launch(e_far);
    // Where straight segments would put it: the seabed points whose straight line to the towfish grazes the sphere,
    // at the two-way time of the bent ray that lands there.
    const auto sample_of_landing = [&](double x_m) {
        double lo = 0.05, hi = 1.5; // depression: landing range falls as it rises
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            (water.trace(ray_at(mid), bare, t_max)->surface.point.x > x_m ? lo : hi) = mid;
        }
        return sample_of_launch(0.5 * (lo + hi));
    };
    const double s1 = sample_of_landing(H / std::tan(tangent_depression(x0, cz, a, +1)));
    const double s2 = sample_of_landing(H / std::tan(tangent_depression(x0, cz, a, -1)));

    std::size_t first_sh = l.size(), last_sh = 0;
    for (std::size_t k = 0; k < l.size(); ++k)
        if (l[k].kind == sample_class::shadow) first_sh = std::min(first_sh, k), last_sh = k;
    MESSAGE("shadow " << first_sh << "-" << last_sh << "; bent rays " << k1 << "-" << k2 << "; straight segments " << s1 << "-"
                      << s2);
    REQUIRE(first_sh < l.size());
    // The straight segments' shadow lies several samples away: the check below tells the two apart.
    CHECK(std::abs(s2 - k2) > 4.0);
    CHECK(std::abs(double(first_sh) - k1) <= 1.0);
    CHECK(std::abs(double(last_sh + 1) - k2) <= 1.0);
    for (std::size_t k = first_sh; k <= last_sh; ++k) CHECK(l[k].kind == sample_class::shadow);
}

TEST_CASE("A sphere between two columns' launch cones is labelled, highlight and shadow, where the image shows it") {
    // A 1 deg fan of two columns: their cones, 0.25 deg either side of the track, pass 0.11 m either side of a sphere
    // 0.2 m across resting on the seabed at 24 m. Both miss it; the check by target (ray_density::along_split_targets)
    // divides them over it, in the image's pass and in the bare seabed's, whose rays the labels test against the
    // objects: without it, the image has no sphere and the labels neither.
    const double a = 0.1, x0 = 24.0;
    std::vector<object<double>> objs{object<double>({sphere<double>({x0, 0, a}, a, {1, 8, 4})}, {})};
    const scene::scene sc(scene::flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
    receiver_params rp;
    rp.sample_rate_hz = fs_hz;
    rp.max_range_m = 35.0;
    rp.pulse.length_s = short_pulse_s;
    beam::ideal_fan_params<double> fan;
    fan.along_width_deg = 1.0;
    fan.vertical_width_deg = 90.0;
    fan.depression_deg = 45.0;
    const auto labels_with = [&](bool check) {
        const sim_t sim(scattering::lambertian<double>({.mu_db = {-27.0, -10.0}}), propagation::straight<double>(), beam::ideal_fan<double>(fan),
                        motion::straight_line<double>(), rp, ray_density{.along = 2, .across = 0, .per_sample = 4.0, .along_split_targets = check});
        // A shadow here is a third of the seabed's echo blocked: the sphere spans 0.2 m of the beam's 0.45 m.
        return label_line(sim, sc, towfish(), side::starboard, label_params{.shadow_fraction = 0.3});
    };
    const auto count = [](const std::vector<sample_label>& l, sample_class kind) {
        return std::count_if(l.begin(), l.end(), [&](const sample_label& x) { return x.kind == kind && x.object == 8u; });
    };
    const auto with = labels_with(true), without = labels_with(false);
    MESSAGE("highlight " << count(with, sample_class::highlight) << ", shadow " << count(with, sample_class::shadow)
                         << " samples; without the check " << count(without, sample_class::highlight) << " and "
                         << count(without, sample_class::shadow));
    // The shadow: from the ray grazing the sphere's top to where it lands, about 12 samples on the flat seabed.
    const double top_m = 2 * a, land_m = x0 * H / (H - top_m);
    const double k_shadow_end = sample_of(std::hypot(land_m, H));
    std::size_t last_shadow = 0;
    for (std::size_t k = 0; k < with.size(); ++k)
        if (with[k].kind == sample_class::shadow) last_shadow = k;
    CHECK(count(with, sample_class::highlight) >= 3);
    CHECK(count(with, sample_class::shadow) >= 5);
    CHECK(std::abs(double(last_shadow + 1) - k_shadow_end) <= 2.0);
    CHECK(count(without, sample_class::highlight) == 0);
    CHECK(count(without, sample_class::shadow) == 0);
}

TEST_CASE("render_labelled is render and label_render in one trace: the same image and labels to the bit, on any number of threads") {
    const survey s = rough_survey();
    const std::size_t first = 14, count = 10;
    const auto both = render_labelled(s.sim, s.world, first, count, {.threads = 2});
    const waterfall<double> image = s.sim.render(s.world, first, count, 1);
    const label_image labels = label_render(s.sim, s.world, first, count, {.threads = 1});
    CHECK(both.image.pings == count);
    CHECK(both.image.samples == image.samples);
    CHECK(both.image.dt_s == image.dt_s);
    CHECK(both.image.values == image.values);
    CHECK(both.labels.pings == count);
    CHECK(both.labels.samples == labels.samples);
    CHECK(both.labels.values == labels.values);
    // The pings chosen see the targets: the comparison covers highlights and shadows, not only bare seabed.
    std::size_t highlights = 0, shadows = 0;
    for (const sample_label& l : both.labels.values) {
        highlights += l.kind == sample_class::highlight;
        shadows += l.kind == sample_class::shadow;
    }
    CHECK(highlights > 20u);
    CHECK(shadows > 20u);
    const auto one = render_labelled(s.sim, s.world, first, count, {.threads = 1});
    CHECK(one.image.values == both.image.values);
    CHECK(one.labels.values == both.labels.values);
    // render's contract: a progress callback that says stop after 3 pings cancels, naming 3.
    std::size_t stopped_at = 0;
    try {
        (void)render_labelled(s.sim, s.world, first, count,
                              {.threads = 1, .progress = [](const render_progress& p) { return p.done < 3; }});
    } catch (const render_cancelled& c) {
        stopped_at = c.done();
    }
    CHECK(stopped_at == 3u);
    CHECK_THROWS_WITH_AS((void)render_labelled(s.sim, s.world, 0, 1, {}, {.shadow_fraction = 0.0}),
                         doctest::Contains("label_params.shadow_fraction"), invalid_parameter);
}

// Straight water that does not say how far its rays reach: the simulator then traces the whole scene, and the
// labels trace the bare seabed on every side.
struct unbounded_straight : propagation::straight<double> {
private:
    using propagation::straight<double>::reach_speed_mps;
};

TEST_CASE("Labels are the same whether or not the bare seabed's pass is skipped on sides no object reaches, and a "
          "moored mine no side reaches changes none") {
    namespace sb = sss::seabed;
    auto bed = sss_test::rough_field<double>(161, 321, 0.25, {0.0, 0.0}, 11); // 40 m x 80 m
    const auto h = sb::seabed_height_of(bed);
    std::vector<object<double>> objs;
    objs.push_back(sb::lying_cylinder(sb::lying_cylinder_params<double>{.center_m = {18.0, 20.0}, .heading_deg = 60.0, .length_m = 2.0,
                                                                        .radius_m = 0.2, .ids = {.material = 1, .object = 1, .label = 1}},
                                      h));
    sb::pipeline_params<double> pipe;
    pipe.route_m = {{30.0, 54.0}, {33.0, 58.0}};
    pipe.radius_m = 0.15;
    pipe.ids = {.material = 1, .object = 2, .label = 2};
    objs.push_back(sb::pipeline(pipe, h));
    // A moored mine beyond the far end, 4 m up: it would raise the scene's top, but no side of these pings reaches
    // it, so no side launches for its height (simulator::trace: the top of the objects over the side's area).
    sb::tethered_mine_params<double> mine;
    mine.anchor_m = {12.0, 70.0};
    mine.case_height_m = 4.0;
    mine.object_id = 3;
    mine.class_id = 3;
    std::vector<object<double>> with_mine = objs;
    with_mine.push_back(sb::tethered_mine(mine, h));
    const double z0 = bed.seabed_height_m(8.0, 10.0);
    const scene::scene world_mine(bed, object_set<double>(std::move(with_mine)));
    const scene::scene world(std::move(bed), object_set<double>(std::move(objs)));
    REQUIRE(world_mine.top_m() > world.seabed().top_m() + 1.0);
    // Without the mine, the two objects lie below the seabed's highest crest: an unbounded simulator, which launches for
    // the whole scene's top, launches the same rays.
    REQUIRE(world.top_m() == world.seabed().top_m());
    const motion::straight_line_params<double> tow{.start_m = {8.0, 5.0}, .heading_deg = 0.0, .speed_mps = 2.5,
                                                   .altitude_m = z0 + 9.0, .ping_interval_s = 1.0};
    const auto sim = make_simulator(30.0, 1.0, tow);
    using unbounded_t = simulator<scattering::lambertian<double>, unbounded_straight, beam::ideal_fan<double>, motion::straight_line<double>>;
    static_assert(!ReachBoundedPropagation<unbounded_straight>);
    const unbounded_t whole(sim.scattering(), unbounded_straight{}, sim.beam(), sim.motion(), sim.receiver(), sim.density());
    const std::size_t pings = 24; // y = 5 .. 62.5 m: the mine beyond
    std::size_t skipped = 0, traced = 0;
    for (std::size_t i = 0; i < pings; ++i)
        for (side sd : {side::port, side::starboard}) {
            const bool skip = sss::detail::bare_pass_repeats_first(sim, world, sim.motion().pose_at(i), sd);
            (skip ? skipped : traced) += 1;
            CHECK(sss::detail::bare_pass_repeats_first(sim, world_mine, sim.motion().pose_at(i), sd) == skip);
            CHECK_FALSE(sss::detail::bare_pass_repeats_first(whole, world, whole.motion().pose_at(i), sd));
        }
    CHECK(skipped > 20u); // most sides see no object ...
    CHECK(traced >= 2u);  // ... and those that reach one of the two objects trace the bare seabed
    const label_image fast = label_render(sim, world, 0, pings, {.threads = 1});
    const label_image full = label_render(whole, world, 0, pings, {.threads = 1});
    CHECK(fast.values == full.values);
    CHECK(render_labelled(sim, world, 0, pings, {.threads = 2}).labels.values == full.values);
    const auto mined = render_labelled(sim, world_mine, 0, pings, {.threads = 2});
    CHECK(mined.labels.values == full.values);
    CHECK(mined.image.values == render_labelled(sim, world, 0, pings, {.threads = 1}).image.values);
    std::size_t highlights = 0, shadows = 0;
    for (const sample_label& l : full.values) {
        highlights += l.kind == sample_class::highlight;
        shadows += l.kind == sample_class::shadow;
    }
    CHECK(highlights > 10u);
    CHECK(shadows > 10u);
}

// Straight water that counts the rays it traces.
struct counted_straight : propagation::straight<double> {
    std::atomic<std::size_t>* rays = nullptr;
    template <Scene S> std::optional<path<double>> trace(const ray<double>& r, const S& s, double t) const {
        ++*rays;
        return propagation::straight<double>::trace(r, s, t);
    }
    template <Scene S>
    void trace_many(std::span<const ray<double>> rs, const S& s, double t, std::span<std::optional<path<double>>> out) const {
        *rays += rs.size();
        propagation::straight<double>::trace_many(rs, s, t, out);
    }
    template <Scene S>
    std::optional<path<double>> trace_beside(const ray<double>& r, const S& s, double t, const vec3<double>& a, double a_clear_range_m) const {
        ++*rays;
        return propagation::straight<double>::trace_beside(r, s, t, a, a_clear_range_m);
    }
};

TEST_CASE("The bare seabed is traced again only on sides where a ray met an object, not wherever an object is near") {
    // A sphere of radius 0.2 m 1 m above a flat seabed, 20 m to starboard: on the track (filling the 1 degree beam), or
    // 0.5 m ahead of it, inside the rectangle the starboard rays can reach (+-0.56 m along track) but outside the beam
    // (+-0.19 m at its range).
    const sim_t plain = make_simulator(30.0, 1.0);
    std::atomic<std::size_t> rays{0};
    counted_straight water;
    water.rays = &rays;
    const simulator<scattering::lambertian<double>, counted_straight, beam::ideal_fan<double>, motion::straight_line<double>> sim(
        plain.scattering(), water, plain.beam(), plain.motion(), plain.receiver(), plain.density());
    for (const double ahead_m : {0.5, 0.0}) {
        std::vector<object<double>> objs{object<double>({sphere<double>(vec3<double>{20.0, ahead_m, 1.0}, 0.2, {1, 1, 1})}, {})};
        const scene::scene world(scene::flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
        REQUIRE_FALSE(sss::detail::bare_pass_repeats_first(sim, world, sim.motion().pose_at(0), side::starboard));
        rays = 0;
        (void)sim.ping(world, 0);
        const std::size_t image_rays = rays.exchange(0);
        const label_image labels = label_render(sim, world, 0, 1, {.threads = 1});
        const std::size_t label_rays = rays.load();
        std::size_t highlights = 0, shadows = 0;
        for (const sample_label& l : labels.values) {
            highlights += l.kind == sample_class::highlight;
            shadows += l.kind == sample_class::shadow;
        }
        INFO("sphere " << ahead_m << " m ahead: " << image_rays << " rays for the image, " << label_rays << " for the labels");
        if (ahead_m > 0.0) { // unseen: the labels trace what the image traces, and mark nothing
            CHECK(label_rays == image_rays);
            CHECK(highlights + shadows == 0u);
        } else { // seen: the bare seabed and each of its rays through the objects alone are traced too
            CHECK(label_rays > image_rays);
            CHECK(highlights > 0u);
            CHECK(shadows > 0u);
        }
    }
}

TEST_CASE("On rough relief every box encloses the samples its object's echo dominates, and the label image, COCO and YOLO agree") {
    const survey s = rough_survey();
    const label_image img = label_render(s.sim, s.world, 0, s.pings, {.threads = 2});
    // The same labels on one thread (the first pings).
    const label_image one = label_render(s.sim, s.world, 0, 8, {.threads = 1});
    CHECK(std::equal(one.values.begin(), one.values.end(), img.values.begin()));
    const auto boxes = io::object_boxes(img, io::box_extent::highlight);
    const auto full = io::object_boxes(img, io::box_extent::highlight_and_shadow);
    REQUIRE(boxes.size() == 3u);
    REQUIRE(full.size() == 3u);
    // Independently of the labeller: the samples where an object returns at least half the echo energy.
    std::map<std::uint32_t, std::vector<std::pair<std::size_t, std::size_t>>> dominant;
    for (std::size_t i = 0; i < s.pings; ++i)
        for (const side sd : {side::port, side::starboard}) {
            std::map<std::uint32_t, std::vector<double>> e;
            std::vector<double> total(img.samples, 0.0);
            s.sim.trace(s.world, s.sim.motion().pose_at(i), sd, [&](const tube_echo<double>& t) {
                const double a = t.t0_s / dt_s, b = t.t1_s / dt_s;
                auto& mine = e[t.surface.object];
                mine.resize(img.samples, 0.0);
                for (auto k = std::size_t(a); k < img.samples && double(k) <= b; ++k) {
                    const double w = b > a ? (std::min(b, double(k + 1)) - std::max(a, double(k))) / (b - a) : 1.0;
                    if (w > 0) mine[k] += w * t.power, total[k] += w * t.power;
                }
            });
            for (auto& [id, v] : e)
                if (id != no_object)
                    for (std::size_t k = 0; k < img.samples; ++k)
                        if (v[k] > 0 && v[k] >= 0.5 * total[k] * (1 + 1e-9))
                            dominant[id].push_back({i, sd == side::port ? img.samples - 1 - k : img.samples + k});
        }
    for (std::size_t b = 0; b < 3; ++b) {
        const auto& box = boxes[b];
        CAPTURE(box.object);
        CHECK(box.object == b + 1);
        CHECK(box.class_id == b + 1);
        REQUIRE(!dominant[box.object].empty());
        for (const auto& [row, col] : dominant[box.object]) {
            CHECK(row >= box.y);
            CHECK(row < box.y + box.height);
            CHECK(col >= box.x);
            CHECK(col < box.x + box.width);
        }
        // The box with the shadow holds the highlight's box and has a shadow (every object stands on or over the seabed).
        CHECK(full[b].x <= box.x);
        CHECK(full[b].y <= box.y);
        CHECK(full[b].x + full[b].width >= box.x + box.width);
        CHECK(full[b].y + full[b].height >= box.y + box.height);
        CHECK(full[b].area > box.area);
    }
    // The pipeline runs the length of the survey; the mine's case floats clear of the seabed: its box with the shadow
    // reaches further out in range than its highlight.
    CHECK(boxes[2].height == s.pings);
    CHECK(full[1].x + full[1].width > boxes[1].x + boxes[1].width + 5);

    // Files: COCO and YOLO from the same labels.
    const std::vector<io::label_class> classes{{1, "cylinder"}, {2, "mine"}, {3, "pipeline"}};
    for (const auto extent : {io::box_extent::highlight, io::box_extent::highlight_and_shadow}) {
        const auto& bx = extent == io::box_extent::highlight ? boxes : full;
        const std::vector<io::coco_image> set{{"survey.png", &img}};
        io::write_text("survey_coco.json", io::coco_json(set, classes, extent));
        io::write_text("survey.txt", io::yolo_txt(img, classes, extent));
        const auto coco = nlohmann::json::parse(slurp("survey_coco.json"));
        // Every field the format requires, with its type; ids unique and cross-referenced.
        REQUIRE(coco.contains("images"));
        REQUIRE(coco.contains("annotations"));
        REQUIRE(coco.contains("categories"));
        std::set<long> image_ids, category_ids, annotation_ids;
        for (const auto& im : coco["images"]) {
            CHECK(im["id"].is_number_integer());
            CHECK(im["file_name"] == "survey.png");
            CHECK(im["width"] == img.width());
            CHECK(im["height"] == img.pings);
            CHECK(image_ids.insert(im["id"].get<long>()).second);
        }
        for (const auto& c : coco["categories"]) {
            CHECK(c["name"].is_string());
            CHECK(c["supercategory"].is_string());
            CHECK(category_ids.insert(c["id"].get<long>()).second);
        }
        CHECK(category_ids == std::set<long>{1, 2, 3});
        REQUIRE(coco["annotations"].size() == 3u);
        std::size_t n = 0;
        for (const auto& an : coco["annotations"]) {
            CHECK(annotation_ids.insert(an["id"].get<long>()).second);
            CHECK(image_ids.count(an["image_id"].get<long>()) == 1u);
            CHECK(category_ids.count(an["category_id"].get<long>()) == 1u);
            CHECK(an["iscrowd"] == 0);
            const auto bb = an["bbox"].get<std::vector<double>>();
            REQUIRE(bb.size() == 4u);
            CHECK(bb[0] >= 0);
            CHECK(bb[1] >= 0);
            CHECK(bb[2] > 0);
            CHECK(bb[3] > 0);
            CHECK(bb[0] + bb[2] <= double(img.width()));
            CHECK(bb[1] + bb[3] <= double(img.pings));
            // The mask: runs down the columns, starting with zeros; its area is the annotation's, inside its box.
            const auto& seg = an["segmentation"];
            CHECK(seg["size"] == std::vector<std::size_t>{img.pings, img.width()});
            const auto counts = seg["counts"].get<std::vector<std::size_t>>();
            std::size_t pos = 0, ones = 0, mismatches = 0, outside = 0;
            bool inside = false;
            for (const std::size_t run : counts) {
                for (std::size_t r = 0; r < run; ++r, ++pos) {
                    const std::size_t col = pos / img.pings, row = pos % img.pings;
                    mismatches += io::in_mask(img.at(row, col), bx[n].object, extent) != inside;
                    if (inside) {
                        ++ones;
                        outside += double(col) < bb[0] || double(col) >= bb[0] + bb[2] || double(row) < bb[1] || double(row) >= bb[1] + bb[3];
                    }
                }
                inside = !inside;
            }
            CHECK(pos == img.pings * img.width());
            CHECK(mismatches == 0u);
            CHECK(outside == 0u);
            CHECK(an["area"] == ones);
            CHECK(double(ones) <= bb[2] * bb[3]);
            // The same box as the label image's.
            CHECK(an["category_id"] == bx[n].class_id);
            CHECK(bb == std::vector<double>{double(bx[n].x), double(bx[n].y), double(bx[n].width), double(bx[n].height)});
            ++n;
        }
        // YOLO: the same boxes, normalised, class index in the list's order.
        std::istringstream yolo(slurp("survey.txt"));
        std::size_t cls = 0, lines = 0;
        double xc = 0, yc = 0, w = 0, h = 0;
        while (yolo >> cls >> xc >> yc >> w >> h) {
            REQUIRE(lines < bx.size());
            const auto& b = bx[lines++];
            CHECK(classes[cls].id == b.class_id);
            CHECK(std::abs(w * double(img.width()) - double(b.width)) < 1e-3); // pixels
            CHECK(std::abs(h * double(img.pings) - double(b.height)) < 1e-3);
            CHECK(std::abs((xc - w / 2) * double(img.width()) - double(b.x)) < 1e-3);
            CHECK(std::abs((yc - h / 2) * double(img.pings) - double(b.y)) < 1e-3);
        }
        CHECK(lines == 3u);
    }
    // Ground range: the flat-bottom mapping keeps every object's highlight.
    std::vector<double> alt(s.pings, 9.0);
    const auto ground = ground_range_labels(img, alt, {.cell_m = 0.05, .cells = 0, .sound_speed_mps = c_mps});
    CHECK(io::object_boxes(ground, io::box_extent::highlight).size() == 3u);
}

TEST_CASE("An image with no object in the swath gets an empty YOLO file and a COCO file without annotations") {
    // The sphere lies 200 m east: outside the 40 m range.
    std::vector<object<double>> objs{object<double>({sphere<double>({200, 0, 1}, 0.5, {1, 4, 1})}, {})};
    const scene::scene sc(scene::flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
    const auto sim = make_simulator(40.0, 1.0);
    const label_image img = label_render(sim, sc, 0, 3);
    const std::vector<io::label_class> classes{{1, "sphere"}};
    io::write_text("empty.txt", io::yolo_txt(img, classes, io::box_extent::highlight_and_shadow));
    const std::vector<io::coco_image> set{{"empty.png", &img}};
    io::write_text("empty_coco.json", io::coco_json(set, classes, io::box_extent::highlight_and_shadow));
    io::write_label_images("empty", img, classes);
    CHECK(slurp("empty.txt").empty());
    const auto coco = nlohmann::json::parse(slurp("empty_coco.json"));
    CHECK(coco["annotations"].empty());
    CHECK(coco["images"].size() == 1u);
    const auto legend = nlohmann::json::parse(slurp("empty_legend.json"));
    CHECK(legend["class_png"]["4"] == "shadow");
    CHECK(legend["instance_png"].size() == 1u);
    // And the label image is only water column, seabed and no coverage.
    std::size_t water = 0, seabed = 0;
    for (const auto& l : img.values) {
        water += l.kind == sample_class::water_column;
        seabed += l.kind == sample_class::seabed;
        CHECK(l.object == no_object);
    }
    CHECK(water > 0u);
    CHECK(seabed > 0u);
}

TEST_CASE("Ground-range labels cover exactly the cells the ground-range image has a value for, far edge included") {
    // Every slant sample is seabed and every image sample 1: a label cell must be covered where the image is 1.
    const std::size_t n = 667;
    const double dt = 5e-5, c = 1500.0, cell = 0.1;
    label_image slant{.pings = 40, .samples = n, .dt_s = dt, .values = {}};
    slant.values.assign(slant.pings * slant.width(), sample_label{.kind = sample_class::seabed, .object = no_object, .label = 1, .material = 0});
    const waterfall<double> ones{.pings = slant.pings, .samples = n, .dt_s = dt, .values = std::vector<double>(slant.pings * 2 * n, 1.0)};
    std::vector<double> alt;
    for (std::size_t i = 0; i < slant.pings; ++i) alt.push_back(1.0 + 0.4731 * double(i)); // the far edge falls anywhere in a cell
    const label_image g = ground_range_labels(slant, alt, {.cell_m = cell, .cells = 0, .sound_speed_mps = c});
    const waterfall<double> image = to_ground_range(ones, alt, c, cell, g.samples);
    REQUIRE(image.width() == g.width());
    std::size_t covered = 0, edge_rows = 0;
    for (std::size_t i = 0; i < g.pings; ++i) {
        std::size_t last = 0;
        for (std::size_t j = 0; j < g.width(); ++j) {
            const bool labelled = g.at(i, j).kind != sample_class::no_coverage;
            CHECK(labelled == (image.at(i, j) > 0.0));
            covered += labelled;
            if (labelled && j >= g.samples) last = j - g.samples;
        }
        // The last labelled cell is the last whose centre's range lies within half a sample of the last centre.
        const double dr = 0.5 * c * dt;
        const auto range = [&](std::size_t j) { return std::hypot((double(j) + 0.5) * cell, alt[i]) / dr; };
        CHECK(range(last) - 0.5 <= double(n) - 1.0);
        CHECK(range(last + 1) - 0.5 > double(n) - 1.0);
        edge_rows += range(last + 1) < double(n); // a cell the old rule (floor(r) < n) labelled and the image leaves empty
    }
    CHECK(covered > 0u);
    CHECK(edge_rows > 0u); // the case in question occurs here
}
