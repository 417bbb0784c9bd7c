#pragma once
/// \file
/// One survey rendered across processes with MPI (optional, like Embree: this header needs <mpi.h> and an MPI
/// library to link, e.g. Debian's libopenmpi-dev; without <mpi.h> it declares nothing). Not in sss.hpp.
///
/// Work split. The pings [first, first + count) are cut into chunks of `chunk_pings` consecutive pings, and chunk k
/// goes to rank k mod size: interleaved, so that slow stretches of a line (rough ground, objects, turns) are shared
/// among all ranks rather than falling to one. Each rank renders its chunks with simulator::render on its own
/// threads (its pool), then the root gathers every rank's rows (MPI_Gatherv) and puts them in ping order. A ping
/// depends only on its index, never on which process renders it or with what, so the root's waterfall has the same
/// bytes as one process's simulator::render of the whole range.
///
/// Launch: every rank runs the same program and calls render collectively, e.g. on one machine
/// `mpirun -np 2 ./survey`, on a cluster `mpirun -np 8 --hostfile hosts --map-by node ./survey` (one rank per
/// node, its threads on the node's cores); each rank needs the scene (build it from the same seed, or map the same
/// raw seabed file from shared storage: io/mapped_height_field.hpp).

#if __has_include(<mpi.h>)
#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/receiver/image.hpp"

namespace sss::mpi {

/// Settings of sss::mpi::render.
struct render_params {
    MPI_Comm comm = MPI_COMM_WORLD; ///< the ranks that share the work
    int root = 0;                   ///< the rank that receives the waterfall
    std::size_t chunk_pings = 4;    ///< pings per chunk dealt to a rank, >= 1
    unsigned threads = 0;           ///< threads per rank (0: the machine's concurrency)
};

/// Renders pings [first, first + count) of `sim` over `scene` across the ranks of p.comm (a collective call: every
/// rank calls it with the same arguments). Returns the whole waterfall on p.root, an empty one (no values) elsewhere.
template <class Sim, class Sc>
[[nodiscard]] waterfall<typename Sim::value_type> render(const Sim& sim, const Sc& scene, std::size_t first,
                                                         std::size_t count, const render_params& p = {}) {
    using T = typename Sim::value_type;
    static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>, "sss::mpi::render: float or double");
    sss::require(p.chunk_pings >= 1, "mpi::render_params.chunk_pings", "must be >= 1");
    int rank = 0, size = 1;
    MPI_Comm_rank(p.comm, &rank);
    MPI_Comm_size(p.comm, &size);
    sss::require(p.root >= 0 && p.root < size, "mpi::render_params.root", "must be a rank of the communicator");
    const std::size_t chunk = p.chunk_pings, chunks = (count + chunk - 1) / chunk;
    const std::size_t width = 2 * sim.samples_per_line();
    const auto ranks = static_cast<std::size_t>(size);
    auto pings_in = [&](std::size_t k) { return std::min(chunk, count - k * chunk); };

    std::vector<T> mine;
    for (std::size_t k = static_cast<std::size_t>(rank); k < chunks; k += ranks) {
        const waterfall<T> w = sim.render(scene, first + k * chunk, pings_in(k), p.threads);
        mine.insert(mine.end(), w.values.begin(), w.values.end());
    }

    const bool root = rank == p.root;
    std::vector<int> counts(root ? ranks : 0), displs(root ? ranks : 0);
    if (root) {
        std::size_t at = 0;
        for (std::size_t r = 0; r < ranks; ++r) {
            std::size_t rows = 0;
            for (std::size_t k = r; k < chunks; k += ranks) rows += pings_in(k);
            sss::require(rows * width <= static_cast<std::size_t>(INT_MAX) && at <= static_cast<std::size_t>(INT_MAX),
                                 "mpi::render.count", "gives more values than one MPI message can carry");
            counts[r] = static_cast<int>(rows * width);
            displs[r] = static_cast<int>(at);
            at += rows * width;
        }
    }
    const MPI_Datatype type = std::is_same_v<T, float> ? MPI_FLOAT : MPI_DOUBLE;
    std::vector<T> gathered(root ? count * width : 0);
    MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), type, gathered.data(), counts.data(), displs.data(), type,
                p.root, p.comm);

    waterfall<T> out;
    out.samples = sim.samples_per_line();
    out.dt_s = sim.dt_s();
    if (!root) return out;
    out.pings = count;
    out.values.assign(count * width, T(0));
    for (std::size_t r = 0; r < ranks; ++r) {
        std::size_t from = static_cast<std::size_t>(displs[r]);
        for (std::size_t k = r; k < chunks; k += ranks) {
            const std::size_t n = pings_in(k) * width;
            std::copy_n(gathered.begin() + static_cast<std::ptrdiff_t>(from), n,
                        out.values.begin() + static_cast<std::ptrdiff_t>(k * chunk * width));
            from += n;
        }
    }
    return out;
}

} // namespace sss::mpi

#endif
