// Fuzz target: raw float32 heights with their text sidecar (sss::io::read_raw_f32). The input is the sidecar's
// text, one NUL byte, then the raw data (no NUL: the whole input is the sidecar and the data file is empty).
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "sss/io/height_field_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view in = sss_fuzz::bytes(data, size);
    const std::size_t nul = in.find('\0');
    const std::string_view side = in.substr(0, nul);
    const std::string_view raw = nul == std::string_view::npos ? std::string_view{} : in.substr(nul + 1);
    const sss_fuzz::temp_file file(".raw", raw);
    const sss_fuzz::temp_file sidecar(".raw.txt", side);
    return sss_fuzz::run([&] {
        const auto hf = sss::io::read_raw_f32<double>(file.path());
        sss_fuzz::promise(hf.heights_m().size() * 4 == raw.size(), "one float32 per vertex");
        for (double h : hf.heights_m()) sss_fuzz::promise(std::isfinite(h), "finite heights");
    });
}
