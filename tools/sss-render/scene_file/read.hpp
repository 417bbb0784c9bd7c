#pragma once
/// \file
/// Reading a scene file (TOML, through toml++) into a resolved `description`. Every error is a `scene_error`
/// whose one-line message names the file, the line and column, the key path and what is wrong; an unknown key
/// is an error that suggests the closest valid key.

#include "error.hpp"
#include "scene.hpp"

#include <sss/core/constants.hpp>
#include <sss/core/error.hpp>
#include <sss/scattering/lambertian.hpp>
#include <sss/scattering/sediments.hpp>
#include <sss/seabed/composite.hpp>

// toml++ is compiled here, header-only, with its internal checks switched off rather than assumed. toml++ 3.3's
// parser asserts a condition on some malformed keys that it then goes on to report as an ordinary parse error
// (with line and column); under NDEBUG it *assumes* that condition instead, which is undefined behaviour when it
// fails. Fuzzing found one: a table header "[,". This is the only file that includes toml++, so every
// translation unit sees the same definitions.
#pragma push_macro("NDEBUG")
#undef NDEBUG
#undef TOML_HEADER_ONLY
#define TOML_HEADER_ONLY 1
#define TOML_ASSERT(expr) static_cast<void>(0)
#include <toml++/toml.h>
#pragma pop_macro("NDEBUG")

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace sss::scene_file {

namespace detail {
/// toml++ 3.3 tells whitespace from other code points through a table with gaps: for most code points of the Basic
/// Multilingual Plane outside ASCII (U+00A1 to U+0499 among them) it reaches an unreachable branch, undefined
/// behaviour wherever it checks for whitespace (found by fuzzing: a bare value such as `3t"\u0159`, or the first
/// character after a line-ending backslash in a multi-line string). Before toml++ reads a scene, every such code
/// point is therefore moved to plane 16 (private use: U+100000 plus the code point), where toml++'s checks return
/// at once; strings, key names and messages are moved back. Plane 16 is not available to scene files.
inline constexpr char32_t plane16 = 0x100000;

/// The well-formed UTF-8 sequence (RFC 3629) at t[i]: its code point and length, or length 0.
inline std::size_t utf8_at(std::string_view t, std::size_t i, char32_t& cp) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(t[k]); };
    const unsigned lead = byte(i);
    std::size_t n = 0;
    if (lead >= 0xC2 && lead <= 0xDF) n = 2, cp = lead & 0x1Fu;
    else if (lead >= 0xE0 && lead <= 0xEF) n = 3, cp = lead & 0x0Fu;
    else if (lead >= 0xF0 && lead <= 0xF4) n = 4, cp = lead & 0x07u;
    else return 0;
    if (i + n > t.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        if ((byte(i + k) & 0xC0u) != 0x80u) return 0;
        cp = (cp << 6) | (byte(i + k) & 0x3Fu);
    }
    constexpr char32_t least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return n;
}

inline void append_utf8(std::string& out, char32_t cp) {
    const auto put = [&](unsigned v) { out.push_back(static_cast<char>(v)); };
    const auto c = static_cast<unsigned>(cp);
    if (c < 0x80) put(c);
    else if (c < 0x800) put(0xC0 | (c >> 6)), put(0x80 | (c & 0x3F));
    else if (c < 0x10000) put(0xE0 | (c >> 12)), put(0x80 | ((c >> 6) & 0x3F)), put(0x80 | (c & 0x3F));
    else put(0xF0 | (c >> 18)), put(0x80 | ((c >> 12) & 0x3F)), put(0x80 | ((c >> 6) & 0x3F)), put(0x80 | (c & 0x3F));
}

/// The text toml++ reads: code points U+0080 to U+FFFF moved to plane 16 (a leading byte order mark stays, and
/// toml++ skips it; code points beyond U+FFFF stay, toml++'s checks return at once for them); bytes that are not well-formed UTF-8 stay as they are, for toml++ to report. A code point of
/// plane 16 in the text is a scene_error naming its line and column.
inline std::string to_plane16(std::string_view t, const std::string& file) {
    std::string out;
    out.reserve(t.size() + t.size() / 2);
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < t.size();) {
        char32_t cp = 0;
        const std::size_t n = static_cast<unsigned char>(t[i]) < 0x80 ? 0 : utf8_at(t, i, cp);
        if (n == 0) {
            if (t[i] == '\n') ++line, column = 0;
            out.push_back(t[i++]);
        } else {
            if (cp >= plane16)
                throw scene_error(file + ":" + std::to_string(line) + ":" + std::to_string(column) +
                                         ": a private-use character of plane 16, which scene files cannot hold");
            if (cp > 0xFFFF || (i == 0 && cp == 0xFEFF)) out.append(t.substr(i, n));
            else append_utf8(out, plane16 + cp);
            i += n;
        }
        ++column;
    }
    return out;
}

/// The deepest dotted key a scene file may hold (`a.b.c = 1`, `[a.b.c]`): toml++ bounds nested values but walks a
/// dotted key recursively, so a key of 100,000 parts overflowed the stack. A scene's deepest is 3.
inline constexpr std::size_t max_key_parts = 64;

/// Throws scene_error at the first key of more than max_key_parts parts: chains of bare keys or quoted strings
/// joined by dots, outside comments and strings (numbers such as 1.5 make chains of two).
inline void check_key_depth(std::string_view t, const std::string& file) {
    std::size_t line = 1, line_start = 0, parts = 0, chain_start = 0;
    bool after_dot = false;
    const auto bare = [](char c) {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '+';
    };
    for (std::size_t i = 0; i < t.size();) {
        const char c = t[i];
        if (c == '\n') {
            ++line, line_start = ++i, parts = 0, after_dot = false;
            continue;
        }
        if (c == '#') { // a comment, to the end of the line
            while (i < t.size() && t[i] != '\n') ++i;
            continue;
        }
        if (c == '"' || c == '\'') { // a string (a quoted key part, or a value), multi-line ones included
            const std::string_view three = c == '"' ? std::string_view("\"\"\"") : std::string_view("\'\'\'");
            const bool triple = t.substr(i, 3) == three;
            const std::string_view close = triple ? three : three.substr(0, 1); // no allocation per string
            std::size_t j = i + close.size();
            while (j < t.size() && t.compare(j, close.size(), close) != 0) {
                if (t[j] == '\\' && c == '"' && j + 1 < t.size()) ++j; // an escape in a basic string: its next character
                if (t[j] == '\n') {
                    if (!triple) break;
                    ++line, line_start = j + 1;
                }
                ++j;
            }
            if (!after_dot) parts = 0, chain_start = i;
            const bool closed = j < t.size() && t.compare(j, close.size(), close) == 0;
            i = closed ? j + close.size() : j; // unclosed: toml++ says where
            // A multi-line string may end in one or two quotes of its own before its closing three ("""a"""").
            for (int extra = 0; closed && triple && extra < 2 && i < t.size() && t[i] == c; ++extra) ++i;
            ++parts, after_dot = false;
        } else if (bare(c)) {
            if (!after_dot) parts = 0, chain_start = i;
            while (i < t.size() && bare(t[i])) ++i;
            ++parts, after_dot = false;
        } else if (c == '.') {
            after_dot = parts > 0;
            ++i;
        } else {
            if (c != ' ' && c != '\t') parts = 0, after_dot = false;
            ++i;
        }
        if (parts > max_key_parts)
            throw scene_error(file + ":" + std::to_string(line) + ":" + std::to_string(chain_start - line_start + 1) +
                              ": a dotted key of more than " + std::to_string(max_key_parts) + " parts");
    }
}

