// Fuzz target: binary PGM height maps (sss::io::read_pgm16), 8- and 16-bit samples.
#include <cmath>

#include "fuzz_support.hpp"
#include "sss/io/height_field_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const sss_fuzz::temp_file file(".pgm", sss_fuzz::bytes(data, size));
    return sss_fuzz::run([&] {
        const auto hf = sss::io::read_pgm16<float>(file.path(), 0.5f, {10.0f, -4.0f}, {.scale_m = 0.01f, .offset_m = -30.0f});
        sss_fuzz::promise(hf.heights_m().size() == hf.nx() * hf.ny(), "grid size");
        for (float h : hf.heights_m()) sss_fuzz::promise(std::isfinite(h) && h >= -30.0f && h <= -30.0f + 655.36f, "heights in the sample range");
    });
}
