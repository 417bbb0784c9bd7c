// Height field files: ESRI ASCII grids, raw float32 with a sidecar, and 16-bit PGM. Round trips, the
// conventions (rows north to south, corner versus centre registration), and bad files named by line or
// byte offset.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "sss/io/height_field_io.hpp"
#include "sss/io/mapped_height_field.hpp"
#include "sss/io/sound_speed_profile.hpp"
#include "sss/io/trajectory_csv.hpp"
#include "support/scratch_dir.hpp"
#include "support/temporaries.hpp"

namespace fs = std::filesystem;
using sss::vec2;
using sss::scene::height_field;

namespace {

using sss_test::scratch_dir;

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }
std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

template <class T> height_field<T> sample_field() {
    // 7 x 4 vertices with values that need all their digits.
    std::vector<T> h(28);
    for (std::size_t i = 0; i < h.size(); ++i)
        h[i] = T(std::sin(double(i) * 1.7) * 12.3456789 - 3.0 + 1e-3 * double(i));
    return height_field<T>({.nx = 7, .ny = 4, .cell_m = T(0.3), .origin_m = vec2<T>{T(500123.25), T(-42.125)}, .heights_m = std::move(h)});
}

template <class T> void check_same(const height_field<T>& a, const height_field<T>& b) {
    REQUIRE(a.nx() == b.nx());
    REQUIRE(a.ny() == b.ny());
    CHECK(a.cell_m() == b.cell_m());
    CHECK(a.origin_m().x == b.origin_m().x);
    CHECK(a.origin_m().y == b.origin_m().y);
    CHECK(std::ranges::equal(a.heights(), b.heights())); // heights() also views a mapped field's heights
}

// The file_error of f(), or a failed check when it throws none.
template <class F> sss::file_error error_of(F&& f) {
    try {
        f();
    } catch (const sss::file_error& e) {
        return e;
    }
    FAIL("no file_error thrown");
    return sss::file_error("", 0, "");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

} // namespace

TEST_CASE_TEMPLATE("An ESRI ASCII grid written and read back gives the same heights, spacing and origin", T, float,
                   double) {
    scratch_dir d;
    const auto hf = sample_field<T>();
    const std::string path = d.file("grid.asc");
    sss::io::write_esri_ascii(path, hf);
    check_same(hf, sss::io::read_esri_ascii<T>(path));
    CHECK(sss_test::temporaries_left(path) == 0);
    // Writing again replaces the file.
    sss::io::write_esri_ascii(path, height_field<T>({.nx = 2, .ny = 2, .cell_m = T(1), .heights_m = {T(1), T(2), T(3), T(4)}}));
    CHECK(sss::io::read_esri_ascii<T>(path).nx() == 2);
}

TEST_CASE("A float grid's heights, cell size and centre read back to the bit where rounding through double is off by one") {
    // 0x1.5c87fap-84 prints as 7.038531e-26: its nearest double, rounded to float, gives the next float.
    const float f = std::bit_cast<float>(std::uint32_t(0x15ae43fdu));
    scratch_dir d;
    const std::string path = d.file("tiny.asc");
    const height_field<float> hf({.nx = 2, .ny = 2, .cell_m = f, .origin_m = vec2<float>{f, -f}, .heights_m = {f, -f, 1.0f, f}});
    sss::io::write_esri_ascii(path, hf);
    check_same(hf, sss::io::read_esri_ascii<float>(path));
    // The raw format's sidecar likewise, read into memory and mapped.
    const std::string raw = d.file("tiny.raw");
    sss::io::write_raw_f32(raw, hf);
    check_same(hf, sss::io::read_raw_f32<float>(raw));
    check_same(hf, sss::io::map_raw_f32(raw));
}