/// `to_plane16` undone: code points U+100080 to U+10FFFF moved back to U+0080 to U+FFFF.
inline std::string from_plane16(std::string_view t) {
    std::string out;
    out.reserve(t.size());
    for (std::size_t i = 0; i < t.size();) {
        char32_t cp = 0;
        const std::size_t n = static_cast<unsigned char>(t[i]) < 0x80 ? 0 : utf8_at(t, i, cp);
        if (n == 0) {
            out.push_back(t[i++]);
            continue;
        }
        if (cp >= plane16 + 0x80) append_utf8(out, cp - plane16);
        else out.append(t.substr(i, n));
        i += n;
    }
    return out;
}


/// Levenshtein distance (Levenshtein, 1966, Soviet Physics Doklady 10(8)), for "did you mean".
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
            diag = up;
        }
    }
    return row[b.size()];
}

/// Reads one table: typed getters that record each key they read, then `finish()` rejects the others.
class table_reader {
public:
    table_reader(const std::string& file, const toml::table& t, std::string path)
        : file_(file), t_(t), path_(std::move(path)) {}

    [[nodiscard]] std::string key_path(std::string_view key) const {
        return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
    }
    [[noreturn]] void fail_at(const toml::source_region& where, std::string_view key, const std::string& why) const {
        std::ostringstream s;
        s << file_;
        if (where.begin.line != 0) s << ':' << where.begin.line << ':' << where.begin.column;
        s << ": " << key_path(key) << ": " << why;
        throw scene_error(from_plane16(s.str()));
    }
    [[noreturn]] void fail(std::string_view key, const std::string& why) const {
        const toml::node* n = t_.get(key);
        fail_at(n ? n->source() : t_.source(), key, why);
    }
    /// Where this table begins and its key path ("scene.toml:12:1: object[0]"), for errors found once the scene is
    /// built.
    [[nodiscard]] std::string where() const {
        std::ostringstream s;
        s << file_;
        if (t_.source().begin.line != 0) s << ':' << t_.source().begin.line << ':' << t_.source().begin.column;
        s << ": " << path_;
        return from_plane16(s.str());
    }

    [[nodiscard]] const toml::node* node(std::string_view key) {
        seen_.insert(std::string(key));
        return t_.get(key);
    }

