#pragma once
/// \file
/// The one way sss's writers save a file, and the one way its readers load one: a writer writes
/// `path + ".tmp"` and renames it over `path` only once everything is written, so `path` is never left half
/// written and a failure leaves no file; a reader loads the whole file, or throws sss::file_error naming it.

#include <array>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "sss/core/error.hpp"

namespace sss::detail {

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

/// Writes through a buffer into `path + ".tmp"`, then `commit()` renames it over `path`. If the writer is
/// destroyed without commit (an exception), the temporary file is removed.
class atomic_file {
public:
    explicit atomic_file(std::string path) : path_(std::move(path)), tmp_(path_ + ".tmp") {
        f_ = std::fopen(tmp_.c_str(), "wb");
        if (!f_) throw file_error(path_, 0, "cannot open '" + tmp_ + "' for writing: " + std::strerror(errno));
    }
    atomic_file(const atomic_file&) = delete;
    atomic_file& operator=(const atomic_file&) = delete;
    ~atomic_file() {
        if (f_) {
            std::fclose(f_);
            std::error_code ec;
            std::filesystem::remove(tmp_, ec);
        }
    }
    void write(std::string_view bytes) {
        if (std::fwrite(bytes.data(), 1, bytes.size(), f_) != bytes.size())
            throw file_error(path_, 0, "write error on '" + tmp_ + "': " + std::strerror(errno));
    }
    void commit() {
        const bool ok = std::fflush(f_) == 0 && !std::ferror(f_);
        const int closed = std::fclose(f_);
        f_ = nullptr;
        std::error_code ec;
        if (!ok || closed != 0) {
            std::filesystem::remove(tmp_, ec);
            throw file_error(path_, 0, "write error on '" + tmp_ + "'");
        }
        std::filesystem::rename(tmp_, path_, ec);
        if (ec) {
            std::error_code ignored;
            std::filesystem::remove(tmp_, ignored);
            throw file_error(path_, 0, "cannot rename '" + tmp_ + "' over it: " + ec.message());
        }
    }

private:
    std::string path_, tmp_;
    std::FILE* f_ = nullptr;
};

/// Writes `bytes` to `path` atomically (see atomic_file).
inline void save_file(const std::string& path, std::string_view bytes) {
    atomic_file out(path);
    out.write(bytes);
    out.commit();
}

} // namespace sss::detail
