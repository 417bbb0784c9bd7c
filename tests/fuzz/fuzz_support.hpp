// Shared by the fuzz targets (tests/fuzz/fuzz_<target>.cpp, built by tests/fuzz/run.sh with libFuzzer).
//
// A target is one file defining
//     int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
// that hands the bytes to one reader through sss_fuzz::run(...). A reader may reject its input only with an
// sss::error (file_error, invalid_parameter); any other exception, a crash, a sanitizer report, a leak or
// an allocation beyond libFuzzer's -malloc_limit_mb is a finding. What a reader accepts is checked for the
// promises the reader documents (finite heights, increasing depths, ...) by the target itself.
// Its seed corpus lives in tests/fuzz/corpus/<target>/ (small files, committed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <string_view>
#include <typeinfo>
#include <unistd.h>

#include "sss/core/error.hpp"

namespace sss_fuzz {

/// Stops the run with a message: libFuzzer records the input as a crash.
[[noreturn]] inline void fail(const char* what, const char* detail = "") {
    std::fprintf(stderr, "sss fuzz finding: %s %s\n", what, detail);
    std::abort();
}

/// Aborts unless `ok`: for the promises a reader makes about what it returns.
inline void promise(bool ok, const char* what) {
    if (!ok) fail("broken promise:", what);
}

/// Calls f(); an sss::error is a valid rejection, anything else thrown is a finding.
template <class F> int run(F&& f) {
    try {
        f();
    } catch (const sss::error&) {
        // Rejected with a named error: what a reader must do with bad input.
    } catch (const std::exception& e) {
        fail(typeid(e).name(), e.what());
    } catch (...) {
        fail("an exception not derived from std::exception");
    }
    return 0;
}

/// A file holding `bytes`, under a name unique to this process (removed on destruction).
class temp_file {
public:
    explicit temp_file(std::string_view suffix, std::string_view bytes) {
        const char* dir = std::getenv("TMPDIR");
        path_ = std::string(dir && *dir ? dir : "/tmp") + "/sss_fuzz_" + std::to_string(::getpid()) + std::string(suffix);
        write(path_, bytes);
    }
    temp_file(const temp_file&) = delete;
    temp_file& operator=(const temp_file&) = delete;
    ~temp_file() { std::remove(path_.c_str()); }
    [[nodiscard]] const std::string& path() const noexcept { return path_; }
    static void write(const std::string& path, std::string_view bytes) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) fail("cannot write the fuzz input file", path.c_str());
    }

private:
    std::string path_;
};

inline std::string_view bytes(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

} // namespace sss_fuzz