TEST_CASE("A raw height file and its sidecar are replaced together: a sidecar that cannot be replaced leaves the old data") {
    scratch_dir d;
    const std::string path = d.file("sea.raw");
    sss::io::write_raw_f32(path, height_field<float>({.nx = 2, .ny = 2, .cell_m = 1.0f, .heights_m = {1, 2, 3, 4}}));
    const std::string old = read_bytes(path);
    fs::remove(path + ".txt");
    fs::create_directory(path + ".txt");
    const height_field<float> bigger({.nx = 3, .ny = 3, .cell_m = 0.5f, .heights_m = std::vector<float>(9, 2.0f)});
    CHECK(error_of([&] { sss::io::write_raw_f32(path, bigger); }).file() == path + ".txt");
    CHECK(read_bytes(path) == old);
    CHECK(sss_test::temporaries_left(path) == 0);
    CHECK(sss_test::temporaries_left(path + ".txt") == 0);
    // With the sidecar's name free again both are written, and read back.
    fs::remove(path + ".txt");
    sss::io::write_raw_f32(path, bigger);
    check_same(bigger, sss::io::read_raw_f32<float>(path));
}

TEST_CASE("An ESRI ASCII grid's first row is the northern one, and xllcorner means the cell's corner") {
    scratch_dir d;
    const std::string path = d.file("corner.asc");
    write_text(path, "NCOLS 3\nnrows 2\nxllcorner 100\nYLLCORNER 200\ncellsize 2\nnodata_value -9999\n"
                     "1 2 3\n4 5 6\n");
    const auto hf = sss::io::read_esri_ascii<double>(path);
    CHECK(hf.nx() == 3);
    CHECK(hf.ny() == 2);
    CHECK(hf.origin_m().x == 101); // the centre of the south-west cell
    CHECK(hf.origin_m().y == 201);
    CHECK(hf.height_m(0, 1) == 1); // first row: north (iy = ny - 1)
    CHECK(hf.height_m(2, 1) == 3);
    CHECK(hf.height_m(0, 0) == 4);
    CHECK(hf.seabed_height_m(101, 201) == 4);
    CHECK(hf.seabed_height_m(105, 203) == 3);

    // Centre registration, values wrapped over lines at will, CRLF line ends.
    write_text(path, "ncols 2\r\nnrows 2\r\nxllcenter 1.5\r\nyllcenter -2.5\r\ncellsize 0.5\r\n7 8 9\r\n10\r\n");
    const auto c = sss::io::read_esri_ascii<float>(path);
    CHECK(c.origin_m().x == 1.5f);
    CHECK(c.origin_m().y == -2.5f);
    CHECK(c.height_m(1, 1) == 8);
    CHECK(c.height_m(1, 0) == 10);
}

TEST_CASE("NODATA in an ESRI ASCII grid is an error naming its line, unless a fill height is given") {
    scratch_dir d;
    const std::string path = d.file("nodata.asc");
    write_text(path, "ncols 2\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n1 2\n3 -9999\n5 6\n");
    const auto e = error_of([&] { (void)sss::io::read_esri_ascii<double>(path); });
    CHECK(e.line() == 8);
    CHECK(e.file() == path);
    CHECK(contains(e.what(), "NODATA"));
    sss::io::esri_ascii_options<double> fill;
    fill.nodata_fill_m = -50.0;
    CHECK(sss::io::read_esri_ascii<double>(path, fill).height_m(1, 1) == -50.0);
    // NaN as the NODATA value (GDAL's for a grid whose no-data cells are NaN): the same, the cell named or filled.
    write_text(path, "ncols 2\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value nan\n1 2\n3 nan\n5 6\n");
    CHECK(error_of([&] { (void)sss::io::read_esri_ascii<double>(path); }).line() == 8);
    CHECK(sss::io::read_esri_ascii<double>(path, fill).height_m(1, 1) == -50.0);
    CHECK(sss::io::read_esri_ascii<double>(path, fill).height_m(0, 0) == 5.0);
}

