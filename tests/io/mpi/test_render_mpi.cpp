// Rendering across processes (sss/mpi/render.hpp), run under `mpirun -np 2` and `-np 3`: the root's waterfall has the
// same bytes as one process's simulator::render, for chunk sizes that divide the pings among the ranks evenly and
// unevenly, rank 0 or 1 as the root (with chunks of its own or none), whole chunks or single rows per message; and the
// root's waterfall and labels those of one process's render_labelled.
// Built and registered only when MPI is found.

#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <sss/labels/ground_truth.hpp>
#include <sss/mpi/render.hpp>
#include <sss/seabed/targets.hpp>
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

/// A rolling towfish 8 m up over x = 64 m heading north, 40 m of range; material 1 (objects) 17 dB brighter than
/// the seabed.
auto towed_simulator() {
    sss::motion::perturbed_params<float> tow;
    tow.start_m = {64.0f, 20.0f};
    tow.altitude_m = 8.0f;
    tow.roll_deg = {2.0f, 5.0f, 0.0f};
    sss::receiver_params rx;
    rx.max_range_m = 40;
    return sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>, sss::beam::ideal_fan<float>,
                          sss::motion::perturbed<float>>(sss::scattering::lambertian<float>({.mu_db = {-27.0f, -10.0f}}), {}, {},
                                                         sss::motion::perturbed<float>(tow), rx);
}

} // namespace

TEST_CASE("pings rendered on two ranks and gathered give the bytes of one process's render") {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    REQUIRE(size >= 2);
    const auto hf = seabed();
    const auto sim = towed_simulator();
    // Even and uneven chunks; rank 0 or 1 as the root; whole chunks per message, and one row per message (1 byte).
    // Three pings in one chunk of 4 leave rank 1, as the root, with nothing to render and everything to receive.
    for (std::size_t count : {std::size_t(11), std::size_t(3)}) {
        const auto one = sim.render(hf, 5, count, 1);
        double energy = 0;
        for (float v : one.values) energy += double(v);
        CHECK(energy > 0);
        for (std::size_t chunk : {std::size_t(1), std::size_t(3), std::size_t(4)})
            for (int root : {0, 1})
                for (std::size_t bytes : {std::size_t(1) << 28, std::size_t(1)}) {
                    CAPTURE(count);
                    CAPTURE(chunk);
                    CAPTURE(root);
                    CAPTURE(bytes);
                    const auto w = sss::mpi::render(sim, hf, 5, count,
                                                    sss::mpi::render_params{.root = root, .chunk_pings = chunk, .threads = 1,
                                                                            .message_bytes = bytes});
                    if (rank != root) {
                        CHECK(w.values.empty());
                        continue;
                    }
                    REQUIRE(w.pings == one.pings);
                    REQUIRE(w.samples == one.samples);
                    REQUIRE(w.values.size() == one.values.size());
                    CHECK(std::memcmp(w.values.data(), one.values.data(), w.values.size() * sizeof(float)) == 0);
                }
    }
}

