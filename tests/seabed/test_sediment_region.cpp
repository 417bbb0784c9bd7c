// One sediment description sets a region's roughness spectrum and its scattering: the relief of a region made
// from a sediment has that sediment's Jackson spectrum, and its material scatters with the same parameters.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <sss/core/error.hpp>
#include <sss/seabed/sediment_region.hpp>

namespace sb = sss::seabed;
namespace sc = sss::scattering;

TEST_CASE("a region made from a sediment name takes TR 9407's roughness spectrum for it (w2 in SI, gamma 3.25)") {
    const sb::sediment_region<double> sand{.id = 0, .sediment = sb::sediment_named<double>("medium_sand"), .outer_scale_m = 30.0};
    const auto t = sb::texture(sand);
    // Medium sand: w2 = 0.004446 cm^4, gamma = 3.25; w2_si = w2 10^(2 gamma - 8) m^(4 - gamma).
    CHECK(t.roughness.spectrum.gamma == doctest::Approx(3.25));
    CHECK(t.roughness.spectrum.w2_si == doctest::Approx(0.004446 * std::pow(10.0, 2.0 * 3.25 - 8.0)).epsilon(1e-3).scale(0));
    CHECK(t.roughness.spectrum.outer_scale_m == 30.0);
    // Rougher sediments have stronger spectra: gravel over sand over mud.
    const auto w2 = [](const char* name) { return sb::texture(sb::sediment_region<double>{.sediment = sb::sediment_named<double>(name)}).roughness.spectrum.w2_si; };
    CHECK(w2("sandy_gravel") > w2("medium_sand"));
    CHECK(w2("medium_sand") > w2("sandy_mud"));
}

TEST_CASE("the regions' scattering is Jackson's with the same sediments, material id = region id") {
    const std::vector<sb::sediment_region<double>> regions{
        {.id = 1, .sediment = sb::sediment_named<double>("sandy_mud"), .mean_height_m = -0.3},
        {.id = 0, .sediment = sb::sediment_of_grain_size<double>(1.5)}};
    const auto model = sb::jackson_for(regions, {.frequency_hz = 100e3, .sound_speed_mps = 1500.0});
    const sc::jackson<double> direct({.frequency_hz = 100e3,
                                      .sound_speed_mps = 1500.0,
                                      .materials = {sc::sediment_from_grain_size<double>(1.5), sc::sediment_preset<double>("sandy_mud")}});
    for (double g : {0.1, 0.4, 0.9, 1.4}) {
        CHECK(model.backscatter(g, 0) == direct.backscatter(g, 0));
        CHECK(model.backscatter(g, 1) == direct.backscatter(g, 1));
    }
    // Geometry and scattering come from one description: the texture's spectrum matches the model's material.
    const auto tex = sb::textures(regions);
    CHECK(tex[0].id == 1);
    CHECK(tex[0].roughness.spectrum.w2_si == doctest::Approx(sb::w2_si_from_cm4(model.material(1).w2_cm4, model.material(1).gamma)).scale(0));
}

TEST_CASE("region ids must number the materials without gaps or repeats") {
    const std::vector<sb::sediment_region<double>> gap{{.id = 0, .sediment = sb::sediment_named<double>("rock")},
                                                       {.id = 2, .sediment = sb::sediment_named<double>("clay")}};
    CHECK_THROWS_AS((void)sb::sediments_by_id(gap), sss::error);
    CHECK_THROWS_AS((void)sb::sediment_named<double>("marmalade"), sss::error);
}