TEST_CASE("A raw height file whose size differs from its sidecar's grid is named before it is read") {
    scratch_dir d;
    const std::string path = d.file("big.raw");
    sss::io::write_raw_f32(path, sss::scene::height_field<float>({.nx = 2, .ny = 2, .cell_m = 1.0f, .heights_m = {1, 2, 3, 4}}));
    // A sparse 4 GiB file in its place: its size names it at once (it was read whole first, 4 GiB of memory).
    std::filesystem::resize_file(path, std::uintmax_t(1) << 32);
    const auto e = error_of([&] { (void)sss::io::read_raw_f32<float>(path); });
    CHECK(e.file() == path);
    CHECK(e.byte_offset() == 16);
    CHECK(contains(e.what(), "4294967296 bytes"));
    std::filesystem::remove(path);
    // The banded writer asks of its grid what the reader will: a NaN origin leaves the old files as they were.
    sss::io::write_raw_f32(path, sss::scene::height_field<float>({.nx = 2, .ny = 2, .cell_m = 1.0f, .heights_m = {1, 2, 3, 4}}));
    const std::string before = read_text(path);
    sss::io::raw_grid g{.nx = 2, .ny = 2, .cell_m = 1.0, .origin_x_m = std::nan("")};
    CHECK_THROWS_AS(sss::io::write_raw_f32_by_rows(path, g, 1, [](std::size_t, std::size_t, std::span<float> out) {
                        for (float& v : out) v = 0.0f;
                    }),
                    sss::invalid_parameter);
    CHECK(read_text(path) == before);
}

TEST_CASE("Malformed ESRI ASCII grids are rejected naming the file and line") {
    scratch_dir d;
    const std::string path = d.file("bad.asc");
    struct bad_case {
        std::string text;
        std::size_t line;
        std::string says;
    };
    const std::string head = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
    const std::vector<bad_case> cases = {
        {"nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", 5, "ncols"},
        {"ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3\n4 5 6\n", 5, "cellsize"},
        {"ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -1\n1 2 3\n4 5 6\n", 5, "cellsize"},
        {"ncols 1\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1\n2\n", 1, "ncols"},
        {"ncols 3\nncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", 2, "twice"},
        {"ncols 3\nnrows 2\nfoo 1\n", 3, "foo"},
        {"ncols 3\nnrows 2\ndx 1\n", 3, "square"},
        {head + "1 2 3\n4 x 6\n", 7, "'x'"},
        {head + "1 2 3\n4 nan 6\n", 7, "not finite"},
        {head + "1 2 3\n4 inf 6\n", 7, "not finite"},
        {head + "1 2 3\n4 5\n\n", 8, "file ends after 5 of 6"},
        {head + "1 2 3\n4 5 6\n7\n", 8, "more values"},
        {"ncols 3\nnrows 2\n", 2, "header"},
    };
    for (const auto& c : cases) {
        write_text(path, c.text);
        const auto e = error_of([&] { (void)sss::io::read_esri_ascii<double>(path); });
        CHECK_MESSAGE(e.line() == c.line, c.text);
        CHECK_MESSAGE(contains(e.what(), c.says), e.what());
        CHECK(contains(e.what(), path));
    }
    // 1e39 does not fit a float: not finite as a float height.
    write_text(path, head + "1 2 3\n4 1e39 6\n");
    CHECK(error_of([&] { (void)sss::io::read_esri_ascii<float>(path); }).line() == 7);
    CHECK(sss::io::read_esri_ascii<double>(path).height_m(1, 0) == 1e39);
    // Header values a double holds and a float does not: named by their own lines (they were line 0).
    write_text(path, "ncols 3\nnrows 2\nxllcorner 1e39\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n");
    CHECK(error_of([&] { (void)sss::io::read_esri_ascii<float>(path); }).line() == 3);
    write_text(path, "ncols 3\nnrows 2\nxllcorner 0\nyllcenter -1e40\ncellsize 1\n1 2 3\n4 5 6\n");
    CHECK(error_of([&] { (void)sss::io::read_esri_ascii<float>(path); }).line() == 4);
    write_text(path, "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1e-60\n1 2 3\n4 5 6\n");
    const auto tiny = error_of([&] { (void)sss::io::read_esri_ascii<float>(path); });
    CHECK(tiny.line() == 5);
    CHECK(contains(tiny.what(), "cellsize"));
    CHECK(sss::io::read_esri_ascii<double>(path).cell_m() == 1e-60);
    // A missing file.
    const auto e = error_of([&] { (void)sss::io::read_esri_ascii<double>(d.file("missing.asc")); });
    CHECK(contains(e.what(), "missing.asc"));
}

