// Targets on and above rough relief rendered at the default ray density are as accurate as a flat seabed:
// against the converged reference (the same simulator at many times the rays, tests/support/converged_reference.hpp),
// over the samples within 40 dB of the line's peak, the RMS error is at most 0.3 dB and the 99th percentile at most
// 1 dB, and every sample the reference shows at least 40 dB below its lit surroundings (a shadow) is as dark in the
// default render. The scene (tests/support/rough_scenes.hpp): a cylinder lying along the track, a moored spherical
// mine with its tether and anchor, and a pipeline crossing the beam obliquely and spanning a hollow, on gentle
// relief with ripples; straight rays with a level towfish, three-layer water with a rolled and pitched one.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/matrix.hpp>

#include "support/converged_reference.hpp"
#include "support/rough_scenes.hpp"
#include <sss/sss.hpp>

namespace {

template <class P> auto make_sim(const P& water, const sss::ray_density& d = {}) {
    return sss::simulator<sss::scattering::lambertian<double>, P, sss::beam::ideal_fan<double>,
                          sss::motion::straight_line<double>>({}, water, {}, {}, sss_test::rough_receiver(), d);
}

template <class P, class Scene> void check_against_reference(const P& water, const Scene& scene, bool tilted) {
    const auto pose = sss_test::rough_pose<double>(tilted);
    const auto ref = sss_test::converged_line([&](const sss::ray_density& d) { return make_sim(water, d); }, scene,
                                              pose, sss::side::starboard,
                                              {.start = {.along = 16, .across = 0, .per_sample = 4.0}, .max_doublings = 3});
    const auto got = sss_test::to_double(make_sim(water).ping_at(scene, pose).starboard);
    const auto e = sss_test::compare_lines(got, ref.values);
    INFO("reference at {" << ref.density.along << ", 0, " << ref.density.per_sample << "}, last doubling changed it by "
                          << ref.last_change_db << " dB");
    INFO("rms " << e.rms_db << " dB, median " << e.median_db << " dB, 99th percentile " << e.p99_db << " dB over "
                << e.compared << " samples; shadow samples " << e.shadow_samples << ", missed " << e.shadow_misses);
    REQUIRE(ref.converged);
    CHECK(e.compared > 300);
    CHECK(e.rms_db <= 0.3);
    CHECK(e.p99_db <= 1.0);
    CHECK(e.shadow_misses == 0);
}

} // namespace

TEST_CASE("a lying cylinder, a moored mine and a spanning pipeline on rough relief render at the default density as "
          "the converged reference") {
    const auto scene = sss_test::target_scene<double>();
    SUBCASE("straight") { check_against_reference(sss::propagation::straight<double>{}, scene, false); }
    SUBCASE("layered, rolled and pitched") { check_against_reference(sss_test::three_layer_water<double>(), scene, true); }
}

