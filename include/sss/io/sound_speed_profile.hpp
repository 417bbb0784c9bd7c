#pragma once
/// \file
/// Reading and writing sound-speed profiles (depth in m, positive down; speed in m/s).
///
/// Formats read:
/// - CSV: one "depth,speed" pair per line. An optional header line (the first non-comment line, if
///   none of its fields is a number) is skipped. Fields may be separated by ',' or ';' (then spaces around
///   fields are ignored) or, on lines with neither, by white space.
/// - CARIS .svp: a version line "[SVP_VERSION_2]" (any version number accepted), a line with a file
///   name, then one or more sections, each a "Section YYYY-DDD HH:MM:SS lat lon ..." line followed by
///   "depth speed" lines. The file-name line may be missing; a file with no Section line is read as one
///   section. Sections are numbered from 0 in file order.
/// - Kongsberg .asvp: a header in parentheses, "( SoundVelocity 1.00 Id Time Lat Long Radii Valid_from
///   Valid_to Src Hist No_val )" (it may run over several lines), then "depth speed" lines. When the
///   header has all twelve fields, No_val must equal the number of data lines.
/// In every format blank lines are skipped, '#' starts a comment running to the end of the line, a
/// UTF-8 byte order mark and Windows line ends are accepted, and a number may carry a leading '+'.
///
/// Every data line must hold exactly two finite numbers; depths must increase strictly (within a
/// section, and far enough apart for the gradient to be finite) and speeds lie within 1000 to 2500 m/s (sound in
/// water; a column in km/s or ft/s is refused). Anything else throws sss::file_error naming the file (or the name
/// given for a stream) and the 1-based line, and nothing is returned: a profile is only built once
/// the whole input has been read and checked.
///
/// Written (atomically: to a temporary name, then renamed): CSV with a "depth_m,speed_mps" header and the shortest decimal form that reads back to the
/// same value, so write-then-read round-trips exactly.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/io/detail/atomic_file.hpp"
#include "sss/io/detail/sound_speed_knots.hpp"
#include "sss/io/detail/text.hpp"
#include "sss/propagation/profile.hpp"

namespace sss::io {

// ------------------------------------------------------------------------------------------------
// CSV

/// Reads a depth,speed CSV profile from `in`; `name` labels error messages.
template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_sound_speed_csv(std::istream& in, std::string_view name) {
    using namespace detail::svp;
    const std::string text = sss::detail::read_stream(in, name);
    const auto lines = read_lines(text);
    knot_list<T> knots;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (i == 0) { // a header line: no field is a number
            const auto fields = split_fields(lines[0]);
            if (std::none_of(fields.begin(), fields.end(),
                             [](const sss::detail::text_field& f) { return sss::detail::parse_finite(f.text).has_value(); }))
                continue;
        }
        knots.add(lines[i], name);
    }
    if (knots.depth.empty()) throw file_error(name, 0, "no depth,speed data lines");
    return std::move(knots).build();
}

/// Reads a depth,speed CSV profile from a file.
template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_sound_speed_csv(const std::filesystem::path& path) {
    auto in = detail::svp::open_for_reading(path);
    return read_sound_speed_csv<T>(in, path.string());
}

// ------------------------------------------------------------------------------------------------
// CARIS .svp

/// Every section of a CARIS .svp profile read from `in`, in file order; `name` labels error messages.
template <Real T = double>
[[nodiscard]] std::vector<propagation::sound_speed_profile<T>> read_caris_svp_sections(std::istream& in,
                                                                                      std::string_view name) {
    using namespace detail::svp;
    const std::string text = sss::detail::read_stream(in, name);
    const auto lines = read_lines(text);
    if (lines.empty()) throw file_error(name, 0, "empty file: expected a \"[SVP_VERSION_2]\" line");
    if (!iequals_prefix(lines[0].text, "[SVP_VERSION")) {
        throw file_error(name, lines[0].number,
                         "expected a version line such as \"[SVP_VERSION_2]\", found " + quote(lines[0].text));
    }
    std::vector<knot_list<T>> sections;
    std::vector<std::size_t> section_line;
    std::size_t i = 1;
    // The file-name line: anything that is neither a section header nor a data line.
    if (i < lines.size() && !iequals_prefix(lines[i].text, "Section") && !looks_like_data(lines[i])) ++i;
    for (; i < lines.size(); ++i) {
        if (iequals_prefix(lines[i].text, "Section")) {
            sections.emplace_back();
            section_line.push_back(lines[i].number);
            continue;
        }
        if (sections.empty()) { // data with no Section header: one implicit section
            sections.emplace_back();
            section_line.push_back(lines[i].number);
        }
        sections.back().add(lines[i], name);
    }
    if (sections.empty()) throw file_error(name, 0, "no sections and no depth speed data lines");
    std::vector<propagation::sound_speed_profile<T>> out;
    out.reserve(sections.size());
    for (std::size_t k = 0; k < sections.size(); ++k) {
        if (sections[k].depth.empty()) throw file_error(name, section_line[k], "section has no depth speed lines");
    }
    for (auto& s : sections) out.push_back(std::move(s).build());
    return out;
}

