// Scene files are UTF-8 text: characters outside ASCII are kept in strings and comments, refused with the line
// and column elsewhere, and never reach the undefined behaviour toml++ 3.3 has on most of them where it looks for
// whitespace (the inputs below are fuzzing findings; under UndefinedBehaviorSanitizer they abort without the
// guard in scene_file/read.hpp).

#include <doctest/doctest.h>

#include "scene_file/read.hpp"
#include "scene_file/write.hpp"

#include <filesystem>
#include <string>

namespace {

std::string error_of(const std::string& text) {
    try {
        (void)sss::scene_file::parse(text, "t.toml");
    } catch (const sss::scene_file::scene_error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("a character outside ASCII where toml++ looks for whitespace is an error with its line and column") {
    // Fuzzing finding: a bare value running into a quote and a U+0159.
    CHECK(error_of("s = 3t_pery_+_km\"\xc5\x99s") == "t.toml:1:5: Error while parsing value: could not determine value type");
    // Bare keys are ASCII; a no-break space is not TOML whitespace.
    CHECK(error_of("[seabed]\n\xc2\xa1" "cell_m = 0.1\n").starts_with("t.toml:2:1: "));
    CHECK(error_of("[seabed]\n\xc2\xa0" "cell_m = 0.1\n").find("saw '\xc2\xa0'") != std::string::npos);
    // After a line-ending backslash toml++ skips whitespace: the first character after it may be anything.
    CHECK(error_of("a = \"\"\"foo \\\n   \xc5\x99\"\"\"\n") == "t.toml:1:1: a: unknown key");
    // A quoted key outside ASCII is named as written.
    CHECK(error_of("\"\xc5\x99\" = 1\n") == "t.toml:1:1: \xc5\x99: unknown key");
    // Plane 16 (private use) carries the guard's shifted characters, so a scene file cannot hold it.
    CHECK(error_of("x = 1 \xf4\x80\x80\x80\n") == "t.toml:1:7: a private-use character of plane 16, which scene files cannot hold");
}

TEST_CASE("text outside ASCII in strings and comments reads back unchanged") {
    const std::string text = "\xef\xbb\xbf# D\xc3\xa9mo, Bj\xc3\xb8rnafjorden \xe2\x80\x94 50\xc2\xb0N\n"
                             "[seabed]\nfile = \"Bj\xc3\xb8rnafjorden \xe6\xb5\xb7\xe5\xba\x95 \xf0\x9f\x8c\x8a.asc\"\n";
    const auto d = sss::scene_file::parse(text, "t.toml");
    CHECK(d.bed.file == "Bj\xc3\xb8rnafjorden \xe6\xb5\xb7\xe5\xba\x95 \xf0\x9f\x8c\x8a.asc");
    // The resolved scene writes the file key absolute (beside_scene, absolute_path), the name's bytes unchanged.
    const auto again = sss::scene_file::parse(sss::scene_file::to_toml(d), "resolved.toml");
    CHECK(again.bed.file == (std::filesystem::current_path() / d.bed.file).string());
    // Bytes that are not UTF-8 are toml++'s to refuse, with a position.
    CHECK(error_of("[seabed]\nfile = \"\xc3(\"\n").starts_with("t.toml:2:"));
}

TEST_CASE("a dotted key of more than 64 parts is an error with its place, not a stack overflow in toml++") {
    // toml++ walks a dotted key recursively: 100,000 parts overflowed the stack.
    std::string deep;
    for (int i = 0; i < 100000; ++i) deep += i ? ".a" : "a";
    CHECK(error_of("[render]\npings = 2\n[" + deep + "]\n") == "t.toml:3:2: a dotted key of more than 64 parts");
    CHECK(error_of("# c\n  " + deep + " = 1\n") == "t.toml:2:3: a dotted key of more than 64 parts");
    // Not keys: numbers, strings with dots, dots in comments, and 64 parts (then an unknown key).
    std::string dots(1000, '.');
    CHECK(error_of("[render] # " + dots + "\npings = 2\n") == "");
    CHECK(error_of("[output]\nstem = \"" + dots + "\"\n").find("dotted") == std::string::npos);
    std::string parts;
    for (int i = 0; i < 64; ++i) parts += i ? ".a" : "a";
    CHECK(error_of(parts + " = 1\n") == "t.toml:1:1: a: unknown key");
    // A multi-line string ending in quotes of its own ("""q"""" is q") does not hide the key after it, nor does a
    // line-ending backslash in one lose count of the lines.
    CHECK(error_of("t = { s = \"\"\"q\"\"\"\", " + deep + " = 1 }\n").find("a dotted key of more than 64 parts") != std::string::npos);
    CHECK(error_of("t = \'\'\'q\'\'\'\'\'\n" + deep + " = 1\n") == "t.toml:2:1: a dotted key of more than 64 parts");
    CHECK(error_of("s = \"\"\"a \\\n b\"\"\"\n" + deep + " = 1\n") == "t.toml:3:1: a dotted key of more than 64 parts");
}
