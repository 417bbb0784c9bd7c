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
    void write_string(std::string_view s) {
        out_ += '"';
        for (const char ch : s) {
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
