#pragma once
/// \file
/// Reading and writing height fields (sss::scene::height_field) in three formats:
///
/// - ESRI ASCII grid (.asc): a text header (ncols, nrows, xllcorner or xllcenter, yllcorner or yllcenter,
///   cellsize, optional NODATA_value; keywords in any case) and nrows x ncols values, rows from north to
///   south. Each value is taken as the height of one vertex at its cell's centre, so vertex (0, 0) lies at
///   (xllcenter, yllcenter) = (xllcorner + cellsize/2, yllcorner + cellsize/2). A NODATA value is an error
///   unless a fill height is given. The writer writes xllcenter/yllcenter (exact, no half-cell arithmetic)
///   and the shortest decimal form that reads back to the same value.
/// - Raw float32: `file` holds nx * ny IEEE-754 binary32 values, little-endian, row-major with row 0 the
///   southern row (heights[iy * nx + ix]), nothing else; `file + ".txt"` is a text sidecar, one `key value`
///   per line, `#` starting a comment:
///       format sss-height-raw-f32le 1
///       nx 4096
///       ny 4096
///       cell_m 0.25
///       origin_x_m 0
///       origin_y_m 0
///   A double height field is rounded to float32 on writing.
/// - 16-bit binary PGM (P5, maxval <= 65535, big-endian samples, first row north): heights
///   h = offset_m + scale_m * sample. PGM holds no geometry: the reader takes cell size and origin, and the
///   writer notes all four numbers in a header comment for people (the reader ignores comments).
///
/// Errors are sss::file_error naming the file and the line (text) or the byte offset (binary). Heights
/// that are not finite are rejected at load. A reader returns a complete height field or throws; a writer
/// writes `path + ".tmp"` and renames it over `path`, so `path` is never left half written.
/// No PNG: it needs a library that sss does not depend on.

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/scene/height_field.hpp"

namespace sss::io {

namespace detail {

/// The whole file as bytes; file_error when it cannot be read.
inline std::string read_all(const std::string& path) {
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

/// Writes through a buffer into `path + ".tmp"`, then `commit()` renames it over `path`. If the writer
/// is destroyed without commit (an exception), the temporary file is removed.
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

/// Appends the shortest decimal form of x that reads back to x.
template <class V> inline void append_number(std::string& out, V x) {
    std::array<char, 64> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
    out.append(buf.data(), res.ptr);
}

/// A whitespace-separated token of a text file and the line it starts on (1-based).
struct token {
    std::string_view text;
    std::size_t line = 0;
};

/// Splits text into tokens, tracking lines; `#` comments (to end of line) are skipped when enabled.
class tokenizer {
public:
    tokenizer(std::string_view text, bool hash_comments) : text_(text), comments_(hash_comments) {}

    /// The next token, or an empty one at the end (its line is then the file's last line).
    token next() {
        skip_space();
        if (pos_ >= text_.size()) return token{{}, !text_.empty() && text_.back() == '\n' ? line_ - 1 : line_};
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
        return token{text_.substr(start, pos_ - start), line_};
    }
    /// Skips to the start of the next line.
    void skip_line() {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    }
    [[nodiscard]] std::size_t line() const noexcept { return line_; }
    /// True when only whitespace (and comments) remain.
    [[nodiscard]] bool at_end() {
        skip_space();
        return pos_ >= text_.size();
    }
    /// Position of the next unread character, and its line, for look-ahead.
    [[nodiscard]] std::size_t position() const noexcept { return pos_; }
    void rewind(std::size_t pos, std::size_t line) noexcept {
        pos_ = pos;
        line_ = line;
    }

private:
    static bool is_space(char c) noexcept {
        return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
    }
    void skip_space() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_;
                ++pos_;
            } else if (is_space(c)) {
                ++pos_;
            } else if (comments_ && c == '#') {
                skip_line();
            } else {
                break;
            }
        }
    }
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    bool comments_;
};

/// Parses a whole token as a double; nullopt when it is not a number (non-finite values do parse).
inline std::optional<double> parse_double(std::string_view s) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double v = 0;
    const auto res = std::from_chars(s.data(), s.data() + s.size(), v);
    if (res.ec != std::errc{} || res.ptr != s.data() + s.size() || s.empty()) return std::nullopt;
    return v;
}

