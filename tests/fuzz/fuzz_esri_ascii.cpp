// Fuzz target: ESRI ASCII grids (sss::io::read_esri_ascii), with and without a NODATA fill.
#include <cmath>

#include "fuzz_support.hpp"
#include "sss/io/height_field_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const sss_fuzz::temp_file file(".asc", sss_fuzz::bytes(data, size));
    return sss_fuzz::run([&] {
        const sss::io::esri_ascii_options<float> fill{.nodata_fill_m = -1.0f};
        const auto hf = sss::io::read_esri_ascii<float>(file.path(), size % 2 ? fill : sss::io::esri_ascii_options<float>{});
        sss_fuzz::promise(hf.nx() >= 2 && hf.ny() >= 2 && hf.heights_m().size() == hf.nx() * hf.ny(), "grid size");
        for (float h : hf.heights_m()) sss_fuzz::promise(std::isfinite(h), "finite heights");
        sss_fuzz::promise(std::isfinite(hf.cell_m()) && hf.cell_m() > 0, "positive cell");
        sss_fuzz::promise(hf.bottom_m() <= hf.top_m(), "bottom below top");
    });
}
