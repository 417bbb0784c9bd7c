#pragma once
/// \file
/// The exceptions sss throws. Everything derives from `sss::error`, so one catch clause covers the library.
/// Messages name what was wrong: the parameter, or the file and line (or byte offset).

#include <cmath>
#include <concepts>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace sss {

/// Base of every exception thrown by sss.
class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A parameter outside its valid range, or not finite. `parameter()` names it as the user spelled it.
class invalid_parameter : public error {
public:
    invalid_parameter(std::string_view parameter, std::string_view why)
        : error("sss: invalid parameter '" + std::string(parameter) + "': " + std::string(why)),
          parameter_(parameter) {}
    [[nodiscard]] const std::string& parameter() const noexcept { return parameter_; }

private:
    std::string parameter_;
};

/// A file that cannot be read or written, or whose content is malformed. `file()` and `line()`
/// (0 when the fault is not tied to a line; then `byte_offset()` may say where) locate it.
class file_error : public error {
public:
    file_error(std::string_view file, std::size_t line, std::string_view why, std::size_t byte_offset = 0)
        : error(compose(file, line, byte_offset, why)), file_(file), line_(line), byte_offset_(byte_offset) {}
    [[nodiscard]] const std::string& file() const noexcept { return file_; }
    [[nodiscard]] std::size_t line() const noexcept { return line_; }
    [[nodiscard]] std::size_t byte_offset() const noexcept { return byte_offset_; }

private:
    static std::string compose(std::string_view file, std::size_t line, std::size_t offset, std::string_view why) {
        // Appended piece by piece: GCC 12 at -O3 warns (falsely) of an overflow in "..." + std::to_string(n).
        std::string where = "sss: ";
        where += file;
        if (line != 0) {
            where += ':';
            where += std::to_string(line);
        } else if (offset != 0) {
            where += " (byte ";
            where += std::to_string(offset);
            where += ')';
        }
        where += ": ";
        where += why;
        return where;
    }
    std::string file_;
    std::size_t line_;
    std::size_t byte_offset_;
};

/// The message of e without its leading "sss: ", to be wrapped in another error's message (a file_error naming the
/// file whose content was an invalid parameter).
[[nodiscard]] inline std::string_view message_body(const error& e) noexcept {
    const std::string_view m = e.what();
    return m.starts_with("sss: ") ? m.substr(5) : m;
}

// ---------------------------------------------------------------------------------------------
// Validation helpers. Each throws invalid_parameter naming the parameter; the message is composed
// only when the check fails, so a passing check costs a comparison (they are used on hot paths too).

/// Throws invalid_parameter(name, why) unless `ok`.
inline void require(bool ok, std::string_view name, std::string_view why) {
    if (!ok) [[unlikely]] throw invalid_parameter(name, why);
}
/// Throws invalid_parameter(name, why()) unless `ok`; `why` (returning a string) is called only on failure,
/// so a message with numbers in it costs nothing when the check passes:
/// `sss::require(n == m, "x.paths", [&] { return "has " + std::to_string(n) + " entries"; })`.
template <std::invocable Why> void require(bool ok, std::string_view name, Why&& why) {
    if (!ok) [[unlikely]] throw invalid_parameter(name, std::forward<Why>(why)());
}
/// Throws unless x is finite.
template <class T> void require_finite(T x, std::string_view name) {
    if (!std::isfinite(x)) [[unlikely]] throw invalid_parameter(name, "must be finite, got " + std::to_string(x));
}
/// Throws unless x is finite and > 0.
template <class T> void require_positive(T x, std::string_view name) {
    require_finite(x, name);
    if (!(x > T(0))) [[unlikely]] throw invalid_parameter(name, "must be > 0, got " + std::to_string(x));
}
/// Throws unless x is finite and >= 0.
template <class T> void require_non_negative(T x, std::string_view name) {
    require_finite(x, name);
    if (!(x >= T(0))) [[unlikely]] throw invalid_parameter(name, "must be >= 0, got " + std::to_string(x));
}
/// Throws unless x > 0 wherever `needed` (say a rim's width, needed when the rim has a height):
/// "must be > 0 when <because>".
template <class T> void require_positive_when(bool needed, T x, std::string_view name, std::string_view because) {
    if (needed && !(x > T(0))) [[unlikely]] throw invalid_parameter(name, "must be > 0 when " + std::string(because));
}
/// Throws unless lo <= x <= hi (and x finite).
template <class T> void require_in_range(T x, T lo, T hi, std::string_view name) {
    require_finite(x, name);
    if (!(x >= lo && x <= hi)) [[unlikely]]
        throw invalid_parameter(name, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                                          std::to_string(x));
}

} // namespace sss
