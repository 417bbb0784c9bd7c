// Seabeds larger than memory: a raw height file written band by band is the same whatever the bands, and a height
// field over the memory-mapped file gives the in-memory field's heights and the same rendered pings.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <sss/io/height_field_io.hpp>
#include <sss/io/mapped_height_field.hpp>
#include <sss/seabed/wave_sum.hpp>
#include <sss/simulator.hpp>

namespace {

std::string bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

const sss::io::raw_grid grid{.nx = 301, .ny = 257, .cell_m = 0.25, .origin_x_m = -20.0, .origin_y_m = 5.0};

sss::seabed::wave_sum_surface<float> surface() {
    sss::seabed::wave_sum_params<float> p;
    p.spectrum = sss::seabed::power_law_spectrum<float>{2e-4f, 3.25f, 0.0f};
    p.longest_m = 40.0f;
    p.waves = 48;
    return sss::seabed::wave_sum_surface<float>(p, 0.25f, 11);
}

void write(const std::string& path, std::size_t band_rows) {
    const auto s = surface();
    sss::io::write_raw_f32_by_rows(path, grid, band_rows, [&](std::size_t iy0, std::size_t rows, std::span<float> out) {
        s.fill_rows(grid.nx, iy0, rows, grid.cell_m, grid.origin_x_m, grid.origin_y_m, out);
    });
}

} // namespace

TEST_CASE("a seabed written band by band has the same bytes whatever the band height (seamless bands)") {
    write("one.raw", grid.ny);
    write("seven.raw", 7);
    write("sixty_four.raw", 64);
    const std::string a = bytes_of("one.raw");
    REQUIRE(a.size() == 4 * grid.nx * grid.ny);
    CHECK(bytes_of("seven.raw") == a);
    CHECK(bytes_of("sixty_four.raw") == a);
    // The heights follow the point formula, and their mean square is near the band's variance.
    const auto s = surface();
    const auto hf = sss::io::read_raw_f32<float>("seven.raw");
    double ms = 0;
    for (std::size_t iy = 0; iy < grid.ny; ++iy)
        for (std::size_t ix = 0; ix < grid.nx; ++ix) {
            const double want = s.height_m(grid.origin_x_m + double(ix) * grid.cell_m, grid.origin_y_m + double(iy) * grid.cell_m);
            REQUIRE(std::abs(double(hf.height_m(ix, iy)) - want) <= 1e-5 + 1e-5 * std::abs(want));
            ms += want * want;
        }
    ms /= double(grid.nx * grid.ny);
    CHECK(ms > 0.3 * s.variance_m2());
    CHECK(ms < 3.0 * s.variance_m2());
}

TEST_CASE("a wave-sum row gives each vertex the same bits whatever its width (columns a block at a time)") {
    // 2500 vertices a row spans three blocks of 1024 columns; each vertex alone (a row of one, at its own x) must
    // hold the same float, so rows of any width, and any split of a wide seabed, agree.
    const auto s = surface();
    constexpr std::size_t nx = 2500;
    std::vector<float> wide(2 * nx), one(2);
    s.fill_rows(nx, 7, 2, 0.25, -20.0, 5.0, std::span<float>(wide));
    std::size_t differ = 0;
    for (std::size_t ix : {std::size_t(0), std::size_t(1023), std::size_t(1024), std::size_t(2047), std::size_t(2048), nx - 1}) {
        s.fill_rows(1, 7, 2, 0.25, -20.0 + static_cast<double>(ix) * 0.25, 5.0, std::span<float>(one));
        differ += (one[0] != wide[ix]) + (one[1] != wide[nx + ix]);
    }
    CHECK(differ == 0);
}

TEST_CASE("a memory-mapped seabed renders the same pings as the same seabed in memory") {
    write("seabed.raw", 32);
    const auto mapped = sss::io::map_raw_f32("seabed.raw");
    const auto loaded = sss::io::read_raw_f32<float>("seabed.raw");
    REQUIRE(mapped.heights_m().empty()); // nothing copied: the heights stay in the file
    REQUIRE(mapped.heights().size() == loaded.heights_m().size());
    CHECK(std::equal(mapped.heights().begin(), mapped.heights().end(), loaded.heights_m().begin()));
    CHECK(mapped.top_m() == loaded.top_m());
    CHECK(mapped.bottom_m() == loaded.bottom_m());

    sss::motion::straight_line_params<float> track;
    track.start_m = {17.5f, 20.0f};
    track.heading_deg = 0.0f;
    track.altitude_m = 6.0f;
    sss::receiver_params rx;
    rx.max_range_m = 30;
    const sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>, sss::beam::ideal_fan<float>,
                         sss::motion::straight_line<float>>
        sim({}, {}, {}, sss::motion::straight_line<float>(track), rx);
    const auto a = sim.render(mapped, 0, 6, 2), b = sim.render(loaded, 0, 6, 2);
    double energy = 0;
    for (float v : a.values) energy += double(v);
    CHECK(energy > 0);
    CHECK(a.values == b.values);
    // A copy of the mapped field keeps the mapping alive.
    const auto copy = mapped;
    CHECK(sim.render(copy, 2, 1, 1).values == sim.render(loaded, 2, 1, 1).values);
}

