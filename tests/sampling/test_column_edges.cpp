// Along-track columns narrow where the first return moves across them: the nearest range a launch plane reaches is
// the closed form a brute-force search over depressions finds; columns stay even, bit for bit, under a beam narrow
// along track; under a wide one each column holds the onset's movement to the tolerance; and a fan 120 degrees wide
// along track over a level seabed matches the flat-seabed quadrature from its first sample on; and a beam a few degrees
// wide, pitched and sampled finely, narrows its columns where that makes its first samples right.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "../support/compare.hpp"
#include "../support/flat_seabed_oracle.hpp"
#include <sss/sss.hpp>

namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;

// D / (largest component against the plane's unit normal n over the depressions), searched on a fine grid: the
// nearest point of the plane at distance D along a ray of the launch plane.
double nearest_by_search(sss::side sd, double along, double e0, double e1, const sss::mat3<double>& R, double D,
                         const sss::vec3<double>& n = {0.0, 0.0, 1.0}) {
    double best = -1.0;
    for (int i = 0; i <= 200000; ++i) {
        const double e = e0 + (e1 - e0) * double(i) / 200000.0;
        best = std::max(best, -glm::dot(R * sss::beam_direction<double>(sd, along, e), n));
    }
    return best > 0.0 ? D / best : std::numeric_limits<double>::infinity();
}

// The level seabed's closed form, written out: H / max over the depressions of the downward component
// A + B cos e + C sin e, A, B, C from the body axes' world up components (R's third row).
double level_form(sss::side sd, double along, double e0, double e1, const sss::mat3<double>& R, double H) {
    const double sa = std::sin(along), ca = std::cos(along);
    const double A = -R[0][2] * sa, B = -R[1][2] * (sd == sss::side::starboard ? 1.0 : -1.0) * ca, C = -R[2][2] * ca;
    double best = std::max(A + B * std::cos(e0) + C * std::sin(e0), A + B * std::cos(e1) + C * std::sin(e1));
    const double phi = std::atan2(C, B);
    for (int m = -1; m <= 1; ++m) {
        const double e = phi + double(m) * 2.0 * 3.14159265358979323846;
        if (e > e0 && e < e1) best = std::max(best, A + std::hypot(B, C));
    }
    return H > 0.0 && best > 0.0 ? H / best : std::numeric_limits<double>::infinity();
}

} // namespace

TEST_CASE("the nearest range of a launch plane is H / cos(a - a_n), found by searching the depressions") {
    const double H = 10.0;
    for (const double pitch : {0.0, 10.0 * deg, -25.0 * deg}) {
        for (const double roll : {0.0, 15.0 * deg}) {
            const sss::mat3<double> R = sss::body_to_world_rotation(roll, pitch, 0.3);
            for (const sss::side sd : {sss::side::port, sss::side::starboard}) {
                for (const double a : {-1.2, -0.4, 0.0, 0.2, 0.9}) {
                    for (const auto& [e0, e1] : {std::pair{-10.0 * deg, 80.0 * deg}, std::pair{5.0 * deg, 40.0 * deg}}) {
                        CAPTURE(pitch);
                        CAPTURE(roll);
                        CAPTURE(a);
                        CAPTURE(e1);
                        const double got = sss::nearest_range_m<double>(sd, a, e0, e1, R, H);
                        const double want = nearest_by_search(sd, a, e0, e1, R, H);
                        if (std::isinf(want)) CHECK(std::isinf(got));
                        else CHECK(got == doctest::Approx(want).epsilon(1e-6));
                    }
                }
            }
        }
    }
    // Level, with the vertical in the fan: the closed form itself.
    const sss::mat3<double> level = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    CHECK(sss::nearest_range_m<double>(sss::side::starboard, 0.5, 0.0, 90.0 * deg, level, H) ==
          doctest::Approx(H / std::cos(0.5)));
    // None of the fan descends: no first return.
    CHECK(std::isinf(sss::nearest_range_m<double>(sss::side::starboard, 0.0, -30.0 * deg, -5.0 * deg, level, H)));
}

