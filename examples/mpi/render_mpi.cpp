// A survey line rendered across MPI ranks (sss/mpi/render.hpp): every rank builds the same seabed from one seed,
// renders its share of the pings (chunks dealt round-robin), and rank 0 writes the waterfall as raw float32
// (pings x 2 samples, row-major) to argv[1] (default render_mpi.f32) and prints the time.
// Run: mpirun -np 2 ./sss_render_mpi out.f32 [pings = 64]; the same file comes out of -np 1 (or no mpirun at all).
// Built only when MPI is found.

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <sss/mpi/render.hpp>
#include <sss/seabed/wave_sum.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/sss.hpp>

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    int status = 0;
    try {
        const std::string out = argc > 1 ? argv[1] : "render_mpi.f32";
        const std::size_t pings = argc > 2 ? std::stoul(argv[2]) : 64;
        constexpr std::size_t n = 2049; // 512 m square at 0.25 m
        sss::seabed::wave_sum_params<float> p;
        p.spectrum = sss::seabed::power_law_spectrum<float>{2e-4f, 3.25f, 0.0f};
        p.longest_m = 200.0f;
        const sss::seabed::wave_sum_surface<float> surface(p, 0.25f, 2026);
        std::vector<float> h(n * n);
        surface.fill_rows(n, 0, n, 0.25, 0.0, 0.0, std::span<float>(h));
        const sss::scene::height_field<float> seabed({.nx = n, .ny = n, .cell_m = 0.25f, .heights_m = std::move(h)});

        sss::motion::perturbed_params<float> tow;
        tow.start_m = {256.0f, 100.0f};
        tow.altitude_m = 10.0f;
        tow.roll_deg = {2.0f, 6.0f, 0.0f};
        sss::receiver_params rx;
        rx.max_range_m = 100;
        const sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>,
                             sss::beam::ideal_fan<float>, sss::motion::perturbed<float>>
            sim({}, {}, {}, sss::motion::perturbed<float>(tow), rx);

        MPI_Barrier(MPI_COMM_WORLD);
        const auto t0 = std::chrono::steady_clock::now();
        const auto w = sss::mpi::render(sim, seabed, 0, pings, sss::mpi::render_params{.threads = 1});
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (rank == 0) {
            // Written whole under a temporary name, then renamed: a failed write leaves no partial file behind.
            const std::string part = out + ".part";
            std::FILE* f = std::fopen(part.c_str(), "wb");
            if (f == nullptr) throw std::runtime_error("cannot open " + part + " for writing");
            const bool written = std::fwrite(w.values.data(), sizeof(float), w.values.size(), f) == w.values.size();
            const bool closed = std::fclose(f) == 0;
            std::error_code renamed; // std::filesystem::rename replaces an existing file, on Windows too
            if (closed && written) std::filesystem::rename(part, out, renamed);
            if (!closed || !written || renamed) {
                std::remove(part.c_str());
                throw std::runtime_error("cannot write " + out);
            }
            std::printf("%zu pings on %d rank(s), one thread each: %.2f s (%.1f pings/s) -> %s\n", pings, size, s,
                        double(pings) / s, out.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sss_render_mpi (rank %d): %s\n", rank, e.what());
        status = 1;
    }
    MPI_Finalize();
    return status;
}