TEST_CASE("waterfall and labels rendered on two ranks and gathered are one process's render_labelled, to the bit") {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    namespace sb = sss::seabed;
    auto hf = seabed();
    const auto height = sb::seabed_height_of(hf);
    std::vector<sss::scene::object<float>> objects;
    // Two cylinders along track, one each side of the track (x = 64 m), 14 and 16 m off it.
    objects.push_back(sb::lying_cylinder(sb::lying_cylinder_params<float>{.center_m = {80.0f, 22.0f}, .heading_deg = 0.0f, .length_m = 4.0f,
                                                                          .radius_m = 0.4f, .ids = {.material = 1, .object = 1, .label = 1}},
                                         height));
    objects.push_back(sb::lying_cylinder(sb::lying_cylinder_params<float>{.center_m = {50.0f, 22.0f}, .heading_deg = 0.0f, .length_m = 4.0f,
                                                                          .radius_m = 0.3f, .ids = {.material = 1, .object = 2, .label = 2}},
                                         height));
    const sss::scene::scene world(std::move(hf), sss::scene::object_set<float>(std::move(objects)));
    const auto sim = towed_simulator();
    const auto one = sss::render_labelled(sim, world, 5, 11, {.threads = 1});
    // Rank 1 as the root, and rows sent two at a time (a message of 2 rows of image and labels, not 3).
    const std::size_t row_bytes = one.image.width() * (sizeof(float) + sizeof(sss::sample_label));
    for (std::size_t bytes : {std::size_t(1) << 28, 2 * row_bytes + 1}) {
        CAPTURE(bytes);
        const auto gathered = sss::mpi::render_labelled(
            sim, world, 5, 11, sss::mpi::render_params{.root = 1, .chunk_pings = 3, .threads = 1, .message_bytes = bytes});
        if (rank != 1) {
            CHECK(gathered.image.values.empty());
            CHECK(gathered.labels.values.empty());
            continue;
        }
        REQUIRE(gathered.image.values.size() == one.image.values.size());
        CHECK(std::memcmp(gathered.image.values.data(), one.image.values.data(), one.image.values.size() * sizeof(float)) ==
              0);
        CHECK(gathered.image.pings == 11u);
        CHECK(gathered.labels.pings == 11u);
        CHECK(gathered.labels.samples == one.labels.samples);
        CHECK(gathered.labels.values == one.labels.values);
    }
    if (rank != 1) return;
    // Both cylinders are in view: the labels compared hold highlights of each.
    std::size_t first_object = 0, second_object = 0;
    for (const sss::sample_label& l : one.labels.values) {
        first_object += l.kind == sss::sample_class::highlight && l.object == 1u;
        second_object += l.kind == sss::sample_class::highlight && l.object == 2u;
    }
    CHECK(first_object > 10u);
    CHECK(second_object > 10u);
}

namespace {

/// The seabed, but a ray from the towfish at ping 9 (y = 21.8 m) fails: a ping that only one rank renders.
struct failing_at_ping_9 {
    using value_type = float;
    const sss::scene::height_field<float>* seabed;
    [[nodiscard]] std::optional<sss::hit<float>> intersect(const sss::ray<float>& r, float t_max_m) const {
        if (r.origin.y > 21.75f && r.origin.y < 21.85f) throw sss::invalid_parameter("test.ping", "fails at ping 9");
        return seabed->intersect(r, t_max_m);
    }
    [[nodiscard]] float seabed_height_m(float x, float y) const { return seabed->seabed_height_m(x, y); }
    [[nodiscard]] float top_m() const { return seabed->top_m(); }
};

} // namespace

TEST_CASE("a ping that fails on one rank fails the render on every rank, none left waiting; one chunk for SIZE_MAX") {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    const auto hf = seabed();
    const auto sim = towed_simulator();
    // Pings 5 to 15 in chunks of 3: pings 8 to 10 go to rank 1 (on 2 ranks or more), which fails at ping 9; the
    // others render their shares and would wait for rank 1's rows.
    try {
        (void)sss::mpi::render(sim, failing_at_ping_9{&hf}, 5, 11, sss::mpi::render_params{.chunk_pings = 3, .threads = 1});
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(rank == 1);
        CHECK(e.parameter() == "test.ping");
    } catch (const sss::error& e) {
        CHECK(rank != 1);
        CHECK(std::string(e.what()).find("rank 1 failed") != std::string::npos);
    }
    // chunk_pings = SIZE_MAX asks for one chunk: it overflowed to none, and an empty image came back as whole.
    const auto w = sss::mpi::render(sim, hf, 5, 4, sss::mpi::render_params{.chunk_pings = SIZE_MAX, .threads = 1});
    if (rank == 0) {
        const auto one = sim.render(hf, 5, 4, 1);
        REQUIRE(w.values.size() == one.values.size());
        CHECK(std::memcmp(w.values.data(), one.values.data(), w.values.size() * sizeof(float)) == 0);
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
