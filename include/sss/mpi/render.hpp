#pragma once
/// \file
/// One survey rendered across processes with MPI (optional, like Embree: this header needs <mpi.h> and an MPI
/// library to link, e.g. Debian's libopenmpi-dev; without <mpi.h> it declares nothing). Not in sss.hpp.
///
/// Work split. The pings [first, first + count) are cut into chunks of `chunk_pings` consecutive pings, and chunk k
/// goes to rank k mod size: interleaved, so that slow stretches of a line (rough ground, objects, turns) are shared
/// among all ranks rather than falling to one. Each rank renders all its pings as one job on its own threads (its
/// pool, one ping at a time per thread, as simulator::render): the root into their places in the waterfall, the
/// others into a buffer of their share. Then each other rank sends its chunks to the root, which receives them in
/// their places: messages of whole rows (an MPI type of a row), at most `message_bytes` each, so an image of any size
/// moves (no count of values need fit an int) and the root holds one image, not a gathered copy beside it. A rank
/// that fails (a bad ping, memory) does not leave the others waiting: the ranks agree on failure before any row
/// moves, and every rank throws (the failed one its own error). A ping depends only on its index, never on which
/// process renders it or with what, so the root's waterfall has the same bytes as one process's simulator::render of
/// the whole range. render_labelled does the same for the waterfall and its ground-truth labels
/// (labels/ground_truth.hpp), sent side by side; XTF and the other products are written on the root from these and
/// the motion's poses, as from one process's render. The messages go over a duplicate of the communicator, so they
/// never match the caller's own.
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
    /// Most bytes per message to the root (at least one row). Some MPI transports mishandle messages over 2 GiB.
    std::size_t message_bytes = std::size_t(1) << 28;
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

/// An MPI datatype or communicator of this call's own, freed when it goes out of scope (also when the call throws).
struct owned_type {
    MPI_Datatype type = MPI_DATATYPE_NULL;
    owned_type() = default;
    owned_type(const owned_type&) = delete;
    owned_type& operator=(const owned_type&) = delete;
    ~owned_type() {
        if (type != MPI_DATATYPE_NULL) MPI_Type_free(&type);
    }
};
struct owned_comm {
    MPI_Comm comm = MPI_COMM_NULL;
    explicit owned_comm(MPI_Comm of) { MPI_Comm_dup(of, &comm); }
    owned_comm(const owned_comm&) = delete;
    owned_comm& operator=(const owned_comm&) = delete;
    ~owned_comm() {
        if (comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
    }
};

/// `row`: one row of `width` values of the committed type `value`, so that messages count rows, not values (an
/// image of more than 2^31 values moves whole).
inline void make_row_type(owned_type& row, MPI_Datatype value, std::size_t width) {
    sss::require(width <= static_cast<std::size_t>(INT_MAX), "mpi::render", "a line of more than 2^31 samples per side");
    MPI_Type_contiguous(static_cast<int>(width), value, &row.type);
    MPI_Type_commit(&row.type);
}

/// sample_label as one MPI type (its padding skipped), committed.
inline void make_label_type(owned_type& label) {
    const int lengths[4] = {1, 1, 1, 1};
    const MPI_Aint at[4] = {offsetof(sample_label, kind), offsetof(sample_label, object), offsetof(sample_label, label),
                            offsetof(sample_label, material)};
    static_assert(sizeof(sample_class) == 1 && sizeof(sample_label::object) == 4 && sizeof(sample_label::label) == 4 &&
                  sizeof(sample_label::material) == 4);
    MPI_Datatype types[4] = {MPI_UINT8_T, MPI_UINT32_T, MPI_UINT32_T, MPI_UINT32_T};
    owned_type packed;
    MPI_Type_create_struct(4, lengths, at, types, &packed.type);
    MPI_Type_create_resized(packed.type, 0, static_cast<MPI_Aint>(sizeof(sample_label)), &label.type);
    MPI_Type_commit(&label.type);
}

/// One image's rows on one rank: `width` values of V each, sent and received as MPI type `row`.
template <class V> struct row_set {
    V* data;
    std::size_t width;
    MPI_Datatype row;
};

/// Moves every other rank's rows to the root, straight into their places in the root's image (the root rendered its
/// own there): chunk by chunk in ping order, each in messages of at most `message_rows` rows. Each of `images` is, on
/// the root, its whole image (count x width), and on another rank that rank's chunks one after the other. Each rank
/// sends to the root alone, in the order the root receives from it, so no message can overtake another.
template <class... V>
void send_rows_to_root(const chunking& c, int rank, int root, MPI_Comm comm, std::size_t message_rows,
                       const row_set<V>&... images) {
    const auto r0 = static_cast<std::size_t>(root);
    std::size_t at = 0; // a non-root rank: rows of `mine` sent so far
    for (std::size_t k = 0; k < c.chunks; ++k) {
        const std::size_t owner = k % c.ranks;
        if (owner == r0) continue;
        const bool receive = rank == root, send = static_cast<std::size_t>(rank) == owner;
        if (!receive && !send) continue;
        for (std::size_t done = 0; done < c.pings_in(k);) {
            const std::size_t rows = std::min(message_rows, c.pings_in(k) - done);
            const std::size_t row = receive ? k * c.chunk + done : at + done;
            (
                [&] {
                    auto* p = images.data + row * images.width;
                    if (receive)
                        MPI_Recv(p, static_cast<int>(rows), images.row, static_cast<int>(owner), 0, comm, MPI_STATUS_IGNORE);
                    else
                        MPI_Send(p, static_cast<int>(rows), images.row, root, 0, comm);
                }(),
                ...);
            done += rows;
        }
        if (send) at += c.pings_in(k);
    }
}

/// Rows per message: as many as `message_bytes` holds, at least one, at most INT_MAX.
[[nodiscard]] inline std::size_t rows_per_message(std::size_t message_bytes, std::size_t row_bytes) noexcept {
    const std::size_t rows = row_bytes == 0 ? 1 : message_bytes / row_bytes;
    return std::clamp<std::size_t>(rows, 1, static_cast<std::size_t>(INT_MAX));
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
    const detail::owned_comm comm(p.comm); // this call's messages never meet the caller's
    const bool root = rank == p.root;
    const std::size_t width = 2 * sim.samples_per_line();
    waterfall<T> out, mine; // the root's whole; a non-root rank's chunks in order
    out.samples = mine.samples = sim.samples_per_line();
    out.dt_s = sim.dt_s();
    detail::owned_type row;
    detail::agree(p, rank, [&] {
        // Every rank checks the whole range as one process's render would, so that all refuse it together.
        sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first",
                     "first + count overflows the ping index");
        (void)checked_elements(count, width, "render.count");
        detail::make_row_type(row, detail::value_type_of<T>(), width);
        const std::vector<std::size_t> pings = detail::pings_of(c, rank);
        // The root renders its rows in their places in the waterfall; the others theirs one after the other.
        waterfall<T>& into = root ? out : mine;
        into.values.assign((root ? count : pings.size()) * width, T(0));
        run_pings(pings.size(), render_control{.threads = p.threads},
                  [&](std::size_t j) { into.set_row(root ? pings[j] : j, sim.ping(scene, first + pings[j])); });
    });
    waterfall<T>& from = root ? out : mine;
    detail::send_rows_to_root(c, rank, p.root, comm.comm, detail::rows_per_message(p.message_bytes, width * sizeof(T)),
                              detail::row_set<T>{from.values.data(), width, row.type});
    if (root) out.pings = count;
    return out;
}

