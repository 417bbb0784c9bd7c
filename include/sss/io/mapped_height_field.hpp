#pragma once
/// \file
/// Seabeds larger than memory (POSIX only; an optional header, not in sss.hpp): a height field whose heights stay
/// in a memory-mapped raw float32 file, and a writer that builds such a file band of rows by band of rows.
///
/// The file format is height_field_io.hpp's raw float32 + text sidecar (`path`, `path + ".txt"`).
/// map_raw_f32(path) maps the file read-only (mmap, MAP_SHARED) and gives a height_field<float> over it: the
/// heights are read in two passes of bands of rows (the finiteness check and the bounds, then the maximum pyramid),
/// and the pages behind each pass are released as it goes (madvise MADV_DONTNEED), so that building the field
/// holds a band of rows, not the heights, and only the pages under the rays of the pings being rendered come back
/// into memory (and those of the 16 x 16 heights each side fits its launch plane to, over the area its rays reach:
/// simulator::sloping_launch). Resident memory is then the pyramid (a third of the heights' bytes) plus those pages,
/// whatever the seabed's size. The operating system reads pages on demand and may drop them again under memory
/// pressure.
///
/// write_raw_f32_by_rows(path, grid, band_rows, fill) writes an nx x ny grid in bands of band_rows rows, asking
/// fill(iy0, rows, out) for rows [iy0, iy0 + rows) each time: only one band is ever in memory. With a fill that
/// depends on the vertex only (seabed/wave_sum.hpp's fill_rows), any band height gives the same bytes.
/// Like every writer it writes temporaries and renames them (the data and its sidecar together): a failure leaves no
/// file, and old ones as they were.
///
/// A mapped file must not be changed in place while a field maps it. Replacing it the way sss's writers do (a new
/// file renamed over the name) is safe: the mapping keeps the old file's data. Truncating or overwriting it in place
/// (`truncate`, `cp` or `dd` onto it, a writer that opens it for writing) is not: the pages released as the field is
/// built are read again from the file, and a page beyond a shortened file's end stops the process with SIGBUS, which
/// no library can turn into an error.

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sss/core/error.hpp"
#include "sss/io/height_field_io.hpp"
#include "sss/scene/height_field.hpp"

namespace sss::io {

/// A read-only memory map of a whole file; unmapped when destroyed.
class mapped_file {
public:
    explicit mapped_file(const std::string& path) : path_(path) {
        const int fd = ::open(path.c_str(), O_RDONLY);
        if (fd < 0) throw file_error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
        struct stat st {};
        if (::fstat(fd, &st) != 0) {
            const int e = errno;
            ::close(fd);
            throw file_error(path, 0, std::string("cannot stat: ") + std::strerror(e));
        }
        size_ = static_cast<std::size_t>(st.st_size);
        if (size_ > 0) {
            void* p = ::mmap(nullptr, size_, PROT_READ, MAP_SHARED, fd, 0);
            if (p == MAP_FAILED) {
                const int e = errno;
                ::close(fd);
                throw file_error(path, 0, std::string("cannot map: ") + std::strerror(e));
            }
            data_ = p;
        }
        ::close(fd); // the mapping keeps the file
    }
    mapped_file(const mapped_file&) = delete;
    mapped_file& operator=(const mapped_file&) = delete;
    ~mapped_file() {
        if (data_) ::munmap(data_, size_);
    }

