#pragma once
/// \file
/// One survey rendered across processes with MPI (optional, like Embree: this header needs <mpi.h> and an MPI
/// library to link, e.g. Debian's libopenmpi-dev; without <mpi.h> it declares nothing). Not in sss.hpp.
///
/// Work split. The pings [first, first + count) are cut into chunks of `chunk_pings` consecutive pings, and chunk k
/// goes to rank k mod size: interleaved, so that slow stretches of a line (rough ground, objects, turns) are shared
/// among all ranks rather than falling to one. Each rank renders all its pings as one job on its own threads (its
/// pool, one ping at a time per thread, as simulator::render), then the root gathers every rank's rows
/// (MPI_Gatherv) and puts them in ping order. A rank that fails (a bad ping, memory) does not leave the others
/// waiting: the ranks agree on failure before the gather, and every rank throws (the failed one its own error). A ping
/// depends only on its index, never on which process renders it or with what, so the root's waterfall has the same
/// bytes as one process's simulator::render of the whole range. render_labelled does the same for the waterfall
/// and its ground-truth labels (labels/ground_truth.hpp), gathered side by side; XTF and the other products are
/// written on the root from these and the motion's poses, as from one process's render.
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
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/core/render_control.hpp"
#include "sss/labels/ground_truth.hpp"
#include "sss/receiver/image.hpp"

namespace sss::mpi {

/// Settings of sss::mpi::render.
struct render_params {
    MPI_Comm comm = MPI_COMM_WORLD; ///< the ranks that share the work
    int root = 0;                   ///< the rank that receives the waterfall
    std::size_t chunk_pings = 4;    ///< pings per chunk dealt to a rank, >= 1
    unsigned threads = 0;           ///< threads per rank (0: the machine's concurrency)
};

namespace detail {

/// How the range's pings are dealt: chunk k holds its pings [k chunk, k chunk + pings_in(k)) and goes to rank
/// k mod ranks.
struct chunking {
    std::size_t count, chunk, chunks, ranks;
    [[nodiscard]] std::size_t pings_in(std::size_t k) const noexcept { return std::min(chunk, count - k * chunk); }
};

[[nodiscard]] inline chunking chunks_of(std::size_t count, const render_params& p, int& rank, int& size) {
    sss::require(p.chunk_pings >= 1, "mpi::render_params.chunk_pings", "must be >= 1");
    MPI_Comm_rank(p.comm, &rank);
    MPI_Comm_size(p.comm, &size);
    sss::require(p.root >= 0 && p.root < size, "mpi::render_params.root", "must be a rank of the communicator");
    // count / chunk rounded up, without the overflow of count + chunk - 1 (chunk_pings = SIZE_MAX: one chunk).
    return {count, p.chunk_pings, count / p.chunk_pings + (count % p.chunk_pings != 0 ? 1 : 0), static_cast<std::size_t>(size)};
}

/// The rank's pings, as offsets from the range's first, its chunks in order.
[[nodiscard]] inline std::vector<std::size_t> pings_of(const chunking& c, int rank) {
    std::vector<std::size_t> out;
    for (std::size_t k = static_cast<std::size_t>(rank); k < c.chunks; k += c.ranks)
        for (std::size_t i = 0; i < c.pings_in(k); ++i) out.push_back(k * c.chunk + i);
    return out;
}

/// Runs `work` (this rank's share) and has every rank agree whether all succeeded: a rank whose work threw rethrows
/// its error, the others throw one naming the lowest failed rank. None is left in a collective call the failed
/// one never makes.
template <class Work> void agree(const render_params& p, int rank, Work&& work) {
    std::exception_ptr failure;
    try {
        work();
    } catch (...) {
        failure = std::current_exception();
    }
    int failed = failure ? rank : INT_MAX, lowest = INT_MAX;
    MPI_Allreduce(&failed, &lowest, 1, MPI_INT, MPI_MIN, p.comm);
    if (failure) std::rethrow_exception(failure);
    if (lowest != INT_MAX)
        throw sss::error("sss: mpi::render: rank " + std::to_string(lowest) +
                         " failed to render its pings (its error is reported there); nothing was gathered");
}

/// Every rank's rows (`width` values of type V per ping, its chunks in order in `mine`) gathered on the root in
/// ping order; empty elsewhere. `type` is V's MPI type.
template <class V>
[[nodiscard]] std::vector<V> gather_rows(const std::vector<V>& mine, std::size_t width, const chunking& c, int rank,
                                         const render_params& p, MPI_Datatype type) {
    const bool root = rank == p.root;
    // Every rank works out every rank's share, so that all of them refuse a message too large together (none is
    // left waiting in MPI_Gatherv for a root that threw).
    std::vector<int> counts(c.ranks), displs(c.ranks);
    std::size_t at = 0;
    for (std::size_t r = 0; r < c.ranks; ++r) {
        std::size_t rows = 0;
        for (std::size_t k = r; k < c.chunks; k += c.ranks) rows += c.pings_in(k);
        sss::require(rows * width <= static_cast<std::size_t>(INT_MAX) && at <= static_cast<std::size_t>(INT_MAX),
                     "mpi::render.count", "gives more values than one MPI message can carry");
        counts[r] = static_cast<int>(rows * width);
        displs[r] = static_cast<int>(at);
        at += rows * width;
    }
    std::vector<V> gathered(root ? c.count * width : 0);
    MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), type, gathered.data(), counts.data(), displs.data(), type,
                p.root, p.comm);
    if (!root) return {};
    std::vector<V> out(c.count * width);
    for (std::size_t r = 0; r < c.ranks; ++r) {
        auto from = static_cast<std::size_t>(displs[r]);
        for (std::size_t k = r; k < c.chunks; k += c.ranks) {
            const std::size_t n = c.pings_in(k) * width;
            std::copy_n(gathered.begin() + static_cast<std::ptrdiff_t>(from), n,
                        out.begin() + static_cast<std::ptrdiff_t>(k * c.chunk * width));
            from += n;
        }
    }
    return out;
}