/// render_labelled (labels/ground_truth.hpp) across the ranks of p.comm, as render above: each rank renders its
/// chunks' waterfall and labels in one pass, and the root receives both. Returns on p.root the image and labels one
/// process's render_labelled returns, to the bit; elsewhere both empty.
template <class Sim, class Seabed>
[[nodiscard]] labelled_waterfall<typename Sim::value_type> render_labelled(const Sim& sim, const scene::scene<Seabed>& sc,
                                                                           std::size_t first, std::size_t count,
                                                                           const render_params& p = {},
                                                                           const label_params& lp = {}) {
    using T = typename Sim::value_type;
    int rank = 0, size = 1;
    const detail::chunking c = detail::chunks_of(count, p, rank, size);
    const detail::owned_comm comm(p.comm);
    const bool root = rank == p.root;
    const std::size_t width = 2 * sim.samples_per_line();
    labelled_waterfall<T> out, mine; // the root's whole; a non-root rank's chunks in order
    out.image.samples = out.labels.samples = sim.samples_per_line();
    out.image.dt_s = out.labels.dt_s = sim.dt_s();
    detail::owned_type row, label, label_row;
    detail::agree(p, rank, [&] {
        sss::detail::check_label_params(lp);
        sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first",
                     "first + count overflows the ping index");
        (void)checked_elements(count, width, "render.count");
        detail::make_row_type(row, detail::value_type_of<T>(), width);
        detail::make_label_type(label);
        detail::make_row_type(label_row, label.type, width);
        const std::vector<std::size_t> pings = detail::pings_of(c, rank);
        labelled_waterfall<T>& into = root ? out : mine;
        into.image.samples = into.labels.samples = sim.samples_per_line();
        into.image.values.assign((root ? count : pings.size()) * width, T(0));
        into.labels.values.resize(into.image.values.size());
        run_pings(pings.size(), render_control{.threads = p.threads}, [&](std::size_t j) {
            sss::detail::labelled_ping(sim, sc, first + pings[j], root ? pings[j] : j, into, lp);
        });
    });
    labelled_waterfall<T>& from = root ? out : mine;
    detail::send_rows_to_root(c, rank, p.root, comm.comm,
                              detail::rows_per_message(p.message_bytes, width * (sizeof(T) + sizeof(sample_label))),
                              detail::row_set<T>{from.image.values.data(), width, row.type},
                              detail::row_set<sample_label>{from.labels.values.data(), width, label_row.type});
    if (root) out.image.pings = out.labels.pings = count;
    return out;
}

} // namespace sss::mpi

#endif