    /// A finite number, within the bound its unit allows (unit_bound).
    void number(std::string_view key, double& v) {
        if (const auto* n = node(key)) {
            if (auto d = number_of(*n)) {
                if (!std::isfinite(*d)) fail(key, "must be a finite number");
                if (const auto b = unit_bound(key); b.limit > 0 && !(std::abs(*d) <= b.limit))
                    fail(key, "must lie within +-" + fmt(b.limit) + unit_text(b) + ", got " + fmt(*d));
                v = *d;
            } else
                fail(key, std::string("must be a number, not ") + type_name(*n));
        }
    }
    /// A number > 0, and at least its unit's least value (unit_bound).
    void positive(std::string_view key, double& v) {
        number(key, v);
        if (!(v > 0)) fail(key, "must be > 0, got " + fmt(v));
        not_vanishing(key, v, false);
    }
    /// What a key's unit allows, from its name: the largest magnitude, and the least value a quantity that must
    /// be > 0 may take (smaller ones vanish in single precision or in the renderer's arithmetic). Lengths (`_m`):
    /// within 1e8 m (beyond any survey, UTM's 1e7 m northings included), at least 1e-9 m; levels (`_db`): within
    /// 300 dB (10^30 in power, within single precision with room for the echoes); angles (`_deg`): within 1e6
    /// degrees; times (`_s`): within 1e12 s, at least 1e-9 s; speeds (`_mps`): within 1e5 m/s, at least 1e-6 m/s;
    /// frequencies (`_hz`): within 1e10 Hz, at least 1e-6 Hz. Keys without a unit (ratios, indices, shape
    /// parameters): within 1e30, at least 1e-30, so that single precision holds them (a symmetry index of 1e-300
    /// would become 0); most of them keep narrower checks of their own.
    struct bound {
        double limit = 0; ///< largest magnitude; 0: none
        double least = 0; ///< least value of a quantity > 0
        const char* unit = "";
    };
    [[nodiscard]] static bound unit_bound(std::string_view key) {
        if (key.ends_with("_m")) return {1e8, 1e-9, "m"};
        if (key.ends_with("_db")) return {300, 0, "dB"};
        if (key.ends_with("_deg")) return {1e6, 0, "degrees"};
        if (key.ends_with("_mps")) return {1e5, 1e-6, "m/s"};
        if (key.ends_with("_hz")) return {1e10, 1e-6, "Hz"};
        if (key.ends_with("_s")) return {1e12, 1e-9, "s"};
        return {1e30, 1e-30, ""};
    }
    /// " m", or nothing for a key without a unit.
    [[nodiscard]] static std::string unit_text(const bound& b) { return *b.unit ? std::string(" ") + b.unit : std::string(); }
    void non_negative(std::string_view key, double& v) {
        number(key, v);
        if (!(v >= 0)) fail(key, "must be >= 0, got " + fmt(v));
        if (v > 0) not_vanishing(key, v, true);
    }
    /// A value > 0 that would vanish in the renderer's arithmetic (below its unit's least value) is an error.
    void not_vanishing(std::string_view key, double v, bool zero_allowed) const {
        if (const auto b = unit_bound(key); v < b.least)
            fail(key, std::string(zero_allowed ? "must be 0 or at least " : "must be at least ") + fmt(b.least) + unit_text(b) +
                          ", got " + fmt(v));
    }
    void in_range(std::string_view key, double& v, double lo, double hi) {
        number(key, v);
        if (!(v >= lo && v <= hi)) fail(key, "must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(v));
    }
    void integer(std::string_view key, std::int64_t& v, std::int64_t lo = std::numeric_limits<std::int64_t>::min(),
                 std::int64_t hi = std::numeric_limits<std::int64_t>::max()) {
        if (const auto* n = node(key)) {
            if (!n->is_integer()) fail(key, std::string("must be an integer, not ") + type_name(*n));
            v = n->value<std::int64_t>().value();
            if (v < lo) fail(key, "must be >= " + std::to_string(lo) + ", got " + std::to_string(v));
            if (v > hi) fail(key, "must be <= " + std::to_string(hi) + ", got " + std::to_string(v));
        }
    }
    void boolean(std::string_view key, bool& v) {
        if (const auto* n = node(key)) {
            if (!n->is_boolean()) fail(key, std::string("must be true or false, not ") + type_name(*n));
            v = n->value<bool>().value();
        }
    }
    void string(std::string_view key, std::string& v) {
        if (const auto* n = node(key)) {
            if (!n->is_string()) fail(key, std::string("must be a string, not ") + type_name(*n));
            v = from_plane16(n->value<std::string>().value());
            // A NUL would end a file name early (another file read) and a line of a label file.
            if (v.find('\0') != std::string::npos) fail(key, "must not hold a NUL character (\\u0000)");
        }
    }
    void choice(std::string_view key, std::string& v, std::initializer_list<std::string_view> allowed) {
        string(key, v);
        if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) return;
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(key, "unknown value '" + v + "'" + suggestion(v, allowed) + " (one of: " + list + ")");
    }
    void point(std::string_view key, xy& v) {
        if (const auto* n = node(key)) v = point_of(*n, key);
    }
    [[nodiscard]] xy point_of(const toml::node& n, std::string_view key) const {
        const auto* a = n.as_array();
        if (!a || a->size() != 2 || !all_numbers(*a))
            fail_at(n.source(), key, "must be a pair of numbers [x_m, y_m]");
        const xy v{*number_of(*a->get(0)), *number_of(*a->get(1))};
        if (!std::isfinite(v[0]) || !std::isfinite(v[1])) fail_at(n.source(), key, "must be a pair of finite numbers");
        if (const auto b = unit_bound(key); b.limit > 0 && !(std::abs(v[0]) <= b.limit && std::abs(v[1]) <= b.limit))
            fail_at(n.source(), key, "must lie within +-" + fmt(b.limit) + unit_text(b));
        return v;
    }
    /// The sub-table at key (absent: an empty table).
    [[nodiscard]] table_reader sub(std::string_view key) {
        static const toml::table empty;
        const auto* n = node(key);
        if (!n) return {file_, empty, key_path(key)};
        if (!n->is_table()) fail(key, std::string("must be a table, not ") + type_name(*n));
        return {file_, *n->as_table(), key_path(key)};
    }
    /// Each table of the array of tables at key ([[key]] in TOML).
    [[nodiscard]] std::vector<table_reader> tables(std::string_view key) {
        std::vector<table_reader> out;
        const auto* n = node(key);
        if (!n) return out;
        const auto* a = n->as_array();
        if (!a) fail(key, std::string("must be an array of tables ([[") + key_path(key) + "]]), not " + type_name(*n));
        for (std::size_t i = 0; i < a->size(); ++i) {
            const auto* t = a->get(i)->as_table();
            if (!t) fail_at(a->get(i)->source(), key, "element " + std::to_string(i) + " must be a table");
            out.emplace_back(file_, *t, key_path(key) + "[" + std::to_string(i) + "]");
        }
        return out;
    }
    /// Rejects every key not read, suggesting the closest one that was.
    void finish() const {
        for (const auto& [k, v] : t_) {
            const std::string name(k.str());
            if (seen_.count(name)) continue;
            std::vector<std::string_view> known(seen_.begin(), seen_.end());
            fail_at(k.source(), name, "unknown key" + suggestion(name, known));
        }
    }
    [[nodiscard]] const toml::table& table() const noexcept { return t_; }
    [[nodiscard]] bool was_read(const std::string& key) const { return seen_.count(key) != 0; }
    [[nodiscard]] const std::string& path() const noexcept { return path_; }

    template <class Range> static std::string suggestion(std::string_view got, const Range& known) {
        std::string best;
        std::size_t best_d = std::numeric_limits<std::size_t>::max();
        for (std::string_view k : known) {
            const std::size_t d = edit_distance(got, k);
            if (d < best_d) best_d = d, best = std::string(k);
        }
        if (best.empty() || best_d > std::max<std::size_t>(2, got.size() / 2)) return "";
        return "; did you mean '" + best + "'?";
    }
    static std::string suggestion(std::string_view got, std::initializer_list<std::string_view> known) {
        return suggestion<std::initializer_list<std::string_view>>(got, known);
    }
    /// A number in a message: 15 significant digits, so that a bound and a value just past it read apart.
    static std::string fmt(double v) {
        std::ostringstream s;
        s.precision(15);
        s << v;
        return s.str();
    }

    /// A number node's value as a double: an integer rounded to the nearest double (toml++ gives none for an integer
    /// a double cannot hold exactly, beyond 2^53); empty for any other node.
    [[nodiscard]] static std::optional<double> number_of(const toml::node& n) {
        if (n.is_floating_point()) return n.value<double>();
        if (const auto i = n.value<std::int64_t>(); i && n.is_integer()) return static_cast<double>(*i);
        return std::nullopt;
    }

private:
    static bool all_numbers(const toml::array& a) {
        for (const auto& e : a)
            if (!e.is_number()) return false;
        return true;
    }
    static const char* type_name(const toml::node& n) {
        switch (n.type()) {
        case toml::node_type::table: return "a table";
        case toml::node_type::array: return "an array";
        case toml::node_type::string: return "a string";
        case toml::node_type::integer: return "an integer";
        case toml::node_type::floating_point: return "a number";
        case toml::node_type::boolean: return "a boolean";
        default: return "a date or time";
        }
    }

    const std::string& file_;
    const toml::table& t_;
    std::string path_;
    std::set<std::string> seen_;
};

