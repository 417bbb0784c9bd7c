// The readers share one text core (io/detail/text.hpp): the same lines, comments, delimiters and numbers are
// accepted by every reader, errors name the line and the column, and writers replace files atomically.
#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <thread>

#include "sss/io/detail/atomic_file.hpp"
#include "sss/io/detail/json.hpp"
#include "sss/io/detail/text.hpp"
#include "sss/io/sound_speed_profile.hpp"
#include "sss/io/trajectory_csv.hpp"
#include "support/scratch_dir.hpp"
#include "support/temporaries.hpp"

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

template <class F> sss::file_error error_of(F&& read) {
    try {
        read();
    } catch (const sss::file_error& e) {
        return e;
    }
    return sss::file_error("(none)", 999, "no error");
}

sss::motion::trajectory_samples<double> trajectory(const std::string& text) {
    std::istringstream in(text);
    return sss::io::read_trajectory_csv<double>(in, "nav.csv");
}

sss::propagation::sound_speed_profile<double> profile(const std::string& text) {
    std::istringstream in(text);
    return sss::io::read_sound_speed_csv<double>(in, "cast.csv");
}

} // namespace

TEST_CASE("numbers fill their field: an optional '+', no '+-', no trailing text, sizes unsigned") {
    using sss::detail::parse_double;
    using sss::detail::parse_finite;
    using sss::detail::parse_size;
    CHECK(parse_double("+1.5e3") == 1500.0);
    CHECK(parse_double("-0.25") == -0.25);
    CHECK_FALSE(parse_double("+-1"));
    CHECK_FALSE(parse_double("1.5x"));
    CHECK_FALSE(parse_double(""));
    CHECK_FALSE(parse_double("+"));
    CHECK(parse_double("inf").has_value());
    CHECK_FALSE(parse_finite("inf"));
    CHECK_FALSE(parse_finite("nan"));
    CHECK_FALSE(parse_finite("1e400")); // out of range of double
    CHECK(parse_size("+42") == 42u);
    CHECK_FALSE(parse_size("-1"));
    CHECK_FALSE(parse_size("99999999999999999999999"));
}

TEST_CASE("lines skip a byte order mark, comments and blanks, and remember their number and column") {
    const std::string text = "\xEF\xBB\xBF# header comment\n\n  a, b ;c  # trailing\r\n\t\n  d e\n";
    const auto lines = sss::detail::content_lines(text);
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].text == "a, b ;c");
    CHECK(lines[0].number == 3);
    CHECK(lines[0].column == 3);
    const auto f = sss::detail::split_fields(lines[0]);
    REQUIRE(f.size() == 3);
    CHECK(f[1].text == "b");
    CHECK(f[1].column == 6);
    CHECK(f[2].text == "c");
    CHECK(f[2].column == 9);
    const auto g = sss::detail::split_fields(lines[1]);
    REQUIRE(g.size() == 2);
    CHECK(g[1].text == "e");
    CHECK(g[1].column == 5);
}

TEST_CASE("the trajectory and sound-speed readers accept the same delimiters: ',' or ';' or blanks") {
    for (const std::string sep : {",", ";", " ", "\t", " ; "}) {
        CAPTURE(sep);
        const auto t = trajectory("time" + sep + "x" + sep + "y" + sep + "z\n0" + sep + "1" + sep + "2" + sep +
                                  "5\n1" + sep + "2" + sep + "3" + sep + "5\n");
        REQUIRE(t.time_s.size() == 2);
        CHECK(t.position_m[1].x == 2.0);
        const auto p = profile("0" + sep + "1500\n10" + sep + "1490\n");
        CHECK(p.depths_m().size() == 2);
        CHECK(p.speeds_mps()[1] == 1490.0);
    }
}

TEST_CASE("a bad field is reported with its line and column by every delimited reader") {
    const sss::file_error t = error_of([] { (void)trajectory("time,x,y,z\n0,0,0,5\n1, 0,zz,5\n"); });
    CHECK(t.line() == 3);
    CHECK(contains(t.what(), "nav.csv:3: column 6:"));
    const sss::file_error p = error_of([] { (void)profile("depth,speed\n0,1500\n 5;  fast\n"); });
    CHECK(p.line() == 3);
    CHECK(contains(p.what(), "cast.csv:3: column 6:"));
}