TEST_CASE("a mine moored high at far range, whose rays past it meet nothing within the line, renders at the default "
          "density as the converged reference") {
    // A spherical case (0.5 m radius) 6 m above gentle relief at 24 m: a ray that passes it reaches the seabed beyond
    // the 30 m line, so the case's silhouette lies between a lit ray and one that meets nothing. An 8 deg fan gives
    // columns 0.42 m apart there: the columns either side of the case's centre see its front later than a column
    // through the centre would, by different amounts where the case is off the middle between them. Until such
    // silhouettes went to the along-track check, nothing compared them and nothing divided the columns (RMS 0.21 and
    // 0.26 dB, 99th percentile 0.91 and 1.66 dB at the first two places below). Under a 4 deg fan with the case 0.1 m
    // off the track, 12 samples of its body were 2 dB too bright (0.35 dB RMS) until the check by target divided the
    // columns over the case's whole body, not only around its silhouettes, and over the tether finely enough (0.03 dB).
    const auto relief = [](double x, double y) { return 0.05 * std::sin(0.9 * x + 0.4 * y); };
    for (const auto& [fan_deg, y_m] : {std::pair{8.0, 0.0}, std::pair{8.0, 0.2}, std::pair{4.0, 0.1}}) {
        CAPTURE(fan_deg);
        CAPTURE(y_m);
        std::vector<sss::scene::object<double>> objs;
        objs.push_back(sss::seabed::tethered_mine(
            sss::seabed::tethered_mine_params<double>{.anchor_m = {24.0, y_m}, .case_height_m = 6.0, .object_id = 1},
            relief));
        const auto scene = sss::scene::scene(sss_test::footprint_field<double>(relief),
                                             sss::scene::object_set<double>(std::move(objs)));
        auto make = [fan = fan_deg](const sss::ray_density& d) {
            return sss::simulator<sss::scattering::lambertian<double>, sss::propagation::straight<double>,
                                  sss::beam::ideal_fan<double>, sss::motion::straight_line<double>>(
                {}, {}, sss::beam::ideal_fan<double>({.along_width_deg = fan}), {}, sss_test::rough_receiver(), d);
        };
        const auto pose = sss_test::rough_pose<double>(false);
        const auto ref = sss_test::converged_line(make, scene, pose, sss::side::starboard,
                                                  {.start = {.along = 16, .across = 0, .per_sample = 4.0}, .max_doublings = 3});
        REQUIRE(ref.converged);
        const auto e = sss_test::compare_lines(sss_test::to_double(make({}).ping_at(scene, pose).starboard), ref.values);
        INFO("rms " << e.rms_db << " dB, 99th percentile " << e.p99_db << " dB over " << e.compared << " samples");
        CHECK(e.compared > 300);
        CHECK(e.rms_db <= 0.1);
        CHECK(e.p99_db <= 0.5);
        CHECK(e.shadow_misses == 0);
    }
}

namespace {

// A sphere 0.16 m across (brighter than the seabed: mu -10 dB against -27), its centre 0.7 of its radius above gentle
// relief at 24 m, between the launch cones of the two columns either side of the track (along-track angles -0.5 and 0.5 deg under an
// 8 deg fan of 8 columns, 0.42 m apart there): its centre at along-track angles -0.2, 0 and 0.2 deg of the towfish's
// frame, so that its 0.38 deg lie between them. The reference against the default render, with and without the
// check by target. The columns are kept evenly spaced (ray_density::along_onset = 0), so that they lie where the sphere
// is placed between them: under the pitched towfish the first return moves across the columns near the vertical's
// plane by more than its tolerance, and those columns would narrow (sampling/column_edges.hpp).
template <class P> void check_small_sphere(const P& water, bool tilted) {
    const auto relief = [](double x, double y) { return 0.05 * std::sin(0.9 * x + 0.4 * y); };
    auto make = [&](sss::ray_density d) {
        d.along_onset = 0.0;
        return sss::simulator<sss::scattering::lambertian<double>, P, sss::beam::ideal_fan<double>, sss::motion::straight_line<double>>(
            sss::scattering::lambertian<double>({.mu_db = {-27.0, -10.0}}), water,
            sss::beam::ideal_fan<double>({.along_width_deg = 8.0}), {}, sss_test::rough_receiver(), d);
    };
    const auto pose = sss_test::rough_pose<double>(tilted);
    const double x0 = 24.0, radius = 0.08;
    for (const double along_deg : {-0.2, 0.0, 0.2}) {
        CAPTURE(along_deg);
        // The world y (along the track) where the sphere's centre lies at that along-track angle: asin(b.x / |b|),
        // b the body-frame offset (beam_direction inverted), which grows with y; by bisection.
        const auto z_at = [&](double y) { return relief(x0, y) + 0.7 * radius; };
        const auto along_at = [&](double y) {
            const sss::vec3<double> b = glm::transpose(pose.body_to_world) *
                                        (sss::vec3<double>{x0, y, z_at(y)} - pose.position);
            return std::asin(b.x / glm::length(b));
        };
        double y_lo = -3.0, y_hi = 3.0;
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (y_lo + y_hi);
            (along_at(mid) < along_deg * std::numbers::pi / 180.0 ? y_lo : y_hi) = mid;
        }
        const double y_m = 0.5 * (y_lo + y_hi), z = z_at(y_m);
        std::vector<sss::scene::object<double>> objs;
        objs.push_back(sss::scene::object<double>(
            {sss::scene::sphere<double>({x0, y_m, z}, radius, {.material = 1, .object = 1, .label = 1})}, {}));
        const auto scene = sss::scene::scene(sss_test::footprint_field<double>(relief),
                                             sss::scene::object_set<double>(std::move(objs)));
        const auto ref = sss_test::converged_line(make, scene, pose, sss::side::starboard,
                                                  {.start = {.along = 16, .across = 0, .per_sample = 4.0}, .max_doublings = 3});
        REQUIRE(ref.converged);
        // The sphere's echo: the samples from its front to past its back (13 samples, 0.5 m of range).
        const double dz = z - double(pose.position.z);
        const double front_m = std::sqrt(x0 * x0 + y_m * y_m + dz * dz) - radius;
        const auto k_front = static_cast<std::size_t>(front_m / (0.5 * 1500.0 * make({}).dt_s()));
        const auto echo_db = [&](const std::vector<double>& line) {
            double got = 0, want = 0;
            for (std::size_t k = k_front - 4; k <= k_front + 8; ++k) {
                got += line[k];
                want += ref.values[k];
            }
            return 10.0 * std::log10(got / want);
        };
        const auto with = sss_test::to_double(make({}).ping_at(scene, pose).starboard);
        const auto without = sss_test::to_double(make({.along_split_targets = false}).ping_at(scene, pose).starboard);
        const auto e = sss_test::compare_lines(with, ref.values);
        INFO("rms " << e.rms_db << " dB, 99th percentile " << e.p99_db << " dB; the sphere's echo " << echo_db(with)
                    << " dB against the reference, " << echo_db(without) << " dB without the check by target");
        CHECK(e.rms_db <= 0.15);
        CHECK(e.p99_db <= 1.0);
        CHECK(std::abs(echo_db(with)) <= 0.5);
        CHECK(e.shadow_misses == 0);
        CHECK(echo_db(without) < -1.5); // both columns miss it: the sphere all but vanishes
    }
}

} // namespace

