// Fuzz target: sss-render scene files (TOML, tools/sss-render/scene_file/read.hpp). A scene is read or refused
// with an sss::error naming file, line and column; a scene that is read prints (--dry-run's form) as TOML that
// reads back and prints the same.
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "sss-render/scene_file/read.hpp"
#include "sss-render/scene_file/write.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    return sss_fuzz::run([&] {
        const auto scene = sss::scene_file::parse(text, "fuzz.toml");
        const std::string resolved = sss::scene_file::to_toml(scene);
        const auto again = sss::scene_file::parse(resolved, "resolved.toml");
        sss_fuzz::promise(sss::scene_file::to_toml(again) == resolved, "the resolved scene reads back to itself");
    });
}