/// Parses a whole token as a non-negative integer.
inline std::optional<std::size_t> parse_size(std::string_view s) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    std::size_t v = 0;
    const auto res = std::from_chars(s.data(), s.data() + s.size(), v);
    if (res.ec != std::errc{} || res.ptr != s.data() + s.size() || s.empty()) return std::nullopt;
    return v;
}

inline std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

/// A height read from a file, converted to T; nullopt when not finite in T.
template <Real T> inline std::optional<T> finite_height(double v) {
    const T h = static_cast<T>(v);
    if (!std::isfinite(h)) return std::nullopt;
    return h;
}

} // namespace detail

// ----------------------------------------------------------------------------------------------------
// ESRI ASCII grid

/// Options for reading ESRI ASCII grids.
template <Real T> struct esri_ascii_options {
    /// Height (m) given to NODATA vertices; without it a NODATA value is an error.
    std::optional<T> nodata_fill_m{};
};

/// Reads an ESRI ASCII grid (.asc) as a height field; see the file comment for the conventions.
template <Real T> [[nodiscard]] scene::height_field<T> read_esri_ascii(const std::string& path,
                                                                       const esri_ascii_options<T>& options = {}) {
    const std::string text = detail::read_all(path);
    detail::tokenizer tok(text, false);
    auto fail = [&](std::size_t line, const std::string& why) -> file_error { return file_error(path, line, why); };

    std::optional<std::size_t> ncols, nrows;
    std::size_t first_data_line = 0;
    std::optional<double> x_ll, y_ll, cellsize, nodata;
    bool x_center = false, y_center = false;
    // Header: keyword/value pairs until the first token that is not a keyword.
    for (;;) {
        const std::size_t pos = tok.position(), line = tok.line();
        const detail::token key = tok.next();
        if (key.text.empty()) throw fail(key.line, "file ends in the header");
        const std::string k = detail::lower(key.text);
        const bool known = k == "ncols" || k == "nrows" || k == "xllcorner" || k == "xllcenter" || k == "yllcorner" ||
                           k == "yllcenter" || k == "cellsize" || k == "nodata_value";
        if (!known) {
            if (k == "dx" || k == "dy")
                throw fail(key.line, "'" + std::string(key.text) + "': only square cells (cellsize) are supported");
            if (!detail::parse_double(key.text))
                throw fail(key.line, "unknown header keyword '" + std::string(key.text) + "'");
            tok.rewind(pos, line);
            first_data_line = key.line;
            break;
        }
        const detail::token val = tok.next();
        if (val.text.empty() || val.line != key.line)
            throw fail(key.line, "header keyword '" + std::string(key.text) + "' has no value");
        auto dup = [&](bool seen) {
            if (seen) throw fail(key.line, "header keyword '" + std::string(key.text) + "' given twice");
        };
        if (k == "ncols" || k == "nrows") {
            const auto v = detail::parse_size(val.text);
            if (!v || *v < 2)
                throw fail(val.line, "'" + std::string(key.text) + "' must be an integer >= 2, got '" +
                                         std::string(val.text) + "'");
            std::optional<std::size_t>& slot = k == "ncols" ? ncols : nrows;
            dup(slot.has_value());
            slot = v;
            continue;
        }
        const auto v = detail::parse_double(val.text);
        if (!v || !std::isfinite(*v))
            throw fail(val.line,
                       "'" + std::string(key.text) + "' must be a finite number, got '" + std::string(val.text) + "'");
        if (k == "xllcorner" || k == "xllcenter") {
            dup(x_ll.has_value());
            x_ll = v;
            x_center = k == "xllcenter";
        } else if (k == "yllcorner" || k == "yllcenter") {
            dup(y_ll.has_value());
            y_ll = v;
            y_center = k == "yllcenter";
        } else if (k == "cellsize") {
            dup(cellsize.has_value());
            if (!(*v > 0)) throw fail(val.line, "'cellsize' must be > 0, got '" + std::string(val.text) + "'");
            cellsize = v;
        } else {
            dup(nodata.has_value());
            nodata = v;
        }
    }
    if (!ncols) throw fail(first_data_line, "header lacks 'ncols'");
    if (!nrows) throw fail(first_data_line, "header lacks 'nrows'");
    if (!x_ll) throw fail(first_data_line, "header lacks 'xllcorner' or 'xllcenter'");
    if (!y_ll) throw fail(first_data_line, "header lacks 'yllcorner' or 'yllcenter'");
    if (!cellsize) throw fail(first_data_line, "header lacks 'cellsize'");
    const std::size_t nx = *ncols, ny = *nrows;
    if (nx > (std::size_t(1) << 30) || ny > (std::size_t(1) << 30) || nx * ny > (std::size_t(1) << 40))
        throw fail(first_data_line, "grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " is too large");

    std::vector<T> heights(nx * ny);
    for (std::size_t row = 0; row < ny; ++row) {
        const std::size_t iy = ny - 1 - row; // rows run north to south
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const detail::token t = tok.next();
            if (t.text.empty())
                throw fail(t.line, "file ends after " + std::to_string(row * nx + ix) + " of " +
                                       std::to_string(nx * ny) + " values");
            const auto v = detail::parse_double(t.text);
            if (!v)
                throw fail(t.line, "'" + std::string(t.text) + "' is not a number (row " + std::to_string(row) +
                                       ", column " + std::to_string(ix) + ")");
            std::optional<T> h;
            if (nodata && *v == *nodata) {
                if (!options.nodata_fill_m)
                    throw fail(t.line, "NODATA at row " + std::to_string(row) + ", column " + std::to_string(ix) +
                                           " (a height field needs every vertex)");
                h = *options.nodata_fill_m;
            } else {
                h = detail::finite_height<T>(*v);
            }
            if (!h || !std::isfinite(*h))
                throw fail(t.line, "height '" + std::string(t.text) + "' at row " + std::to_string(row) + ", column " +
                                       std::to_string(ix) + " is not finite");
            heights[iy * nx + ix] = *h;
        }
    }
    if (!tok.at_end()) {
        const detail::token extra = tok.next();
        throw fail(extra.line, "more values than ncols x nrows = " + std::to_string(nx * ny) + " ('" +
                                   std::string(extra.text) + "')");
    }
    const double half = 0.5 * *cellsize;
    const vec2<T> origin{static_cast<T>(x_center ? *x_ll : *x_ll + half),
                         static_cast<T>(y_center ? *y_ll : *y_ll + half)};
    try {
        return scene::height_field<T>(nx, ny, static_cast<T>(*cellsize), origin, std::move(heights));
    } catch (const invalid_parameter& e) {
        throw fail(0, e.what());
    }
}