TEST_CASE_TEMPLATE("Raw float32 with its sidecar round-trips, little-endian, south row first", T, float, double) {
    scratch_dir d;
    const std::string path = d.file("field.raw");
    // Heights that float32 holds exactly, so the double round trip is exact too.
    std::vector<T> h(12);
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = T(double(i) * 0.25 - 1.5);
    const height_field<T> hf({.nx = 4, .ny = 3, .cell_m = T(0.5), .origin_m = vec2<T>{T(10), T(-20)}, .heights_m = h});
    sss::io::write_raw_f32(path, hf);
    check_same(hf, sss::io::read_raw_f32<T>(path));
    CHECK(sss_test::temporaries_left(path) == 0);
    const std::string bytes = read_bytes(path);
    REQUIRE(bytes.size() == 48);
    // Vertex 1 is 0.25 - 1.5 = -1.25f = 0xBFA00000, stored low byte first.
    CHECK((unsigned char)bytes[4] == 0x00);
    CHECK((unsigned char)bytes[6] == 0xA0);
    CHECK((unsigned char)bytes[7] == 0xBF);
    CHECK(contains(read_bytes(path + ".txt"), "format sss-height-raw-f32le 1"));
}

TEST_CASE("Bad raw height files are rejected naming the sidecar line or the data's byte offset") {
    scratch_dir d;
    const std::string path = d.file("bad.raw");
    const height_field<float> hf({.nx = 3, .ny = 2, .cell_m = 1.0f, .heights_m = {1, 2, 3, 4, 5, 6}});
    sss::io::write_raw_f32(path, hf);
    const std::string good_side = read_bytes(path + ".txt");
    const std::string good_data = read_bytes(path);

    // A NaN in vertex 4: bytes 16..19.
    std::string data = good_data;
    data[16] = 0;
    data[17] = 0;
    data[18] = char(0xC0);
    data[19] = 0x7F;
    write_text(path, data);
    auto e = error_of([&] { (void)sss::io::read_raw_f32<float>(path); });
    CHECK(e.byte_offset() == 16);
    CHECK(contains(e.what(), "vertex 4"));
    // Too short.
    write_text(path, good_data.substr(0, 20));
    e = error_of([&] { (void)sss::io::read_raw_f32<double>(path); });
    CHECK(e.byte_offset() == 20);
    CHECK(contains(e.what(), "needs 24"));
    write_text(path, good_data);

    // Sidecar faults, by line.
    struct bad_side {
        std::string text;
        std::size_t line;
        std::string says;
    };
    const std::vector<bad_side> cases = {
        {"format sss-height-raw-f32le 2\n", 1, "unknown format"},
        {"format sss-height-raw-f32le 1\nnx 3\nny two\n", 3, "ny"},
        {"# comment\n\nformat sss-height-raw-f32le 1\nnx 3\nny 2\ncell_m 0\n", 6, "cell_m"},
        {"format sss-height-raw-f32le 1\nnx 3\nny 2\ncell_m 1\norigin_x_m 0\norigin_y_m 0\ncolour blue\n", 7, "colour"},
        {"format sss-height-raw-f32le 1\nnx 3 4\n", 2, "too many"},
        {"format sss-height-raw-f32le 1\nnx 3\nny 2\ncell_m 1\norigin_x_m 0\n", 0, "origin_y_m"},
    };
    for (const auto& c : cases) {
        write_text(path + ".txt", c.text);
        e = error_of([&] { (void)sss::io::read_raw_f32<float>(path); });
        CHECK_MESSAGE(e.line() == c.line, c.text);
        CHECK_MESSAGE(contains(e.what(), c.says), e.what());
        CHECK(e.file() == path + ".txt");
    }
    // The sidecar's grid disagrees with the data's size.
    write_text(path + ".txt", "format sss-height-raw-f32le 1\nnx 4\nny 2\ncell_m 1\norigin_x_m 0\norigin_y_m 0\n");
    e = error_of([&] { (void)sss::io::read_raw_f32<float>(path); });
    CHECK(e.file() == path);
    CHECK(e.byte_offset() == 24);
}

