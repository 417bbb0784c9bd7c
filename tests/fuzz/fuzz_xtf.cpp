// Fuzz target: XTF files (sss::io::parse_xtf, what sss::io::read_xtf reads), two-channel sidescan in 8-bit,
// 16-bit or float samples; what is accepted must be finite and consistent, and must write and read back.
#include <cmath>
#include <span>

#include "fuzz_support.hpp"
#include "sss/io/xtf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return sss_fuzz::run([&] {
        const sss::io::xtf_file f = sss::io::parse_xtf(std::span<const std::uint8_t>(data, size), "fuzz.xtf");
        for (const auto& p : f.pings) {
            for (float v : p.port) sss_fuzz::promise(std::isfinite(v), "finite port samples");
            for (float v : p.starboard) sss_fuzz::promise(std::isfinite(v), "finite starboard samples");
        }
        // What was read writes again and reads back with the same pings and sample counts.
        const auto bytes = sss::io::encode_xtf(f);
        const sss::io::xtf_file again = sss::io::parse_xtf(std::span<const std::uint8_t>(bytes), "again.xtf");
        sss_fuzz::promise(again.pings.size() == f.pings.size(), "ping count survives a round trip");
        for (std::size_t i = 0; i < f.pings.size(); ++i)
            sss_fuzz::promise(again.pings[i].port.size() == f.pings[i].port.size() &&
                                  again.pings[i].starboard.size() == f.pings[i].starboard.size(),
                              "sample counts survive a round trip");
    });
}
