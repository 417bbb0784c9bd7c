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
/// section) and speeds be positive. Anything else throws sss::file_error naming the file (or the name
/// given for a stream) and the 1-based line, and nothing is returned: a profile is only built once
/// the whole input has been read and checked.
///
/// Written: CSV with a "depth_m,speed_mps" header and the shortest decimal form that reads back to the
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
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"
#include "sss/propagation/profile.hpp"

namespace sss::io {

// Not `detail`: a nested namespace of that name would hide sss::detail from the rest of sss::io.
namespace detail::svp {

/// One line of text with its 1-based number.
struct text_line {
    std::size_t number;
    std::string text; // comment, line end and surrounding blanks removed; never empty
};

[[nodiscard]] inline std::string_view trim(std::string_view s) noexcept {
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; };
    while (!s.empty() && blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && blank(s.back())) s.remove_suffix(1);
    return s;
}

/// All non-blank lines of `in`, comments stripped. Throws file_error if the stream fails.
[[nodiscard]] inline std::vector<text_line> read_lines(std::istream& in, std::string_view name) {
    std::vector<text_line> lines;
    std::string raw;
    std::size_t number = 0;
    while (std::getline(in, raw)) {
        ++number;
        std::string_view view(raw);
        if (number == 1 && view.starts_with("\xEF\xBB\xBF")) view.remove_prefix(3);
        if (const auto hash = view.find('#'); hash != std::string_view::npos) view = view.substr(0, hash);
        view = trim(view);
        if (!view.empty()) lines.push_back({number, std::string(view)});
    }
    if (in.bad()) throw file_error(name, number + 1, "read error");
    return lines;
}

[[nodiscard]] inline bool iequals_prefix(std::string_view text, std::string_view prefix) noexcept {
    if (text.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i) {
        if (std::tolower(static_cast<unsigned char>(text[i])) != std::tolower(static_cast<unsigned char>(prefix[i])))
            return false;
    }
    return true;
}

/// Splits a data line into fields: on ',' / ';' when present, else on white space.
[[nodiscard]] inline std::vector<std::string_view> split_fields(std::string_view line) {
    std::vector<std::string_view> fields;
    if (line.find_first_of(",;") != std::string_view::npos) {
        std::size_t start = 0;
        while (true) {
            const std::size_t end = line.find_first_of(",;", start);
            fields.push_back(trim(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
            if (end == std::string_view::npos) break;
            start = end + 1;
        }
        return fields;
    }
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
        if (j > i) fields.push_back(line.substr(i, j - i));
        i = j;
    }
    return fields;
}

/// A finite number spelled by the whole of `field`, or nullopt.
[[nodiscard]] inline std::optional<double> parse_number(std::string_view field) noexcept {
    if (!field.empty() && field.front() == '+') field.remove_prefix(1); // from_chars rejects '+'
    double value = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (ec != std::errc() || end != field.data() + field.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

[[nodiscard]] inline std::string quote(std::string_view s) { return "'" + std::string(s) + "'"; }

/// The shortest decimal spelling that reads back as v.
template <Real T> [[nodiscard]] std::string shortest(T v) {
    char buf[64];
    const auto result = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, result.ptr);
}

/// Knots accumulated from data lines, checked as they arrive.
template <Real T> struct knot_list {
    std::vector<T> depth;
    std::vector<T> speed;
    std::size_t first_line = 0;

    void add(const text_line& line, std::string_view name) {
        const auto fields = split_fields(line.text);
        if (fields.size() != 2) {
            throw file_error(name, line.number,
                             "expected 2 columns (depth m, speed m/s), found " + std::to_string(fields.size()) +
                                 " in " + quote(line.text));
        }
        const auto d = parse_number(fields[0]);
        if (!d) throw file_error(name, line.number, "depth " + quote(fields[0]) + " is not a finite number");
        const auto c = parse_number(fields[1]);
        if (!c) throw file_error(name, line.number, "speed " + quote(fields[1]) + " is not a finite number");
        constexpr double largest = static_cast<double>(std::numeric_limits<T>::max());
        if (std::abs(*d) > largest) throw file_error(name, line.number, "depth " + quote(fields[0]) + " is out of range");
        if (!(*c > 0.0) || *c > largest)
            throw file_error(name, line.number, "speed " + quote(fields[1]) + " must be a positive number of m/s");
        const T depth_m = static_cast<T>(*d);
        const T speed_mps = static_cast<T>(*c);
        if (!(speed_mps > T(0))) // a positive double that underflows T
            throw file_error(name, line.number, "speed " + quote(fields[1]) + " must be a positive number of m/s");
        if (!depth.empty() && !(depth_m > depth.back())) {
            throw file_error(name, line.number,
                             "depth " + quote(fields[0]) + " does not increase: the previous depth is " +
                                 shortest(depth.back()) + " m (depths must increase strictly)");
        }
        if (depth.empty()) first_line = line.number;
        depth.push_back(depth_m);
        speed.push_back(speed_mps);
    }

    [[nodiscard]] propagation::sound_speed_profile<T> build() && {
        return propagation::sound_speed_profile<T>(std::move(depth), std::move(speed));
    }
};

[[nodiscard]] inline bool looks_like_data(const text_line& line) {
    const auto fields = split_fields(line.text);
    return fields.size() == 2 && parse_number(fields[0]) && parse_number(fields[1]);
}

[[nodiscard]] inline std::ifstream open_for_reading(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw file_error(path.string(), 0, "cannot open for reading");
    return in;
}

} // namespace detail::svp

// ------------------------------------------------------------------------------------------------
// CSV

/// Reads a depth,speed CSV profile from `in`; `name` labels error messages.
template <Real T = double>
[[nodiscard]] propagation::sound_speed_profile<T> read_sound_speed_csv(std::istream& in, std::string_view name) {
    using namespace detail::svp;
    const auto lines = read_lines(in, name);
    knot_list<T> knots;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (i == 0) { // a header line: no field is a number
            const auto fields = split_fields(lines[0].text);
            if (std::none_of(fields.begin(), fields.end(), [](std::string_view f) { return parse_number(f).has_value(); }))
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
    const auto lines = read_lines(in, name);
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
    const auto lines = read_lines(in, name);
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
        const std::string_view text = lines[i].text;
        const auto close = text.find(')');
        header += ' ';
        header += text.substr(0, close);
        if (close != std::string_view::npos) {
            if (!trim(text.substr(close + 1)).empty()) {
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
        const auto fields = split_fields(trim(h));
        if (fields.size() == 12) {
            std::size_t n = 0;
            const auto f = fields.back();
            const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), n);
            if (ec == std::errc() && end == f.data() + f.size()) declared = n;
        }
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

/// Writes `profile` as CSV to the file at `path` (created or replaced).
template <Real T>
void write_sound_speed_csv(const std::filesystem::path& path, const propagation::sound_speed_profile<T>& profile) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw file_error(path.string(), 0, "cannot open for writing");
    write_sound_speed_csv(out, profile, path.string());
}

} // namespace sss::io
