#pragma once
/// \file
/// Reading and writing height fields (sss::scene::height_field) in three formats:
///
/// - ESRI ASCII grid (.asc): a text header (ncols, nrows, xllcorner or xllcenter, yllcorner or yllcenter,
///   cellsize, optional NODATA_value; keywords in any case) and nrows x ncols values, rows from north to
///   south. Each value is taken as the height of one vertex at its cell's centre, so vertex (0, 0) lies at
///   (xllcenter, yllcenter) = (xllcorner + cellsize/2, yllcorner + cellsize/2). A NODATA value (NaN too, as
///   GDAL writes it) is an error unless a fill height is given. The writer writes xllcenter/yllcenter (exact, no
///   half-cell arithmetic) and the shortest decimal form that reads back to the same value.
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
/// - Binary PGM (P5, first row north): heights h = offset_m + scale_m * sample. The writer writes 16-bit
///   samples (big-endian); the reader takes any maxval up to 65535, one byte per sample below 256 as the format
///   says, so 8-bit images load too. PGM holds no geometry: the reader takes cell size and origin, and the
///   writer notes all four numbers in a header comment for people (the reader ignores comments).
///
/// Errors are sss::file_error naming the file and the line (text) or the byte offset (binary). Heights
/// that are not finite are rejected at load. A reader returns a complete height field or throws; a writer
/// writes a temporary of its own next to `path` and renames it over `path`, so `path` is never left half written.
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

#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/io/detail/atomic_file.hpp"
#include "sss/io/detail/text.hpp"
#include "sss/scene/height_field.hpp"

namespace sss::io {


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
    const std::string text = sss::detail::read_file(path);
    sss::detail::tokenizer tok(text, false);
    auto fail = [&](std::size_t line, const std::string& why) -> file_error { return file_error(path, line, why); };

