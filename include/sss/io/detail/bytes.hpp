#pragma once
/// \file
/// Little-endian byte packing, and the binary writers' write to a temporary then rename (atomic_file.hpp).

#include <bit>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/io/detail/atomic_file.hpp"

namespace sss::detail {

/// Stores `v` (an integer or IEEE float) little-endian at `out + offset`.
template <class V> void put_le(std::uint8_t* out, std::size_t offset, V v) noexcept {
    static_assert(std::is_arithmetic_v<V>);
    using U = std::conditional_t<sizeof(V) == 1, std::uint8_t,
              std::conditional_t<sizeof(V) == 2, std::uint16_t, std::conditional_t<sizeof(V) == 4, std::uint32_t, std::uint64_t>>>;
    const U u = std::bit_cast<U>(v);
    for (std::size_t i = 0; i < sizeof(V); ++i) out[offset + i] = static_cast<std::uint8_t>(u >> (8 * i));
}

/// Reads a little-endian `V` at `in + offset`.
template <class V> [[nodiscard]] V get_le(const std::uint8_t* in, std::size_t offset) noexcept {
    static_assert(std::is_arithmetic_v<V>);
    using U = std::conditional_t<sizeof(V) == 1, std::uint8_t,
              std::conditional_t<sizeof(V) == 2, std::uint16_t, std::conditional_t<sizeof(V) == 4, std::uint32_t, std::uint64_t>>>;
    U u = 0;
    for (std::size_t i = 0; i < sizeof(V); ++i) u = static_cast<U>(u | (U(in[offset + i]) << (8 * i)));
    return std::bit_cast<V>(u);
}

/// Copies `text` into a fixed, zero-filled character field of `size` bytes, always ending in a zero byte (readers
/// take such fields as C strings): a longer text is cut to size - 1 bytes, not inside a UTF-8 character.
inline void put_chars(std::uint8_t* out, std::size_t offset, std::string_view text, std::size_t size) noexcept {
    std::memset(out + offset, 0, size);
    if (size == 0) return;
    std::size_t n = text.size() < size ? text.size() : size - 1;
    if (n < text.size())
        while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n; // text[n] continues a character
    std::memcpy(out + offset, text.data(), n);
}

/// The text of a fixed character field, up to its first zero byte.
[[nodiscard]] inline std::string get_chars(const std::uint8_t* in, std::size_t offset, std::size_t size) {
    std::size_t n = 0;
    while (n < size && in[offset + n] != 0) ++n;
    return std::string(reinterpret_cast<const char*>(in + offset), n);
}

/// Writes `bytes` to `path` through a temporary renamed onto `path` when complete (atomic_file); on any failure the
/// temporary is removed, nothing is left at `path` by this call, and a file_error names the file.
inline void write_file_atomically(const std::string& path, const void* bytes, std::size_t size) {
    atomic_file out(path);
    out.write(bytes, size);
    out.commit();
}

inline void write_file_atomically(const std::string& path, std::string_view text) {
    write_file_atomically(path, text.data(), text.size());
}

/// The whole content of a binary file; file_error if it cannot be read.
[[nodiscard]] inline std::vector<std::uint8_t> read_file_bytes(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw file_error(path, 0, "is a directory, not a file");
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) throw file_error(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
    std::vector<std::uint8_t> bytes;
    std::uint8_t buffer[65536];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    const bool failed = std::ferror(f) != 0;
    std::fclose(f);
    if (failed) throw file_error(path, 0, "read error");
    return bytes;
}

} // namespace sss::detail
