// Every ray of one side of a ping stays over the rectangle side_reach gives, straight or refracted, under any
// attitude; the rectangle hugs the beam's footprint. Over that rectangle a scene shows only what lies there, which
// spares a curved ray the chords from the towfish down to a hill elsewhere, and changes nothing else.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <optional>
#include <random>
#include <vector>

#include <sss/beam/ideal_fan.hpp>
#include <sss/beam/planar_array.hpp>
#include <sss/core/pose.hpp>
#include <sss/propagation/layered.hpp>
#include <sss/propagation/straight.hpp>
#include <sss/sampling/reach.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/simulator.hpp>

#include "support/converged_reference.hpp"
#include "support/rough_scenes.hpp"

namespace {

const double deg = 3.141592653589793 / 180.0;
using sss::vec3;

bool inside(const sss::plane_rectangle<double>& r, const vec3<double>& p) {
    return p.x >= r.lo.x && p.x <= r.hi.x && p.y >= r.lo.y && p.y <= r.hi.y;
}

// Water whose speed falls by 30 m/s over 50 m below a fast surface layer: strongly bent rays.
sss::propagation::layered<double> bending_water() {
    sss::propagation::layered_params<double> p;
    p.surface_z_m = 60.0;
    p.frequency_hz = 100e3;
    return sss::propagation::layered<double>(sss::propagation::sound_speed_profile<double>({0, 20, 70, 300}, {1520, 1518, 1488, 1490}), p);
}

// Counts the scene's queries; with `regional`, it also bounds its geometry over a rectangle (AreaScene).
template <class S, bool regional> struct counted {
    using value_type = double;
    const S* s;
    std::size_t* calls;
    [[nodiscard]] std::optional<sss::hit<double>> intersect(const sss::ray<double>& r, double t) const {
        ++*calls;
        return s->intersect(r, t);
    }
    [[nodiscard]] double seabed_height_m(double x, double y) const { return s->seabed_height_m(x, y); }
    [[nodiscard]] double top_m() const { return s->top_m(); }
    [[nodiscard]] double top_m(const sss::vec2<double>& lo, const sss::vec2<double>& hi) const
        requires regional
    {
        return s->top_m(lo, hi);
    }
};

} // namespace

TEST_CASE("every ray of a side stays over its reach, straight or refracted, under roll, pitch and yaw") {
    const auto water = bending_water();
    const sss::propagation::straight<double> straight({.sound_speed_mps = 1500});
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 4, .vertical_width_deg = 100, .depression_deg = 40});
    const sss::beam::planar_array<double> array(sss::beam::planar_array_params<double>{});
    std::mt19937_64 g(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double t_max_s = 0.12;
    std::size_t checked = 0;
    for (const double yaw : {0.0, 37.0, 181.0, -95.0})
        for (const double roll : {0.0, -12.0, 9.0})
            for (const double pitch : {0.0, 7.0})
                for (const auto sd : {sss::side::port, sss::side::starboard})
                    for (int beam = 0; beam < 2; ++beam) {
                        const auto pose = sss::make_pose<double>(0.0, vec3<double>{120.0, -40.0, 30.0}, roll * deg, pitch * deg, yaw * deg);
                        const auto ext = beam == 0 ? fan.extent(sd) : array.extent(sd);
                        const double k_bent = water.reach_speed_mps(pose.position.z);
                        const auto bent = sss::side_reach(pose, sd, ext, t_max_s * k_bent, true);
                        const auto flat = sss::side_reach(pose, sd, ext, t_max_s * straight.reach_speed_mps(30.0), true);
                        for (int n = 0; n < 300; ++n) {
                            const double a = ext.along_min_rad + (ext.along_max_rad - ext.along_min_rad) * u(g);
                            const double e = ext.depression_min_rad + (ext.depression_max_rad - ext.depression_min_rad) * u(g);
                            const sss::ray<double> r{pose.position, pose.to_world(sss::beam_direction(sd, a, e))};
                            // Seabeds at several depths catch the rays at many distances within the time.
                            for (const double z : {25.0, 10.0, -20.0, -150.0}) {
                                const sss::scene::flat_seabed<double> floor(z);
                                if (const auto p = water.trace(r, floor, t_max_s)) {
                                    ++checked;
                                    CHECK(inside(bent, p->surface.point));
                                }
                                if (const auto p = straight.trace(r, floor, t_max_s)) {
                                    ++checked;
                                    CHECK(inside(flat, p->surface.point));
                                }
                            }
                        }
                    }
    CHECK(checked > 20000);
}

