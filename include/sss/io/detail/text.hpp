#pragma once
/// \file
/// The text-parsing core shared by sss's readers (height fields, sound-speed profiles, trajectories), so that
/// they agree on what a line, a comment, a field and a number are:
///
/// - a UTF-8 byte order mark at the start of the text is skipped; lines end at '\n' ('\r' before it is a blank);
/// - '#' starts a comment that runs to the end of the line (readers of formats without comments opt out);
/// - blanks are space, tab, '\r', '\v' and '\f'; blank lines (after the comment is removed) are skipped;
/// - a delimited line is split at ',' or ';' when it holds either (blanks around each field are ignored),
///   otherwise at runs of blanks;
/// - a number fills its whole field: decimal or scientific (`std::from_chars`), with an optional leading '+';
///   a size is an unsigned decimal integer;
/// - an error names the file (or the name given for a stream), the 1-based line and, where one field is at
///   fault, its 1-based column (in bytes from the start of the line).

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <istream>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

#include "sss/core/error.hpp"

namespace sss::detail {

/// True for the blanks of the text core: space, tab, CR, VT, FF (not LF, which ends a line).
[[nodiscard]] constexpr bool is_blank(char c) noexcept {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// True for a blank or a line feed.
[[nodiscard]] constexpr bool is_space(char c) noexcept { return c == '\n' || is_blank(c); }

/// `s` without leading and trailing blanks and line feeds.
[[nodiscard]] inline std::string_view trim(std::string_view s) noexcept {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
}

/// ASCII lower case of `s` (other bytes unchanged).
[[nodiscard]] inline std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

/// True when `text` starts with `prefix`, ignoring ASCII case.
[[nodiscard]] inline bool iequals_prefix(std::string_view text, std::string_view prefix) noexcept {
    if (text.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i) {
        char a = text[i], b = prefix[i];
        if (a >= 'A' && a <= 'Z') a = static_cast<char>(a - 'A' + 'a');
        if (b >= 'A' && b <= 'Z') b = static_cast<char>(b - 'A' + 'a');
        if (a != b) return false;
    }
    return true;
}

/// `s` in single quotes, for error messages. (Appended rather than `"'" + std::string(s)`: at -O3 GCC 12 warns of a
/// memcpy bound in that insert, a false -Wstringop-overflow.)
[[nodiscard]] inline std::string quote(std::string_view s) {
    std::string out;
    out.reserve(s.size() + 2);
    out += '\'';
    out.append(s);
    out += '\'';
    return out;
}

/// The number spelled by the whole of `field` (an optional leading '+'; "inf" and "nan" parse too), or nullopt.
[[nodiscard]] inline std::optional<double> parse_double(std::string_view field) noexcept {
    if (!field.empty() && field.front() == '+') {
        field.remove_prefix(1); // from_chars rejects '+'
        if (!field.empty() && field.front() == '-') return std::nullopt;
    }
    if (field.empty()) return std::nullopt;
    double v = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (ec != std::errc{} || end != field.data() + field.size()) return std::nullopt;
    return v;
}

/// The number spelled by the whole of `field` as a T, rounded once from the decimal (parsing a double and rounding
/// that to float rounds twice, which for a few values, 7.038531e-26 among them, gives the float next to the nearest);
/// nullopt as parse_double. Infinite where the value is beyond T's range.
template <class T> [[nodiscard]] inline std::optional<T> parse_as(std::string_view field) noexcept {
    if constexpr (std::is_same_v<T, double>) {
        return parse_double(field);
    } else {
        const auto d = parse_double(field); // the grammar, and the range: from_chars reports overflow as an error
        if (!d) return std::nullopt;
        if (field.front() == '+') field.remove_prefix(1);
        T v{};
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
        if (ec != std::errc{} || end != field.data() + field.size()) return static_cast<T>(*d); // out of T's range
        return v;
    }
}

/// A finite number spelled by the whole of `field`, or nullopt.
[[nodiscard]] inline std::optional<double> parse_finite(std::string_view field) noexcept {
    const auto v = parse_double(field);
    if (!v || !std::isfinite(*v)) return std::nullopt;
    return v;
}

/// An unsigned decimal integer spelled by the whole of `field` (an optional leading '+'), or nullopt.
[[nodiscard]] inline std::optional<std::size_t> parse_size(std::string_view field) noexcept {
    if (!field.empty() && field.front() == '+') field.remove_prefix(1);
    if (field.empty()) return std::nullopt;
    std::size_t v = 0;
    const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (ec != std::errc{} || end != field.data() + field.size()) return std::nullopt;
    return v;
}

/// Appends the shortest decimal form of x that reads back to x.
template <class V> inline void append_number(std::string& out, V x) {
    std::array<char, 64> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
    out.append(buf.data(), res.ptr);
}

/// x converted to T; nullopt when it is not finite in T (a double beyond float's range, say).
template <class T> [[nodiscard]] inline std::optional<T> finite_as(double x) {
    const T v = static_cast<T>(x);
    if (!std::isfinite(v)) return std::nullopt;
    return v;
}

/// The shortest decimal form of x that reads back to x.
template <class V> [[nodiscard]] inline std::string shortest(V x) {
    std::string s;
    append_number(s, x);
    return s;
}

/// A file_error at a line and (when not 0) a column of a text: "name:line: column c: why".
[[nodiscard]] inline file_error error_at(std::string_view name, std::size_t line, std::size_t column,
                                         std::string_view why) {
    if (column == 0) return file_error(name, line, why);
    return file_error(name, line, "column " + std::to_string(column) + ": " + std::string(why));
}

/// One non-blank line of a text: its content with the comment and surrounding blanks removed (never empty),
/// its 1-based number and the 1-based column at which the content starts.
struct text_line {
    std::string_view text;
    std::size_t number = 0;
    std::size_t column = 1;
};

/// One field of a line and its 1-based column in the line.
struct text_field {
    std::string_view text;
    std::size_t column = 1;
};

/// The non-blank lines of `text` (see the file comment); `comment` is the comment character, or '\0' for none.
[[nodiscard]] inline std::vector<text_line> content_lines(std::string_view text, char comment = '#') {
    std::vector<text_line> lines;
    std::size_t bom = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
    std::size_t number = 0;
    for (std::size_t pos = 0; pos <= text.size();) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view raw = text.substr(pos, end - pos);
        const std::size_t line_start = pos;
        pos = end + 1;
        ++number;
        std::size_t skip = 0;
        if (number == 1) skip = bom;
        raw.remove_prefix(skip);
        if (comment != '\0')
            if (const auto c = raw.find(comment); c != std::string_view::npos) raw = raw.substr(0, c);
        std::size_t lead = 0;
        while (lead < raw.size() && is_blank(raw[lead])) ++lead;
        raw.remove_prefix(lead);
        while (!raw.empty() && is_blank(raw.back())) raw.remove_suffix(1);
        if (raw.empty()) continue;
        lines.push_back({raw, number, static_cast<std::size_t>(raw.data() - (text.data() + line_start)) + 1});
    }
    return lines;
}

/// The fields of `line` separated by runs of blanks, each with its column.
[[nodiscard]] inline std::vector<text_field> split_blanks(const text_line& line) {
    std::vector<text_field> fields;
    const std::string_view s = line.text;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && is_blank(s[i])) ++i;
        std::size_t j = i;
        while (j < s.size() && !is_blank(s[j])) ++j;
        if (j > i) fields.push_back({s.substr(i, j - i), line.column + i});
        i = j;
    }
    return fields;
}

