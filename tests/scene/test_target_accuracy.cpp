// Targets on and above rough relief rendered at the default ray density are as accurate as a flat seabed:
// against the converged reference (the same simulator at many times the rays, tests/support/converged_reference.hpp),
// over the samples within 40 dB of the line's peak, the RMS error is at most 0.3 dB and the 99th percentile at most
// 1 dB, and every sample the reference shows at least 40 dB below its lit surroundings (a shadow) is as dark in the
// default render. The scene (tests/support/rough_scenes.hpp): a cylinder lying along the track, a moored spherical
// mine with its tether and anchor, and a pipeline crossing the beam obliquely and spanning a hollow, on gentle
// relief with ripples; straight rays with a level towfish, three-layer water with a rolled and pitched one.

#include <doctest/doctest.h>

#include <vector>

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