TEST_CASE("a sphere smaller than the columns' spacing, between two columns' launch cones, renders at the default "
          "density as the converged reference") {
    SUBCASE("straight") { check_small_sphere(sss::propagation::straight<double>{}, false); }
    SUBCASE("layered, rolled and pitched") { check_small_sphere(sss_test::three_layer_water<double>(), true); }
}

namespace {

/// The cable scenes' simulator: Lambertian (the cable 17 dB brighter than the seabed), straight rays, the 8 deg fan of
/// 8 columns, at ray density d.
auto cable_sim(sss::ray_density d) {
    return sss::simulator<sss::scattering::lambertian<double>, sss::propagation::straight<double>, sss::beam::ideal_fan<double>,
                          sss::motion::straight_line<double>>(sss::scattering::lambertian<double>({.mu_db = {-27.0, -10.0}}), {},
                                                              sss::beam::ideal_fan<double>({.along_width_deg = 8.0}), {},
                                                              sss_test::rough_receiver(), d);
}

} // namespace

TEST_CASE("a thin cable across the track between two columns' launch cones renders at the default density as the "
          "converged reference, and that reference as 512 plain columns") {
    // A cable 6 cm across lying 10 m across the track on gentle relief (18 to 28 m out), under the 8 deg fan of 8
    // columns whose cones pass 0.16 to 0.24 m either side of it: both miss it. The check by target divides the columns
    // over its launch intervals until the narrowest are a quarter of its angular thickness wide (two levels past the
    // columns' own depth here). The converged reference is checked against brute force: doubling the columns from 16 to
    // 128 alone had left a moored mine's tether 0.2 dB off (docs/design/along-track.md).
    const auto relief = [](double x, double y) { return 0.05 * std::sin(0.9 * x + 0.4 * y); };
    const double radius = 0.03;
    std::vector<sss::scene::object<double>> objs;
    objs.push_back(sss::scene::object<double>(
        {}, {sss::scene::cylinder<double>({18.0, 0.0, relief(18.0, 0.0) + radius}, {28.0, 0.0, relief(28.0, 0.0) + radius}, radius,
                                          {.material = 1, .object = 1, .label = 1})}));
    const auto scene = sss::scene::scene(sss_test::footprint_field<double>(relief), sss::scene::object_set<double>(std::move(objs)));
    const auto make = cable_sim;
    const auto pose = sss_test::rough_pose<double>(false);
    const auto ref = sss_test::converged_line(make, scene, pose, sss::side::starboard,
                                              {.start = {.along = 16, .across = 0, .per_sample = 4.0}, .max_doublings = 3});
    REQUIRE(ref.converged);
    const auto brute = sss_test::to_double(
        make({.along = 512, .across = 0, .per_sample = 4.0, .along_split = 3, .along_split_targets = false}).ping_at(scene, pose).starboard);
    const auto e_ref = sss_test::compare_lines(brute, ref.values);
    const auto e = sss_test::compare_lines(sss_test::to_double(make({}).ping_at(scene, pose).starboard), ref.values);
    const auto e_off = sss_test::compare_lines(sss_test::to_double(make({.along_split_targets = false}).ping_at(scene, pose).starboard),
                                               ref.values);
    INFO("default: rms " << e.rms_db << " dB, 99th percentile " << e.p99_db << " dB; without the check by target: rms "
                         << e_off.rms_db << " dB; 512 plain columns against the reference: rms " << e_ref.rms_db << " dB");
    CHECK(e_ref.rms_db <= 0.05);
    CHECK(e.rms_db <= 0.15);
    CHECK(e.p99_db <= 1.0);
    CHECK(e.shadow_misses == 0);
    CHECK(e_off.rms_db > 1.0);
}