TEST_CASE_TEMPLATE("A 16-bit PGM round-trips to within half a vertical step, first row north", T, float, double) {
    scratch_dir d;
    const std::string path = d.file("field.pgm");
    const auto hf = sample_field<T>();
    const auto vertical = sss::io::pgm16_fit(hf);
    sss::io::write_pgm16(path, hf, vertical);
    const auto back = sss::io::read_pgm16<T>(path, hf.cell_m(), hf.origin_m(), vertical);
    REQUIRE(back.nx() == hf.nx());
    REQUIRE(back.ny() == hf.ny());
    double worst = 0;
    for (std::size_t i = 0; i < hf.heights_m().size(); ++i)
        worst = std::max(worst, std::abs(double(back.heights_m()[i]) - double(hf.heights_m()[i])));
    CHECK(worst <= 0.5 * double(vertical.scale_m) * (1 + 1e-4));
    CHECK(back.top_m() == doctest::Approx(double(hf.top_m())).epsilon(1e-5));
    // The lowest height is sample 0, the highest 65535; samples are big-endian.
    const std::string bytes = read_bytes(path);
    CHECK(bytes.substr(0, 3) == "P5\n");
    CHECK(contains(bytes, "\n7 4\n65535\n"));
    CHECK(sss_test::temporaries_left(path) == 0);
    // A height outside the 16-bit range is refused, naming the vertex; the old file stays.
    CHECK_THROWS_AS(
        sss::io::write_pgm16(path, hf, sss::io::pgm_vertical<T>{vertical.scale_m, vertical.offset_m + T(1)}),
        sss::invalid_parameter);
    CHECK(read_bytes(path) == bytes);
}

TEST_CASE("A hand-made 8-bit and 16-bit PGM read with scale and offset, rows from the north") {
    scratch_dir d;
    const std::string path = d.file("hand.pgm");
    // 2 x 2, maxval 1000 (two bytes per sample), a comment in the header.
    write_text(path,
               std::string("P5\n# made by hand\n2 2\n1000\n") + std::string("\x00\x01\x00\x02\x03\xE8\x00\x00", 8));
    const auto hf = sss::io::read_pgm16<double>(path, 2.0, {5, 6}, {0.01, -3.0});
    CHECK(hf.height_m(0, 1) == doctest::Approx(-2.99)); // first row: north
    CHECK(hf.height_m(1, 1) == doctest::Approx(-2.98));
    CHECK(hf.height_m(0, 0) == doctest::Approx(7.0));
    CHECK(hf.height_m(1, 0) == doctest::Approx(-3.0));
    write_text(path, std::string("P5 3 2 255\n") + std::string("\x01\x02\x03\x04\x05\xFF", 6));
    const auto b = sss::io::read_pgm16<float>(path, 1.0f, {}, {0.5f, 0.0f});
    CHECK(b.height_m(2, 0) == 127.5f);
}

