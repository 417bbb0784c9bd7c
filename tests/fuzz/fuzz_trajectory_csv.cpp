// Fuzz target: trajectory CSV (sss::io::read_trajectory_csv), then the trajectory built from what was read
// (sss::motion::trajectory), whose poses must be finite.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "fuzz_support.hpp"
#include "sss/io/trajectory_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(sss_fuzz::bytes(data, size));
    return sss_fuzz::run([&] {
        std::istringstream in(text);
        auto samples = sss::io::read_trajectory_csv<double>(in, "fuzz.csv");
        sss_fuzz::promise(samples.position_m.size() >= 2, "at least two samples");
        const sss::motion::trajectory<double> traj(std::move(samples));
        for (std::size_t i = 0; i < std::min<std::size_t>(4, traj.ping_count()); ++i) {
            const sss::pose<double> p = traj.pose_at(i);
            sss_fuzz::promise(std::isfinite(p.position.x) && std::isfinite(p.position.y) && std::isfinite(p.position.z),
                              "finite positions");
        }
    });
}