TEST_CASE("the nearest range of a launch plane to a sloping plane is D over its rays' largest component against the "
          "normal, D the plane's distance: the plane's foot where a ray points at it, and the level form bit for bit") {
    const double D = 9.5;
    const sss::vec3<double> level_n{0.0, 0.0, 1.0};
    const sss::vec3<double> sloping_along = glm::normalize(sss::vec3<double>{-0.15, -0.075, 1.0});
    const sss::vec3<double> sloping_across = glm::normalize(sss::vec3<double>{0.3, -0.2, 1.0});
    for (const sss::vec3<double> n : {sloping_along, sloping_across, level_n}) {
        for (const double pitch : {0.0, 10.0 * deg}) {
            const sss::mat3<double> R = sss::body_to_world_rotation(6.0 * deg, pitch, 0.3);
            for (const sss::side sd : {sss::side::port, sss::side::starboard}) {
                for (const double a : {-0.4, 0.0, 0.07, 0.9}) {
                    CAPTURE(n.x);
                    CAPTURE(pitch);
                    CAPTURE(a);
                    const double got = sss::nearest_range_to_plane_m<double>(sd, a, -10.0 * deg, 80.0 * deg, R, n, D);
                    const double want = nearest_by_search(sd, a, -10.0 * deg, 80.0 * deg, R, D, n);
                    CHECK(got >= D * (1.0 - 1e-12)); // no point of the plane is nearer than its foot
                    if (std::isinf(want)) CHECK(std::isinf(got));
                    else CHECK(got == doctest::Approx(want).epsilon(1e-6));
                    if (n.x == 0.0 && n.y == 0.0) CHECK(got == level_form(sd, a, -10.0 * deg, 80.0 * deg, R, D));
                }
            }
        }
    }
    // A level towfish: the ray towards the plane's foot, -n, lies in the launch plane of along-track angle asin(-n.y)
    // (the towfish heading +y) and within the depressions: the range is D itself.
    const sss::vec3<double> n = glm::normalize(sss::vec3<double>{-0.15, -0.075, 1.0});
    const sss::mat3<double> level = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    CHECK(sss::nearest_range_to_plane_m<double>(sss::side::starboard, std::asin(-n.y), 0.0, 90.0 * deg, level, n, D) ==
          doctest::Approx(D).epsilon(1e-12));
}

TEST_CASE("columns stay evenly spaced, bit for bit, where the first return barely moves across them") {
    const sss::mat3<double> level = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    const double a0 = -1.75 * deg, a1 = 1.75 * deg; // a 3.5 degree beam
    std::vector<double> edges;
    sss::column_edges(edges, a0, a1, 8, 0.05, 100.0, [&](double a) {
        return sss::nearest_range_m<double>(sss::side::starboard, a, 0.0, 80.0 * deg, level, 10.0);
    });
    REQUIRE(edges.size() == 9);
    for (std::size_t j = 0; j <= 8; ++j) CHECK(edges[j] == a0 + (a1 - a0) * double(j) / 8.0);
}

TEST_CASE("columns under a beam wide along track hold the first return's movement across each to the tolerance") {
    const sss::mat3<double> pitched = sss::body_to_world_rotation(0.0, 8.0 * deg, 0.0);
    const double H = 10.0, range = 60.0, tol = 0.0375; // one range sample at 20 kHz
    auto onset = [&](double a) {
        return std::min(range, sss::nearest_range_m<double>(sss::side::starboard, a, -10.0 * deg, 70.0 * deg, pitched, H));
    };
    const double a0 = -80.0 * deg, a1 = 80.0 * deg;
    std::vector<double> edges;
    sss::column_edges(edges, a0, a1, 8, tol, range, onset);
    const std::size_t m = edges.size() - 1;
    CHECK(m > 8);
    CHECK(m <= 4096);
    CHECK(edges.front() == a0);
    CHECK(edges.back() == a1);
    double r_min = range;
    for (int i = 0; i <= 100000; ++i) r_min = std::min(r_min, onset(a0 + (a1 - a0) * double(i) / 100000.0));
    for (std::size_t j = 0; j < m; ++j) {
        CAPTURE(j);
        REQUIRE(edges[j + 1] > edges[j]);
        CHECK(edges[j + 1] - edges[j] <= (a1 - a0) / 8.0 * (1.0 + 1e-9)); // never wider than the even columns
        double lo = range, hi = 0.0;
        int lowest = 0;
        for (int q = 0; q <= 200; ++q) {
            const double r = onset(edges[j] + (edges[j + 1] - edges[j]) * double(q) / 200.0);
            if (r < lo) lowest = q;
            lo = std::min(lo, r);
            hi = std::max(hi, r);
        }
        // The tolerance where the column's onset begins, growing farther out; a quarter of it near the nearest
        // return where the onset turns within the column (the grid's slope and curvature estimate it, hence the
        // margin).
        const bool turns = lowest > 0 && lowest < 200;
        const double allowed = tol * std::max(turns ? 0.25 : 1.0, 8.0 * (lo - r_min) / r_min);
        CHECK(hi - lo <= 1.2 * allowed);
    }
    // A cap on the count widens every column alike and keeps the ends.
    sss::column_edges(edges, a0, a1, 8, tol, range, onset, 100);
    CHECK(edges.size() == 101);
    CHECK(edges.front() == a0);
    CHECK(edges.back() == a1);
}

