// Inputs the fuzz targets (tests/fuzz/) found to break a promise, kept as regression tests: each must now be
// refused with an sss::error naming what is wrong, or give a finite result.

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

#include <sss/io/trajectory_csv.hpp>
#include <sss/motion/trajectory.hpp>

namespace {

// The name in the invalid_parameter thrown building a trajectory from CSV text ("" when none is thrown).
std::string trajectory_error(const std::string& text) {
    std::istringstream in(text);
    const auto samples = sss::io::read_trajectory_csv<double>(in, "fuzz.csv");
    try {
        const sss::motion::trajectory<double> t(samples);
        for (std::size_t i = 0; i < std::min<std::size_t>(4, t.ping_count()); ++i) {
            const auto p = t.pose_at(i);
            CHECK(std::isfinite(p.position.x));
            CHECK(std::isfinite(p.position.y));
            CHECK(std::isfinite(p.position.z));
        }
    } catch (const sss::invalid_parameter& e) {
        return e.parameter();
    }
    return {};
}

} // namespace

TEST_CASE("a trajectory whose times span 1e300 s is refused by name, not cast to a ping count out of range") {
    // fuzz_trajectory_csv, UBSan: "1e+301 is outside the range of representable values of type 'unsigned long'".
    CHECK(trajectory_error("time,x,y,z\n0,0,0,5\n1e300,0,1,5\n") == "trajectory.time_s");
    CHECK(trajectory_error("ping,x,y,z\n0,0,0,5\n1e17,0,1,5\n") == "trajectory.ping");
}

TEST_CASE("trajectory samples too large to interpolate are refused by name, not turned into infinite poses") {
    // fuzz_trajectory_csv: x of -1e308, 1e308, -1e308 gave an infinite position between the samples.
    CHECK(trajectory_error("time,x,y,z\n0,-1e308,0,5\n1,1e308,1,5\n2,-1e308,1,5\n") == "trajectory.position_m");
    CHECK(trajectory_error("time,x,y,z,heave\n0,0,0,5,1e13\n1,0,1,5,0\n") == "trajectory.heave_m");
    // Keys so close that the change in value per key overflows.
    CHECK(trajectory_error("time,x,y,z\n0,0,0,5\n1e-300,1e10,1,5\n2,0,1,5\n") == "trajectory.position_m");
    // Large but sane coordinates (UTM northings, absolute times) still load.
    CHECK(trajectory_error("time,x,y,z\n1700000000,500000,6200000,5\n1700000001,500001,6200000,5\n").empty());
}
