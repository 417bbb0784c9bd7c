// Seabeds larger than memory: a raw height file written band by band is the same whatever the bands, and a height
// field over the memory-mapped file gives the in-memory field's heights and the same rendered pings.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <iterator>
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

TEST_CASE("a raw file whose size disagrees with its sidecar is refused, naming the file") {
    write("short.raw", 64);
    {
        std::ofstream f("short.raw", std::ios::binary | std::ios::trunc);
        f << "abcd";
    }
    CHECK_THROWS_AS((void)sss::io::map_raw_f32("short.raw"), sss::file_error);
    CHECK_THROWS_AS((void)sss::io::map_raw_f32("missing.raw"), sss::file_error);
}