/// The fields of `line` (see the file comment: ',' or ';' when present, else blanks), each with its column.
[[nodiscard]] inline std::vector<text_field> split_fields(const text_line& line) {
    std::vector<text_field> fields;
    const std::string_view s = line.text;
    const auto at = [&](std::string_view f) { return line.column + static_cast<std::size_t>(f.data() - s.data()); };
    if (s.find_first_of(",;") != std::string_view::npos) {
        std::size_t start = 0;
        for (;;) {
            const std::size_t end = s.find_first_of(",;", start);
            std::string_view f = s.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
            while (!f.empty() && is_blank(f.front())) f.remove_prefix(1);
            while (!f.empty() && is_blank(f.back())) f.remove_suffix(1);
            // An empty field's column is where it would have started.
            fields.push_back({f, f.empty() ? line.column + start : at(f)});
            if (end == std::string_view::npos) break;
            start = end + 1;
        }
        return fields;
    }
    return split_blanks(line);
}

/// A whitespace-separated token of a text and the line and column it starts on (1-based).
struct token {
    std::string_view text;
    std::size_t line = 0;
    std::size_t column = 0;
};

/// Splits a text into whitespace-separated tokens, tracking lines; '#' comments (to the end of the line) are
/// skipped when enabled. For formats that are a stream of tokens rather than of delimited lines (ESRI grids).
class tokenizer {
public:
    tokenizer(std::string_view text, bool hash_comments) : text_(text), comments_(hash_comments) {
        if (text_.starts_with("\xEF\xBB\xBF")) pos_ = line_start_ = 3;
    }

    /// The next token, or an empty one at the end (its line is then the text's last line).
    token next() {
        skip_space();
        if (pos_ >= text_.size()) return token{{}, !text_.empty() && text_.back() == '\n' ? line_ - 1 : line_, 0};
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
        return token{text_.substr(start, pos_ - start), line_, start - line_start_ + 1};
    }
    [[nodiscard]] std::size_t line() const noexcept { return line_; }
    /// True when only whitespace (and comments) remain.
    [[nodiscard]] bool at_end() {
        skip_space();
        return pos_ >= text_.size();
    }
    /// A saved place in the text, for look-ahead.
    struct place {
        std::size_t pos, line, line_start;
    };
    [[nodiscard]] place save() const noexcept { return {pos_, line_, line_start_}; }
    void rewind(const place& p) noexcept {
        pos_ = p.pos;
        line_ = p.line;
        line_start_ = p.line_start;
    }

private:
    void skip_space() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_;
                ++pos_;
                line_start_ = pos_;
            } else if (is_blank(c)) {
                ++pos_;
            } else if (comments_ && c == '#') {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else {
                break;
            }
        }
    }
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t line_start_ = 0;
    bool comments_;
};

/// The whole of `in` as bytes; file_error naming `name` when the stream fails.
[[nodiscard]] inline std::string read_stream(std::istream& in, std::string_view name) {
    std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) throw file_error(name, 0, "read error", data.size());
    return data;
}

} // namespace sss::detail
