// Hard man-made surfaces: the Kirchhoff specular facet term has its closed backscatter form and is reciprocal; a
// simulator can give targets this model while the seabed keeps Jackson's, and a steel cylinder then stands out by
// its highlight as in real records; a scene with one model renders exactly as before.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstddef>
#include <vector>

#include <sss/scattering/by_material.hpp>
#include <sss/scattering/hard_target.hpp>
#include <sss/scattering/jackson.hpp>
#include <sss/scattering/lambertian.hpp>
#include <sss/scattering/sediments.hpp>
#include <sss/scene/cylinder.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/scene.hpp>
#include <sss/simulator.hpp>

namespace {

using sss::scattering::by_material;
using sss::scattering::hard_target;
using sss::scattering::hard_target_params;
using sss::scattering::jackson;
using sss::scattering::lambertian;
using straight = sss::propagation::straight<double>;
using fan = sss::beam::ideal_fan<double>;
using line_motion = sss::motion::straight_line<double>;

} // namespace

TEST_CASE("Kirchhoff facet backscatter is |R|^2 exp(-tan^2 psi / 2 s^2) / (8 pi s^2 cos^4 psi), peaked at normal incidence") {
    const double r = 0.94, s = 0.1;
    for (double graze_deg : {90.0, 85.0, 80.0, 70.0, 45.0}) {
        const double g = sss::deg_to_rad(graze_deg), psi = sss::pi_v<double> / 2 - g;
        const double expected = r * r * std::exp(-std::tan(psi) * std::tan(psi) / (2 * s * s)) /
                                (8 * sss::pi_v<double> * s * s * std::pow(std::cos(psi), 4));
        CHECK(sss::scattering::kirchhoff_specular_sigma(g, g, sss::pi_v<double>, r, s) == doctest::Approx(expected).epsilon(1e-9).scale(0));
    }
    const hard_target<double> steel;
    CHECK(steel.backscatter(sss::pi_v<double> / 2, 0) > 100.0 * steel.backscatter(sss::deg_to_rad(60.0), 0));
}

TEST_CASE("the hard-target model is reciprocal and its backscatter is the bistatic value at phi = pi") {
    const hard_target<double> steel(hard_target_params<double>{.reflection = 0.9, .rms_slope = 0.2, .diffuse_db = -15.0});
    for (double gi : {0.2, 0.7, 1.2})
        for (double gs : {0.3, 0.9, 1.5})
            for (double phi : {0.0, 1.0, 2.5, sss::pi_v<double>})
                CHECK(steel.bistatic(gi, gs, phi, 0) == doctest::Approx(steel.bistatic(gs, gi, phi, 0)).epsilon(1e-12));
    CHECK(steel.backscatter(0.8, 0) == steel.bistatic(0.8, 0.8, sss::pi_v<double>, 0));
}

TEST_CASE("the hard-target model reads a NaN grazing angle as 0 and a NaN bistatic angle as backscatter, as Jackson's does") {
    const hard_target<double> steel(hard_target_params<double>{.reflection = 0.9, .rms_slope = 0.2, .diffuse_db = -15.0});
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(steel.bistatic(nan, 0.3, 1.0, 0) == steel.bistatic(0.0, 0.3, 1.0, 0));
    CHECK(steel.bistatic(0.3, nan, 1.0, 0) == steel.bistatic(0.3, 0.0, 1.0, 0));
    CHECK(steel.bistatic(0.4, 0.3, nan, 0) == steel.bistatic(0.4, 0.3, 3.141592653589793, 0));
    CHECK(std::isfinite(steel.backscatter(nan, 0)));
    CHECK_THROWS_AS(hard_target<double>(hard_target_params<double>{.diffuse_db = -4.971}), sss::invalid_parameter);
    CHECK_NOTHROW(hard_target<double>(hard_target_params<double>{.diffuse_db = -4.9715}));
}

TEST_CASE("by_material sends seabed ids to the seabed model and later ids to the target model") {
    const by_material<lambertian<double>, hard_target<double>> s(lambertian<double>({.mu_db = {-27.0, -30.0}}), hard_target<double>{});
    CHECK(s.material_count() == 3);
    CHECK(s.first_target_material() == 2);
    CHECK(s.backscatter(0.5, 0) == lambertian<double>({.mu_db = {-27.0, -30.0}}).backscatter(0.5, 0));
    CHECK(s.backscatter(0.5, 1) == lambertian<double>({.mu_db = {-27.0, -30.0}}).backscatter(0.5, 1));
    CHECK(s.backscatter(0.5, 2) == hard_target<double>{}.backscatter(0.5, 0));
    CHECK(s.bistatic(0.5, 0.4, 1.0, 7) == hard_target<double>{}.bistatic(0.5, 0.4, 1.0, 5));
}

TEST_CASE("a steel cylinder's highlight under the hard-target model is at least 15 dB above the sand at its range") {
    using sss::scene::cylinder;
    using sss::scene::object;
    using sss::scene::object_set;
    const jackson<double> sand({.frequency_hz = 100e3, .sound_speed_mps = 1500.0, .materials = {sss::scattering::sediment_preset<double>("medium_sand")}});
    // A 1 m diameter cylinder lying along track 25 m to starboard (east); the port side is bare sand.
    std::vector<object<double>> objs{object<double>(
        {}, {cylinder<double>({25.0, -5.0, 0.5}, {25.0, 5.0, 0.5}, 0.5, {.material = 1, .object = 1})})};
    const sss::scene::scene sc(sss::scene::flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
    const line_motion motion(sss::motion::straight_line_params<double>{.altitude_m = 10.0});
    auto contrast_db = [&](const auto& sim) {
        const auto lines = sim.ping(sc, 0);
        const auto peak = static_cast<std::size_t>(std::max_element(lines.starboard.begin(), lines.starboard.end()) -
                                                   lines.starboard.begin());
        double sand_mean = 0.0;
        for (std::size_t k = peak - 10; k <= peak + 10; ++k) sand_mean += lines.port[k] / 21.0;
        return 10.0 * std::log10(lines.starboard[peak] / sand_mean);
    };
    const sss::simulator<by_material<jackson<double>, hard_target<double>>, straight, fan, line_motion> mixed(
        by_material<jackson<double>, hard_target<double>>(sand, hard_target<double>{}), straight{}, fan{}, motion);
    const sss::simulator<jackson<double>, straight, fan, line_motion> all_sand(sand, straight{}, fan{}, motion);
    const double steel = contrast_db(mixed), as_sand = contrast_db(all_sand);
    MESSAGE("highlight above the sand at its range: steel " << steel << " dB, the same cylinder scattering as sand " << as_sand << " dB");
    CHECK(steel >= 15.0);
    CHECK(steel > as_sand + 10.0);
}

TEST_CASE("a scene with one model renders bit-identically with or without the material dispatch") {
    const sss::scene::flat_seabed<double> seabed(0.0, 1);
    const sss::simulator<lambertian<double>, straight, fan, line_motion> plain(lambertian<double>({.mu_db = {-27.0, -31.0}}));
    const sss::simulator<by_material<lambertian<double>, hard_target<double>>, straight, fan, line_motion> mixed(
        by_material<lambertian<double>, hard_target<double>>(lambertian<double>({.mu_db = {-27.0, -31.0}}), hard_target<double>{}));
    CHECK(plain.render(seabed, 0, 3, 1).values == mixed.render(seabed, 0, 3, 1).values);
}
