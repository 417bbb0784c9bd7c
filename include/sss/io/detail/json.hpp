#pragma once
/// \file
/// A small JSON text builder for the writers (labels, sidecars): objects, arrays, strings with escapes, numbers
/// in their shortest round-trip form (non-finite numbers as null). No parser; no dependency.

#include <charconv>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sss::detail {

/// The length (1 to 4) of the well-formed UTF-8 sequence at the start of `s` (Unicode 15, table 3-7: no overlong
/// forms, no surrogates, nothing above U+10FFFF); 0 where it is not one.
[[nodiscard]] inline std::size_t utf8_sequence_length(std::string_view s) noexcept {
    if (s.empty()) return 0;
    const auto b = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
    const unsigned char c = b(0);
    if (c < 0x80) return 1;
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xbf; // the second byte's range
    if (c >= 0xc2 && c <= 0xdf) n = 2;
    else if (c >= 0xe0 && c <= 0xef) {
        n = 3;
        if (c == 0xe0) lo = 0xa0;
        if (c == 0xed) hi = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
        n = 4;
        if (c == 0xf0) lo = 0x90;
        if (c == 0xf4) hi = 0x8f;
    } else
        return 0;
    if (s.size() < n || b(1) < lo || b(1) > hi) return 0;
    for (std::size_t i = 2; i < n; ++i)
        if (b(i) < 0x80 || b(i) > 0xbf) return 0;
    return n;
}

/// Whether `s` is well-formed UTF-8 throughout.
[[nodiscard]] inline bool valid_utf8(std::string_view s) noexcept {
    while (!s.empty()) {
        const std::size_t n = utf8_sequence_length(s);
        if (n == 0) return false;
        s.remove_prefix(n);
    }
    return true;
}

class json_writer {
public:
    /// The text so far.
    [[nodiscard]] const std::string& str() const noexcept { return out_; }

    json_writer& begin_object() { return open('{'); }
    json_writer& end_object() { return close('}'); }
    json_writer& begin_array() { return open('['); }
    json_writer& end_array() { return close(']'); }

    /// An object member's key; the next value (or container) is its value.
    json_writer& key(std::string_view k) {
        separate();
        write_string(k);
        out_ += ':';
        after_key_ = true;
        return *this;
    }
    json_writer& value(std::string_view s) {
        separate();
        write_string(s);
        return *this;
    }
    json_writer& value(const char* s) { return value(std::string_view(s)); }
    json_writer& value(bool b) {
        separate();
        out_ += b ? "true" : "false";
        return *this;
    }
    json_writer& value(double x) {
        separate();
        if (!std::isfinite(x)) {
            out_ += "null";
            return *this;
        }
        char buf[32];
        const auto r = std::to_chars(buf, buf + sizeof buf, x);
        out_.append(buf, r.ptr);
        return *this;
    }
    template <std::integral I>
        requires(!std::same_as<I, bool>)
    json_writer& value(I x) {
        separate();
        out_ += std::to_string(x);
        return *this;
    }
    json_writer& value(float x) { return value(double(x)); }

    /// key(k).value(v)
    template <class V> json_writer& member(std::string_view k, const V& v) { return key(k).value(v); }

    /// A line break (between the elements of long arrays, to keep files readable).
    json_writer& newline() {
        out_ += '\n';
        return *this;
    }

private:
    json_writer& open(char c) {
        separate();
        out_ += c;
        first_.push_back(true);
        return *this;
    }
    json_writer& close(char c) {
        out_ += c;
        first_.pop_back();
        return *this;
    }
    void separate() {
        if (after_key_) {
            after_key_ = false;
            return;
        }
        if (!first_.empty()) {
            if (!first_.back()) out_ += ',';
            first_.back() = false;
        }
    }
    /// A JSON string (RFC 8259, section 7): quotes, backslashes and control characters escaped; a byte that does not
    /// start well-formed UTF-8 becomes U+FFFD, so that the text is always valid JSON (callers that must not alter a
    /// name check it first: io/labels.hpp).
    void write_string(std::string_view s) {
        out_ += '"';
        while (!s.empty()) {
            const std::size_t n = utf8_sequence_length(s);
            if (n > 1) {
                out_.append(s.data(), n);
                s.remove_prefix(n);
                continue;
            }
            const char ch = s.front();
            s.remove_prefix(1);
            if (n == 0) {
                out_ += "\\ufffd";
                continue;
            }
            const auto u = static_cast<unsigned char>(ch);
            if (ch == '"') out_ += "\\\"";
            else if (ch == '\\') out_ += "\\\\";
            else if (ch == '\n') out_ += "\\n";
            else if (ch == '\t') out_ += "\\t";
            else if (ch == '\r') out_ += "\\r";
            else if (u < 0x20) {
                const char* hex = "0123456789abcdef";
                out_ += "\\u00";
                out_ += hex[u >> 4];
                out_ += hex[u & 15];
            } else out_ += ch;
        }
        out_ += '"';
    }

    std::string out_;
    std::vector<bool> first_;
    bool after_key_ = false;
};

} // namespace sss::detail