TEST_CASE("a thin cable oblique to the track, crossing every column, renders at the default density as 256 plain "
          "columns, and so does one 400 m long passing under the towfish or through the beam") {
    // The same cable 6 cm across, 10 m across the track and turned 15, 30 and 60 deg towards it: it crosses the whole
    // 8 deg beam, too wide along track to be one target. It is cut along its axis into pieces, each a target where it
    // is narrower along track than a column, so the columns over it divide; and a launch interval of a column over a
    // piece is halved until it is narrower than an eighth of the piece's width in depression, so that two rays on the
    // seabed either side of it no longer step over it, and its cross-section is sampled. Then 400 m long about the same point: across the track it passes
    // under the towfish and its ends lie beyond the line's range on both sides (only the part on the side and within
    // range is followed); at 60 deg both ends and its closest points lie outside the beam. 256 plain columns at 4 rays
    // per sample are within 0.01 dB RMS of 512 and 1024 here (docs/design/along-track.md).
    const auto relief = [](double x, double y) { return 0.05 * std::sin(0.9 * x + 0.4 * y); };
    const double radius = 0.03;
    const auto make = cable_sim;
    const auto pose = sss_test::rough_pose<double>(false);
    struct cable {
        double angle_deg, half_length_m;
    };
    for (const cable c : {cable{15.0, 5.0}, cable{30.0, 5.0}, cable{60.0, 5.0}, cable{0.0, 200.0}, cable{60.0, 200.0}}) {
        const double t = std::tan(c.angle_deg * std::numbers::pi / 180.0), x0 = 23.0 - c.half_length_m,
                     x1 = 23.0 + c.half_length_m, y0 = -c.half_length_m * t, y1 = c.half_length_m * t;
        std::vector<sss::scene::object<double>> objs;
        objs.push_back(sss::scene::object<double>(
            {}, {sss::scene::cylinder<double>({x0, y0, relief(x0, y0) + radius}, {x1, y1, relief(x1, y1) + radius}, radius,
                                              {.material = 1, .object = 1, .label = 1})}));
        const auto scene = sss::scene::scene(sss_test::footprint_field<double>(relief), sss::scene::object_set<double>(std::move(objs)));
        const auto brute = sss_test::to_double(
            make({.along = 256, .across = 0, .per_sample = 4.0, .along_split = 3, .along_split_targets = false}).ping_at(scene, pose).starboard);
        const auto e = sss_test::compare_lines(sss_test::to_double(make({}).ping_at(scene, pose).starboard), brute);
        const auto e_off =
            sss_test::compare_lines(sss_test::to_double(make({.along_split_targets = false}).ping_at(scene, pose).starboard), brute);
        CAPTURE(c.angle_deg);
        CAPTURE(c.half_length_m);
        INFO("default: rms " << e.rms_db << " dB, 99th percentile " << e.p99_db << " dB; without the check by target: rms "
                             << e_off.rms_db << " dB, 99th percentile " << e_off.p99_db << " dB");
        CHECK(e.rms_db <= 0.1);
        CHECK(e.p99_db <= 0.3);
        CHECK(e.shadow_misses == 0);
        if (c.angle_deg != 30.0) CHECK(e_off.p99_db > 1.0); // at 30 deg the columns alone reach 0.9 dB
    }
}