/// Writes `hf` as an ESRI ASCII grid with xllcenter/yllcenter.
template <Real T> void write_esri_ascii(const std::string& path, const scene::height_field<T>& hf) {
    detail::atomic_file out(path);
    std::string buf;
    buf += "ncols " + std::to_string(hf.nx()) + "\nnrows " + std::to_string(hf.ny()) + "\nxllcenter ";
    detail::append_number(buf, hf.origin_m().x);
    buf += "\nyllcenter ";
    detail::append_number(buf, hf.origin_m().y);
    buf += "\ncellsize ";
    detail::append_number(buf, hf.cell_m());
    buf += '\n';
    for (std::size_t row = 0; row < hf.ny(); ++row) {
        const std::size_t iy = hf.ny() - 1 - row;
        for (std::size_t ix = 0; ix < hf.nx(); ++ix) {
            if (ix) buf += ' ';
            detail::append_number(buf, hf.height_m(ix, iy));
        }
        buf += '\n';
        if (buf.size() > (std::size_t(1) << 20)) {
            out.write(buf);
            buf.clear();
        }
    }
    out.write(buf);
    out.commit();
}

// ----------------------------------------------------------------------------------------------------
// Raw little-endian float32 with a text sidecar

/// The sidecar's file name for a raw height file.
[[nodiscard]] inline std::string raw_sidecar_path(const std::string& path) { return path + ".txt"; }

