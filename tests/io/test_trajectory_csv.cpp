// Reading trajectories from CSV: column names in any order, units, comments, and errors that name the line.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sss/core/constants.hpp"
#include "sss/io/trajectory_csv.hpp"
#include "sss/motion/trajectory.hpp"

namespace {

using sss::io::read_trajectory_csv;

constexpr double pi = sss::pi_v<double>;

/// The file_error thrown reading `text`, or a default one (line 999) when nothing is thrown.
sss::file_error error_of(const std::string& text) {
    std::istringstream in(text);
    try {
        (void)read_trajectory_csv<double>(in, "survey.csv");
    } catch (const sss::file_error& e) {
        return e;
    }
    return sss::file_error("(none)", 999, "no error");
}

} // namespace

TEST_CASE("A trajectory file with columns in any order, comments, units and CRLF line ends loads its samples") {
    std::istringstream in("\xEF\xBB\xBF# survey line 3\r\n"
                          "\r\n"
                          "Heading_deg, y_m, TIME_S, x, z_m, pitch_rad, roll, heave_m, sway  # header\r\n"
                          "90, 0.0, 100.0, 0.0, 12.0, 0.01, -2.0, 0.25, 0.5\r\n"
                          "# a comment between rows\n"
                          "  91.5 ,1.0,100.5,+2.0,12.5,-0.02,1e0,0,-0.5\n"
                          "92,2,101,4,13,0,0,0,0 # trailing comment\n");
    const auto s = read_trajectory_csv<double>(in, "line3.csv");
    REQUIRE(s.time_s.size() == 3);
    CHECK(s.ping.empty());
    CHECK(s.time_s[1] == 100.5);
    CHECK(s.position_m[1].x == 2.0);
    CHECK(s.position_m[1].y == 1.0);
    CHECK(s.position_m[1].z == 12.5);
    CHECK(s.yaw_rad[1] == doctest::Approx(91.5 * pi / 180.0));  // degrees in the file
    CHECK(s.pitch_rad[1] == doctest::Approx(-0.02));             // _rad: radians in the file
    CHECK(s.roll_rad[0] == doctest::Approx(-2.0 * pi / 180.0));  // bare angle names are degrees
    CHECK(s.heave_m[0] == 0.25);
    CHECK(s.sway_m[1] == -0.5);
}

TEST_CASE("A per-ping file keys the samples by ping, with times optional") {
    std::istringstream in("ping,x,y,z\n10,0,0,5\n11,0,1,5\n13,0,3,5\n");
    const auto s = read_trajectory_csv<float>(in, "pings.csv");
    CHECK(s.time_s.empty());
    REQUIRE(s.ping.size() == 3);
    const sss::motion::trajectory<float> traj(s);
    CHECK(traj.keyed_by_ping());
    CHECK(traj.ping_count() == 4);                                      // pings 10 .. 13
    CHECK(static_cast<double>(traj.pose_at(2).position.y) == doctest::Approx(2.0)); // ping 12
    CHECK(traj.pose_at(2).yaw_rad == doctest::Approx(0.0f).scale(1.0f));
}

TEST_CASE("A bad row fails with sss::file_error naming the file and its line") {
    const std::string header = "# trajectory\ntime,x,y,z\n";
    const std::string good = "0,0,0,5\n1,0,1,5\n";
    struct bad_case {
        std::string text;
        std::size_t line;
        const char* why;
    };
    const bad_case cases[] = {
        {header + good + "2,0,abc,5\n", 5, "'abc' is not a finite number"},
        {header + good + "2,0,2\n", 5, "expected 4 fields, found 3"},
        {header + good + "2,0,2,5,7\n", 5, "expected 4 fields, found 5"},
        {header + good + "1,0,2,5\n", 5, "time must strictly increase"},
        {header + "0,0,0,5\n\n# c\n0.5,0,nan,5\n", 6, "is not a finite number"},
        {header + good + "2,0,2,inf\n", 5, "is not a finite number"},
        {header + good + "2,0,,5\n", 5, "'' is not a finite number"},
        {header + good + "2,0,1.5e,5\n", 5, "is not a finite number"},
        {"time,x,y,z,depth\n" + good, 1, "unknown column 'depth'"},
        {"time,x,yaw,y,z,heading_deg\n", 1, "repeats the yaw column"},
        {"# only x and y\ntime,x,y\n", 2, "missing column 'z'"},
        {"x,y,z\n", 1, "one of 'time' or 'ping'"},
        {"ping,time,x,y,z\n1,0,0,0,5\n2,0,0,1,5\n", 3, "time must strictly increase"},
        // A towfish on its side or nose down: roll and pitch within 90 deg of level, after wrapping.
        {"time,x,y,z,roll\n0,0,0,5,359\n1,0,1,5,95\n", 3, "column 'roll': '95' is 90 deg or more from level"},
        {"time,x,y,z,pitch_deg\n0,0,0,5,-90\n1,0,1,5,0\n", 2, "column 'pitch': '-90' is 90 deg or more"},
        {"time,x,y,z,roll_rad\n0,0,0,5,0.1\n1,0,1,5,3.1\n", 3, "column 'roll': '3.1' is 90 deg or more"},
    };
    for (const bad_case& c : cases) {
        CAPTURE(c.text);
        const sss::file_error e = error_of(c.text);
        CHECK(e.file() == "survey.csv");
        CHECK(e.line() == c.line);
        CHECK(std::string(e.what()).find("survey.csv:" + std::to_string(c.line)) != std::string::npos);
        CHECK(std::string(e.what()).find(c.why) != std::string::npos);
    }
    // Angles that wrap to within 90 deg of level load: a roll of 359 deg is -1 deg, a pitch of 6 rad about -16 deg.
    std::istringstream wrapped("time,x,y,z,roll,pitch_rad\n0,0,0,5,359,6\n1,0,1,5,-270.5,0\n");
    const auto w = sss::io::read_trajectory_csv<double>(wrapped, "wrapped.csv");
    REQUIRE(w.roll_rad.size() == 2);
    const sss::motion::trajectory<double> wt(w, sss::motion::trajectory_params<double>{});
    CHECK(wt.pose_at(0).roll_rad == doctest::Approx(-sss::pi_v<double> / 180.0).epsilon(1e-12));
    CHECK(wt.pose_at(0).pitch_rad == doctest::Approx(6.0 - 2.0 * sss::pi_v<double>).epsilon(1e-12));
    CHECK(wt.pose_at(10).roll_rad == doctest::Approx(89.5 * sss::pi_v<double> / 180.0).epsilon(1e-12));
    // Faults not tied to one line: line 0.
    CHECK(error_of("# nothing here\n").line() == 0);
    CHECK(std::string(error_of("time,x,y,z\n0,0,0,5\n").what()).find("at least 2 samples") != std::string::npos);
}