namespace {

// Fans `along_deg` wide along track, 10 m above a level seabed, 30 m per side, Lambert, straight rays, against the
// quadrature of the sonar equation: the error over the samples within 40 dB of the peak, with the default ray density
// and with the columns near the first return left whole.
struct fan_errors {
    sss_test::db_error divided, whole;
};

template <class T> fan_errors wide_fan_errors(double along_deg) {
    sss::receiver_params rx;
    rx.max_range_m = 30.0;
    const sss::beam::ideal_fan<T> fan({.along_width_deg = T(along_deg), .vertical_width_deg = T(90), .depression_deg = T(45)});
    using sim_t = sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>,
                                 sss::motion::straight_line<T>>;
    const auto make = [&](sss::ray_density d) {
        return sim_t(sss::scattering::lambertian<T>(T(-27)),
                     sss::propagation::straight<T>({.sound_speed_mps = T(1500), .absorption_db_per_km = T(30)}), fan,
                     sss::motion::straight_line<T>({.altitude_m = T(10)}), rx, d);
    };
    const sim_t divided = make({}), whole = make({.along_split_nadir = false});
    sss_test::oracle_setup o;
    o.altitude_m = 10.0;
    o.absorption_db_per_km = 30.0;
    o.dt_s = divided.dt_s();
    o.samples = divided.samples_per_line();
    o.pulse_length_s = divided.receiver().pulse.length_s;
    o.pulse = divided.receiver().pulse.shape == sss::pulse_shape::hann ? sss_test::envelope::hann : sss_test::envelope::rectangular;
    o.rel_tol = 1e-5;
    const sss::beam::ideal_fan<double> fan_d({.along_width_deg = along_deg, .vertical_width_deg = 90.0, .depression_deg = 45.0});
    const auto expected = sss_test::oracle_line(o, fan_d, sss::scattering::lambertian<double>(-27.0), sss::side::starboard);
    const sss::scene::flat_seabed<T> bed{};
    return {sss_test::compare_db(divided.ping(bed, 0).starboard, expected, 40.0),
            sss_test::compare_db(whole.ping(bed, 0).starboard, expected, 40.0)};
}

} // namespace

TEST_CASE_TEMPLATE("over a level seabed, fans 20 to 120 degrees wide along track match the quadrature from their first "
                   "sample, where columns whole near the first return leave up to 0.73 dB there",
                   T, float, double) {
    // Evenly spaced columns (8 of 15 degrees under 120, the nearest centred 7.5 degrees off the vertical) left the
    // first two samples after the nadir time silent: the columns are narrower where the first return moves across
    // them (column_edges). It still moves by up to a sample across each (a quarter where it turns within one), and
    // just after it the echo rises as the square root of the time: each column's first partial sample stood for its
    // whole width at its centre's onset. Divided into thirds there (ray_density::along_split_nadir), with the launch
    // intervals either side shared in steps, what is left is the across-track quadrature's few hundredths of a dB.
    // The bounds hold both constants of the rule: without the steps (simulator::nadir_taper), 120 degrees is 0.013 dB
    // RMS; with the nearest column's threshold (nadir_first_spread) a quarter of a sample like the others', the first
    // sample is 0.22 dB off under 20 degrees and 0.97 dB under 120.
    struct fan_case {
        double along_deg;
        double whole_worst_db; // what whole columns leave at least (under 60 degrees they leave 0.125 dB: none asked)
    };
    for (const fan_case c : {fan_case{20.0, 0.3}, fan_case{60.0, -1.0}, fan_case{120.0, 0.3}}) {
        const double along_deg = c.along_deg;
        CAPTURE(along_deg);
        const auto [divided, whole] = wide_fan_errors<T>(along_deg);
        INFO("divided: rms " << divided.rms_db << " dB, worst " << divided.worst_db << " dB at sample "
                             << divided.worst_index << "; whole: rms " << whole.rms_db << " dB, worst " << whole.worst_db
                             << " dB at sample " << whole.worst_index);
        CHECK(std::abs(divided.worst_db) <= 0.15); // 0.044, 0.099, 0.031 dB in double
        CHECK(divided.rms_db <= 0.01);             // 0.002, 0.004, 0.006 dB
        if (c.whole_worst_db > 0.0) CHECK(std::abs(whole.worst_db) > c.whole_worst_db); // 0.455 and 0.726 dB
    }
}