/// Reads `path` (raw float32) and its sidecar `path + ".txt"`.
template <Real T> [[nodiscard]] scene::height_field<T> read_raw_f32(const std::string& path) {
    const std::string side_path = raw_sidecar_path(path);
    const std::string side = detail::read_all(side_path);
    std::optional<std::size_t> nx, ny;
    std::optional<double> cell, ox, oy;
    bool format_seen = false;
    std::size_t line_no = 0;
    for (std::size_t pos = 0; pos <= side.size();) {
        std::size_t end = side.find('\n', pos);
        if (end == std::string::npos) end = side.size();
        std::string_view line(side.data() + pos, end - pos);
        pos = end + 1;
        ++line_no;
        if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        detail::tokenizer tok(line, false);
        const detail::token key = tok.next();
        if (key.text.empty()) continue;
        const detail::token val = tok.next();
        if (val.text.empty()) throw file_error(side_path, line_no, "'" + std::string(key.text) + "' has no value");
        const std::string k(key.text);
        auto dup = [&](bool seen) {
            if (seen) throw file_error(side_path, line_no, "'" + k + "' given twice");
        };
        if (k == "format") {
            const detail::token ver = tok.next();
            if (val.text != "sss-height-raw-f32le" || ver.text != "1")
                throw file_error(side_path, line_no,
                                 "unknown format '" + std::string(val.text) + " " + std::string(ver.text) +
                                     "' (expected 'sss-height-raw-f32le 1')");
            dup(format_seen);
            format_seen = true;
        } else if (k == "nx" || k == "ny") {
            const auto v = detail::parse_size(val.text);
            if (!v || *v < 2)
                throw file_error(side_path, line_no,
                                 "'" + k + "' must be an integer >= 2, got '" + std::string(val.text) + "'");
            std::optional<std::size_t>& slot = k == "nx" ? nx : ny;
            dup(slot.has_value());
            slot = v;
        } else if (k == "cell_m" || k == "origin_x_m" || k == "origin_y_m") {
            const auto v = detail::parse_double(val.text);
            if (!v || !std::isfinite(*v))
                throw file_error(side_path, line_no,
                                 "'" + k + "' must be a finite number, got '" + std::string(val.text) + "'");
            if (k == "cell_m" && !(*v > 0)) throw file_error(side_path, line_no, "'cell_m' must be > 0");
            std::optional<double>& slot = k == "cell_m" ? cell : (k == "origin_x_m" ? ox : oy);
            dup(slot.has_value());
            slot = v;
        } else {
            throw file_error(side_path, line_no, "unknown key '" + k + "'");
        }
        if (!tok.next().text.empty()) throw file_error(side_path, line_no, "too many values for '" + k + "'");
    }
    const char* missing = !format_seen ? "format"
                          : !nx        ? "nx"
                          : !ny        ? "ny"
                          : !cell      ? "cell_m"
                          : !ox        ? "origin_x_m"
                          : !oy        ? "origin_y_m"
                                       : nullptr;
    if (missing) throw file_error(side_path, 0, std::string("lacks the key '") + missing + "'");
    if (*nx > (std::size_t(1) << 30) || *ny > (std::size_t(1) << 30) || *nx * *ny > (std::size_t(1) << 40))
        throw file_error(side_path, 0, "grid too large");

    const std::string data = detail::read_all(path);
    const std::size_t n = *nx * *ny;
    if (data.size() != 4 * n)
        throw file_error(path, 0,
                         "holds " + std::to_string(data.size()) + " bytes, the sidecar's " + std::to_string(*nx) +
                             " x " + std::to_string(*ny) + " grid needs " + std::to_string(4 * n),
                         std::min(data.size(), 4 * n));
    std::vector<T> heights(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto* b = reinterpret_cast<const unsigned char*>(data.data() + 4 * i);
        const std::uint32_t bits = static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
                                   (static_cast<std::uint32_t>(b[2]) << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
        const float h = std::bit_cast<float>(bits);
        if (!std::isfinite(h))
            throw file_error(path, 0,
                             "height of vertex " + std::to_string(i) + " (ix " + std::to_string(i % *nx) + ", iy " +
                                 std::to_string(i / *nx) + ") is not finite",
                             4 * i);
        heights[i] = static_cast<T>(h);
    }
    try {
        return scene::height_field<T>(*nx, *ny, static_cast<T>(*cell),
                                      vec2<T>{static_cast<T>(*ox), static_cast<T>(*oy)}, std::move(heights));
    } catch (const invalid_parameter& e) {
        throw file_error(side_path, 0, e.what());
    }
}

/// Writes `hf` as raw float32 to `path` and its sidecar to `path + ".txt"` (each atomically).
template <Real T> void write_raw_f32(const std::string& path, const scene::height_field<T>& hf) {
    const std::span<const T> h = hf.heights();
    for (std::size_t i = 0; i < h.size(); ++i)
        if (!std::isfinite(static_cast<float>(h[i])))
            throw file_error(path, 0, "height of vertex " + std::to_string(i) + " does not fit float32");
    {
        detail::atomic_file out(path);
        std::string buf;
        buf.reserve(std::min<std::size_t>(4 * h.size(), std::size_t(1) << 20));
        for (std::size_t i = 0; i < h.size(); ++i) {
            const std::uint32_t bits = std::bit_cast<std::uint32_t>(static_cast<float>(h[i]));
            for (int k = 0; k < 4; ++k) buf += static_cast<char>((bits >> (8 * k)) & 0xffu);
            if (buf.size() >= (std::size_t(1) << 20)) {
                out.write(buf);
                buf.clear();
            }
        }
        out.write(buf);
        out.commit();
    }
    detail::atomic_file side(raw_sidecar_path(path));
    std::string s = "# sss height field: float32 little-endian, row-major, row 0 = south (min y), heights in metres\n"
                    "format sss-height-raw-f32le 1\nnx " +
                    std::to_string(hf.nx()) + "\nny " + std::to_string(hf.ny()) + "\ncell_m ";
    detail::append_number(s, hf.cell_m());
    s += "\norigin_x_m ";
    detail::append_number(s, hf.origin_m().x);
    s += "\norigin_y_m ";
    detail::append_number(s, hf.origin_m().y);
    s += '\n';
    side.write(s);
    side.commit();
}

// ----------------------------------------------------------------------------------------------------
// 16-bit binary PGM

/// The vertical mapping of PGM samples: h = offset_m + scale_m * sample (m).
template <Real T> struct pgm_vertical {
    T scale_m{};  ///< metres per sample step (finite, non-zero)
    T offset_m{}; ///< height of sample 0 (m)
};

/// The mapping that spreads hf's heights over the full 16-bit range (scale 1 m for a flat field).
template <Real T> [[nodiscard]] pgm_vertical<T> pgm16_fit(const scene::height_field<T>& hf) noexcept {
    const T span = hf.top_m() - hf.bottom_m();
    return pgm_vertical<T>{span > T(0) ? span / T(65535) : T(1), hf.bottom_m()};
}

/// Reads a binary PGM (P5) as heights h = vertical.offset_m + vertical.scale_m * sample, with vertex
/// spacing cell_m and vertex (0, 0) (the first sample of the last row: south-west) at origin_m.
template <Real T> [[nodiscard]] scene::height_field<T> read_pgm16(const std::string& path, T cell_m, vec2<T> origin_m,
                                                                  pgm_vertical<T> vertical) {
    sss::detail::require_positive(cell_m, "read_pgm16.cell_m");
    sss::detail::require_finite(origin_m.x, "read_pgm16.origin_m.x");
    sss::detail::require_finite(origin_m.y, "read_pgm16.origin_m.y");
    sss::detail::require_finite(vertical.scale_m, "read_pgm16.vertical.scale_m");
    sss::detail::require(vertical.scale_m != T(0), "read_pgm16.vertical.scale_m", "must not be 0");
    sss::detail::require_finite(vertical.offset_m, "read_pgm16.vertical.offset_m");
    const std::string data = detail::read_all(path);
    std::size_t pos = 0;
    auto fail = [&](std::size_t offset, const std::string& why) { return file_error(path, 0, why, offset); };
    if (data.size() < 2 || data[0] != 'P' || data[1] != '5') throw fail(0, "not a binary PGM (no 'P5' magic number)");
    pos = 2;
    auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; };
    // Header numbers are separated by whitespace, with '#' comments running to the end of a line.
    auto header_number = [&](const char* what) -> std::size_t {
        const std::size_t before = pos;
        while (pos < data.size() && (is_space(data[pos]) || data[pos] == '#')) {
            if (data[pos] == '#') {
                while (pos < data.size() && data[pos] != '\n' && data[pos] != '\r') ++pos;
            } else {
                ++pos;
            }
        }
        if (pos == before) throw fail(pos, std::string("expected whitespace before the ") + what);
        const std::size_t start = pos;
        while (pos < data.size() && data[pos] >= '0' && data[pos] <= '9') ++pos;
        const auto v = detail::parse_size(std::string_view(data).substr(start, pos - start));
        if (!v) throw fail(start, std::string("expected the ") + what + " as a decimal number");
        return *v;
    };
    const std::size_t width = header_number("width");
    const std::size_t height = header_number("height");
    const std::size_t maxval = header_number("maxval");
    if (width < 2 || height < 2)
        throw fail(2, "image of " + std::to_string(width) + " x " + std::to_string(height) +
                          " pixels: a height field needs at least 2 x 2");
    if (width > (std::size_t(1) << 30) || height > (std::size_t(1) << 30)) throw fail(2, "image too large");
    if (maxval < 1 || maxval > 65535) throw fail(pos, "maxval must lie in [1, 65535], got " + std::to_string(maxval));
    if (pos >= data.size() || !is_space(data[pos])) throw fail(pos, "expected one whitespace byte after maxval");
    ++pos;
    const std::size_t bytes = maxval < 256 ? 1 : 2;
    const std::size_t need = width * height * bytes;
    if (data.size() - pos < need)
        throw fail(data.size(), "file ends after " + std::to_string(data.size() - pos) + " of " + std::to_string(need) +
                                    " sample bytes");
    if (data.size() - pos > need) throw fail(pos + need, "trailing bytes after the image");
    std::vector<T> heights(width * height);
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    for (std::size_t row = 0; row < height; ++row) {
        const std::size_t iy = height - 1 - row; // the first row is north
        for (std::size_t ix = 0; ix < width; ++ix) {
            const std::size_t at = pos + (row * width + ix) * bytes;
            const std::uint32_t sample = bytes == 1 ? p[at] : ((static_cast<std::uint32_t>(p[at]) << 8) | p[at + 1]);
            if (sample > maxval)
                throw fail(at, "sample " + std::to_string(sample) + " exceeds maxval " + std::to_string(maxval));
            const T h = vertical.offset_m + vertical.scale_m * static_cast<T>(sample);
            if (!std::isfinite(h)) throw fail(at, "height of sample " + std::to_string(sample) + " is not finite");
            heights[iy * width + ix] = h;
        }
    }
    return scene::height_field<T>(width, height, cell_m, origin_m, std::move(heights));
}