TEST_CASE("the sound-speed CSV writer replaces a file atomically: a failed write leaves no file behind") {
    const std::filesystem::path dir = std::filesystem::current_path() / "atomic";
    std::filesystem::create_directories(dir);
    const auto path = dir / "cast.csv";
    const auto prof = profile("0,1500\n10,1490\n");
    sss::io::write_sound_speed_csv(path, prof);
    CHECK(std::filesystem::exists(path));
    CHECK(sss_test::temporaries_left(path) == 0);
    CHECK(sss::io::read_sound_speed_csv<double>(path).speeds_mps()[1] == 1490.0);
    // A target whose directory does not exist: file_error, and nothing is created.
    const auto nowhere = dir / "missing" / "cast.csv";
    CHECK(error_of([&] { sss::io::write_sound_speed_csv(nowhere, prof); }).file() == nowhere.string());
    CHECK_FALSE(std::filesystem::exists(dir / "missing"));
    // An atomic_file destroyed before commit removes its temporary and leaves the old file untouched.
    {
        sss::detail::atomic_file out(path.string());
        out.write("half");
    }
    CHECK(sss_test::temporaries_left(path) == 0);
    CHECK(sss::io::read_sound_speed_csv<double>(path).depths_m().size() == 2);
}

TEST_CASE("two writers of one path never share a temporary: the file is always one writer's whole text") {
    const sss_test::scratch_dir d("sss_atomic_race_");
    const std::string path = d.file("out.txt");
    // A file named like a temporary is someone else's: no writer opens, truncates or removes it.
    const std::string bystander = path + ".tmp";
    sss::detail::save_file(bystander, "not a temporary");
    const std::string a(200000, 'a'), b(300000, 'b');
    for (int round = 0; round < 20; ++round) {
        std::thread other([&] { sss::detail::save_file(path, b); });
        sss::detail::save_file(path, a);
        other.join();
        const std::string got = sss::detail::read_file(path);
        CHECK((got == a || got == b));
    }
    CHECK(sss::detail::read_file(bystander) == "not a temporary");
    std::filesystem::remove(bystander);
    CHECK(sss_test::temporaries_left(path) == 0);
}

TEST_CASE("a float is read back from its shortest decimal rounded once, to the bit, where rounding through double is "
          "off by one") {
    // 0x1.5c87fap-84 prints as 7.038531e-26; its nearest double lies so close to the midpoint between that float and
    // the next that rounding the double to float gives the next one.
    const float f = std::bit_cast<float>(std::uint32_t(0x15ae43fdu));
    const std::string text = sss::detail::shortest(f);
    CHECK(text == "7.038531e-26");
    CHECK(static_cast<float>(*sss::detail::parse_double(text)) != f);
    CHECK(sss::detail::parse_as<float>(text) == f);
    CHECK(sss::detail::parse_as<float>("-" + text) == -f);
    CHECK(sss::detail::parse_as<float>("+1e39") == std::numeric_limits<float>::infinity());
    CHECK(sss::detail::parse_as<float>("1e-50") == 0.0f);
    CHECK(!sss::detail::parse_as<float>("1e"));
}

TEST_CASE("the JSON writer escapes control characters and makes bytes that are not UTF-8 U+FFFD: its text always parses") {
    sss::detail::json_writer j;
    j.begin_object().member("name", std::string("a\"b\\c\n\x01 caf\xc3\xa9 \xe9 \xed\xa0\x80 \xf4\x90\x80\x80 end")).end_object();
    CHECK(j.str() == "{\"name\":\"a\\\"b\\\\c\\n\\u0001 caf\xc3\xa9 \\ufffd \\ufffd\\ufffd\\ufffd \\ufffd\\ufffd\\ufffd\\ufffd end\"}");
    CHECK(sss::detail::valid_utf8("caf\xc3\xa9 \xe6\xb5\xb7 \xf0\x9f\x90\x9f"));
    CHECK(!sss::detail::valid_utf8("\xc0\xaf"));         // overlong '/'
    CHECK(!sss::detail::valid_utf8("\xed\xa0\x80"));     // a surrogate
    CHECK(!sss::detail::valid_utf8("\xf4\x90\x80\x80")); // above U+10FFFF
    CHECK(!sss::detail::valid_utf8("\xe6\xb5"));         // cut short
}