TEST_CASE("a tolerance too fine for the cap keeps every column no wider than the even ones, and a vanishing one the cap") {
    const sss::mat3<double> level = sss::body_to_world_rotation(0.0, 0.0, 0.0);
    auto onset = [&](double a) {
        return sss::nearest_range_m<double>(sss::side::starboard, a, -10.0 * deg, 70.0 * deg, level, 10.0);
    };
    const double a0 = -80.0 * deg, a1 = 80.0 * deg;
    std::vector<double> edges;
    for (const double tol : {7.5e-4, 1e-19, 1e-300}) {
        CAPTURE(tol);
        sss::column_edges(edges, a0, a1, 8, tol, 15.0, onset);
        REQUIRE(edges.size() == 4097);
        CHECK(edges.front() == a0);
        CHECK(edges.back() == a1);
        for (std::size_t j = 0; j + 1 < edges.size(); ++j) {
            CHECK(edges[j + 1] >= edges[j]);
            CHECK(edges[j + 1] - edges[j] <= (a1 - a0) / 8.0 * (1.0 + 1e-9));
        }
    }
}

namespace {

// A towfish held at one pose: pitched bow up, 10 m above a level seabed.
struct pitched_towfish {
    using value_type = double;
    double pitch_rad = 0.0;
    [[nodiscard]] sss::pose<double> pose_at(std::size_t) const noexcept {
        return sss::make_pose<double>(0.0, sss::vec3<double>{0.0, 0.0, 10.0}, 0.0, pitch_rad, 0.0);
    }
};

} // namespace

TEST_CASE("under a pitched towfish sampled finely, a beam a few degrees wide narrows its columns and its first samples "
          "match a render at 256 even columns where even ones are more than a dB off") {
    // The default 100 kHz planar array (5.6 degrees along track), 10 degrees of pitch, 100 kHz sampling: the first
    // return moves 23 samples across the beam, 2.3 across each of its 10 even columns.
    static_assert(sss::Motion<pitched_towfish>);
    const sss::beam::planar_array<double> array(sss::beam::planar_array_params<double>{.frequency_hz = 100e3});
    sss::receiver_params rx;
    rx.sample_rate_hz = 100e3;
    rx.max_range_m = 20.0;
    using sim_t = sss::simulator<sss::scattering::lambertian<double>, sss::propagation::straight<double>,
                                 sss::beam::planar_array<double>, pitched_towfish>;
    const auto make = [&](sss::ray_density d) {
        return sim_t(sss::scattering::lambertian<double>(-27.0),
                     sss::propagation::straight<double>({.sound_speed_mps = 1500.0, .absorption_db_per_km = 0.0}), array,
                     pitched_towfish{10.0 * deg}, rx, d);
    };
    // The columns near the first return left whole (ray_density::along_split_nadir), to show what the narrowing alone
    // does: dividing them there takes even columns to 0.10 dB and narrowed ones to 0.06 dB.
    const sim_t narrowed = make(sss::ray_density{.along_split_nadir = false});
    const sim_t even = make(sss::ray_density{.along_split_nadir = false, .along_onset = 0.0});
    const sim_t converged = make(sss::ray_density{.along = 256, .along_onset = 0.0});
    const sss::scene::flat_seabed<double> bed(0.0);
    const auto reference = converged.ping(bed, 0).starboard;
    const auto e_narrowed = sss_test::compare_db(narrowed.ping(bed, 0).starboard, reference, 40.0);
    const auto e_even = sss_test::compare_db(even.ping(bed, 0).starboard, reference, 40.0);
    INFO("narrowed: rms " << e_narrowed.rms_db << " dB, worst " << e_narrowed.worst_db << " dB at sample "
                          << e_narrowed.worst_index << "; even: rms " << e_even.rms_db << " dB, worst " << e_even.worst_db
                          << " dB at sample " << e_even.worst_index);
    CHECK(std::abs(e_even.worst_db) > 1.0); // 1.3 dB, in the first samples
    CHECK(std::abs(e_narrowed.worst_db) <= 0.25); // 0.11 dB
    CHECK(e_narrowed.rms_db <= 0.01);
    // The columns the trace takes: 24 for the even 10.
    const auto ext = array.extent(sss::side::starboard);
    const std::size_t n_even = narrowed.along_columns(ext, sss::side::starboard);
    CHECK(n_even == 10);
    const sss::mat3<double> R = pitched_towfish{10.0 * deg}.pose_at(0).body_to_world;
    std::vector<double> edges;
    sss::column_edges(edges, ext.along_min_rad, ext.along_max_rad, n_even, 0.5 * 1500.0 / rx.sample_rate_hz,
                      rx.max_range_m, [&](double a) {
                          return sss::nearest_range_m<double>(sss::side::starboard, a, ext.depression_min_rad,
                                                              ext.depression_max_rad, R, 10.0);
                      });
    CHECK(edges.size() - 1 > n_even);
}
