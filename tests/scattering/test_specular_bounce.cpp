// One specular bounce: a compile-time choice that changes nothing where the reflected ray escapes, adds the
// bounced path's echo at the summed travel time where it meets something, and never adds energy.

#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/scene/sphere.hpp>

namespace {

using jackson_d = sss::scattering::jackson<double>;
using bouncing_d = sss::scattering::specular_bounce<jackson_d>;

jackson_d sand() {
    return jackson_d({.frequency_hz = 100000.0,
                      .sound_speed_mps = 1500.0,
                      .materials = {sss::scattering::sediment_preset<double>(sss::scattering::sediment::medium_sand)}});
}

/// A policy built on specular_bounce that declares the bounce switched off: the simulator must read the value.
struct bounce_declared_off : bouncing_d {
    using bouncing_d::bouncing_d;
    static constexpr bool specular_bounce_enabled = false;
};

template <class S>
using sim_t = sss::simulator<S, sss::propagation::straight<double>, sss::beam::ideal_fan<double>, sss::motion::straight_line<double>>;

double total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

} // namespace

static_assert(sss::Reflecting<jackson_d> && sss::Scattering<bouncing_d>);
static_assert(!sss::Reflecting<sss::scattering::lambertian<double>>);

TEST_CASE("the coherent reflection coefficient lies in [0, 1] and falls with roughness finer than the patch") {
    const auto j = sand();
    for (double g = 0.0; g <= 1.5708; g += 0.01) {
        const double r = j.reflection(g, 0, 0.1);
        CHECK(r >= 0.0);
        CHECK(r <= 1.0);
        CHECK(j.reflection(g, 0, 1.0) <= r + 1e-15); // a larger patch leaves more roughness to reduce it
    }
}

TEST_CASE("with nothing for the reflected ray to meet, the bounce leaves the render unchanged") {
    sss::receiver_params rx;
    rx.max_range_m = 40;
    const sss::scene::flat_seabed<double> seabed;
    const sim_t<jackson_d> plain(sand(), {}, {}, {}, rx);
    const sim_t<bouncing_d> bouncing(bouncing_d(sand()), {}, {}, {}, rx);
    const auto a = plain.ping(seabed, 0), b = bouncing.ping(seabed, 0);
    CHECK(a.starboard == b.starboard);
    CHECK(a.port == b.port);
}