    std::optional<std::size_t> ncols, nrows;
    std::size_t first_data_line = 0;
    std::optional<double> x_ll, y_ll, cellsize, nodata;
    std::string_view x_text, y_text, cell_text; // their texts, rounded once to T where taken as they are
    std::size_t x_line = 0, y_line = 0, cell_line = 0;
    bool x_center = false, y_center = false;
    // Header: keyword/value pairs until the first token that is not a keyword.
    for (;;) {
        const auto before = tok.save();
        const sss::detail::token key = tok.next();
        if (key.text.empty()) throw fail(key.line, "file ends in the header");
        const std::string k = sss::detail::lower(key.text);
        const bool known = k == "ncols" || k == "nrows" || k == "xllcorner" || k == "xllcenter" || k == "yllcorner" ||
                           k == "yllcenter" || k == "cellsize" || k == "nodata_value";
        if (!known) {
            if (k == "dx" || k == "dy")
                throw fail(key.line, "'" + std::string(key.text) + "': only square cells (cellsize) are supported");
            if (!sss::detail::parse_double(key.text))
                throw fail(key.line, "unknown header keyword '" + std::string(key.text) + "'");
            tok.rewind(before);
            first_data_line = key.line;
            break;
        }
        const sss::detail::token val = tok.next();
        if (val.text.empty() || val.line != key.line)
            throw fail(key.line, "header keyword '" + std::string(key.text) + "' has no value");
        auto dup = [&](bool seen) {
            if (seen) throw fail(key.line, "header keyword '" + std::string(key.text) + "' given twice");
        };
        if (k == "ncols" || k == "nrows") {
            const auto v = sss::detail::parse_size(val.text);
            if (!v || *v < 2)
                throw fail(val.line, "'" + std::string(key.text) + "' must be an integer >= 2, got '" +
                                         std::string(val.text) + "'");
            std::optional<std::size_t>& slot = k == "ncols" ? ncols : nrows;
            dup(slot.has_value());
            slot = v;
            continue;
        }
        const auto v = sss::detail::parse_double(val.text);
        // NODATA_value may be NaN (GDAL writes "nan" for a grid whose no-data cells are NaN); the rest are finite.
        const bool nan_nodata = k == "nodata_value" && v && std::isnan(*v);
        if (!v || (!std::isfinite(*v) && !nan_nodata))
            throw fail(val.line,
                       "'" + std::string(key.text) + "' must be a finite number, got '" + std::string(val.text) + "'");
        if (k == "xllcorner" || k == "xllcenter") {
            dup(x_ll.has_value());
            x_ll = v;
            x_text = val.text;
            x_line = val.line;
            x_center = k == "xllcenter";
        } else if (k == "yllcorner" || k == "yllcenter") {
            dup(y_ll.has_value());
            y_ll = v;
            y_text = val.text;
            y_line = val.line;
            y_center = k == "yllcenter";
        } else if (k == "cellsize") {
            dup(cellsize.has_value());
            if (!(*v > 0)) throw fail(val.line, "'cellsize' must be > 0, got '" + std::string(val.text) + "'");
            cellsize = v;
            cell_text = val.text;
            cell_line = val.line;
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
    // Each value takes at least two bytes (a digit and a separator): a grid the file cannot hold is refused
    // before its heights are allocated.
    // Both at most 2^30, so the product cannot overflow; it is checked all the same, by the one helper.
    if (nx > (std::size_t(1) << 30) || ny > (std::size_t(1) << 30) || checked_mul(nx, ny, "ncols * nrows") > max_elements)
        throw fail(first_data_line, "grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " is too large");
    if (nx * ny > text.size() / 2 + 1)
        throw fail(first_data_line, "grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " values cannot fit in " +
                                        std::to_string(text.size()) + " bytes");

    std::vector<T> heights(nx * ny);
    for (std::size_t row = 0; row < ny; ++row) {
        const std::size_t iy = ny - 1 - row; // rows run north to south
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const sss::detail::token t = tok.next();
            if (t.text.empty())
                throw fail(t.line, "file ends after " + std::to_string(row * nx + ix) + " of " +
                                       std::to_string(nx * ny) + " values");
            const auto v = sss::detail::parse_double(t.text);
            if (!v)
                throw fail(t.line, "'" + std::string(t.text) + "' is not a number (row " + std::to_string(row) +
                                       ", column " + std::to_string(ix) + ")");
            std::optional<T> h;
            if (nodata && (*v == *nodata || (std::isnan(*nodata) && std::isnan(*v)))) {
                if (!options.nodata_fill_m)
                    throw fail(t.line, "NODATA at row " + std::to_string(row) + ", column " + std::to_string(ix) +
                                           " (a height field needs every vertex)");
                h = *options.nodata_fill_m;
            } else {
                h = sss::detail::parse_as<T>(t.text); // rounded once to T (parse_as)
            }
            if (!h || !std::isfinite(*h))
                throw fail(t.line, "height '" + std::string(t.text) + "' at row " + std::to_string(row) + ", column " +
                                       std::to_string(ix) + " is not finite");
            heights[iy * nx + ix] = *h;
        }
    }
    if (!tok.at_end()) {
        const sss::detail::token extra = tok.next();
        throw fail(extra.line, "more values than ncols x nrows = " + std::to_string(nx * ny) + " ('" +
                                   std::string(extra.text) + "')");
    }
    // A centre and the cell size as written (write_esri_ascii: the shortest text of a T) read back exactly; a corner
    // is moved by half a cell in double first.
    const double half = 0.5 * *cellsize;
    const auto as_t = [](std::string_view written, double v) {
        return sss::detail::parse_as<T>(written).value_or(static_cast<T>(v));
    };
    const vec2<T> origin{x_center ? as_t(x_text, *x_ll) : static_cast<T>(*x_ll + half),
                         y_center ? as_t(y_text, *y_ll) : static_cast<T>(*y_ll + half)};
    const T cell = as_t(cell_text, *cellsize);
    // Values a double holds but T does not (a float's range ends at 3.4e38, its least positive value is 1.4e-45):
    // named by their lines, as the rest of the header is.
    if (!std::isfinite(origin.x)) throw fail(x_line, "the grid's x origin '" + std::string(x_text) + "' is beyond the height type's range");
    if (!std::isfinite(origin.y)) throw fail(y_line, "the grid's y origin '" + std::string(y_text) + "' is beyond the height type's range");
    if (!(cell > T(0)) || !std::isfinite(cell))
        throw fail(cell_line, "'cellsize' " + std::string(cell_text) + " is not a positive number in the height type");
    try {
        return scene::height_field<T>({.nx = nx, .ny = ny, .cell_m = cell, .origin_m = origin, .heights_m = std::move(heights)});
    } catch (const invalid_parameter& e) {
        throw fail(0, std::string(message_body(e)));
    }
}

/// Writes `hf` as an ESRI ASCII grid with xllcenter/yllcenter.
template <Real T> void write_esri_ascii(const std::string& path, const scene::height_field<T>& hf) {
    sss::detail::atomic_file out(path);
    std::string buf;
    buf += "ncols " + std::to_string(hf.nx()) + "\nnrows " + std::to_string(hf.ny()) + "\nxllcenter ";
    sss::detail::append_number(buf, hf.origin_m().x);
    buf += "\nyllcenter ";
    sss::detail::append_number(buf, hf.origin_m().y);
    buf += "\ncellsize ";
    sss::detail::append_number(buf, hf.cell_m());
    buf += '\n';
    for (std::size_t row = 0; row < hf.ny(); ++row) {
        const std::size_t iy = hf.ny() - 1 - row;
        for (std::size_t ix = 0; ix < hf.nx(); ++ix) {
            if (ix) buf += ' ';
            sss::detail::append_number(buf, hf.height_m(ix, iy));
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

/// The geometry a raw height file's sidecar gives.
struct raw_grid {
    std::size_t nx = 0;      ///< vertices along x (east)
    std::size_t ny = 0;      ///< vertices along y (north)
    double cell_m = 0;       ///< vertex spacing (m)
    double origin_x_m = 0;   ///< world x of vertex (0, 0) (m)
    double origin_y_m = 0;   ///< world y of vertex (0, 0) (m)
};

namespace detail {

/// A sidecar as read: its grid, and the text of its three lengths, so that a float height field takes each of them
/// rounded once from the text (parse_as) rather than twice, through double.
struct raw_sidecar_read {
    raw_grid grid;
    std::string cell_text, origin_x_text, origin_y_text;

    /// The cell size, rounded once to T.
    template <Real T> [[nodiscard]] T cell_m() const { return number<T>(cell_text, grid.cell_m); }
    /// The origin, each coordinate rounded once to T.
    template <Real T> [[nodiscard]] vec2<T> origin_m() const {
        return {number<T>(origin_x_text, grid.origin_x_m), number<T>(origin_y_text, grid.origin_y_m)};
    }

private:
    template <Real T> static T number(const std::string& text, double v) {
        return sss::detail::parse_as<T>(text).value_or(static_cast<T>(v)); // out of T's range: as T rounds v
    }
};

/// read_raw_sidecar, keeping the lengths' text.
[[nodiscard]] inline raw_sidecar_read read_raw_sidecar_text(const std::string& path) {
    const std::string side_path = raw_sidecar_path(path);
    std::string texts[3];
    const std::string side = sss::detail::read_file(side_path);
    std::optional<std::size_t> nx, ny;
    std::optional<double> cell, ox, oy;
    bool format_seen = false;
    for (const sss::detail::text_line& line : sss::detail::content_lines(side)) {
        const std::size_t line_no = line.number;
        const auto fields = sss::detail::split_blanks(line);
        const std::string k(fields[0].text);
        if (fields.size() < 2) throw file_error(side_path, line_no, "'" + k + "' has no value");
        const std::string_view val = fields[1].text;
        const std::size_t col = fields[1].column;
        auto dup = [&](bool seen) {
            if (seen) throw file_error(side_path, line_no, "'" + k + "' given twice");
        };
        std::size_t expected = 2;
        if (k == "format") {
            expected = 3;
            const std::string_view ver = fields.size() > 2 ? fields[2].text : std::string_view{};
            if (val != "sss-height-raw-f32le" || ver != "1")
                throw sss::detail::error_at(side_path, line_no, col,
                                            "unknown format '" + std::string(val) + " " + std::string(ver) +
                                                "' (expected 'sss-height-raw-f32le 1')");
            dup(format_seen);
            format_seen = true;
        } else if (k == "nx" || k == "ny") {
            const auto v = sss::detail::parse_size(val);
            if (!v || *v < 2)
                throw sss::detail::error_at(side_path, line_no, col,
                                            "'" + k + "' must be an integer >= 2, got '" + std::string(val) + "'");
            std::optional<std::size_t>& slot = k == "nx" ? nx : ny;
            dup(slot.has_value());
            slot = v;
        } else if (k == "cell_m" || k == "origin_x_m" || k == "origin_y_m") {
            const auto v = sss::detail::parse_finite(val);
            if (!v)
                throw sss::detail::error_at(side_path, line_no, col,
                                            "'" + k + "' must be a finite number, got '" + std::string(val) + "'");
            if (k == "cell_m" && !(*v > 0)) throw sss::detail::error_at(side_path, line_no, col, "'cell_m' must be > 0");
            const int which = k == "cell_m" ? 0 : (k == "origin_x_m" ? 1 : 2);
            std::optional<double>& slot = which == 0 ? cell : (which == 1 ? ox : oy);
            dup(slot.has_value());
            slot = v;
            texts[which] = std::string(val);
        } else {
            throw sss::detail::error_at(side_path, line_no, fields[0].column, "unknown key '" + k + "'");
        }
        if (fields.size() > expected)
            throw sss::detail::error_at(side_path, line_no, fields[expected].column, "too many values for '" + k + "'");
    }
    const char* missing = !format_seen ? "format"
                          : !nx        ? "nx"
                          : !ny        ? "ny"
                          : !cell      ? "cell_m"
                          : !ox        ? "origin_x_m"
                          : !oy        ? "origin_y_m"
                                       : nullptr;
    if (missing) throw file_error(side_path, 0, std::string("lacks the key '") + missing + "'");
    if (*nx > (std::size_t(1) << 30) || *ny > (std::size_t(1) << 30))
        throw file_error(side_path, 0, "grid too large: nx and ny must be <= 2^30");
    return {.grid = {.nx = *nx, .ny = *ny, .cell_m = *cell, .origin_x_m = *ox, .origin_y_m = *oy},
            .cell_text = std::move(texts[0]),
            .origin_x_text = std::move(texts[1]),
            .origin_y_text = std::move(texts[2])};
}

} // namespace detail

/// Reads the sidecar `path + ".txt"` of the raw height file `path`: one `key value` pair a line, `#` comments;
/// every key once, none unknown; 2 <= nx, ny <= 2^30 (a mapped file may exceed sss::max_elements; a file read
/// into memory may not). Errors name the line and column.
[[nodiscard]] inline raw_grid read_raw_sidecar(const std::string& path) {
    return detail::read_raw_sidecar_text(path).grid;
}

/// The text of the sidecar of a raw height file, each number in the shortest text that reads back to it in `Number`
/// (float for a float height field: "0.1", not "0.10000000149011612").
template <class Number = double> [[nodiscard]] std::string raw_sidecar_text(const raw_grid& g) {
    std::string s = "# sss height field: float32 little-endian, row-major, row 0 = south (min y), heights in metres\n"
                    "format sss-height-raw-f32le 1\nnx " +
                    std::to_string(g.nx) + "\nny " + std::to_string(g.ny) + "\ncell_m ";
    sss::detail::append_number(s, static_cast<Number>(g.cell_m));
    s += "\norigin_x_m ";
    sss::detail::append_number(s, static_cast<Number>(g.origin_x_m));
    s += "\norigin_y_m ";
    sss::detail::append_number(s, static_cast<Number>(g.origin_y_m));
    s += '\n';
    return s;
}

/// Writes the sidecar of the raw height file `path` (atomically), as raw_sidecar_text.
template <class Number = double> void write_raw_sidecar(const std::string& path, const raw_grid& g) {
    sss::detail::save_file(raw_sidecar_path(path), raw_sidecar_text<Number>(g));
}

/// Reads `path` (raw float32) and its sidecar `path + ".txt"`.
template <Real T> [[nodiscard]] scene::height_field<T> read_raw_f32(const std::string& path) {
    const std::string side_path = raw_sidecar_path(path);
    const detail::raw_sidecar_read sidecar = detail::read_raw_sidecar_text(path);
    const raw_grid& g = sidecar.grid;
    if (checked_mul(g.nx, g.ny, "nx * ny") > max_elements)
        throw file_error(side_path, 0, "grid too large: nx * ny exceeds sss::max_elements");
    const std::size_t n = g.nx * g.ny;
    // The size first: a wrong file beside the sidecar (a survey's 50 GB instead of its tile) is named, not read.
    std::error_code size_error;
    if (const auto size = std::filesystem::file_size(path, size_error); !size_error && size != 4 * n)
        throw file_error(path, 0,
                         "holds " + std::to_string(size) + " bytes, the sidecar's " + std::to_string(g.nx) + " x " +
                             std::to_string(g.ny) + " grid needs " + std::to_string(4 * n),
                         static_cast<std::size_t>(std::min<std::uintmax_t>(size, 4 * n)));
    const std::string data = sss::detail::read_file(path);
    if (data.size() != 4 * n)
        throw file_error(path, 0,
                         "holds " + std::to_string(data.size()) + " bytes, the sidecar's " + std::to_string(g.nx) +
                             " x " + std::to_string(g.ny) + " grid needs " + std::to_string(4 * n),
                         std::min(data.size(), 4 * n));
    std::vector<T> heights(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto* b = reinterpret_cast<const unsigned char*>(data.data() + 4 * i);
        const std::uint32_t bits = static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
                                   (static_cast<std::uint32_t>(b[2]) << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
        const float h = std::bit_cast<float>(bits);
        if (!std::isfinite(h))
            throw file_error(path, 0,
                             "height of vertex " + std::to_string(i) + " (ix " + std::to_string(i % g.nx) + ", iy " +
                                 std::to_string(i / g.nx) + ") is not finite",
                             4 * i);
        heights[i] = static_cast<T>(h);
    }
    try {
        return scene::height_field<T>({.nx = g.nx,
                                       .ny = g.ny,
                                       .cell_m = sidecar.cell_m<T>(),
                                       .origin_m = sidecar.origin_m<T>(),
                                       .heights_m = std::move(heights)});
    } catch (const invalid_parameter& e) {
        throw file_error(side_path, 0, message_body(e));
    }
}

/// Writes `hf` as raw float32 to `path` and its sidecar to `path + ".txt"`, together (detail::commit_together: a
/// failure writing either leaves both old files as they were).
template <Real T> void write_raw_f32(const std::string& path, const scene::height_field<T>& hf) {
    const std::span<const T> h = hf.heights();
    for (std::size_t i = 0; i < h.size(); ++i)
        if (!std::isfinite(static_cast<float>(h[i])))
            throw file_error(path, 0, "height of vertex " + std::to_string(i) + " does not fit float32");
    sss::detail::atomic_file out(path);
    sss::detail::atomic_file side(raw_sidecar_path(path));
    {
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
    }
    side.write(raw_sidecar_text<T>({.nx = hf.nx(),
                                    .ny = hf.ny(),
                                    .cell_m = double(hf.cell_m()),
                                    .origin_x_m = double(hf.origin_m().x),
                                    .origin_y_m = double(hf.origin_m().y)}));
    sss::detail::commit_together(out, side);
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
    sss::require_positive(cell_m, "read_pgm16.cell_m");
    sss::require_finite(origin_m.x, "read_pgm16.origin_m.x");
    sss::require_finite(origin_m.y, "read_pgm16.origin_m.y");
    sss::require_finite(vertical.scale_m, "read_pgm16.vertical.scale_m");
    sss::require(vertical.scale_m != T(0), "read_pgm16.vertical.scale_m", "must not be 0");
    sss::require_finite(vertical.offset_m, "read_pgm16.vertical.offset_m");
    const std::string data = sss::detail::read_file(path);
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
        const auto v = sss::detail::parse_size(std::string_view(data).substr(start, pos - start));
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
    const std::size_t need = checked_mul(checked_mul(width, height, "width * height"), bytes, "width * height"); // < 2^61
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
    return scene::height_field<T>({.nx = width, .ny = height, .cell_m = cell_m, .origin_m = origin_m, .heights_m = std::move(heights)});
}

/// Writes `hf` as a 16-bit binary PGM with sample = round((h - offset_m) / scale_m); throws
/// invalid_parameter naming the vertex when a height maps outside [0, 65535].
template <Real T>
void write_pgm16(const std::string& path, const scene::height_field<T>& hf, pgm_vertical<T> vertical) {
    sss::require_finite(vertical.scale_m, "write_pgm16.vertical.scale_m");
    sss::require(vertical.scale_m != T(0), "write_pgm16.vertical.scale_m", "must not be 0");
    sss::require_finite(vertical.offset_m, "write_pgm16.vertical.offset_m");
    const std::size_t nx = hf.nx(), ny = hf.ny();
    std::string buf = "P5\n# sss height field: h_m = offset_m + scale_m * sample; scale_m ";
    sss::detail::append_number(buf, vertical.scale_m);
    buf += " offset_m ";
    sss::detail::append_number(buf, vertical.offset_m);
    buf += " cell_m ";
    sss::detail::append_number(buf, hf.cell_m());
    buf += " origin_m ";
    sss::detail::append_number(buf, hf.origin_m().x);
    buf += ' ';
    sss::detail::append_number(buf, hf.origin_m().y);
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
    sss::detail::atomic_file out(path);
    out.write(buf);
    out.commit();
}

} // namespace sss::io