TEST_CASE("A value beyond the scalar type's range, or an angle beyond 10^6 degrees, fails naming its line and column") {
    std::istringstream x("time,x,y,z\n0,0,0,5\n1,1e39,1,5\n");
    try {
        (void)sss::io::read_trajectory_csv<float>(x, "survey.csv");
        FAIL("no error");
    } catch (const sss::file_error& e) {
        CHECK(e.line() == 3);
        CHECK(std::string(e.what()).find("survey.csv:3: column 3: column 'x': '1e39' is out of range") != std::string::npos);
    }
    // A UTM northing in float would move in half-metre steps: refused, naming where; a double holds it.
    std::istringstream utm("time,x,y,z\n0,500000.5,6543210.12,5\n1,500001,6543211.37,5\n");
    try {
        (void)sss::io::read_trajectory_csv<float>(utm, "utm.csv");
        FAIL("no error");
    } catch (const sss::file_error& e) {
        CHECK(e.line() == 2);
        CHECK(std::string(e.what()).find("utm.csv:2: column 3: column 'x': '500000.5' lies 131 km or more") != std::string::npos);
    }
    std::istringstream utm_double("time,x,y,z\n0,500000.5,6543210.12,5\n1,500001,6543211.37,5\n");
    CHECK(sss::io::read_trajectory_csv<double>(utm_double, "utm.csv").position_m[0].y == 6543210.12);
    std::istringstream same("time,x,y,z\n0,0,0,5\n1,1e39,1,5\n");
    CHECK(sss::io::read_trajectory_csv<double>(same, "survey.csv").position_m[1].x == 1e39); // a double holds it
    const sss::file_error yaw = error_of("time,x,y,z,yaw\n0,0,0,5,0\n1,0,1,5,3.6e300\n");
    CHECK(yaw.line() == 3);
    CHECK(std::string(yaw.what()).find("angles lie within 10^6 degrees") != std::string::npos);
    std::istringstream turns("time,x,y,z,yaw\n0,0,0,5,0\n1,0,1,5,-7200\n"); // twenty turns is a heading
    CHECK(sss::io::read_trajectory_csv<double>(turns, "survey.csv").yaw_rad.size() == 2);
}

TEST_CASE("A file on disk loads into a trajectory whose poses reproduce the samples; a missing file is a file_error") {
    const std::filesystem::path path = std::filesystem::current_path() / "trajectory_csv_test.csv";
    {
        std::ofstream out(path);
        out << "time_s,x_m,y_m,z_m,yaw_deg\n";
        for (int i = 0; i <= 10; ++i) out << i << "," << 0.5 * i << "," << 2.0 * i << ",10," << 45 + i << "\n";
    }
    sss::motion::trajectory_params<double> p;
    p.ping_interval_s = 0.5;
    const auto traj = sss::io::load_trajectory_csv<double>(path, p);
    CHECK(traj.ping_count() == 21);
    const auto q = traj.pose_at(8); // t = 4 s
    CHECK(q.position.x == doctest::Approx(2.0));
    CHECK(q.position.y == doctest::Approx(8.0));
    CHECK(q.yaw_rad == doctest::Approx(49.0 * pi / 180.0));
    std::filesystem::remove(path);
    try {
        (void)sss::io::read_trajectory_csv<double>(path);
        FAIL("no exception for a missing file");
    } catch (const sss::file_error& e) {
        CHECK(e.file() == path.string());
        CHECK(std::string(e.what()).find("cannot open") != std::string::npos);
    }
}