TEST_CASE("a column's reach (one along-track angle) holds every ray of the column and lies within its side's") {
    const sss::propagation::straight<double> straight({.sound_speed_mps = 1500});
    const sss::beam::planar_array<double> array(sss::beam::planar_array_params<double>{});
    std::mt19937_64 g(23);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double t_max_s = 0.12, reach_m = t_max_s * straight.reach_speed_mps(30.0);
    std::size_t checked = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const auto pose = sss::make_pose<double>(0.0, vec3<double>{-300.0 * u(g), 800.0 * u(g), 30.0}, (24 * u(g) - 12) * deg,
                                                 (16 * u(g) - 8) * deg, 360 * u(g) * deg);
        const auto sd = trial % 2 == 0 ? sss::side::port : sss::side::starboard;
        const auto ext = array.extent(sd);
        const auto side = sss::side_reach(pose, sd, ext, reach_m, true);
        const double a = ext.along_min_rad + (ext.along_max_rad - ext.along_min_rad) * u(g);
        const sss::beam_extent<double> column{a, a, ext.depression_min_rad, ext.depression_max_rad};
        const auto r = sss::side_reach(pose, sd, column, reach_m, true);
        CHECK(r.lo.x >= side.lo.x);
        CHECK(r.lo.y >= side.lo.y);
        CHECK(r.hi.x <= side.hi.x);
        CHECK(r.hi.y <= side.hi.y);
        for (int n = 0; n <= 64; ++n) {
            const double e = ext.depression_min_rad + (ext.depression_max_rad - ext.depression_min_rad) * n / 64.0;
            const sss::ray<double> ray{pose.position, pose.to_world(sss::beam_direction(sd, a, e))};
            for (const double z : {25.0, 0.0, -60.0}) {
                const sss::scene::flat_seabed<double> floor(z);
                if (const auto p = straight.trace(ray, floor, t_max_s)) {
                    ++checked;
                    CHECK(inside(r, p->surface.point));
                }
            }
        }
    }
    CHECK(checked > 5000);
}

TEST_CASE("a level side's reach hugs its footprint; a bounced path's is the square around the towfish") {
    const sss::beam::planar_array<double> array(sss::beam::planar_array_params<double>{});
    const auto pose = sss::make_pose<double>(0.0, vec3<double>{0.0, 0.0, 10.0}, 0.0, 0.0, 0.0);
    const auto ext = array.extent(sss::side::starboard);
    const auto r = sss::side_reach(pose, sss::side::starboard, ext, 100.0, true);
    // Heading north (+y), starboard is east: 100 m out, a few metres along track.
    CHECK(r.lo.x >= -1.1);
    CHECK(r.hi.x == doctest::Approx(101.0).epsilon(0.002));
    CHECK(r.hi.y - r.lo.y < 2 * 100 * std::sin(double(ext.along_max_rad)) + 2.5);
    const auto sq = sss::side_reach(pose, sss::side::starboard, ext, 100.0, false);
    CHECK(sq.lo.x == doctest::Approx(-101.0));
    CHECK(sq.hi.y == doctest::Approx(101.0));
}

TEST_CASE("a hill outside a side's reach no longer makes its refracted rays look for geometry from the towfish down") {
    // The rough relief of the accuracy tests, 10 m below the towfish, and a tower rising above it 30 m behind: the
    // whole scene's top is above the towfish, so without the area view every chord from the towfish down is handed to
    // the scene. With the area view the rays start their chords just above the relief; the line is the same up to
    // chords' rounding (a fine chord tolerance here: with the default, rays grazing a crest within it may change
    // sides).
    using namespace sss;
    auto heights = sss_test::ripple_field<double>();
    const double x0 = heights.origin_m().x, y0 = heights.origin_m().y, c = heights.cell_m();
    std::vector<double> h(heights.heights().begin(), heights.heights().end());
    for (std::size_t iy = 0; iy < heights.ny(); ++iy)
        for (std::size_t ix = 0; ix < heights.nx(); ++ix) {
            const double x = x0 + double(ix) * c, y = y0 + double(iy) * c;
            if (std::abs(x) < 1.0 && std::abs(y + 3.5) < 0.4) h[iy * heights.nx() + ix] = 14.0;
        }
    const scene::height_field<double> tower({.nx = heights.nx(), .ny = heights.ny(), .cell_m = c, .origin_m = {x0, y0}, .heights_m = std::move(h)});
    REQUIRE(tower.top_m() > sss_test::rough_altitude_m);

    propagation::layered_params<double> wp = sss_test::three_layer_water<double>().params();
    wp.chord_tolerance_m = 1e-7;
    const propagation::layered<double> water(sss_test::three_layer_water<double>().profile(), wp);
    const simulator<scattering::lambertian<double>, propagation::layered<double>> sim({}, water, {}, {}, sss_test::rough_receiver());
    const auto pose = sss_test::rough_pose<double>(false);
    std::size_t calls_whole = 0, calls_region = 0;
    const counted<scene::height_field<double>, false> whole{&tower, &calls_whole};
    const counted<scene::height_field<double>, true> regional{&tower, &calls_region};
    const auto line = [&](const auto& s) {
        time_sampler out(sim.samples_per_line(), sim.dt_s(), sim.receiver().pulse);
        sim.trace(s, pose, side::starboard, [&](const tube_echo<double>& e) { out.add_span(e.t0_s, e.t1_s, e.power); });
        std::vector<double> v;
        out.render(v);
        return v;
    };
    const auto a = line(whole), b = line(regional);
    const auto e = sss_test::compare_lines(b, a);
    MESSAGE("scene queries: whole scene " << calls_whole << ", area view " << calls_region << "; line RMS " << e.rms_db << " dB, p99 " << e.p99_db << " dB");
    CHECK(e.rms_db < 0.01);
    CHECK(e.p99_db < 0.01);
    CHECK(double(calls_region) < 0.6 * double(calls_whole));
}