TEST_CASE("a bounce off the seabed onto a raised bank adds echoes at the summed travel time and never adds energy") {
    // Flat seabed at z = 0 with a bank rising steeply to 6 m beyond 30 m on the starboard side (east): rays that
    // bounce off the flat part travel on to the bank's face and come back the same way, later than the direct echo
    // from the same face.
    const std::size_t nx = 801, ny = 401;
    const double cell = 0.1;
    std::vector<double> h(nx * ny, 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double x = -20.0 + double(ix) * cell;
            h[iy * nx + ix] = x > 30.0 ? std::min(6.0, (x - 30.0) * 3.0) : 0.0;
        }
    const sss::scene::height_field<double> bank({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = {-20.0, -20.0}, .heights_m = h});
    sss::receiver_params rx;
    rx.max_range_m = 60;
    const sim_t<jackson_d> plain(sand(), {}, sss::beam::ideal_fan<double>({.along_width_deg = 1.0, .vertical_width_deg = 80.0, .depression_deg = 40.0}), {}, rx);
    const sim_t<bouncing_d> bouncing(bouncing_d(sand()), {}, sss::beam::ideal_fan<double>({.along_width_deg = 1.0, .vertical_width_deg = 80.0, .depression_deg = 40.0}), {}, rx);
    const auto a = plain.ping(bank, 0), b = bouncing.ping(bank, 0);
    // Port sees only flat seabed: identical.
    CHECK(a.port == b.port);
    // Starboard gains energy only from bounced paths: every sample at least the plain one.
    double extra = 0;
    std::size_t first_extra = b.starboard.size();
    for (std::size_t k = 0; k < b.starboard.size(); ++k) {
        CHECK(b.starboard[k] >= a.starboard[k] * (1 - 1e-12));
        if (b.starboard[k] > a.starboard[k] * (1 + 1e-9)) {
            first_extra = std::min(first_extra, k);
            extra += b.starboard[k] - a.starboard[k];
        }
    }
    CHECK(extra > 0);
    // A path bounced once off the plane z = 0 is as long as the straight line from the towfish's mirror image
    // (z = -10 m) to where it ends; on the bank (x >= 30 m, z >= 0) that is at least the distance from the image to
    // the bank's foot, sqrt(30^2 + 10^2): no bounced echo can arrive earlier.
    const double bounce_path = std::sqrt(30.0 * 30.0 + 10.0 * 10.0);
    const double t_bounce = 2.0 * bounce_path / 1500.0;
    CHECK(double(first_extra) * plain.dt_s() >= t_bounce - 2 * plain.dt_s());
    // Energy never increases through a bounce: the bounced echoes carry less than the direct echo of the bank.
    double bank_direct = 0;
    for (std::size_t k = std::size_t(t_bounce / plain.dt_s()) - 5; k < a.starboard.size(); ++k) bank_direct += a.starboard[k];
    CHECK(extra < bank_direct);
    CHECK(total(b.starboard) > total(a.starboard));

    // The same policy with specular_bounce_enabled = false does not bounce: exactly the plain render.
    const sim_t<bounce_declared_off> off(bounce_declared_off(sand()), {},
                                         sss::beam::ideal_fan<double>({.along_width_deg = 1.0, .vertical_width_deg = 80.0, .depression_deg = 40.0}),
                                         {}, rx);
    const auto c = off.ping(bank, 0);
    CHECK(c.starboard == a.starboard);
    CHECK(c.port == a.port);
}

TEST_CASE("a sphere above a flat seabed returns a second echo at the seabed-bounce travel time, only with the bounce") {
    // Towfish 10 m above a sandy seabed; a 1 m sphere 20 m to starboard with its centre 3 m above the seabed.
    // Direct echoes come from the sphere's near side, between 20.19 m and 21.17 m of range. A path bounced once off
    // the seabed is as long as the line from the towfish's mirror image (10 m below the seabed) to the sphere, whose
    // nearest point lies |C - I| - a = sqrt(20^2 + 13^2) - 1 = 22.85 m away.
    using namespace sss::scene;
    const surface_ids ids{0, 5, 3};
    std::vector<object<double>> objs{object<double>({sphere<double>({20.0, 0.0, 3.0}, 1.0, ids)}, {})};
    const scene sc(flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
    sss::receiver_params rx;
    rx.max_range_m = 40;
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 1.0, .vertical_width_deg = 80.0, .depression_deg = 40.0});
    const sss::motion::straight_line<double> still({.start_m = {0.0, 0.0}, .heading_deg = 0.0, .speed_mps = 0.0, .altitude_m = 10.0, .ping_interval_s = 0.1});
    const sim_t<jackson_d> plain(sand(), {}, fan, still, rx);
    const sim_t<bouncing_d> bouncing(bouncing_d(sand()), {}, fan, still, rx);
    const auto pose = plain.motion().pose_at(0);
    const double c = 1500.0;
    const double t_direct_end = 2.0 * std::sqrt(20.0 * 20.0 + 7.0 * 7.0 - 1.0) / c;
    const double t_bounce = 2.0 * (std::sqrt(20.0 * 20.0 + 13.0 * 13.0) - 1.0) / c;

    auto sphere_energy = [&](const auto& sim, double t_from, double t_to, double& first) {
        double e = 0;
        first = 1e9;
        sim.trace(sc, pose, sss::side::starboard, [&](const sss::tube_echo<double>& t) {
            const double t0 = std::min(t.t0_s, t.t1_s);
            if (t.surface.object == 5u && t0 >= t_from && t0 <= t_to) {
                e += t.power;
                first = std::min(first, t0);
            }
        });
        return e;
    };
    double first_direct = 0, first_bounce = 0, first_plain_late = 0;
    const double direct = sphere_energy(plain, 0.0, t_direct_end + 1e-6, first_direct);
    const double bounced = sphere_energy(bouncing, t_direct_end + 1e-6, 1.0, first_bounce);
    const double plain_late = sphere_energy(plain, t_direct_end + 1e-6, 1.0, first_plain_late);
    INFO("direct " << direct << " from " << first_direct << " s; bounced " << bounced << " from " << first_bounce
                   << " s (predicted " << t_bounce << " s)");
    CHECK(direct > 0);
    CHECK(first_direct == doctest::Approx(2.0 * (std::sqrt(449.0) - 1.0) / c).epsilon(1e-3).scale(0));
    // Present with the bounce, at the bounced path's travel time...
    CHECK(bounced > 0);
    CHECK(first_bounce == doctest::Approx(t_bounce).epsilon(2e-3).scale(0));
    // ... absent without it.
    CHECK(plain_late == 0.0);
    // Energy never increases through a bounce.
    CHECK(bounced < direct);
    // And the rendered line shows it: a later echo in the bounce render only.
    const auto a = plain.ping(sc, 0), b = bouncing.ping(sc, 0);
    const auto k = static_cast<std::size_t>(t_bounce / plain.dt_s()) + 1;
    CHECK(b.starboard[k] > a.starboard[k]);
}

