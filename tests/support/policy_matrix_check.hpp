#pragma once
// The policy-matrix check: one combination of policies renders a flat seabed within 0.2 dB RMS (1 dB worst) of the
// independent oracle, at the library's default ray density. The matrix is split over translation units by
// propagation policy (test_policy_matrix_<propagation>.cpp) to keep each one's compile time and run time small.

#include <doctest/doctest.h>

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "support/compare.hpp"
#include "support/flat_seabed_oracle.hpp"
#include "support/policy_sets.hpp"

namespace sss_test {

// The oracle of a combination, computed once from its double-precision twin and shared by float and double.
template <class S, class P, class B, class M>
const std::vector<double>& expected_line(const sss_test::oracle_setup& o, sss::side sd) {
    static std::map<int, std::vector<double>> cache;
    const int key = sd == sss::side::port ? 0 : 1;
    auto it = cache.find(key);
    if (it == cache.end()) {
        using sss_test::matrix_policy;
        const auto beam = matrix_policy<B>::make();
        const auto scattering = matrix_policy<S>::make();
        // The propagation policy chooses its oracle: straight rays or closed-form arcs.
        it = cache.emplace(key, matrix_policy<P>::oracle_line(o, beam, scattering, sd)).first;
    }
    return it->second;
}

template <class Combo> void check_against_oracle() {
    using S = std::tuple_element_t<0, Combo>;
    using P = std::tuple_element_t<1, Combo>;
    using B = std::tuple_element_t<2, Combo>;
    using M = std::tuple_element_t<3, Combo>;
    using T = typename S::value_type;
    using sss_test::matrix_policy;
    using sss_test::rebind_t;

    sss::receiver_params rx;
    rx.sample_rate_hz = 20000.0;
    rx.max_range_m = 40.0;
    rx.pulse = {100e-6, sss::pulse_shape::rectangular};
    const sss::simulator<S, P, B, M> sim(matrix_policy<S>::make(), matrix_policy<P>::make(), matrix_policy<B>::make(),
                                         matrix_policy<M>::make(), rx);
    const sss::scene::flat_seabed<T> seabed(T(0));
    const std::size_t ping = 3;
    const auto lines = sim.ping(seabed, ping);

    // The oracle sees the double-precision twins of the same policies.
    using SD = rebind_t<S, double>;
    using PD = rebind_t<P, double>;
    using BD = rebind_t<B, double>;
    using MD = rebind_t<M, double>;
    const auto motion = matrix_policy<MD>::make();
    const sss::pose<double> pose = motion.pose_at(ping);
    sss_test::oracle_setup o;
    o.altitude_m = pose.position.z;
    o.roll_rad = pose.roll_rad;
    o.pitch_rad = pose.pitch_rad;
    o.yaw_rad = pose.yaw_rad;
    o.dt_s = sim.dt_s();
    o.samples = sim.samples_per_line();
    o.pulse_length_s = rx.pulse.length_s;
    o.source_level = 1.0;
    matrix_policy<SD>::describe(o, matrix_policy<SD>::make());
    matrix_policy<PD>::describe(o, matrix_policy<PD>::make());
    matrix_policy<BD>::describe(o, matrix_policy<BD>::make());
    matrix_policy<MD>::describe(o, motion);

    for (sss::side sd : {sss::side::port, sss::side::starboard}) {
        const auto& expected = expected_line<SD, PD, BD, MD>(o, sd);
        const auto& got = sd == sss::side::port ? lines.port : lines.starboard;
        const auto err = sss_test::compare_db(got, expected, 40.0);
        const std::string side_name = sd == sss::side::port ? "port" : "starboard";
        INFO(side_name << ": rms " << err.rms_db << " dB, worst " << err.worst_db << " dB at sample " << err.worst_index
                       << " of " << err.compared);
        CHECK(err.compared > 100);
        CHECK(err.rms_db <= 0.2);
        CHECK(std::abs(err.worst_db) <= 1.0);
    }
}

} // namespace sss_test