    [[nodiscard]] const void* data() const noexcept { return data_; }
    [[nodiscard]] std::size_t size() const noexcept { return size_; }
    /// Drops the mapped pages from this process's resident memory; they are read again when touched.
    void release_resident() const noexcept {
        if (data_) (void)::madvise(data_, size_, MADV_DONTNEED);
    }
    /// The same for the whole pages of bytes [0, end_byte) from begin_byte's page on: a pass reading the file in
    /// order drops what lies behind it.
    void release_resident(std::size_t begin_byte, std::size_t end_byte) const noexcept {
        const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
        if (!data_ || page == 0) return;
        const std::size_t first = begin_byte / page * page, last = std::min(end_byte, size_) / page * page;
        if (last > first) (void)::madvise(static_cast<char*>(data_) + first, last - first, MADV_DONTNEED);
    }

private:
    std::string path_;
    void* data_ = nullptr;
    std::size_t size_ = 0;
};

/// A height field over the memory-mapped raw float32 file `path` (see the file comment); the same heights, hits
/// and renders as read_raw_f32<float>(path), without holding the heights in memory.
[[nodiscard]] inline scene::height_field<float> map_raw_f32(const std::string& path) {
    static_assert(std::endian::native == std::endian::little, "map_raw_f32 reads little-endian floats in place");
    const detail::raw_sidecar_read sidecar = detail::read_raw_sidecar_text(path);
    const raw_grid& g = sidecar.grid;
    auto file = std::make_shared<const mapped_file>(path);
    const std::size_t n = g.nx * g.ny;
    if (file->size() != 4 * n)
        throw file_error(path, 0,
                         "holds " + std::to_string(file->size()) + " bytes, the sidecar's grid needs " +
                             std::to_string(4 * n),
                         std::min(file->size(), 4 * n));
    const auto* heights = static_cast<const float*>(file->data());
    try {
        scene::height_field<float> hf({.nx = g.nx,
                                       .ny = g.ny,
                                       .cell_m = sidecar.cell_m<float>(),
                                       .origin_m = sidecar.origin_m<float>()},
                                      scene::external_heights<float>{
                                          .data = heights,
                                          .keeper = file,
                                          .read_done = [f = file.get()](std::size_t first, std::size_t count) {
                                              f->release_resident(4 * first, 4 * (first + count));
                                          }});
        file->release_resident();
        return hf;
    } catch (const invalid_parameter& e) {
        // The grid's numbers come from the sidecar (a cell size that float rounds to 0, say), the heights from the data
        // file: the message names the file at fault.
        const std::string& what = e.parameter();
        const bool grid = what == "height_field.nx" || what == "height_field.ny" || what == "height_field.cell_m" ||
                          what.starts_with("height_field.origin_m");
        throw file_error(grid ? raw_sidecar_path(path) : path, 0, message_body(e));
    }
}

/// Writes an nx x ny raw float32 height file (and its sidecar) band by band: fill(iy0, rows, std::span<float> out)
/// fills rows [iy0, iy0 + rows) row-major (nx * rows values). band_rows >= 1.
template <class Fill>
void write_raw_f32_by_rows(const std::string& path, const raw_grid& g, std::size_t band_rows, Fill&& fill) {
    // What read_raw_sidecar will ask of the sidecar, before either file is touched.
    sss::require(g.nx >= 2 && g.ny >= 2, "write_raw_f32_by_rows.grid", "needs nx, ny >= 2");
    sss::require(g.nx <= (std::size_t(1) << 30) && g.ny <= (std::size_t(1) << 30), "write_raw_f32_by_rows.grid",
                 "needs nx, ny <= 2^30");
    sss::require(g.cell_m > 0 && std::isfinite(g.cell_m), "write_raw_f32_by_rows.grid.cell_m", "must be > 0");
    sss::require_finite(g.origin_x_m, "write_raw_f32_by_rows.grid.origin_x_m");
    sss::require_finite(g.origin_y_m, "write_raw_f32_by_rows.grid.origin_y_m");
    sss::require(band_rows >= 1, "write_raw_f32_by_rows.band_rows", "must be >= 1");
    sss::detail::atomic_file out(path);
    sss::detail::atomic_file side(raw_sidecar_path(path));
    {
        std::vector<float> band(g.nx * std::min(band_rows, g.ny));
        std::string bytes;
        for (std::size_t iy0 = 0; iy0 < g.ny; iy0 += band_rows) {
            const std::size_t rows = std::min(band_rows, g.ny - iy0);
            const std::span<float> part(band.data(), g.nx * rows);
            fill(iy0, rows, part);
            bytes.resize(4 * part.size());
            for (std::size_t i = 0; i < part.size(); ++i) {
                if (!std::isfinite(part[i]))
                    throw file_error(path, 0, "height of vertex " + std::to_string(iy0 * g.nx + i) + " is not finite");
                const std::uint32_t bits = std::bit_cast<std::uint32_t>(part[i]);
                for (std::size_t k = 0; k < 4; ++k) bytes[4 * i + k] = static_cast<char>((bits >> (8 * k)) & 0xffu);
            }
            out.write(bytes);
        }
    }
    side.write(raw_sidecar_text(g));
    sss::detail::commit_together(out, side); // a failure writing either leaves both old files as they were
}

} // namespace sss::io