TEST_CASE("every echo piece carries its ray: the launch direction and the time to the first surface, the bounce point "
          "for a bounced path") {
    // The sphere above the seabed of the test above, with the bounce on. Straight water at 1500 m/s: a direct piece's
    // ray reaches its surface at launch * c * first_leg_s from the transducer; a bounced piece's ray reaches its
    // bounce point there (on the seabed, z = 0, or on the sphere), before the piece's own, later, surface.
    using namespace sss::scene;
    std::vector<object<double>> objs{object<double>({sphere<double>({20.0, 0.0, 3.0}, 1.0, {0, 5, 3})}, {})};
    const scene sc(flat_seabed<double>(0.0), object_set<double>(std::move(objs)));
    sss::receiver_params rx;
    rx.max_range_m = 40;
    const sss::beam::ideal_fan<double> fan({.along_width_deg = 1.0, .vertical_width_deg = 80.0, .depression_deg = 40.0});
    const sss::motion::straight_line<double> still({.start_m = {0.0, 0.0}, .heading_deg = 0.0, .speed_mps = 0.0, .altitude_m = 10.0, .ping_interval_s = 0.1});
    const sim_t<bouncing_d> bouncing(bouncing_d(sand()), {}, fan, still, rx);
    const auto pose = bouncing.motion().pose_at(0);
    const double c = 1500.0;
    std::size_t direct = 0, bounced = 0;
    bouncing.trace(sc, pose, sss::side::starboard, [&](const sss::tube_echo<double>& t) {
        REQUIRE(std::abs(glm::length(t.launch) - 1.0) < 1e-12);
        const glm::dvec3 end = pose.position + t.launch * (c * t.first_leg_s);
        if (std::abs(t.t0_s - 2.0 * t.first_leg_s) < 1e-12) { // direct: out to the surface and back
            ++direct;
            CHECK(glm::length(end - t.surface.point) < 1e-9 * c * t.first_leg_s);
        } else { // bounced: the first leg ends on the seabed or on the sphere, and is the shorter part of the time
            ++bounced;
            const bool on_seabed = std::abs(end.z) < 1e-9;
            const bool on_sphere = std::abs(glm::length(end - glm::dvec3{20.0, 0.0, 3.0}) - 1.0) < 1e-9;
            CHECK((on_seabed || on_sphere));
            CHECK(t.first_leg_s < 0.5 * t.t0_s);
        }
    });
    CHECK(direct > 100);
    CHECK(bounced > 10);
}