#if defined(__linux__)
namespace {

// A line of /proc/self/status in KiB ("VmRSS", "VmHWM"); -1 where there is none.
double status_kib(const std::string& key) {
    std::ifstream f("/proc/self/status");
    std::string k;
    while (f >> k) {
        if (k == key + ":") {
            double kib = -1;
            f >> kib;
            return kib;
        }
        std::getline(f, k);
    }
    return -1;
}

} // namespace

TEST_CASE("mapping a seabed never holds its heights in memory: the peak is the pyramid and a band of rows") {
    // 2049 x 4097 heights (32 MiB); their pyramid is a third of that. Reading the whole file into the mapping's
    // pages would raise the peak by the file's size.
    const sss::io::raw_grid big{.nx = 2049, .ny = 4097, .cell_m = 0.1, .origin_x_m = 0.0, .origin_y_m = 0.0};
    sss::io::write_raw_f32_by_rows("big.raw", big, 512, [&](std::size_t iy0, std::size_t rows, std::span<float> out) {
        for (std::size_t r = 0; r < rows; ++r)
            for (std::size_t ix = 0; ix < big.nx; ++ix)
                out[r * big.nx + ix] = 0.3f * std::sin(0.01f * float(ix)) * std::cos(0.002f * float(iy0 + r));
    });
    struct remove_at_end {
        ~remove_at_end() {
            std::remove("big.raw");
            std::remove("big.raw.txt");
        }
    } remove_files;
    const double file_kib = 4.0 * double(big.nx * big.ny) / 1024.0;
    {
        std::ofstream reset("/proc/self/clear_refs");
        reset << "5"; // resets the peak (VmHWM) to the present resident memory
    }
    const double before = status_kib("VmRSS");
    if (status_kib("VmHWM") > before + 1024) {
        MESSAGE("this kernel does not reset the peak resident memory; the check is skipped");
        return;
    }
    const auto mapped = sss::io::map_raw_f32("big.raw");
    const double rise = status_kib("VmHWM") - before, pyramid_kib = double(mapped.acceleration_bytes()) / 1024.0;
    MESSAGE("peak rise " << rise / 1024 << " MiB for " << file_kib / 1024 << " MiB of heights and a "
                         << pyramid_kib / 1024 << " MiB pyramid");
    // Under AddressSanitizer every byte read is checked against a shadow byte per 8, whose pages become resident
    // too: an eighth of the file and of the pyramid more.
    double shadow_kib = 0.0;
#if defined(__SANITIZE_ADDRESS__)
    shadow_kib = 0.125 * (file_kib + pyramid_kib);
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    shadow_kib = 0.125 * (file_kib + pyramid_kib);
#endif
#endif
    CHECK(rise < pyramid_kib + 0.25 * file_kib + shadow_kib);
    CHECK(mapped.top_m() == doctest::Approx(0.3).epsilon(1e-3));
}
#endif

TEST_CASE("a raw file whose size disagrees with its sidecar is refused, naming the file") {
    write("short.raw", 64);
    {
        std::ofstream f("short.raw", std::ios::binary | std::ios::trunc);
        f << "abcd";
    }
    CHECK_THROWS_AS((void)sss::io::map_raw_f32("short.raw"), sss::file_error);
    CHECK_THROWS_AS((void)sss::io::map_raw_f32("missing.raw"), sss::file_error);
}

TEST_CASE("a sidecar whose cell size float cannot hold is refused, naming the sidecar; a bad height names the data") {
    // A raw file and its sidecar as written by hand: grid g, heights h.
    const auto put = [](const std::string& name, const sss::io::raw_grid& g, const std::vector<float>& h) {
        std::ofstream(sss::io::raw_sidecar_path(name), std::ios::binary) << sss::io::raw_sidecar_text(g);
        std::ofstream(name, std::ios::binary).write(reinterpret_cast<const char*>(h.data()), std::streamsize(4 * h.size()));
    };
    // The file map_raw_f32 names when it refuses `name`.
    const auto refused = [](const std::string& name) {
        try {
            (void)sss::io::map_raw_f32(name);
        } catch (const sss::file_error& e) {
            return e.file();
        }
        return std::string("(accepted)");
    };
    put("tiny_cell.raw", {.nx = 4, .ny = 3, .cell_m = 1e-50, .origin_x_m = 0, .origin_y_m = 0}, std::vector<float>(12, 0.0f));
    CHECK(refused("tiny_cell.raw") == "tiny_cell.raw.txt");
    std::vector<float> heights(12, 0.0f);
    heights[5] = std::numeric_limits<float>::quiet_NaN();
    put("nan_height.raw", {.nx = 4, .ny = 3, .cell_m = 1, .origin_x_m = 0, .origin_y_m = 0}, heights);
    CHECK(refused("nan_height.raw") == "nan_height.raw");
}