/// Writes `hf` as a 16-bit binary PGM with sample = round((h - offset_m) / scale_m); throws
/// invalid_parameter naming the vertex when a height maps outside [0, 65535].
template <Real T>
void write_pgm16(const std::string& path, const scene::height_field<T>& hf, pgm_vertical<T> vertical) {
    sss::detail::require_finite(vertical.scale_m, "write_pgm16.vertical.scale_m");
    sss::detail::require(vertical.scale_m != T(0), "write_pgm16.vertical.scale_m", "must not be 0");
    sss::detail::require_finite(vertical.offset_m, "write_pgm16.vertical.offset_m");
    const std::size_t nx = hf.nx(), ny = hf.ny();
    std::string buf = "P5\n# sss height field: h_m = offset_m + scale_m * sample; scale_m ";
    detail::append_number(buf, vertical.scale_m);
    buf += " offset_m ";
    detail::append_number(buf, vertical.offset_m);
    buf += " cell_m ";
    detail::append_number(buf, hf.cell_m());
    buf += " origin_m ";
    detail::append_number(buf, hf.origin_m().x);
    buf += ' ';
    detail::append_number(buf, hf.origin_m().y);
    buf += "\n" + std::to_string(nx) + " " + std::to_string(ny) + "\n65535\n";
    const std::size_t header = buf.size();
    buf.resize(header + 2 * nx * ny);
    for (std::size_t row = 0; row < ny; ++row) {
        const std::size_t iy = ny - 1 - row;
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double s =
                std::round((static_cast<double>(hf.height_m(ix, iy)) - static_cast<double>(vertical.offset_m)) /
                           static_cast<double>(vertical.scale_m));
            if (!(s >= 0.0 && s <= 65535.0))
                throw invalid_parameter("write_pgm16.vertical", "height of vertex (ix " + std::to_string(ix) + ", iy " +
                                                                    std::to_string(iy) + ") maps to sample " +
                                                                    std::to_string(s) + ", outside [0, 65535]");
            const auto v = static_cast<std::uint32_t>(s);
            buf[header + 2 * (row * nx + ix)] = static_cast<char>(v >> 8);
            buf[header + 2 * (row * nx + ix) + 1] = static_cast<char>(v & 0xffu);
        }
    }
    detail::atomic_file out(path);
    out.write(buf);
    out.commit();
}

} // namespace sss::io