TEST_CASE("objects outside the beam, beyond the line's range or moored out of it leave both lines bit for bit as with "
          "no objects") {
    // The check by target follows only what lies within the beam and the range, and the rays launch for the top of the
    // objects a side can reach (a moored mine elsewhere raises no ray): the scene's objects are otherwise met by no
    // ray. Behind and ahead of the 8 deg fan (0.25 rad off its axis), 45 m out on a 30 m line, and a mine moored 5 m up
    // 6 m ahead.
    const auto relief = [](double x, double y) { return 0.05 * std::sin(0.9 * x + 0.4 * y); };
    // Each its own object: an object counts as near a side where its bounds reach over the side's area.
    const sss::scene::surface_ids ids{.material = 1, .object = 1, .label = 1};
    std::vector<sss::scene::object<double>> objs;
    for (const auto& [centre, radius] : {std::pair{sss::vec3<double>{23.0, -6.0, 0.2}, 0.2}, std::pair{sss::vec3<double>{-20.0, 5.5, 0.2}, 0.2},
                                         std::pair{sss::vec3<double>{45.0, 0.0, 0.2}, 0.2}, std::pair{sss::vec3<double>{-44.0, 1.0, 0.2}, 0.2}})
        objs.push_back(sss::scene::object<double>({sss::scene::sphere<double>(centre, radius, ids)}, {}));
    objs.push_back(sss::scene::object<double>({}, {sss::scene::cylinder<double>({18.0, 8.0, 0.03}, {28.0, 8.0, 0.03}, 0.03, ids)}));
    objs.push_back(sss::scene::object<double>({}, {sss::scene::cylinder<double>({-30.0, -7.0, 0.03}, {-15.0, -9.0, 0.03}, 0.03, ids)}));
    objs.push_back(sss::scene::object<double>({sss::scene::sphere<double>({20.0, 6.0, 5.0}, 0.5, ids)},
                                              {sss::scene::cylinder<double>({20.0, 6.0, 0.0}, {20.0, 6.0, 4.5}, 0.01, ids)}));
    // Within the area the starboard rays can reach, so that the columns ask the objects and the check by target
    // looks at them, but below the seabed's crests (no higher launch): 2 m ahead at 10 m (0.14 rad off the beam's axis,
    // outside it) and 31 m out on the 30 m line.
    objs.push_back(sss::scene::object<double>({sss::scene::sphere<double>({10.0, 2.0, -0.05}, 0.04, ids)}, {}));
    objs.push_back(sss::scene::object<double>({sss::scene::sphere<double>({29.5, 0.0, -0.02}, 0.01, ids)}, {}));
    const auto with = sss::scene::scene(sss_test::footprint_field<double>(relief), sss::scene::object_set<double>(std::move(objs)));
    const auto without = sss::scene::scene(sss_test::footprint_field<double>(relief), sss::scene::object_set<double>());
    const auto sim = cable_sim({});
    for (const bool tilted : {false, true}) {
        CAPTURE(tilted);
        const auto pose = sss_test::rough_pose<double>(tilted);
        const auto r = *sim.side_area(pose, sss::side::starboard);
        REQUIRE(sss::scene::area_view<std::remove_cvref_t<decltype(with)>>(with, r.lo, r.hi).objects_near());
        REQUIRE(with.top_m(r.lo, r.hi) == with.seabed().top_m(r.lo, r.hi));
        const auto a = sim.ping_at(with, pose), b = sim.ping_at(without, pose);
        CHECK(a.port == b.port);
        CHECK(a.starboard == b.starboard);
    }
}
