// Fuzz target: sound-speed profiles in all three formats (sss::io::read_sound_speed_csv, read_caris_svp_sections,
// read_kongsberg_asvp), each fed the same bytes, in float and double.
#include <cmath>
#include <sstream>
#include <string>

#include "fuzz_support.hpp"
#include "sss/io/sound_speed_profile.hpp"

namespace {
template <class T> void check(const sss::propagation::sound_speed_profile<T>& p) {
    const auto d = p.depths_m();
    const auto c = p.speeds_mps();
    sss_fuzz::promise(!d.empty() && d.size() == c.size(), "one speed per depth");
    for (std::size_t i = 0; i < d.size(); ++i) {
        sss_fuzz::promise(std::isfinite(d[i]) && std::isfinite(c[i]) && c[i] > T(0), "finite depths, positive speeds");
        if (i > 0) sss_fuzz::promise(d[i] > d[i - 1], "depths increase");
        // Between and beyond the knots the profile gives a finite, positive speed.
        const T between = i > 0 ? d[i - 1] + (d[i] - d[i - 1]) / T(3) : d[i] - T(1);
        const T c_between = p.speed_mps(between);
        sss_fuzz::promise(std::isfinite(c_between) && c_between > T(0), "finite, positive speed between knots");
    }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(sss_fuzz::bytes(data, size));
    sss_fuzz::run([&] {
        std::istringstream in(text);
        check(sss::io::read_sound_speed_csv<double>(in, "fuzz.csv"));
    });
    sss_fuzz::run([&] {
        std::istringstream in(text);
        for (const auto& p : sss::io::read_caris_svp_sections<float>(in, "fuzz.svp")) check(p);
    });
    sss_fuzz::run([&] {
        std::istringstream in(text);
        check(sss::io::read_kongsberg_asvp<double>(in, "fuzz.asvp"));
    });
    return 0;
}