/// One section (0-based, in file order) of a CARIS .svp profile read from `in`. The whole input is
/// checked, not only the section returned.
template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_caris_svp(std::istream& in, std::string_view name,
                                                                 std::size_t section = 0) {
    auto all = read_caris_svp_sections<T>(in, name);
    if (section >= all.size()) {
        throw file_error(name, 0,
                         "section " + std::to_string(section) + " requested, the file has " +
                             std::to_string(all.size()) + " (numbered from 0)");
    }
    return std::move(all[section]);
}

template <Real T = double>
[[nodiscard]] std::vector<propagation::sound_speed_profile<T>> read_caris_svp_sections(
    const std::filesystem::path& path) {
    auto in = detail::svp::open_for_reading(path);
    return read_caris_svp_sections<T>(in, path.string());
}

template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_caris_svp(const std::filesystem::path& path,
                                                                 std::size_t section = 0) {
    auto in = detail::svp::open_for_reading(path);
    return read_caris_svp<T>(in, path.string(), section);
}

// ------------------------------------------------------------------------------------------------
// Kongsberg .asvp

/// Reads a Kongsberg .asvp profile from `in`; `name` labels error messages.
template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_kongsberg_asvp(std::istream& in, std::string_view name) {
    using namespace detail::svp;
    const std::string text = sss::detail::read_stream(in, name);
    const auto lines = read_lines(text);
    if (lines.empty()) throw file_error(name, 0, "empty file: expected a \"( SoundVelocity ...)\" header");
    const std::string_view first = lines[0].text;
    if (first.front() != '(' || !iequals_prefix(trim(first.substr(1)), "SoundVelocity")) {
        throw file_error(name, lines[0].number,
                         "expected a header starting \"( SoundVelocity\", found " + quote(first));
    }
    // Gather the header up to its closing parenthesis, which may be on a later line.
    std::string header;
    std::size_t i = 0;
    for (; i < lines.size(); ++i) {
        const std::string_view line = lines[i].text;
        const auto close = line.find(')');
        header += ' ';
        header += line.substr(0, close);
        if (close != std::string_view::npos) {
            if (!trim(line.substr(close + 1)).empty()) {
                throw file_error(name, lines[i].number, "unexpected text after the header's closing ')'");
            }
            break;
        }
    }
    if (i == lines.size()) throw file_error(name, lines[0].number, "header has no closing ')'");
    ++i;
    std::optional<std::size_t> declared;
    {
        std::string_view h = header;
        h = trim(h);
        h.remove_prefix(1); // '('
        const auto fields = split_fields(text_line{trim(h), lines[0].number, 1});
        if (fields.size() == 12) declared = sss::detail::parse_size(fields.back().text);
    }
    knot_list<T> knots;
    for (; i < lines.size(); ++i) knots.add(lines[i], name);
    if (knots.depth.empty()) throw file_error(name, 0, "no depth speed data lines after the header");
    if (declared && *declared != knots.depth.size()) {
        throw file_error(name, lines[0].number,
                         "header declares " + std::to_string(*declared) + " values, the file has " +
                             std::to_string(knots.depth.size()));
    }
    return std::move(knots).build();
}

template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_kongsberg_asvp(const std::filesystem::path& path) {
    auto in = detail::svp::open_for_reading(path);
    return read_kongsberg_asvp<T>(in, path.string());
}

// ------------------------------------------------------------------------------------------------
// Any of the above

/// Reads a profile choosing the format from the file extension (case-insensitive): .svp -> CARIS
/// (first section), .asvp -> Kongsberg, anything else -> CSV.
template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_sound_speed_profile(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); });
    if (ext == ".svp") return read_caris_svp<T>(path);
    if (ext == ".asvp") return read_kongsberg_asvp<T>(path);
    return read_sound_speed_csv<T>(path);
}

// ------------------------------------------------------------------------------------------------
// Writing

/// Writes `profile` as CSV ("depth_m,speed_mps" header, shortest round-trip decimals) to `out`.
/// Throws file_error (naming `name`) if the stream fails.
template <Real T>
void write_sound_speed_csv(std::ostream& out, const propagation::sound_speed_profile<T>& profile,
                           std::string_view name) {
    using detail::svp::shortest;
    out << "depth_m,speed_mps\n";
    const auto depth = profile.depths_m();
    const auto speed = profile.speeds_mps();
    for (std::size_t i = 0; i < depth.size(); ++i) out << shortest(depth[i]) << ',' << shortest(speed[i]) << '\n';
    out.flush();
    if (!out) throw file_error(name, 0, "write failed");
}

/// Writes `profile` as CSV to the file at `path` (created or replaced atomically: written to a temporary next to it,
/// then renamed, so a failure leaves `path` as it was).
template <Real T>
void write_sound_speed_csv(const std::filesystem::path& path, const propagation::sound_speed_profile<T>& profile) {
    std::ostringstream out;
    write_sound_speed_csv(out, profile, path.string());
    sss::detail::save_file(path.string(), out.view());
}

} // namespace sss::io