TEST_CASE("Bad PGM files are rejected naming the byte offset") {
    scratch_dir d;
    const std::string path = d.file("bad.pgm");
    struct bad_case {
        std::string bytes;
        std::size_t offset;
        std::string says;
    };
    const std::vector<bad_case> cases = {
        {"P2\n2 2\n65535\n", 0, "P5"},
        {"P5\n2 x\n65535\n", 5, "height"},
        {"P5\n1 2\n65535\n" + std::string(4, '\0'), 2, "at least 2 x 2"},
        {"P5\n2 2\n70000\n" + std::string(8, '\0'), 12, "maxval"},
        {"P5\n2 2\n65535\n" + std::string(5, '\0'), 18, "file ends after 5 of 8"},
        {"P5\n2 2\n65535\n" + std::string(9, '\0'), 21, "trailing"},
        {std::string("P5\n2 2\n300\n") + std::string("\x00\x01\x00\x02\x01\x2D\x00\x00", 8), 15, "exceeds maxval"},
    };
    for (const auto& c : cases) {
        write_text(path, c.bytes);
        const auto e = error_of([&] { (void)sss::io::read_pgm16<double>(path, 1.0, {}, {1.0, 0.0}); });
        CHECK_MESSAGE(e.byte_offset() == c.offset, e.what());
        CHECK_MESSAGE(contains(e.what(), c.says), e.what());
        CHECK(e.line() == 0);
        CHECK(e.file() == path);
    }
    CHECK_THROWS_AS((void)sss::io::read_pgm16<double>(path, 1.0, {}, {0.0, 0.0}), sss::invalid_parameter);
}

TEST_CASE("A writer that cannot create its file throws naming it and leaves nothing behind") {
    scratch_dir d;
    const std::string path = d.file("no/such/dir/out.asc");
    const height_field<double> hf({.nx = 2, .ny = 2, .cell_m = 1.0, .heights_m = {0, 0, 0, 0}});
    const auto e = error_of([&] { sss::io::write_esri_ascii(path, hf); });
    CHECK(e.file() == path);
    CHECK_FALSE(fs::exists(path));
    CHECK(sss_test::temporaries_left(path) == 0);
}

TEST_CASE("Every reader refuses a directory by naming it, and a grid whose cell is an invalid parameter names the file "
          "once") {
    scratch_dir d;
    const std::string dir = d.file("a_directory.asc");
    fs::create_directories(dir);
    fs::create_directories(d.file("raw.raw"));
    sss::io::write_raw_sidecar(d.file("raw.raw"), {.nx = 2, .ny = 2, .cell_m = 1.0, .origin_x_m = 0.0, .origin_y_m = 0.0});
    const auto says_directory = [&](const sss::file_error& e, const std::string& path) {
        INFO(e.what());
        CHECK(e.file() == path);
        CHECK(contains(e.what(), "is a directory, not a file"));
    };
    says_directory(error_of([&] { (void)sss::io::read_esri_ascii<float>(dir); }), dir);
    says_directory(error_of([&] { (void)sss::io::read_pgm16<float>(dir, 1.0f, {0.0f, 0.0f}, {.scale_m = 1.0f}); }), dir);
    says_directory(error_of([&] { (void)sss::io::read_raw_f32<float>(d.file("raw.raw")); }), d.file("raw.raw"));
    says_directory(error_of([&] { (void)sss::io::read_sound_speed_csv<float>(dir); }), dir);
    says_directory(error_of([&] { (void)sss::io::read_trajectory_csv<float>(dir); }), dir);
    // A cell size that underflows float: named by its line, with one "sss: ".
    write_text(d.file("tiny.asc"), "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1e-300\n1 2\n3 4\n");
    const auto e = error_of([&] { (void)sss::io::read_esri_ascii<float>(d.file("tiny.asc")); });
    INFO(e.what());
    CHECK(e.line() == 5);
    CHECK(contains(e.what(), "'cellsize' 1e-300"));
    CHECK(std::string(e.what()).find("sss: ", 1) == std::string::npos);
}
