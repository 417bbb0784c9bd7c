// sss-render's outputs are replaced all or none: a rename that fails while they are committed puts every old file
// back and keeps none of the new ones, and no temporary or kept copy is left behind either way.

#include <doctest/doctest.h>

#include "render_scene.hpp"
#include "scene_file/read.hpp"
#include "support/scratch_dir.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

void put(const std::filesystem::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string get(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> listing(const std::filesystem::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

} // namespace

TEST_CASE("outputs are replaced all or none: a rename that fails puts every old file back and keeps no new one") {
    namespace sf = sss::scene_file;
    sss_test::scratch_dir d("sss_output_set_");
    put(d.dir / "a.png", "old a");
    put(d.dir / "b.npy", "old b");
    {
        sf::detail::output_set files(d.dir);
        put(files.add("a.png"), "new a");
        put(files.add("c.json"), "new c"); // no old file of that name
        (void)files.add("b.npy");          // its temporary is never written: its rename fails, after the others'
        try {
            (void)files.commit();
            FAIL("no error");
        } catch (const sf::scene_error& e) {
            CHECK(std::string(e.what()).find("b.npy: cannot be replaced") != std::string::npos);
            CHECK(std::string(e.what()).find("the old files kept") != std::string::npos);
        }
    }
    CHECK(get(d.dir / "a.png") == "old a");
    CHECK(get(d.dir / "b.npy") == "old b");
    CHECK(listing(d.dir) == std::vector<std::string>{"a.png", "b.npy"}); // no new file, copy or temporary left
    {
        sf::detail::output_set files(d.dir);
        put(files.add("a.png"), "new a");
        put(files.add("b.npy"), "new b");
        CHECK(files.commit().size() == 2);
    }
    CHECK(get(d.dir / "a.png") == "new a");
    CHECK(get(d.dir / "b.npy") == "new b");
    CHECK(listing(d.dir) == std::vector<std::string>{"a.png", "b.npy"});
}

TEST_CASE("two runs writing one name in one directory never share a temporary or kept file") {
    namespace sf = sss::scene_file;
    sss_test::scratch_dir d("sss_output_set_");
    put(d.dir / "a.png", "old a");
    sf::detail::output_set first(d.dir), second(d.dir);
    const std::string t1 = first.add("a.png"), t2 = second.add("a.png");
    const std::string s1 = first.add_stem("line", {".xtf", ".json"}), s2 = second.add_stem("line", {".xtf", ".json"});
    CHECK(t1 != t2);
    CHECK(s1 != s2);
    put(t1, "first a");
    put(t2, "second a");
    put(s1 + ".xtf", "first xtf");
    put(s1 + ".json", "first json");
    put(s2 + ".xtf", "second xtf");
    put(s2 + ".json", "second json");
    CHECK(first.commit().size() == 3);
    CHECK(get(d.dir / "a.png") == "first a");
    CHECK(get(d.dir / "line.xtf") == "first xtf");
    CHECK(second.commit().size() == 3); // its temporaries were untouched by the first run's commit
    CHECK(get(d.dir / "a.png") == "second a");
    CHECK(get(d.dir / "line.xtf") == "second xtf");
    CHECK(get(d.dir / "line.json") == "second json");
    CHECK(listing(d.dir) == std::vector<std::string>{"a.png", "line.json", "line.xtf"});
}

TEST_CASE("the memory check counts each thread's working memory for its ping, which long lines make larger than the image") {
    namespace sf = sss::scene_file;
    // One ping at 1 GHz over 6 m: lines of 8 M samples. The image is 2 x 8 M values; a ping's time sampler alone
    // holds 8 sub-bins of two moments in double a sample (128 bytes), shared once and copied per thread.
    auto scene = [](int threads, bool labels) {
        return sf::parse("[render]\npings = 1\nthreads = " + std::to_string(threads) +
                             "\n[sonar]\nmax_range_m = 6\nsample_rate_hz = 1e9\n[output]\nyolo = " + (labels ? "true" : "false") +
                             "\n",
                         "long_lines.toml");
    };
    const auto one = sf::detail::estimate_memory<float>(scene(1, false), 1);
    CHECK(one.samples == 8000000.0);
    CHECK(one.threads == 1.0);
    CHECK(one.image < 0.25e9);
    CHECK(one.working > 2.0e9);                  // 8 M samples x (152 + 128) bytes, and the rays' echoes
    CHECK(one.total() > one.image + one.working - 1.0);
    // Threads beyond the pings render nothing at once; with two pings, two threads each hold a ping.
    CHECK(sf::detail::estimate_memory<float>(scene(4, false), 1).working == one.working);
    const auto two = sf::detail::estimate_memory<float>(scene(2, false), 2);
    CHECK(two.threads == 2.0);
    CHECK(two.working - one.working > 1.0e9);
    // Labels add each thread's sums.
    CHECK(sf::detail::estimate_memory<float>(scene(1, true), 1).working > one.working + 1.0e9);
}
