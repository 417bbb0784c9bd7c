#pragma once
// A fresh directory under the system's temporary directory for one test's files, removed with everything in it at
// the end of its scope.

#include <filesystem>
#include <random>
#include <string>
#include <system_error>

namespace sss_test {

struct scratch_dir {
    std::filesystem::path dir;
    explicit scratch_dir(const std::string& prefix = "sss_test_") {
        std::random_device rd;
        dir = std::filesystem::temp_directory_path() / (prefix + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(dir);
    }
    scratch_dir(const scratch_dir&) = delete;
    scratch_dir& operator=(const scratch_dir&) = delete;
    ~scratch_dir() {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
    /// The path of file `name` in it.
    [[nodiscard]] std::string file(const std::string& name) const { return (dir / name).string(); }
};

} // namespace sss_test
