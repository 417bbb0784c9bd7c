// A flat height field renders the flat-seabed oracle as closely as the plane does: the seabed is one interface.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "support/compare.hpp"
#include "support/flat_seabed_oracle.hpp"
#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>

TEST_CASE_TEMPLATE("a flat height field matches the quadrature oracle as closely as the flat plane", T, float, double) {
    sss::receiver_params rx;
    rx.max_range_m = 40.0;
    sss::motion::perturbed_params<T> tow; // rolled and pitched: rays cross the grid obliquely
    tow.start_m = {T(3.3), T(-7.1)};
    tow.heading_deg = T(33);
    tow.altitude_m = T(12);
    tow.roll_deg = {T(3), T(7), T(90)};
    tow.pitch_deg = {T(2), T(5), T(90)};
    const sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>,
                         sss::motion::perturbed<T>>
        sim({}, {}, {}, sss::motion::perturbed<T>{tow}, rx);

    // 257 x 257 vertices at 0.4 m around the towfish, all at z = 2 m.
    const std::size_t n = 257;
    const T cell = T(0.4);
    const sss::scene::height_field<T> grid(n, n, cell, {T(-48), T(-55)}, std::vector<T>(n * n, T(2)));
    const sss::scene::flat_seabed<T> plane(T(2));
    const auto from_grid = sim.ping(grid, 0);
    const auto from_plane = sim.ping(plane, 0);

    const auto pose = sim.motion().pose_at(0);
    sss_test::oracle_setup o;
    o.altitude_m = double(pose.position.z) - 2.0;
    o.roll_rad = double(pose.roll_rad);
    o.pitch_rad = double(pose.pitch_rad);
    o.yaw_rad = double(pose.yaw_rad);
    o.absorption_db_per_km = 60.0;
    o.dt_s = sim.dt_s();
    o.samples = sim.samples_per_line();
    o.pulse_length_s = rx.pulse.length_s;
    const sss::beam::ideal_fan<double> fan;
    const sss::scattering::lambertian<double> lambert;
    for (sss::side sd : {sss::side::port, sss::side::starboard}) {
        const auto expected = sss_test::oracle_line(o, fan, lambert, sd);
        const auto e_grid = sss_test::compare_db(sd == sss::side::port ? from_grid.port : from_grid.starboard, expected);
        const auto e_plane = sss_test::compare_db(sd == sss::side::port ? from_plane.port : from_plane.starboard, expected);
        INFO("grid: rms " << e_grid.rms_db << " dB, worst " << e_grid.worst_db << "; plane: rms " << e_plane.rms_db
                          << " dB, worst " << e_plane.worst_db);
        CHECK(e_grid.compared > 200);
        CHECK(e_grid.rms_db <= 0.2);
        CHECK(std::abs(e_grid.worst_db) <= 1.0);
        CHECK(e_grid.rms_db <= e_plane.rms_db + 0.01);
    }
}
