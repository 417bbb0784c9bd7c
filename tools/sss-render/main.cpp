// sss-render: renders a scene file (TOML; docs/scene-format.md) to the images and arrays it asks for.
//
//   sss-render SCENE [-o DIR] [--pings A:B] [--threads N] [--seed S] [--dry-run]
//
// Progress: a bar (pings done, pings/s, ETA) on a terminal, plain lines otherwise. Outputs are written under
// temporary names and renamed only when every one of them is complete, so an error or Ctrl-C leaves no file.
// Any error: one line on stderr, exit status 1 (2 when CLI11 rejects the command line, 128 + the signal's number when
// interrupted by SIGINT, SIGTERM or SIGHUP: 130, 143, 129; a second such signal ends the process at once, leaving
// its temporary files).

#include "render.hpp"
#include "scene_file/read.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <utility>

namespace {

namespace sf = sss::scene_file;

/// "A:B" -> [A, B); "A:" -> [A, pings). A and B are whole numbers (digits only) with A < B <= pings: the range
/// picks pings of the scene's survey (render.pings, itself at most sf::max_pings), never pings beyond it.
std::pair<std::size_t, std::size_t> ping_range(const std::string& s, std::size_t pings) {
    const auto colon = s.find(':');
    if (colon == std::string::npos) throw CLI::ValidationError("--pings", "expects A:B (first ping, one past the last)");
    const auto whole = [&](const std::string& t) {
        if (t.empty() || t.size() > 18 || !std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; }))
            throw CLI::ValidationError("--pings", "'" + s + "' is not A:B with whole numbers");
        return static_cast<std::size_t>(std::stoull(t));
    };
    const std::size_t a = colon ? whole(s.substr(0, colon)) : 0;
    const std::size_t b = colon + 1 < s.size() ? whole(s.substr(colon + 1)) : pings;
    if (colon + 1 == s.size() && a >= pings)
        throw CLI::ValidationError("--pings", "'" + s + "' starts past the scene's last ping (render.pings = " +
                                                  std::to_string(pings) + ")");
    if (b <= a) throw CLI::ValidationError("--pings", "'" + s + "' is empty: B must exceed A");
    if (b > pings) {
        std::string what = "'" + s + "' reaches past the scene's last ping (render.pings = ";
        what += std::to_string(pings);
        what += "): raise render.pings to render further";
        throw CLI::ValidationError("--pings", what);
    }
    return {a, b};
}

/// The value of `s` if it is a whole number from 0 to max written in digits only (leading zeros allowed);
/// otherwise a ValidationError for `option` (a larger value is an error, not clamped).
std::uint64_t whole_number(const std::string& option, const std::string& s, std::uint64_t max) {
    const std::string max_text = std::to_string(max);
    const std::size_t lead = std::min(s.find_first_not_of('0'), s.empty() ? 0 : s.size() - 1); // keep one digit
    const std::string digits = s.substr(lead);
    if (s.empty() || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
        digits.size() > max_text.size() || (digits.size() == max_text.size() && digits > max_text))
        throw CLI::ValidationError(option, "'" + s + "' is not a whole number from 0 to " + max_text);
    return std::stoull(digits);
}

/// --seed S: 0 to 2^63 - 1.
std::int64_t seed_of(const std::string& s) {
    return static_cast<std::int64_t>(whole_number("--seed", s, std::uint64_t(std::numeric_limits<std::int64_t>::max())));
}

/// --threads N: 0 to sf::max_threads (read here: CLI11's own check calls "1e3" out of range).
unsigned threads_of(const std::string& s) {
    return static_cast<unsigned>(whole_number("--threads", s, std::uint64_t(sf::max_threads)));
}

