// Rendering across processes (sss/mpi/render.hpp), run under `mpirun -np 2`: the root's waterfall has the same bytes
// as one process's simulator::render, for chunk sizes that divide the pings among the ranks evenly and unevenly.
// Built and registered only when MPI is found.

#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <mpi.h>

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include <sss/mpi/render.hpp>
#include <sss/seabed/wave_sum.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/sss.hpp>

namespace {

sss::scene::height_field<float> seabed() {
    constexpr std::size_t n = 513;
    sss::seabed::wave_sum_params<float> p;
    p.spectrum = sss::seabed::power_law_spectrum<float>{2e-4f, 3.25f, 0.0f};
    p.longest_m = 60.0f;
    p.waves = 32;
    const sss::seabed::wave_sum_surface<float> s(p, 0.25f, 5);
    std::vector<float> h(n * n);
    s.fill_rows(n, 0, n, 0.25, 0.0, 0.0, std::span<float>(h));
    return sss::scene::height_field<float>({.nx = n, .ny = n, .cell_m = 0.25f, .heights_m = std::move(h)});
}

} // namespace

TEST_CASE("pings rendered on two ranks and gathered give the bytes of one process's render") {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    CHECK(size == 2);
    const auto hf = seabed();
    sss::motion::perturbed_params<float> tow;
    tow.start_m = {64.0f, 20.0f};
    tow.altitude_m = 8.0f;
    tow.roll_deg = {2.0f, 5.0f, 0.0f};
    sss::receiver_params rx;
    rx.max_range_m = 40;
    const sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>, sss::beam::ideal_fan<float>,
                         sss::motion::perturbed<float>>
        sim({}, {}, {}, sss::motion::perturbed<float>(tow), rx);
    for (std::size_t chunk : {std::size_t(1), std::size_t(3), std::size_t(4)}) {
        const auto w = sss::mpi::render(sim, hf, 5, 11, sss::mpi::render_params{.chunk_pings = chunk, .threads = 1});
        if (rank != 0) {
            CHECK(w.values.empty());
            continue;
        }
        const auto one = sim.render(hf, 5, 11, 1);
        REQUIRE(w.pings == one.pings);
        REQUIRE(w.samples == one.samples);
        REQUIRE(w.values.size() == one.values.size());
        CHECK(std::memcmp(w.values.data(), one.values.data(), w.values.size() * sizeof(float)) == 0);
        double energy = 0;
        for (float v : one.values) energy += double(v);
        CHECK(energy > 0);
    }
}

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    doctest::Context context(argc, argv);
    const int failed = context.run();
    int any = failed != 0 ? 1 : 0, all = 0;
    MPI_Allreduce(&any, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    MPI_Finalize();
    return all;
}
