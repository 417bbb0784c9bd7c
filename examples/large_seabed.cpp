// A seabed larger than it needs to be in memory: an n x n float32 raw height file (default 16384^2 at 0.1 m,
// 1 GiB of heights) synthesised band by band from a pointwise wave sum (seabed/wave_sum.hpp), then memory-mapped
// (io/mapped_height_field.hpp, POSIX) and rendered for a few pings. Prints the time of each stage and the
// process's resident memory (VmRSS) after it, and the peak (VmHWM): after mapping, the resident memory is the
// maximum pyramid plus the pages under the pings' rays, not the heights.
// Usage: sss_large_seabed [n = 16384] [path = large_seabed.raw] [pings = 8]

#include <sss/io/mapped_height_field.hpp>
#include <sss/seabed/wave_sum.hpp>
#include <sss/simulator.hpp>

#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <span>
#include <string>

namespace {

// A line of /proc/self/status in MiB ("VmRSS", "VmHWM"); -1 where there is none.
double status_mib(const std::string& key) {
    std::ifstream f("/proc/self/status");
    std::string k;
    while (f >> k) {
        if (k == key + ":") {
            double kib = -1;
            f >> kib;
            return kib / 1024.0;
        }
        std::getline(f, k);
    }
    return -1;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

} // namespace

int main(int argc, char** argv) try {
    const std::size_t n = argc > 1 ? std::stoul(argv[1]) : 16384;
    const std::string path = argc > 2 ? argv[2] : "large_seabed.raw";
    const std::size_t pings = argc > 3 ? std::stoul(argv[3]) : 8;
    const double cell_m = 0.1;

    sss::seabed::wave_sum_params<float> p;
    p.spectrum = sss::seabed::power_law_spectrum<float>{2e-4f, 3.25f, 0.0f};
    p.longest_m = 400.0f;
    p.waves = 32;
    const sss::seabed::wave_sum_surface<float> surface(p, float(cell_m), 2026);
    const sss::io::raw_grid grid{.nx = n, .ny = n, .cell_m = cell_m, .origin_x_m = 0.0, .origin_y_m = 0.0};

    auto t = std::chrono::steady_clock::now();
    sss::io::write_raw_f32_by_rows(path, grid, 256, [&](std::size_t iy0, std::size_t rows, std::span<float> out) {
        surface.fill_rows(n, iy0, rows, cell_m, 0.0, 0.0, out);
    });
    std::printf("wrote %zu x %zu heights (%.0f MiB) in bands of 256 rows: %.1f s, resident %.0f MiB\n", n, n,
                double(n * n * 4) / (1 << 20), seconds_since(t), status_mib("VmRSS"));

    t = std::chrono::steady_clock::now();
    const auto seabed = sss::io::map_raw_f32(path);
    std::printf("mapped (checks, bounds and pyramid of %.0f MiB): %.1f s, resident %.0f MiB\n",
                double(seabed.acceleration_bytes()) / (1 << 20), seconds_since(t), status_mib("VmRSS"));

    sss::motion::straight_line_params<float> track;
    track.start_m = {float(0.5 * double(n) * cell_m), 100.0f};
    track.heading_deg = 0.0f;
    track.altitude_m = 10.0f;
    sss::receiver_params rx;
    rx.max_range_m = 100;
    const sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>, sss::beam::ideal_fan<float>,
                         sss::motion::straight_line<float>>
        sim({}, {}, {}, sss::motion::straight_line<float>(track), rx);
    t = std::chrono::steady_clock::now();
    const auto w = sim.render(seabed, 0, pings);
    double energy = 0;
    for (float v : w.values) energy += double(v);
    std::printf("rendered %zu pings (100 m per side): %.2f s, resident %.0f MiB, peak %.0f MiB (echo energy %.3g)\n",
                pings, seconds_since(t), status_mib("VmRSS"), status_mib("VmHWM"), energy);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "sss_large_seabed: %s\n", e.what());
    return 1;
}