/// A message as one printable line: control characters (a NUL or a newline read from a broken file) as '?', and
/// at most 2000 bytes, so that a binary or enormous field cannot flood the terminal.
std::string printable(std::string m) {
    for (char& c : m)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    if (m.size() > 2000) {
        std::size_t cut = 2000;
        while (cut > 0 && (static_cast<unsigned char>(m[cut]) & 0xC0) == 0x80) --cut; // not inside a UTF-8 character
        m = m.substr(0, cut) + " [...]";
    }
    return m;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"sss-render: renders a sidescan sonar scene file (TOML) to images and arrays"};
    std::string scene_path, out_dir = ".", pings_arg;
    std::string threads_arg, seed_arg;
    bool dry_run = false;
    app.add_option("scene", scene_path, "the scene file (TOML)")->required();
    app.add_option("-o,--output", out_dir, "directory the outputs go to (created if missing)");
    app.add_option("--pings", pings_arg, "pings A:B of the scene's render.pings to render (default 0:render.pings)");
    app.add_option("--threads", threads_arg, "worker threads (default render.threads; 0 every core)");
    app.add_option("--seed", seed_arg, "replaces seabed.seed (roughness and ripples of a seabed generated from [[seabed.region]] tables): a whole number from 0 to 2^63 - 1");
    app.add_flag("--dry-run", dry_run, "validate, print the resolved scene as TOML and the coverage problems; render nothing");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "sss-render: %s\n", printable(e.what()).c_str());
        return 2;
    }

    try {
        sf::description d = sf::parse_file(scene_path);
        if (app.count("--seed")) {
            if (!d.bed.file.empty()) // as seabed.seed beside seabed.file: refused rather than ignored
                throw CLI::ValidationError("--seed", "the scene loads its seabed from seabed.file (" + d.bed.file +
                                                         "): there is no generated seabed to seed");
            if (d.bed.regions.empty()) // as seabed.seed without regions
                throw CLI::ValidationError("--seed", "the scene's seabed has no [[seabed.region]] tables: there is no "
                                                     "roughness or ripple to seed");
            d.bed.seed = seed_of(seed_arg);
        }
        if (app.count("--threads")) d.run.threads = threads_of(threads_arg);
        const auto [first, last] = pings_arg.empty() ? std::pair<std::size_t, std::size_t>{0, std::size_t(d.run.pings)}
                                                     : ping_range(pings_arg, std::size_t(d.run.pings));
        const sf::render_request request{.scene_path = scene_path, .out_dir = out_dir, .first = first, .last = last,
                                         .pings_asked = pings_arg.empty() ? "render.pings = " + std::to_string(d.run.pings)
                                                                          : "--pings " + pings_arg,
                                         .dry_run = dry_run};
        // The scalar of the world and the simulators (each compiled in its own translation unit).
        return d.run.precision == "double" ? sf::render_scene<double>(d, request) : sf::render_scene<float>(d, request);
    } catch (const sf::interrupted_error& e) {
        std::fprintf(stderr, "\nsss-render: %s\n", printable(e.what()).c_str());
        const int sig = sf::interrupted.load();
        return 128 + (sig > 0 ? sig : 2); // as a shell reports a process the signal ended: 130 for SIGINT
    } catch (const CLI::ValidationError& e) { // a command-line value refused once the scene is known
        std::fprintf(stderr, "sss-render: %s\n", printable(e.what()).c_str());
        return 1;
    } catch (const sss::scene_file::scene_error& e) {
        std::fprintf(stderr, "sss-render: %s\n", printable(e.what()).c_str());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "sss-render: %s\n",
                     printable(scene_path + ": out of memory: the scene needs more than this machine can give (the seabed: "
                                            "seabed.nx x seabed.ny; the image: the pings x sonar.max_range_m x "
                                            "sonar.sample_rate_hz)").c_str());
        return 1;
    } catch (const std::exception& e) {
        // The library's own messages name the parameter or the file; the scene file is named here.
        std::string what = e.what();
        if (what.rfind("sss: ", 0) == 0) what = what.substr(5);
        std::fprintf(stderr, "sss-render: %s\n", printable(scene_path + ": " + what).c_str());
        return 1;
    }
}
