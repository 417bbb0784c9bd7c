#pragma once
// What a writer of a file may leave behind: the files next to it whose names start with its own name followed by
// ".tmp" (the temporaries sss's writers write before renaming, io/detail/atomic_file.hpp).

#include <cstddef>
#include <filesystem>
#include <string>
#include <system_error>

namespace sss_test {

/// Files in path's directory named `<path's file name>.tmp...`.
inline std::size_t temporaries_left(const std::filesystem::path& path) {
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    const std::string prefix = path.filename().string() + ".tmp";
    std::size_t n = 0;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
        if (e.path().filename().string().rfind(prefix, 0) == 0) ++n;
    return n;
}

} // namespace sss_test