/// One axis of a planar array: `<axis>_count`, `<axis>_element_m`, `<axis>_pitch_m` (default the element
/// length: elements edge to edge) and `<axis>_shading` (one weight per element, or empty: uniform).
inline void read_array_axis(table_reader& t, const std::string& axis, array_axis& a) {
    const std::string count = axis + "_count", element = axis + "_element_m", pitch = axis + "_pitch_m", shading = axis + "_shading";
    t.integer(count, a.count, 1);
    if (a.count > 65536) t.fail(count, "must be at most 65536, got " + std::to_string(a.count));
    t.positive(element, a.element_m);
    a.pitch_m = a.element_m;
    t.positive(pitch, a.pitch_m);
    if (a.count > 1 && !(a.pitch_m >= a.element_m))
        t.fail(pitch, "must be at least " + element + " (" + table_reader::fmt(a.element_m) + " m): elements cannot overlap");
    if (const auto* n = t.node(shading)) {
        const auto* list = n->as_array();
        if (!list) t.fail(shading, "must be an array of numbers (one weight per element), or [] for uniform");
        a.shading.clear();
        double sum = 0;
        for (const auto& e : *list) {
            const auto v = table_reader::number_of(e);
            if (!v || !std::isfinite(*v) || *v < 0 || *v > 1e30)
                t.fail(shading, "each weight must be a number in [0, 1e30]");
            a.shading.push_back(*v);
            sum += *v;
        }
        if (!a.shading.empty() && a.shading.size() != std::size_t(a.count))
            t.fail(shading, "must hold one weight per element (" + count + " = " + std::to_string(a.count) + "), got " +
                                std::to_string(a.shading.size()));
        if (!a.shading.empty() && !(sum > 0)) t.fail(shading, "the weights must not all be 0");
    }
}

/// A transmit or receive array table (`[sonar.transmit]`, `[sonar.receive]`): an along and a vertical axis.
/// The keys of each type of [[object]] besides type, class_id and class_name.
inline const std::vector<std::pair<std::string_view, std::vector<std::string_view>>> object_keys{
    {"lying_cylinder", {"center_m", "heading_deg", "length_m", "radius_m"}},
    {"sphere", {"center_m", "height_m", "radius_m"}},
    {"cylinder", {"center_m", "end_m", "end0_height_m", "end1_height_m", "radius_m"}},
    {"tethered_mine", {"anchor_m", "case_shape", "case_height_m", "case_radius_m", "case_length_m", "case_heading_deg"}},
    {"pipeline", {"route_m", "radius_m", "max_span_m"}},
};

/// A Lambertian parameter (dB) at most 10 log10(1/pi) = -4.9715 dB: a perfectly diffuse surface scatters at most what
/// it receives (the library's lambertian holds the same bound; here it names the scene's key and line).
inline void lambert_bound(const table_reader& t, std::string_view key, double mu_db) {
    if (!(mu_db <= sss::scattering::lambert_max_db))
        t.fail(key, "must be <= -4.9715 dB (a Lambertian surface scatters at most 1/pi of what it receives), got " +
                        table_reader::fmt(mu_db));
}

inline void read_array_layout(table_reader t, array_layout& a) {
    read_array_axis(t, "along", a.along);
    read_array_axis(t, "vertical", a.vertical);
    t.finish();
}

} // namespace detail

/// The scene in TOML text `text`, read as if from file `file` (its name is used in messages).

