#pragma once
/// \file
/// The scene-file library's error and the number format of its messages: what building a scene (build.hpp,
/// coverage.hpp) needs of the reader, without toml++.

#include <sss/core/error.hpp>

#include <sstream>
#include <string>

namespace sss::scene_file {

/// A scene file that cannot be used: "file:line:column: key.path: what is wrong".
class scene_error : public sss::error {
public:
    using sss::error::error;
};

namespace detail {

/// A number as the messages write it (std::ostream's default: six significant digits).
[[nodiscard]] inline std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

} // namespace detail
} // namespace sss::scene_file