template <class T> [[nodiscard]] MPI_Datatype value_type_of() noexcept {
    static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>, "sss::mpi::render: float or double");
    return std::is_same_v<T, float> ? MPI_FLOAT : MPI_DOUBLE;
}

} // namespace detail

/// Renders pings [first, first + count) of `sim` over `scene` across the ranks of p.comm (a collective call: every
/// rank calls it with the same arguments). Returns the whole waterfall on p.root, an empty one (no values) elsewhere.
template <class Sim, class Sc>
[[nodiscard]] waterfall<typename Sim::value_type> render(const Sim& sim, const Sc& scene, std::size_t first,
                                                         std::size_t count, const render_params& p = {}) {
    using T = typename Sim::value_type;
    int rank = 0, size = 1;
    const detail::chunking c = detail::chunks_of(count, p, rank, size);
    const std::size_t width = 2 * sim.samples_per_line();
    std::vector<T> mine;
    detail::agree(p, rank, [&] {
        // Every rank checks the whole range as one process's render would, so that all refuse it together.
        sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first",
                     "first + count overflows the ping index");
        (void)checked_elements(count, width, "render.count");
        const std::vector<std::size_t> pings = detail::pings_of(c, rank);
        waterfall<T> w;
        w.pings = pings.size();
        w.samples = sim.samples_per_line();
        w.dt_s = sim.dt_s();
        w.values.assign(pings.size() * width, T(0));
        run_pings(pings.size(), render_control{.threads = p.threads},
                  [&](std::size_t j) { w.set_row(j, sim.ping(scene, first + pings[j])); });
        mine = std::move(w.values);
    });
    waterfall<T> out;
    out.samples = sim.samples_per_line();
    out.dt_s = sim.dt_s();
    out.values = detail::gather_rows(mine, width, c, rank, p, detail::value_type_of<T>());
    if (rank == p.root) out.pings = count;
    return out;
}

/// render_labelled (labels/ground_truth.hpp) across the ranks of p.comm, as render above: each rank renders its
/// chunks' waterfall and labels in one pass, and the root gathers both. Returns on p.root the image and labels one
/// process's render_labelled returns, to the bit; elsewhere both empty.
template <class Sim, class Seabed>
[[nodiscard]] labelled_waterfall<typename Sim::value_type> render_labelled(const Sim& sim, const scene::scene<Seabed>& sc,
                                                                           std::size_t first, std::size_t count,
                                                                           const render_params& p = {},
                                                                           const label_params& lp = {}) {
    using T = typename Sim::value_type;
    int rank = 0, size = 1;
    const detail::chunking c = detail::chunks_of(count, p, rank, size);
    const std::size_t width = 2 * sim.samples_per_line();
    std::vector<T> mine;
    std::vector<std::uint32_t> mine_labels; // four words per label: class, object, label, material
    detail::agree(p, rank, [&] {
        sss::detail::check_label_params(lp);
        sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first",
                     "first + count overflows the ping index");
        (void)checked_elements(count, width, "render.count");
        const std::vector<std::size_t> pings = detail::pings_of(c, rank);
        labelled_waterfall<T> both;
        both.image.pings = both.labels.pings = pings.size();
        both.image.samples = both.labels.samples = sim.samples_per_line();
        both.image.dt_s = both.labels.dt_s = sim.dt_s();
        both.image.values.assign(pings.size() * width, T(0));
        both.labels.values.resize(both.image.values.size());
        run_pings(pings.size(), render_control{.threads = p.threads},
                  [&](std::size_t j) { sss::detail::labelled_ping(sim, sc, first + pings[j], j, both, lp); });
        mine = std::move(both.image.values);
        for (const sample_label& l : both.labels.values)
            mine_labels.insert(mine_labels.end(), {static_cast<std::uint32_t>(l.kind), l.object, l.label, l.material});
    });
    labelled_waterfall<T> out;
    out.image.samples = out.labels.samples = sim.samples_per_line();
    out.image.dt_s = out.labels.dt_s = sim.dt_s();
    out.image.values = detail::gather_rows(mine, width, c, rank, p, detail::value_type_of<T>());
    const std::vector<std::uint32_t> words = detail::gather_rows(mine_labels, 4 * width, c, rank, p, MPI_UINT32_T);
    if (rank != p.root) return out;
    out.image.pings = out.labels.pings = count;
    out.labels.values.resize(count * width);
    for (std::size_t i = 0; i < out.labels.values.size(); ++i)
        out.labels.values[i] = {static_cast<sample_class>(words[4 * i]), words[4 * i + 1], words[4 * i + 2], words[4 * i + 3]};
    return out;
}

} // namespace sss::mpi

#endif
