// Greyscale PNG files: the header holds the image's size and depth, and an image that does not fit its size is
// refused naming the file, with nothing written.

#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "sss/io/png.hpp"
#include "support/scratch_dir.hpp"
#include "support/temporaries.hpp"

namespace {

std::vector<std::uint8_t> bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t be32(const std::vector<std::uint8_t>& b, std::size_t at) {
    return std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 | std::uint32_t(b[at + 2]) << 8 | b[at + 3];
}

} // namespace

TEST_CASE("A greyscale PNG's header gives its width, height, bit depth and colour type") {
    const sss_test::scratch_dir tmp;
    const std::string p8 = tmp.file("a.png"), p16 = tmp.file("b.png");
    sss::io::write_png_grey8(p8, 3, 2, std::vector<std::uint8_t>{0, 1, 2, 3, 4, 5});
    sss::io::write_png_grey16(p16, 2, 3, std::vector<std::uint16_t>{0, 1, 2, 3, 4, 65535});
    for (const auto& [path, w, h, depth] : {std::tuple{p8, 3u, 2u, 8}, std::tuple{p16, 2u, 3u, 16}}) {
        const auto b = bytes_of(path);
        REQUIRE(b.size() > 33);
        CHECK(b[0] == 0x89);
        CHECK(std::string(b.begin() + 12, b.begin() + 16) == "IHDR");
        CHECK(be32(b, 16) == w);
        CHECK(be32(b, 20) == h);
        CHECK(int(b[24]) == depth);
        CHECK(int(b[25]) == 0); // greyscale
    }
}

TEST_CASE("A PNG whose pixels do not fill its size, or of no size, is refused naming the file, and nothing is written") {
    const sss_test::scratch_dir tmp;
    const std::string path = tmp.file("short.png");
    try {
        sss::io::write_png_grey8(path, 4, 3, std::vector<std::uint8_t>(11, 0));
        FAIL("no error");
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "png samples");
        CHECK(std::string(e.what()).find(path) != std::string::npos);
    }
    try {
        sss::io::write_png_grey16(path, 0, 3, std::vector<std::uint16_t>{});
        FAIL("no error");
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "png size");
        CHECK(std::string(e.what()).find(path) != std::string::npos);
    }
    CHECK(!std::filesystem::exists(path));
    CHECK(sss_test::temporaries_left(path) == 0);
}

TEST_CASE("The display maps a level beyond any number (infinity) to white, and zero, negatives and NaN to black") {
    const std::vector<double> v{1.0, 10.0, std::numeric_limits<double>::infinity(), 100.0, 0.0, -1.0,
                                std::numeric_limits<double>::quiet_NaN()};
    const auto grey = sss::io::to_grey_db<std::uint8_t>(std::span<const double>(v), {.dynamic_range_db = 20.0});
    // The window's top is the finite peak (100: 20 dB), its floor 0 dB.
    CHECK(grey == std::vector<std::uint8_t>{0, 128, 255, 255, 0, 0, 0});
}
