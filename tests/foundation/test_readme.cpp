// The README cannot drift from the code: its policy table lists exactly the policies the headers ship (and
// sss::policies<T> names), and every figure it states in dB names, in a marker
// `<!-- bound: <file> "<text>" -->`, the assertion of a test that holds the same number.

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

fs::path source_dir() { return fs::path(SSS_SOURCE_DIR); }

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    REQUIRE_MESSAGE(in, "cannot read " << p.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The README with its fenced code blocks blanked out (prose and tables only).
std::string readme_prose() {
    std::istringstream in(read(source_dir() / "README.md"));
    std::string out, line;
    bool fenced = false;
    while (std::getline(in, line)) {
        if (line.rfind("```", 0) == 0) {
            fenced = !fenced;
            out += '\n';
            continue;
        }
        out += fenced ? std::string() : line;
        out += '\n';
    }
    return out;
}

const std::vector<std::string> families{"scattering", "propagation", "beam", "motion"};

/// family -> policy names, from the headers' `static_assert(<Concept><name<float>> ...)` lines.
std::map<std::string, std::set<std::string>> shipped_policies() {
    const std::map<std::string, std::string> concept_of{
        {"Scattering", "scattering"}, {"Propagation", "propagation"}, {"Beam", "beam"}, {"Motion", "motion"}};
    std::map<std::string, std::set<std::string>> out;
    const std::regex assert_re(R"(static_assert\((Scattering|Propagation|Beam|Motion)<(\w+)<float>>)");
    for (const auto& family : families)
        for (const auto& e : fs::directory_iterator(source_dir() / "include" / "sss" / family)) {
            if (e.path().extension() != ".hpp") continue;
            const std::string text = read(e.path());
            for (std::sregex_iterator it(text.begin(), text.end(), assert_re), end; it != end; ++it)
                out[concept_of.at((*it)[1].str())].insert((*it)[2].str());
        }
    return out;
}

/// family -> the names in backticks in the third column of the README's policy table row for that family.
std::map<std::string, std::set<std::string>> readme_table() {
    std::map<std::string, std::set<std::string>> out;
    std::istringstream in(readme_prose());
    std::string line;
    const std::regex row_re(R"(^\| *(\w+) *\|[^|]*\|([^|]*)\| *$)");
    const std::regex name_re("`(\\w+)`");
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, row_re)) continue;
        const std::string shipped = m[2].str();
        for (std::sregex_iterator it(shipped.begin(), shipped.end(), name_re), end; it != end; ++it)
            out[m[1].str()].insert((*it)[1].str());
    }
    return out;
}

std::vector<double> numbers_in(const std::string& s) {
    std::vector<double> v;
    const std::regex num_re(R"((\d+(?:\.\d+)?))");
    for (std::sregex_iterator it(s.begin(), s.end(), num_re), end; it != end; ++it) v.push_back(std::stod((*it)[1].str()));
    return v;
}

} // namespace

TEST_CASE("the README's policy table lists exactly the policies each family ships") {
    const auto shipped = shipped_policies();
    const auto table = readme_table();
    for (const auto& family : families) {
        CAPTURE(family);
        REQUIRE(shipped.count(family) == 1);
        REQUIRE_MESSAGE(table.count(family) == 1, "README.md has no policy table row for " << family);
        for (const auto& name : shipped.at(family))
            CHECK_MESSAGE(table.at(family).count(name) == 1, "README.md's policy table omits " << family << "::" << name);
        for (const auto& name : table.at(family))
            CHECK_MESSAGE(shipped.at(family).count(name) == 1, "README.md's policy table names " << name
                                                                   << ", which include/sss/" << family << " does not ship");
    }
}

TEST_CASE("sss::policies<T> names every shipped policy") {
    const std::string bundle = read(source_dir() / "include" / "sss" / "policies.hpp");
    for (const auto& [family, names] : shipped_policies())
        for (const auto& name : names)
            CHECK_MESSAGE(bundle.find("using " + name + " = " + family + "::" + name + "<T>;") != std::string::npos,
                          "policies.hpp does not name " << family << "::" << name);
}

TEST_CASE("every bound the README states is the bound a test asserts, with the same number") {
    const std::string prose = readme_prose();
    const std::regex marker_re(R"re(<!-- bound: (\S+) "([^"]+)" -->)re");
    std::size_t markers = 0;
    for (std::sregex_iterator it(prose.begin(), prose.end(), marker_re), end; it != end; ++it) {
        ++markers;
        const std::string file = (*it)[1].str(), text = (*it)[2].str();
        CAPTURE(file);
        CAPTURE(text);
        REQUIRE(fs::exists(source_dir() / file));
        CHECK_MESSAGE(read(source_dir() / file).find(text) != std::string::npos, file << " does not assert " << text);
        // The number the README states is the last one before the marker.
        const auto before = numbers_in(prose.substr(0, static_cast<std::size_t>(it->position())));
        REQUIRE(!before.empty());
        const auto asserted = numbers_in(text);
        bool same = false;
        for (double a : asserted) same = same || a == before.back();
        CHECK_MESSAGE(same, "README.md states " << before.back() << " where " << file << " asserts " << text);
    }
    CHECK(markers >= 1);
}

TEST_CASE("every figure in dB in the README's prose is followed by the test bound it quotes") {
    // Each "<number> dB" must be followed by a bound marker before the next such figure.
    const std::string prose = readme_prose();
    const std::regex token_re(R"re((\d+(?:\.\d+)?) dB|<!-- bound:)re");
    std::string pending;
    for (std::sregex_iterator it(prose.begin(), prose.end(), token_re), end; it != end; ++it) {
        if ((*it)[1].matched) {
            CHECK_MESSAGE(pending.empty(), "README.md states " << pending << " dB without a bound marker");
            pending = (*it)[1].str();
        } else {
            pending.clear();
        }
    }
    CHECK_MESSAGE(pending.empty(), "README.md states " << pending << " dB without a bound marker");
}
