#pragma once
/// \file
/// The one way sss's writers save a file, and the one way its readers load one. A writer writes a temporary file
/// of its own next to `path` (`path + ".tmp-" + 16 hexadecimal digits`, created exclusively, so that two writers of
/// the same path, in one process or in two, never share one and no other file of that name is touched) and renames
/// it over `path` only once everything is written: `path` is never left half written, and a failure leaves no file
/// and the old `path` as it was. Files that belong together (a raw height file and its sidecar, label images and
/// their legend) are all written and closed before the first is renamed (commit_together), so that a failure while
/// writing any of them leaves every old file as it was. A reader loads the whole file, or throws sss::file_error
/// naming it.
///
/// Where the system has POSIX fsync, the temporary's bytes are on the disk before it is renamed, and the rename is
/// before commit returns (the directory synced too): a machine that loses power meanwhile keeps the old file or the
/// new one whole, never an empty or cut-short one under the name.

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "sss/core/error.hpp"

// POSIX systems (not MinGW, whose unistd.h has no fsync): the bytes and the renames are synced to the disk.
#if (defined(__unix__) || defined(__APPLE__)) && __has_include(<unistd.h>) && __has_include(<fcntl.h>)
#include <fcntl.h>
#include <unistd.h>
#define SSS_DETAIL_POSIX_SYNC 1
#endif

namespace sss::detail {

/// Syncs the open file `f` to the disk (POSIX fsync); true where that worked or the system has no fsync.
[[nodiscard]] inline bool sync_to_disk(std::FILE* f) noexcept {
#ifdef SSS_DETAIL_POSIX_SYNC
    return ::fsync(::fileno(f)) == 0 || errno == EINVAL; // EINVAL: a file that cannot be synced (a pipe, /dev/null)
#else
    (void)f;
    return true;
#endif
}

/// Syncs the directory holding `path`, so that a rename into it is on the disk (POSIX); best effort.
inline void sync_directory_of(const std::string& path) noexcept {
#ifdef SSS_DETAIL_POSIX_SYNC
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    if (dir.empty()) dir = ".";
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);
    (void)::close(fd);
#else
    (void)path;
#endif
}
#undef SSS_DETAIL_POSIX_SYNC

/// The whole file as bytes; file_error when it cannot be read.
[[nodiscard]] inline std::string read_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw file_error(path, 0, "is a directory, not a file");
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw file_error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
    std::string data;
    std::array<char, 1 << 16> buf{};
    for (;;) {
        const std::size_t got = std::fread(buf.data(), 1, buf.size(), f);
        data.append(buf.data(), got);
        if (got < buf.size()) break;
    }
    const bool bad = std::ferror(f) != 0;
    std::fclose(f);
    if (bad) throw file_error(path, 0, "read error", data.size());
    return data;
}

/// A fresh suffix for a temporary file name: 16 hexadecimal digits from the random device, the clock and a
/// per-process counter (so that neither a poor random device nor two calls in one clock tick repeat one).
[[nodiscard]] inline std::string temporary_suffix() {
    static std::atomic<std::uint64_t> counter{0};
    std::uint64_t x = counter.fetch_add(1, std::memory_order_relaxed) * 0x9e3779b97f4a7c15ull;
    x ^= static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    try {
        std::random_device rd;
        x ^= (static_cast<std::uint64_t>(rd()) << 32) ^ static_cast<std::uint64_t>(rd());
    } catch (...) { // no random device: the clock and the counter
    }
    // A 64-bit mix (splitmix64's finaliser) so that the counter's low bits spread over every digit.
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    static constexpr char hex[] = "0123456789abcdef";
    std::string s(16, '0');
    for (std::size_t i = 0; i < 16; ++i) s[i] = hex[(x >> (60 - 4 * i)) & 0xfu];
    return s;
}

/// Writes through a buffer into a temporary file of its own next to `path` (see the file comment); `commit()`
/// renames it over `path`. `close()` ends the writing and keeps the temporary for a later commit (files committed
/// together). If the writer is destroyed without commit (an exception), the temporary file is removed.
class atomic_file {
public:
    explicit atomic_file(std::string path) : path_(std::move(path)) {
        // Created exclusively ("x"): a name some other file or writer has is never opened; a few fresh names are
        // tried before giving up.
        int why = 0;
        for (int attempt = 0; attempt < 16 && !f_; ++attempt) {
            tmp_ = path_ + ".tmp-" + temporary_suffix();
            errno = 0;
            f_ = std::fopen(tmp_.c_str(), "wbx");
            why = errno;
            if (!f_ && why != EEXIST) break;
        }
        if (!f_) throw file_error(path_, 0, "cannot open '" + tmp_ + "' for writing: " + std::strerror(why));
    }
    atomic_file(const atomic_file&) = delete;
    atomic_file& operator=(const atomic_file&) = delete;
    ~atomic_file() {
        if (f_) std::fclose(f_);
        if (!committed_) {
            std::error_code ec;
            std::filesystem::remove(tmp_, ec);
        }
    }

    /// The file this writes (not the temporary).
    [[nodiscard]] const std::string& path() const noexcept { return path_; }

    void write(std::string_view bytes) { write(bytes.data(), bytes.size()); }
    void write(const void* bytes, std::size_t size) {
        if (!f_) throw file_error(path_, 0, "write after the file was closed");
        if (size != 0 && std::fwrite(bytes, 1, size, f_) != size)
            throw file_error(path_, 0, "write error on '" + tmp_ + "': " + std::strerror(errno));
    }

    /// Ends the writing: everything is flushed to the temporary, which stays until commit (or destruction). Throws
    /// file_error (disk full, ...) naming the file.
    void close() {
        if (!f_) return;
        const bool ok = std::fflush(f_) == 0 && !std::ferror(f_) && sync_to_disk(f_);
        const int closed = std::fclose(f_);
        f_ = nullptr;
        if (!ok || closed != 0) throw file_error(path_, 0, "write error on '" + tmp_ + "' (disk full?)");
    }

    /// close(), then renames the temporary over `path`.
    void commit() {
        close();
        std::error_code ec;
        std::filesystem::rename(tmp_, path_, ec);
        if (ec) throw file_error(path_, 0, "cannot rename '" + tmp_ + "' over it: " + ec.message());
        committed_ = true;
        sync_directory_of(path_);
    }

private:
    std::string path_, tmp_;
    std::FILE* f_ = nullptr;
    bool committed_ = false;
};

/// Commits files that belong together: every one is closed (a write error on any leaves every old file as it was,
/// and every temporary is removed by its writer), and a target that is a directory is refused, before the first is
/// renamed. The renames follow in the order given; one that fails after another succeeded (the directory changed
/// under the writer between them) throws with the files before it already replaced.
template <class... Files> void commit_together(Files&... files) {
    (files.close(), ...);
    const auto not_a_directory = [](const atomic_file& f) {
        std::error_code ec;
        if (std::filesystem::is_directory(f.path(), ec)) throw file_error(f.path(), 0, "is a directory, not a file");
    };
    (not_a_directory(files), ...);
    (files.commit(), ...);
}

/// Writes `bytes` to `path` atomically (see atomic_file).
inline void save_file(const std::string& path, std::string_view bytes) {
    atomic_file out(path);
    out.write(bytes);
    out.commit();
}

} // namespace sss::detail