[[nodiscard]] inline description parse(std::string_view text, const std::string& file) {
    detail::check_key_depth(text, file);
    const std::string shifted = detail::to_plane16(text, file);
    toml::table root;
    try {
        root = toml::parse(shifted, file);
    } catch (const toml::parse_error& e) {
        std::ostringstream s;
        s << file << ':' << e.source().begin.line << ':' << e.source().begin.column << ": " << e.description();
        throw scene_error(detail::from_plane16(s.str()));
    }
    description d;
    d.path = file;
    detail::table_reader top(file, root, "");

    {
        auto r = top.sub("render");
        r.integer("pings", d.run.pings, 1, max_pings);
        r.integer("threads", d.run.threads, 0, max_threads);
        r.integer("rays_along", d.run.rays_along, 1);
        if (d.run.rays_along > 4096) r.fail("rays_along", "must be <= 4096, got " + std::to_string(d.run.rays_along));
        r.positive("rays_per_sample", d.run.rays_per_sample);
        if (d.run.rays_per_sample > 1024)
            r.fail("rays_per_sample", "must be <= 1024, got " + detail::table_reader::fmt(d.run.rays_per_sample));
        r.choice("seabed_edges_along", d.run.seabed_edges_along, {"auto", "on", "off"});
        r.integer("along_split", d.run.along_split, 1);
        if (d.run.along_split > 6561) r.fail("along_split", "must be <= 6561 (3^8), got " + std::to_string(d.run.along_split));
        r.boolean("along_split_by_weight", d.run.along_split_by_weight);
        r.boolean("refine_facets", d.run.refine_facets);
        r.boolean("bracket_facet_edges", d.run.bracket_facet_edges);
        r.boolean("along_split_sparse", d.run.along_split_sparse);
        r.boolean("along_split_targets", d.run.along_split_targets);
        r.boolean("along_split_nadir", d.run.along_split_nadir);
        r.non_negative("along_split_echo", d.run.along_split_echo);
        r.non_negative("along_onset", d.run.along_onset);
        r.non_negative("max_launch_step_deg", d.run.max_launch_step_deg);
        if (d.run.max_launch_step_deg > 90.0)
            r.fail("max_launch_step_deg", "must be <= 90, got " + detail::table_reader::fmt(d.run.max_launch_step_deg));
        r.boolean("sloping_launch", d.run.sloping_launch);
        r.choice("precision", d.run.precision, {"float", "double"});
        r.finish();
    }
    {
        // The Lambert bound holds where Lambert's law is used: sonar.scattering, peeked at before it is read.
        const auto* sonar_table = top.table().get_as<toml::table>("sonar");
        const auto* scattering = sonar_table ? sonar_table->get_as<std::string>("scattering") : nullptr;
        const bool lambert_scene = !scattering || scattering->get() == "lambertian";
        auto s = top.sub("seabed");
        auto& b = d.bed;
        s.string("file", b.file);
        if (seabed_format_of(b.file) == seabed_format::unknown)
            s.fail("file", "'" + b.file + "' is not a height file sss reads (.asc, .raw with its .raw.txt sidecar, .pgm)");
        // A key the seabed would not use is an error rather than ignored (as [[seabed.region]] with a file is). The
        // regions are read below; here it matters only how many there are (a value that is not an array of tables is
        // refused there).
        const toml::node* region_node = s.table().get("region");
        const std::size_t regions = !region_node ? 0 : region_node->is_array() ? region_node->as_array()->size() : 1;
        for (const auto& [key, why] : unused_seabed_keys(b.file, regions))
            if (s.table().get(key)) s.fail(key, why);
        s.number("pgm_scale_m", b.pgm_scale_m);
        if (b.pgm_scale_m == 0) s.fail("pgm_scale_m", "must not be 0");
        s.number("pgm_offset_m", b.pgm_offset_m);
        s.integer("nx", b.nx, 2);
        s.integer("ny", b.ny, 2);
        s.positive("cell_m", b.cell_m);
        s.point("origin_m", b.origin_m);
        s.integer("seed", b.seed, 0);
        s.non_negative("blend_m", b.blend_m);
        // Held to the blend's reach only where it blends (two or more regions): a seabed that does not use it keeps
        // the default, whatever its cell (at cell_m = 1 mm the default 0.5 m is 500 cells).
        const auto unused = unused_seabed_keys(b.file, regions);
        const bool blends = std::none_of(unused.begin(), unused.end(), [](const auto& u) { return u.key == std::string_view("blend_m"); });
        if (blends && !(b.blend_m <= sss::seabed::max_blend_cells * b.cell_m))
            s.fail("blend_m", "must be at most " + detail::table_reader::fmt(sss::seabed::max_blend_cells) + " cells (" +
                                  detail::table_reader::fmt(sss::seabed::max_blend_cells * b.cell_m) +
                                  " m at cell_m = " + detail::table_reader::fmt(b.cell_m) + " m): the blend is smoothed cell by cell");
        s.non_negative("warp_m", b.warp_m);
        s.positive("warp_scale_m", b.warp_scale_m);
        s.integer("partition_seed", b.partition_seed, 0);
        for (auto& rt : s.tables("region")) {
            region g;
            rt.string("sediment", g.sediment);
            try {
                (void)sss::scattering::sediment_preset<double>(g.sediment);
            } catch (const sss::error&) {
                rt.fail("sediment", "unknown sediment '" + g.sediment + "' (one of: " + sss::scattering::sediment_names() + ")");
            }
            rt.number("mean_height_m", g.mean_height_m);
            rt.non_negative("outer_scale_m", g.outer_scale_m);
            rt.number("mu_db", g.mu_db);
            if (lambert_scene) lambert_bound(rt, "mu_db", g.mu_db);
            for (auto& pt : rt.tables("ripples")) {
                ripples p;
                pt.positive("wavelength_m", p.wavelength_m);
                if (p.wavelength_m < 2 * b.cell_m)
                    pt.fail("wavelength_m", "must be at least 2 cells (" + detail::table_reader::fmt(2 * b.cell_m) + " m)");
                pt.non_negative("height_m", p.height_m);
                pt.number("crest_heading_deg", p.crest_heading_deg);
                pt.positive("symmetry_index", p.symmetry_index);
                pt.non_negative("sinuosity_m", p.sinuosity_m);
                pt.non_negative("sinuosity_wavelength_m", p.sinuosity_wavelength_m);
                if (p.sinuosity_m > 0 && !(p.sinuosity_wavelength_m > 0))
                    pt.fail("sinuosity_m", "needs sinuosity_wavelength_m > 0 (the meander's wavelength)");
                pt.non_negative("perturbation_m", p.perturbation_m);
                pt.in_range("height_variation", p.height_variation, 0, 1);
                pt.finish();
                g.ripple_sets.push_back(p);
            }
            rt.finish();
            b.regions.push_back(g);
        }
        if (!b.file.empty() && s.table().get("site")) s.fail("site", "a loaded seabed takes no [[seabed.site]] tables");
        for (auto& st : s.tables("site")) {
            site p;
            st.number("x_m", p.x_m);
            st.number("y_m", p.y_m);
            st.integer("region", p.region, 0);
            if (p.region >= std::int64_t(b.regions.size()))
                st.fail("region", "no region " + std::to_string(p.region) + " (the scene has " +
                                      std::to_string(b.regions.size()) + " [[seabed.region]] tables)");
            st.finish();
            b.sites.push_back(p);
        }
        for (auto& st : s.tables("stamp")) {
            stamp p;
            st.choice("type", p.type, {"plate", "mound", "scour", "trench"});
            if (p.type == "trench") {
                st.point("start_m", p.start_m);
                st.point("end_m", p.end_m);
                if (std::hypot(p.end_m[0] - p.start_m[0], p.end_m[1] - p.start_m[1]) < 1e-6)
                    st.fail("end_m", "the trench's ends coincide (closer than 1e-6 m)");
                st.positive("width_m", p.width_m);
                st.non_negative("floor_width_m", p.floor_width_m);
                if (!(p.floor_width_m < p.width_m)) st.fail("floor_width_m", "must be below width_m");
                st.non_negative("depth_m", p.depth_m);
                st.non_negative("berm_height_m", p.berm_height_m);
                st.non_negative("berm_width_m", p.berm_width_m);
                if (p.berm_height_m > 0 && !(p.berm_width_m > 0)) st.fail("berm_height_m", "needs berm_width_m > 0");
            } else {
                st.point("center_m", p.center_m);
                st.number("heading_deg", p.heading_deg);
                if (p.type == "plate") {
                    st.positive("length_m", p.length_m);
                    st.positive("width_m", p.width_m);
                    st.number("top_m", p.top_m);
                } else {
                    st.positive("radius_u_m", p.radius_u_m);
                    st.positive("radius_v_m", p.radius_v_m);
                    if (p.type == "mound") {
                        st.non_negative("height_m", p.height_m);
                    } else {
                        st.non_negative("depth_m", p.depth_m);
                        st.non_negative("rim_height_m", p.rim_height_m);
                        st.non_negative("rim_width_m", p.rim_width_m);
                        if (p.rim_height_m > 0 && !(p.rim_width_m > 0)) st.fail("rim_height_m", "needs rim_width_m > 0");
                    }
                }
            }
            st.finish();
            b.stamps.push_back(p);
        }
        if (!b.file.empty() && !b.stamps.empty()) s.fail("stamp", "a loaded seabed takes no [[seabed.stamp]] tables");
        if (b.regions.size() > 1 && b.sites.empty())
            s.fail("region", "several regions need [[seabed.site]] tables placing them");
        if (!b.file.empty() && !b.regions.empty())
            s.fail("file", "a loaded seabed takes no [[seabed.region]] tables");
        s.finish();
    }
    for (auto& ot : top.tables("object")) {
        object o;
        o.origin = ot.where();
        ot.choice("type", o.type, {"lying_cylinder", "tethered_mine", "pipeline", "sphere", "cylinder"});
        ot.integer("class_id", o.class_id, 1, std::numeric_limits<std::uint32_t>::max());
        o.class_name = o.type;
        ot.string("class_name", o.class_name);
        if (o.class_name.empty()) ot.fail("class_name", "must not be empty");
        if (std::any_of(o.class_name.begin(), o.class_name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
            ot.fail("class_name", "must not hold control characters (a class list holds one name per line)");
        if (o.type == "lying_cylinder") {
            ot.point("center_m", o.center_m);
            ot.number("heading_deg", o.heading_deg);
            ot.positive("length_m", o.length_m);
            // The seabed under its axis is sampled every 5 cm (lying_cylinder_params::profile_step_m), at most 1e7 times.
            if (o.length_m > 4e5) ot.fail("length_m", "must be at most 400 km, got " + detail::table_reader::fmt(o.length_m) + " m");
            ot.positive("radius_m", o.radius_m);
        } else if (o.type == "sphere") {
            o.radius_m = 0.5;
            ot.point("center_m", o.center_m);
            ot.number("height_m", o.height_m);
            ot.positive("radius_m", o.radius_m);
        } else if (o.type == "cylinder") {
            ot.point("center_m", o.center_m);
            ot.point("end_m", o.end_m);
            ot.number("end0_height_m", o.end0_height_m);
            ot.number("end1_height_m", o.end1_height_m);
            ot.positive("radius_m", o.radius_m);
            if (std::hypot(o.end_m[0] - o.center_m[0], o.end_m[1] - o.center_m[1], o.end1_height_m - o.end0_height_m) < 1e-6)
                ot.fail("end_m", "the cylinder's ends coincide (closer than 1e-6 m)");
        } else if (o.type == "tethered_mine") {
            ot.point("anchor_m", o.anchor_m);
            ot.choice("case_shape", o.case_shape, {"sphere", "cylinder"});
            ot.positive("case_height_m", o.case_height_m);
            ot.positive("case_radius_m", o.case_radius_m);
            ot.positive("case_length_m", o.case_length_m);
            ot.number("case_heading_deg", o.case_heading_deg);
        } else {
            o.radius_m = 0.3;
            if (const auto* n = ot.node("route_m")) {
                const auto* a = n->as_array();
                if (!a || a->size() < 2) ot.fail("route_m", "must be an array of at least two [x_m, y_m] points");
                for (const auto& e : *a) {
                    o.route_m.push_back(ot.point_of(e, "route_m"));
                    const std::size_t k = o.route_m.size() - 1;
                    if (k > 0 && std::hypot(o.route_m[k][0] - o.route_m[k - 1][0], o.route_m[k][1] - o.route_m[k - 1][1]) < 1e-6)
                        ot.fail_at(e.source(), "route_m", "point " + std::to_string(k) + " lies on the point before it (closer than 1e-6 m)");
                }
            } else
                ot.fail("type", "a pipeline needs route_m");
            // The seabed along the route is sampled every 10 cm (pipeline_params::profile_step_m), at most 1e8 times.
            double route_length_m = 0;
            for (std::size_t k = 1; k < o.route_m.size(); ++k)
                route_length_m += std::hypot(o.route_m[k][0] - o.route_m[k - 1][0], o.route_m[k][1] - o.route_m[k - 1][1]);
            if (route_length_m > 8e6)
                ot.fail("route_m", "is " + detail::table_reader::fmt(route_length_m) + " m long; at most 8000 km");
            ot.positive("radius_m", o.radius_m);
            ot.non_negative("max_span_m", o.max_span_m);
        }
        // A key of another type of object: say whose, rather than suggest the nearest key of this one.
        for (const auto& [k, v] : ot.table()) {
            const std::string name(k.str());
            if (ot.was_read(name)) continue;
            for (const auto& [type, keys] : detail::object_keys)
                if (type != o.type && std::find(keys.begin(), keys.end(), name) != keys.end())
                    ot.fail_at(k.source(), name, "unknown key for type \"" + o.type + "\": it is a key of type \"" +
                                                     std::string(type) + "\"");
        }
        ot.finish();
        d.objects.push_back(o);
    }
    {
        auto w = top.sub("water");
        auto& o = d.sea;
        w.choice("model", o.model, {"straight", "layered"});
        w.in_range("sound_speed_mps", o.sound_speed_mps, 1300, 1700);
        w.in_range("absorption_db_per_km", o.absorption_db_per_km, 0, 1000);
        if (o.model == "layered") {
            w.string("svp_file", o.svp_file);
            const auto list = [&](std::string_view key, std::vector<double>& v) {
                if (const auto* n = w.node(key)) {
                    const auto* a = n->as_array();
                    if (!a || a->empty()) w.fail(key, "must be a non-empty array of numbers");
                    v.clear();
                    for (const auto& e : *a) {
                        const double x = detail::table_reader::number_of(e).value_or(0.0);
                        if (!e.is_number() || !std::isfinite(x)) w.fail(key, "must be a non-empty array of finite numbers");
                        if (const auto b = detail::table_reader::unit_bound(key); b.limit > 0 && !(std::abs(x) <= b.limit))
                            w.fail(key, "each value must lie within +-" + detail::table_reader::fmt(b.limit) +
                                            detail::table_reader::unit_text(b));
                        v.push_back(x);
                    }
                }
            };
            list("depth_m", o.depth_m);
            list("speed_mps", o.speed_mps);
            if (o.depth_m.size() != o.speed_mps.size())
                w.fail("speed_mps", "needs one speed per depth (" + std::to_string(o.depth_m.size()) + " depths, " +
                                        std::to_string(o.speed_mps.size()) + " speeds)");
            for (std::size_t i = 0; i < o.depth_m.size(); ++i) {
                // Strictly in the render's own precision too: knots that coincide in float are one knot.
                if (i > 0 && (!(o.depth_m[i] > o.depth_m[i - 1]) ||
                              (d.run.precision == "float" && !(float(o.depth_m[i]) > float(o.depth_m[i - 1])))))
                    w.fail("depth_m", "must increase strictly (in the render's precision)");
                if (!(o.speed_mps[i] >= 1300 && o.speed_mps[i] <= 1700)) w.fail("speed_mps", "each speed must be in [1300, 1700]");
            }
            w.non_negative("towfish_depth_m", o.towfish_depth_m);
            w.choice("absorption_model", o.absorption_model, {"francois_garrison", "ainslie_mccolm"});
            w.in_range("temperature_c", o.temperature_c, -2, 40);
            w.in_range("salinity_ppt", o.salinity_ppt, 0, 45);
            w.in_range("ph", o.ph, 6, 9);
        }
        w.finish();
    }
    {
        auto s = top.sub("sonar");
        auto& o = d.sensor;
        s.choice("scattering", o.scattering, {"lambertian", "jackson"});
        s.choice("beam", o.beam, {"ideal_fan", "planar_array"});
        // From infrasound to 10 MHz: beyond, the water absorbs a sidescan's echo within millimetres.
        s.in_range("frequency_hz", o.frequency_hz, 1, 1e7);
        s.number("target_mu_db", o.target_mu_db);
        if (o.scattering == "lambertian") lambert_bound(s, "target_mu_db", o.target_mu_db);
        s.in_range("along_width_deg", o.along_width_deg, 1e-6, 179.999);
        s.in_range("vertical_width_deg", o.vertical_width_deg, 1e-6, 180);
        s.in_range("depression_deg", o.depression_deg, -90, 90);
        s.in_range("sample_rate_hz", o.sample_rate_hz, 1, 1e9);
        s.positive("max_range_m", o.max_range_m);
        s.in_range("source_level_db", o.source_level_db, -300, 300);
        s.positive("pulse_length_s", o.pulse_length_s);
        if (o.pulse_length_s > 1) s.fail("pulse_length_s", "must be at most 1 s, got " + detail::table_reader::fmt(o.pulse_length_s));
        // The simulator holds the pulse's shape sample by sample: at most 2^20 samples of it.
        if (o.pulse_length_s * o.sample_rate_hz > 1048576.0)
            s.fail("pulse_length_s", "spans " + detail::table_reader::fmt(o.pulse_length_s * o.sample_rate_hz) +
                                         " samples at sample_rate_hz = " + detail::table_reader::fmt(o.sample_rate_hz) +
                                         "; at most 2^20 (1048576)");
        s.choice("pulse_shape", o.pulse_shape, {"rectangular", "hann", "lfm"});
        s.non_negative("pulse_bandwidth_hz", o.pulse_bandwidth_hz);
        if (o.pulse_shape != "lfm" && o.pulse_bandwidth_hz > 0)
            s.fail("pulse_bandwidth_hz", "applies only to pulse_shape = \"lfm\" (a burst's band is set by its length)");
        if (o.pulse_shape == "lfm" && !(o.pulse_bandwidth_hz * o.pulse_length_s >= 1 && o.pulse_bandwidth_hz * o.pulse_length_s <= 1e4))
            s.fail("pulse_bandwidth_hz", "an lfm pulse needs pulse_bandwidth_hz x pulse_length_s in [1, 10^4], got " +
                                             detail::table_reader::fmt(o.pulse_bandwidth_hz * o.pulse_length_s));
        if (o.beam == "planar_array") {
            s.number("beam_threshold_db", o.beam_threshold_db);
            if (!(o.beam_threshold_db <= -1e-6))
                s.fail("beam_threshold_db", "must be < 0 dB, got " + detail::table_reader::fmt(o.beam_threshold_db));
            detail::read_array_layout(s.sub("transmit"), o.transmit);
            if (s.table().get("receive")) detail::read_array_layout(s.sub("receive"), o.receive.emplace());
        } else {
            for (const char* key : {"transmit", "receive", "beam_threshold_db"})
                if (s.table().get(key))
                    s.fail(key, "needs beam = \"planar_array\" (the ideal fan has no elements; its keys are along_width_deg, "
                                "vertical_width_deg and depression_deg)");
        }
        s.finish();
    }
    {
        auto m = top.sub("motion");
        auto& o = d.tow;
        m.choice("model", o.model, {"perturbed", "trajectory"});
        if (o.model == "trajectory") {
            m.string("trajectory_file", o.trajectory_file);
            if (o.trajectory_file.empty())
                m.fail(m.table().get("trajectory_file") ? "trajectory_file" : "model",
                       "a trajectory needs motion.trajectory_file (a CSV with time or ping, x, y, z columns)");
            m.choice("interpolation", o.interpolation, {"cubic", "linear"});
            if (m.table().get("ping_zero_at")) m.number("ping_zero_at", o.ping_zero_at.emplace());
            m.boolean("roll_from_turn", o.roll_from_turn);
        } else {
            for (const char* key : {"trajectory_file", "interpolation", "ping_zero_at", "roll_from_turn"})
                if (m.table().get(key)) m.fail(key, "needs model = \"trajectory\" (the perturbed motion takes start_m, heading_deg, ...)");
        }
        // The perturbed motion's keys: read (and checked one by one) under both models, used only by perturbed; the
        // checks across keys (a turn needs a radius or a rate) apply only where they are used.
        m.point("start_m", o.start_m);
        m.number("heading_deg", o.heading_deg);
        m.non_negative("speed_mps", o.speed_mps);
        m.positive("altitude_m", o.altitude_m);
        if (o.altitude_m < 1e-3)
            m.fail("altitude_m", "must be at least 0.001 m (the simulator's least clearance above the seabed), got " +
                                     detail::table_reader::fmt(o.altitude_m));
        m.positive("ping_interval_s", o.ping_interval_s);
        m.choice("turn", o.turn, {"none", "port", "starboard"});
        m.non_negative("turn_radius_m", o.turn_radius_m);
        m.non_negative("turn_rate_deg_s", o.turn_rate_deg_s);
        if (o.model == "perturbed" && o.turn != "none" && !(o.turn_radius_m > 0) && !(o.turn_rate_deg_s > 0))
            m.fail("turn", "a turn needs turn_radius_m > 0 or turn_rate_deg_s > 0");
        // A radius or rate that nothing uses is an error rather than ignored: without a turn, or beside the other.
        for (const auto& [key, v] : {std::pair<std::string_view, double>{"turn_radius_m", o.turn_radius_m}, {"turn_rate_deg_s", o.turn_rate_deg_s}})
            if (o.turn == "none" && v > 0) m.fail(key, "applies only to a turn: set turn = \"port\" or \"starboard\"");
        if (o.turn_radius_m > 0 && o.turn_rate_deg_s > 0)
            m.fail("turn_rate_deg_s", "a turn takes turn_radius_m or turn_rate_deg_s, not both (the radius would win)");
        const auto wobble = [&](std::string_view key, oscillation& w, double limit) {
            auto t = m.sub(key);
            t.number("amplitude", w.amplitude);
            if (limit == 0) limit = detail::table_reader::unit_bound(key).limit; // the table's unit: sway_m, yaw_deg
            if (!(std::abs(w.amplitude) < limit))
                t.fail("amplitude", "must be below " + detail::table_reader::fmt(limit) + " in magnitude");
            t.positive("period_s", w.period_s);
            t.number("phase_deg", w.phase_deg);
            t.finish();
        };
        wobble("yaw_deg", o.yaw_deg, 0);
        wobble("sway_m", o.sway_m, 0);
        wobble("pitch_deg", o.pitch_deg, 90);
        wobble("heave_m", o.heave_m, 0);
        wobble("roll_deg", o.roll_deg, 90);
        m.finish();
    }
    {
        auto r = top.sub("receiver");
        auto& o = d.rx;
        r.integer("seed", o.seed, 0);
        r.boolean("speckle", o.speckle);
        r.in_range("transducer_length_m", o.transducer_length_m, 1e-3, 1e3);
        r.non_negative("k_shape", o.k_shape);
        r.positive("texture_patch_m", o.texture_patch_m);
        r.boolean("noise", o.noise);
        r.in_range("sea_state", o.sea_state, 0, 6);
        r.in_range("directivity_index_db", o.directivity_index_db, 0, 300);
        r.in_range("noise_source_level_db", o.noise_source_level_db, -300, 300);
        r.boolean("volume", o.volume);
        r.in_range("sv_db", o.sv_db, -300, 300);
        r.non_negative("psi_sr", o.psi_sr); // 0: the beam's own
        if (!(o.psi_sr <= 4 * sss::pi_v<double>)) r.fail("psi_sr", "must be at most 4 pi sr (the whole sphere)");
        r.boolean("tvg", o.tvg);
        r.in_range("tvg_spreading_n", o.tvg_spreading_n, -60, 60);
        r.in_range("tvg_gain_db", o.tvg_gain_db, -300, 300);
        r.finish();
    }
    {
        auto o = top.sub("output");
        o.string("stem", d.out.stem);
        if (d.out.stem.size() > max_stem_bytes)
            o.fail("stem", "must be at most " + std::to_string(max_stem_bytes) +
                               " bytes (file names hold 255 with the outputs' suffixes and temporary names)");
        if (d.out.stem.empty() || d.out.stem.find('/') != std::string::npos ||
            std::any_of(d.out.stem.begin(), d.out.stem.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
            o.fail("stem", "must be a non-empty file name without '/' or control characters");
        if (d.out.stem == "." || d.out.stem == "..")
            o.fail("stem", "'" + d.out.stem + "' names a directory, not a file stem (its outputs would be hidden files)");
        o.boolean("png", d.out.png);
        o.positive("png_dynamic_range_db", d.out.png_dynamic_range_db);
        o.choice("png_scale", d.out.png_scale, {"db", "quantised"});
        o.boolean("ground_range", d.out.ground_range);
        o.positive("ground_range_cell_m", d.out.ground_range_cell_m);
        o.boolean("npy", d.out.npy);
        o.boolean("xtf", d.out.xtf);
        o.in_range("xtf_origin_latitude_deg", d.out.xtf_origin_latitude_deg, -89, 89); // the local projection's reach
        o.in_range("xtf_origin_longitude_deg", d.out.xtf_origin_longitude_deg, -180, 180);
        o.integer("xtf_utm_zone", d.out.xtf_utm_zone, 0);
        if (d.out.xtf_utm_zone > 60)
            o.fail("xtf_utm_zone", "must be a UTM zone from 1 to 60 (0: none), got " + std::to_string(d.out.xtf_utm_zone));
        o.choice("xtf_utm_hemisphere", d.out.xtf_utm_hemisphere, {"north", "south"});
        if (d.out.xtf_utm_zone > 0) {
            const std::string unused = "is not used with xtf_utm_zone (the world's x and y are UTM easting and northing): leave it out";
            for (const char* key : {"xtf_origin_latitude_deg", "xtf_origin_longitude_deg"})
                if (o.table().get(key)) o.fail(key, unused);
        } else if (o.table().get("xtf_utm_hemisphere"))
            o.fail("xtf_utm_hemisphere", "needs xtf_utm_zone (1 to 60): without a zone the world is a local plane about "
                                         "xtf_origin_latitude_deg and xtf_origin_longitude_deg");
        o.in_range("xtf_start_unix_s", d.out.xtf_start_unix_s, 0, 253402300799); // to the end of the year 9999
        o.boolean("coco", d.out.coco);
        if (d.out.coco && !d.out.png) o.fail("coco", "needs png = true: its annotations name the image STEM.png");
        o.boolean("yolo", d.out.yolo);
        o.boolean("label_images", d.out.label_images);
        // The instance image holds object id + 1 in 16 bits; object k has id k + 1.
        if (d.out.label_images && d.objects.size() > 65534)
            o.fail("label_images", "its 16-bit instance image holds 65534 objects; the scene has " +
                                       std::to_string(d.objects.size()) + ": leave it out, or split the objects over scenes");
        if (d.out.yolo && d.out.stem == "classes")
            o.fail("stem", "'classes' would write both the boxes and the class list of yolo = true to classes.txt: choose another");
        // A render that writes nothing would spend its time for no file: at least one product.
        if (!d.out.png && !d.out.ground_range && !d.out.npy && !d.out.xtf && !d.out.coco && !d.out.yolo && !d.out.label_images)
            o.fail("png", "is false and so is every other product (ground_range, npy, xtf, coco, yolo, label_images): "
                          "the render would write nothing");
        o.finish();
    }
    top.finish();
    // The file keys lead from the scene file's directory (beside_scene).
    for (std::string* key : {&d.bed.file, &d.sea.svp_file, &d.tow.trajectory_file}) *key = beside_scene(file, *key);
    return d;
}

/// The scene in file `path`.
[[nodiscard]] inline description parse_file(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw scene_error(path + ": is a directory, not a scene file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw scene_error(path + ": cannot open the scene file");
    // Read up to the largest scene file (a seabed's heights go in files of their own), not whatever the path gives
    // (/dev/zero).
    constexpr std::size_t max_bytes = std::size_t(16) << 20;
    std::string text;
    char buf[1 << 16];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
        text.append(buf, static_cast<std::size_t>(in.gcount()));
        if (text.size() > max_bytes) throw scene_error(path + ": larger than 16 MiB: not a scene file");
    }
    if (in.bad()) throw scene_error(path + ": cannot read the scene file");
    return parse(text, path);
}

} // namespace sss::scene_file
