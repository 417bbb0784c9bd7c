// Sound-speed profile files: CSV, CARIS .svp and Kongsberg .asvp readers, the CSV writer, and the
// errors that locate a bad line.

#include <doctest/doctest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/io/sound_speed_profile.hpp"

using namespace sss::io;
using sss::propagation::sound_speed_profile;

namespace {

template <class T = double> void check_knots(const sound_speed_profile<T>& p, const std::vector<double>& z,
                                             const std::vector<double>& c) {
    REQUIRE(p.knot_count() == z.size());
    for (std::size_t i = 0; i < z.size(); ++i) {
        CHECK(p.depths_m()[i] == static_cast<T>(z[i]));
        CHECK(p.speeds_mps()[i] == static_cast<T>(c[i]));
    }
}

struct error_info {
    std::string file;
    std::size_t line = 0;
    std::string what;
};

template <class F> error_info file_error_of(F&& read) {
    try {
        read();
    } catch (const sss::file_error& e) {
        return {e.file(), e.line(), e.what()};
    }
    return {"(no throw)", 0, ""};
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A fresh directory under the system temporary directory, removed at scope exit.
struct temp_dir {
    std::filesystem::path path;
    temp_dir() {
        std::random_device rd;
        path = std::filesystem::temp_directory_path() / ("sss_svp_test_" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(path);
    }
    ~temp_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        std::ofstream out(path / name, std::ios::binary);
        out << text;
        return path / name;
    }
};

} // namespace

TEST_CASE("CSV profiles read with or without a header, with comments, separators and Windows line ends") {
    std::istringstream with_header("# CTD cast 14\ndepth_m,speed_mps\n0,1500.5\n10.0, 1498.25  # thermocline\n\n25,1490\n");
    check_knots(read_sound_speed_csv(with_header, "cast.csv"), {0, 10, 25}, {1500.5, 1498.25, 1490});

    std::istringstream bare("0,1500\n5,1501\n");
    check_knots(read_sound_speed_csv(bare, "bare.csv"), {0, 5}, {1500, 1501});

    std::istringstream odd("\xEF\xBB\xBF" "depth;speed\r\n+0.5;1500\r\n1e1;1.4995e3\r\n");
    check_knots(read_sound_speed_csv(odd, "odd.csv"), {0.5, 10}, {1500, 1499.5});

    std::istringstream spaces("  2.5\t1510\n 7.5    1505.5\n");
    check_knots(read_sound_speed_csv(spaces, "spaces.txt"), {2.5, 7.5}, {1510, 1505.5});

    std::istringstream as_float("0,1500\n100,1520.125\n");
    check_knots<float>(read_sound_speed_csv<float>(as_float, "f.csv"), {0, 100}, {1500, 1520.125});
    // A value that fits a double but not a float is an error of that line, not an infinity.
    const auto e = file_error_of([] {
        std::istringstream in("0,1500\n1e300,1500\n");
        (void)read_sound_speed_csv<float>(in, "f.csv");
    });
    CHECK(e.line == 2);
}

TEST_CASE("A bad CSV line raises file_error naming the file and the line") {
    const auto error_for = [](const std::string& text) {
        return file_error_of([&] {
            std::istringstream in(text);
            (void)read_sound_speed_csv(in, "cast.csv");
        });
    };
    // Wrong column count.
    auto e = error_for("depth,speed\n0,1500\n10,1499,7\n");
    CHECK(e.file == "cast.csv");
    CHECK(e.line == 3);
    CHECK(contains(e.what, "cast.csv:3"));
    CHECK(contains(e.what, "2 columns"));
    e = error_for("0,1500\n10\n");
    CHECK(e.line == 2);
    e = error_for("0,1500\n10,,1499\n");
    CHECK(e.line == 2);
    // Non-numeric values (the header is only ever the first line).
    e = error_for("depth,speed\n0,1500\n10,fast\n");
    CHECK(e.line == 3);
    CHECK(contains(e.what, "'fast'"));
    e = error_for("0,1500\ndepth,speed\n");
    CHECK(e.line == 2);
    e = error_for("0,1500\n10,1500x\n");
    CHECK(e.line == 2);
    e = error_for("0,1500\n10,nan\n");
    CHECK(e.line == 2);
    // Depth not increasing, with comments and blank lines counted in the line number.
    e = error_for("# header comment\n0,1500\n\n20,1499\n20,1498\n");
    CHECK(e.line == 5);
    CHECK(contains(e.what, "increase"));
    e = error_for("0,1500\n20,1499\n15,1498\n");
    CHECK(e.line == 3);
    // Negative or zero speed.
    e = error_for("0,1500\n10,-1500\n");
    CHECK(e.line == 2);
    CHECK(contains(e.what, "positive"));
    e = error_for("0,0\n");
    CHECK(e.line == 1);
    // A column in km/s (or ft/s) is not a sound speed in water; knots a float's step apart overflow the gradient.
    e = error_for("depth,speed\n0,1.500\n100,1.520\n");
    CHECK(e.line == 2);
    CHECK(contains(e.what, "in m/s?"));
    CHECK(error_for("0,1500\n10,4921.3\n").line == 2);
    const auto close = file_error_of([] {
        std::istringstream in("0,1500\n1e-37,1600\n");
        (void)read_sound_speed_csv<float>(in, "f.csv");
    });
    CHECK(close.line == 2);
    CHECK(contains(close.what, "too close"));
    // Nothing to read.
    e = error_for("# nothing here\n\n");
    CHECK(e.file == "cast.csv");
    CHECK(contains(e.what, "no depth,speed"));
    e = error_for("depth,speed\n");
    CHECK(contains(e.what, "no depth,speed"));
}

TEST_CASE("CARIS .svp files read one section or all of them") {
    const std::string text = "[SVP_VERSION_2]\n"
                             "D:\\survey\\line7.svp\n"
                             "Section 2015-148 23:49:31 -12:14:35.00 130:55:40.00\n"
                             "0.201690 1539.508000\n"
                             "0.399446 1539.485000\n"
                             "12.5 1538.1\n"
                             "Section 2015-149 23:18:02 -12:16:60.00 130:55:11.00\n"
                             "0.405621\t1539.718000\n"
                             "30 1537.5\n";
    std::istringstream a(text);
    check_knots(read_caris_svp(a, "line7.svp"), {0.201690, 0.399446, 12.5}, {1539.508, 1539.485, 1538.1});
    std::istringstream b(text);
    check_knots(read_caris_svp(b, "line7.svp", 1), {0.405621, 30}, {1539.718, 1537.5});
    std::istringstream c(text);
    CHECK(read_caris_svp_sections(c, "line7.svp").size() == 2);
    // Depths restart in each section; a missing file-name line is accepted.
    std::istringstream d("[SVP_VERSION_2]\nSection 2020-001 00:00:00 0 0\n5 1500\n10 1501\n");
    check_knots(read_caris_svp(d, "noname.svp"), {5, 10}, {1500, 1501});
    // Asking for a section that is not there.
    const auto e = file_error_of([&] {
        std::istringstream in(text);
        (void)read_caris_svp(in, "line7.svp", 2);
    });
    CHECK(e.file == "line7.svp");
    CHECK(contains(e.what, "has 2"));
}

TEST_CASE("A bad CARIS .svp file raises file_error naming the line") {
    const auto error_for = [](const std::string& text) {
        return file_error_of([&] {
            std::istringstream in(text);
            (void)read_caris_svp(in, "bad.svp");
        });
    };
    CHECK(error_for("depth speed\n0 1500\n").line == 1); // no version line
    CHECK(error_for("[SVP_VERSION_2]\nname\nSection 2015-148 23:49:31\n0 1500\n1 1500 3\n").line == 5);
    CHECK(error_for("[SVP_VERSION_2]\nname\nSection 2015-148 23:49:31\n0 1500\n1 abc\n").line == 5);
    CHECK(error_for("[SVP_VERSION_2]\nname\nSection 2015-148 23:49:31\n0 1500\n0 1501\n").line == 5);
    CHECK(error_for("[SVP_VERSION_2]\nname\nSection 2015-148 23:49:31\n0 -1500\n").line == 4);
    // A bad line in a later section is reported even when the first section is asked for.
    CHECK(error_for("[SVP_VERSION_2]\nn\nSection 1\n0 1500\nSection 2\n0 1500\n5 oops\n").line == 7);
    // An empty section.
    const auto e = error_for("[SVP_VERSION_2]\nn\nSection 1\nSection 2\n0 1500\n");
    CHECK(e.line == 3);
    CHECK(contains(e.what, "no depth speed"));
}

TEST_CASE("Kongsberg .asvp files read with a one-line or a wrapped header") {
    std::istringstream one("( SoundVelocity  1.0 0 201806071200 -33.5 151.25 -1 0 0 SVP-16 P 4 )\n"
                           "0.1 1483.6\n5.0 1484.2\n12.0 1488.1\n12000.0 1509.6\n");
    check_knots(read_kongsberg_asvp(one, "cast.asvp"), {0.1, 5, 12, 12000}, {1483.6, 1484.2, 1488.1, 1509.6});
    std::istringstream wrapped("( SoundVelocity 1.00 12 200605290813 22.3452678\n"
                               "66.4483298 4500 200605290813 200605301210 SVP-16 PE 3 )\r\n"
                               "0.1 1483.6\r\n7.0 1485.3\r\n40.0 1483.8\r\n");
    check_knots(read_kongsberg_asvp(wrapped, "w.asvp"), {0.1, 7, 40}, {1483.6, 1485.3, 1483.8});
    // A short header (no value count) is accepted as is.
    std::istringstream shorter("(SoundVelocity 1.0 0)\n0 1500\n10 1490\n");
    check_knots(read_kongsberg_asvp(shorter, "s.asvp"), {0, 10}, {1500, 1490});
}

TEST_CASE("A bad Kongsberg .asvp file raises file_error naming the line") {
    const auto error_for = [](const std::string& text) {
        return file_error_of([&] {
            std::istringstream in(text);
            (void)read_kongsberg_asvp(in, "bad.asvp");
        });
    };
    const std::string header = "( SoundVelocity 1.0 0 201806071200 -33.5 151.25 -1 0 0 SVP-16 P 3 )\n";
    CHECK(error_for("0 1500\n").line == 1);                                  // no header
    CHECK(error_for("( SoundVelocity 1.0 0\n0 1500\n").line == 1);           // unclosed header
    CHECK(error_for(header + "0 1500\n5 1501\n5 1502\n").line == 4);         // depth not increasing
    CHECK(error_for(header + "0 1500\n5 1501 9\n10 1502\n").line == 3);      // three columns
    CHECK(error_for(header + "0 1500\n5 -1501\n10 1502\n").line == 3);       // negative speed
    CHECK(error_for(header + "0 1500\n5 l501\n10 1502\n").line == 3);        // a letter for a digit
    const auto count = error_for(header + "0 1500\n5 1501\n");               // says 3, has 2
    CHECK(count.line == 1);
    CHECK(contains(count.what, "declares 3"));
}

TEST_CASE("Profiles round-trip exactly through CSV files, and the reader follows the file extension") {
    const temp_dir dir;
    const sound_speed_profile<double> original({0.1, 2.0 / 3.0, 17.25, 1234.5678901234567},
                                               {1500.1, 1499.0 + 1.0 / 3.0, 1487.0, 1512.000000000001});
    const auto csv = dir.path / "profile.csv";
    write_sound_speed_csv(csv, original);
    check_knots(read_sound_speed_csv(csv), {0.1, 2.0 / 3.0, 17.25, 1234.5678901234567},
                {1500.1, 1499.0 + 1.0 / 3.0, 1487.0, 1512.000000000001});
    check_knots(read_sound_speed_profile(csv), {0.1, 2.0 / 3.0, 17.25, 1234.5678901234567},
                {1500.1, 1499.0 + 1.0 / 3.0, 1487.0, 1512.000000000001});

    const auto svp = dir.write("cast.SVP", "[SVP_VERSION_2]\ncast.svp\nSection 2015-148 23:49:31\n0 1500\n10 1495\n");
    check_knots(read_sound_speed_profile(svp), {0, 10}, {1500, 1495});
    const auto asvp = dir.write("cast.asvp", "( SoundVelocity 1.0 0 )\n0 1500\n10 1495\n");
    check_knots(read_sound_speed_profile(asvp), {0, 10}, {1500, 1495});
    check_knots(read_kongsberg_asvp(asvp), {0, 10}, {1500, 1495});
    check_knots(read_caris_svp(svp), {0, 10}, {1500, 1495});

    // A bad file on disk is named by its path.
    const auto bad = dir.write("bad.csv", "0,1500\n10,1500,1\n");
    const auto e = file_error_of([&] { (void)read_sound_speed_profile(bad); });
    CHECK(e.file == bad.string());
    CHECK(e.line == 2);
    // A missing file.
    const auto missing = file_error_of([&] { (void)read_sound_speed_csv(dir.path / "nope.csv"); });
    CHECK(contains(missing.file, "nope.csv"));
    CHECK(missing.line == 0);
    CHECK(contains(missing.what, "cannot open"));
    // Writing where no file can be created.
    const auto unwritable = file_error_of([&] { write_sound_speed_csv(dir.path / "no_dir" / "x.csv", original); });
    CHECK(contains(unwritable.what, "cannot open"));
}

TEST_CASE("The CSV writer writes a header and one depth,speed pair per knot") {
    std::ostringstream out;
    write_sound_speed_csv(out, sound_speed_profile<float>({0.f, 12.5f}, {1500.f, 1490.25f}), "memory");
    CHECK(out.str() == "depth_m,speed_mps\n0,1500\n12.5,1490.25\n");
}
