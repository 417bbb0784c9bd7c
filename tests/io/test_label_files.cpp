// The label writers on label images made by hand: every box and COCO mask holds exactly its object's pixels, however
// many objects there are; inputs that would make a wrong or unreadable file are refused by name; the files of one
// label set are replaced together.
#include <doctest/doctest.h>

#include <algorithm>
#include <clocale>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <locale>
#include <map>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sss/io/labels.hpp"
#include "support/scratch_dir.hpp"
#include "support/temporaries.hpp"

namespace {

using namespace sss;
using sss_test::scratch_dir;

std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// An image of `objects` objects: each a highlight rectangle and a shadow rectangle beside it, placed at random (later
// ones overwrite earlier ones), on a seabed with water column above; object k has class k % 5 + 1. Some objects are
// wholly overwritten, and some keep only their shadow.
label_image random_labels(std::size_t pings, std::size_t samples, std::size_t objects, unsigned seed) {
    label_image img{.pings = pings, .samples = samples, .dt_s = 1e-4, .values = {}};
    img.values.assign(pings * img.width(), sample_label{.kind = sample_class::seabed, .object = no_object, .label = 0, .material = 0});
    for (std::size_t r = 0; r < pings; ++r)
        for (std::size_t c = samples - 3; c < samples + 3; ++c) img.values[r * img.width() + c].kind = sample_class::water_column;
    std::mt19937 rng(seed);
    const auto below = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
    for (std::size_t k = 0; k < objects; ++k) {
        const auto id = static_cast<std::uint32_t>(3 * k + 7); // ids need not be dense
        const std::size_t r0 = below(pings), c0 = below(img.width());
        const std::size_t r1 = std::min(pings, r0 + 1 + below(6)), c1 = std::min(img.width(), c0 + 1 + below(8));
        const std::size_t s1 = std::min(img.width(), c1 + below(10));
        for (std::size_t r = r0; r < r1; ++r)
            for (std::size_t c = c0; c < s1; ++c)
                img.values[r * img.width() + c] = {.kind = c < c1 ? sample_class::highlight : sample_class::shadow,
                                                   .object = id,
                                                   .label = static_cast<std::uint32_t>(k % 5 + 1),
                                                   .material = 0};
    }
    return img;
}

} // namespace

TEST_CASE("Each box and COCO mask from an image of many objects holds exactly its object's pixels, and YOLO agrees") {
    const label_image img = random_labels(70, 60, 400, 11);
    const std::vector<io::label_class> classes{{1, "rock"}, {2, "tyre"}, {3, "mine"}, {4, "wreck"}, {5, "pipe"}};
    for (const io::box_extent e : {io::box_extent::highlight, io::box_extent::highlight_and_shadow}) {
        // Brute force, object by object: the objects with a highlight, their class (first highlight by ping, then
        // column), the bounds and count of their mask.
        std::map<std::uint32_t, io::object_box> want;
        for (std::size_t r = 0; r < img.pings; ++r)
            for (std::size_t c = 0; c < img.width(); ++c) {
                const sample_label& l = img.at(r, c);
                if (l.kind == sample_class::highlight && !want.count(l.object))
                    want[l.object] = io::object_box{l.object, l.label, 0, 0, 0, 0, 0};
            }
        for (auto& [id, b] : want) {
            std::size_t x0 = img.width(), y0 = img.pings, xe = 0, ye = 0;
            for (std::size_t r = 0; r < img.pings; ++r)
                for (std::size_t c = 0; c < img.width(); ++c)
                    if (io::in_mask(img.at(r, c), id, e)) {
                        x0 = std::min(x0, c), y0 = std::min(y0, r), xe = std::max(xe, c + 1), ye = std::max(ye, r + 1);
                        ++b.area;
                    }
            b.x = x0, b.y = y0, b.width = xe - x0, b.height = ye - y0;
        }
        const auto got = io::object_boxes(img, e);
        REQUIRE(got.size() == want.size());
        CHECK(got.size() > 100u); // most objects keep a highlight
        auto it = want.begin();
        for (const io::object_box& b : got) {
            const io::object_box& w = (it++)->second;
            CHECK(b.object == w.object);
            CHECK(b.class_id == w.class_id);
            CHECK(b.x == w.x);
            CHECK(b.y == w.y);
            CHECK(b.width == w.width);
            CHECK(b.height == w.height);
            CHECK(b.area == w.area);
        }
        // COCO: every annotation's run-length mask, decoded down the columns, is the object's mask pixel for pixel.
        const std::vector<io::coco_image> set{{"a.png", &img}};
        const auto coco = nlohmann::json::parse(io::coco_json(set, classes, e));
        REQUIRE(coco["annotations"].size() == got.size());
        for (const auto& a : coco["annotations"]) {
            const auto id = a["sss_object_id"].get<std::uint32_t>();
            std::size_t pixel = 0, area = 0;
            bool inside = false, same = true;
            for (const auto& run : a["segmentation"]["counts"]) {
                for (std::size_t i = 0; i < run.get<std::size_t>(); ++i, ++pixel) {
                    const std::size_t c = pixel / img.pings, r = pixel % img.pings;
                    same = same && c < img.width() && io::in_mask(img.at(r, c), id, e) == inside;
                    area += inside;
                }
                inside = !inside;
            }
            CHECK(same);
            CHECK(pixel == img.pings * img.width());
            CHECK(area == a["area"].get<std::size_t>());
            CHECK(area == want[id].area);
        }
        // YOLO: one line per box, in the same order, its class's index and the box's centre and size normalised, to
        // eight decimals with a '.'.
        std::ostringstream want_yolo;
        want_yolo.imbue(std::locale::classic());
        want_yolo << std::fixed << std::setprecision(8);
        for (const io::object_box& b : got)
            want_yolo << (b.class_id - 1) << ' ' << (double(b.x) + 0.5 * double(b.width)) / double(img.width()) << ' '
                      << (double(b.y) + 0.5 * double(b.height)) / double(img.pings) << ' ' << double(b.width) / double(img.width())
                      << ' ' << double(b.height) / double(img.pings) << '\n';
        const std::string yolo = io::yolo_txt(img, classes, e);
        CHECK(yolo == want_yolo.str());
        // The same under a C locale whose decimal point is a comma, where this machine has one (as a GUI program may
        // set): YOLO readers take only '.'.
        for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8", "de_DE", "fr_FR"}) {
            if (!std::setlocale(LC_NUMERIC, name)) continue;
            const std::string in_comma_locale = io::yolo_txt(img, classes, e);
            std::setlocale(LC_NUMERIC, "C");
            CHECK(in_comma_locale == yolo);
            break;
        }
    }
}

TEST_CASE("Label writers refuse an image of the wrong size, and class names or ids that would break a class list or JSON") {
    scratch_dir d;
    label_image img = random_labels(8, 10, 5, 3);
    const std::vector<io::label_class> good{{1, "rock"}, {2, "tyre"}, {3, "mine"}, {4, "wreck"}, {5, "pipe"}};
    img.values.pop_back();
    const auto names_values = [](const auto& f) {
        try {
            f();
        } catch (const invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(no error)");
    };
    CHECK(names_values([&] { (void)io::object_boxes(img, io::box_extent::highlight); }) == "label_image.values");
    CHECK(names_values([&] { (void)io::yolo_txt(img, good, io::box_extent::highlight); }) == "label_image.values");
    const std::vector<io::coco_image> set{{"a.png", &img}};
    CHECK(names_values([&] { (void)io::coco_json(set, good, io::box_extent::highlight); }) == "label_image.values");
    CHECK(names_values([&] { io::write_label_images(d.file("short"), img, good); }) == "label_image.values");
    img = random_labels(8, 10, 5, 3);
    // A newline would make two lines of a class list and shift every later index; bytes that are not UTF-8 make
    // JSON no parser reads; an empty name is an empty line.
    for (const std::string& bad : {std::string("rock\nwreck"), std::string("caf\xe9"), std::string(), std::string("tab\there")}) {
        std::vector<io::label_class> classes = good;
        classes[2].name = bad;
        CAPTURE(bad);
        CHECK(names_values([&] { (void)io::yolo_classes_txt(classes); }) == "label_class.name");
        CHECK(names_values([&] { (void)io::coco_json(std::vector<io::coco_image>{{"a.png", &img}}, classes, io::box_extent::highlight); }) ==
              "label_class.name");
        CHECK(names_values([&] { io::write_label_images(d.file("bad"), img, classes); }) == "label_class.name");
    }
    // Two classes of one id: COCO would list the id twice, YOLO take the first name and the legend the last.
    {
        std::vector<io::label_class> twice = good;
        twice[4].id = 1;
        CHECK(names_values([&] { (void)io::yolo_classes_txt(twice); }) == "label_class.id");
        CHECK(names_values([&] { (void)io::coco_json(std::vector<io::coco_image>{{"a.png", &img}}, twice, io::box_extent::highlight); }) ==
              "label_class.id");
        CHECK(names_values([&] { io::write_label_images(d.file("twice"), img, twice); }) == "label_class.id");
    }
    // A file name that is not UTF-8 (a Linux file name may be any bytes) would be written altered.
    CHECK(names_values([&] { (void)io::coco_json(std::vector<io::coco_image>{{"a\xff.png", &img}}, good, io::box_extent::highlight); }) ==
          "coco_image.file_name");
    CHECK(std::filesystem::is_empty(d.dir)); // nothing written, no temporary left
    // Names in any script are text like any other.
    std::vector<io::label_class> classes = good;
    classes[2].name = "mine \xc3\xa0 orin \xe6\xb5\xb7";
    const auto coco = nlohmann::json::parse(io::coco_json(std::vector<io::coco_image>{{"a.png", &img}}, classes, io::box_extent::highlight));
    CHECK(coco["categories"][2]["name"] == classes[2].name);
}

TEST_CASE("A label set's images and legend are replaced together: one that cannot be replaced leaves the others old") {
    scratch_dir d;
    const std::vector<io::label_class> classes{{1, "rock"}, {2, "tyre"}, {3, "mine"}, {4, "wreck"}, {5, "pipe"}};
    const std::string stem = d.file("set");
    io::write_label_images(stem, random_labels(8, 10, 5, 3), classes);
    const std::string old_class = slurp(stem + "_class.png"), old_instance = slurp(stem + "_instance.png");
    // The legend's name taken by a directory: nothing is renamed, so the old images stay with the old legend gone.
    std::filesystem::remove(stem + "_legend.json");
    std::filesystem::create_directory(stem + "_legend.json");
    const label_image other = random_labels(9, 12, 7, 4);
    try {
        io::write_label_images(stem, other, classes);
        FAIL("no error");
    } catch (const file_error& e) {
        CHECK(e.file() == stem + "_legend.json");
    }
    CHECK(slurp(stem + "_class.png") == old_class);
    CHECK(slurp(stem + "_instance.png") == old_instance);
    for (const char* s : {"_class.png", "_instance.png", "_legend.json"}) CHECK(sss_test::temporaries_left(stem + s) == 0);
}

TEST_CASE("The legend names every value of the instance image, an object whose shadow alone is in the image included") {
    scratch_dir d;
    const std::vector<io::label_class> classes{{1, "rock"}, {2, "tyre"}, {3, "mine"}, {4, "wreck"}, {5, "pipe"}};
    const label_image img = random_labels(40, 50, 120, 11);
    std::map<std::uint32_t, std::uint32_t> in_image; // object -> class: its box's, else its first shadow sample's
    std::size_t shadow_only = 0;
    const auto boxes = io::object_boxes(img, io::box_extent::highlight_and_shadow);
    for (const io::object_box& b : boxes) in_image.emplace(b.object, b.class_id);
    for (const sample_label& l : img.values)
        if (l.kind == sample_class::shadow) in_image.emplace(l.object, l.label);
    for (const auto& [object, cls] : in_image)
        shadow_only += std::none_of(boxes.begin(), boxes.end(), [&](const io::object_box& b) { return b.object == object; });
    REQUIRE(shadow_only > 0u); // the case in question occurs in this image
    const std::string stem = d.file("set");
    io::write_label_images(stem, img, classes);
    const auto legend = nlohmann::json::parse(slurp(stem + "_legend.json"))["instance_png"];
    CHECK(legend.size() == in_image.size() + 1); // and "0": none
    CHECK(legend["0"] == "none");
    for (const auto& [object, cls] : in_image) {
        const std::string key = std::to_string(object + 1);
        REQUIRE(legend.contains(key));
        CHECK(legend[key]["object_id"] == object);
        CHECK(legend[key]["class_id"] == cls);
        CHECK(legend[key]["class"] == classes[cls - 1].name);
    }
}

TEST_CASE("The legend gives an object the class of its box, whose highlight may be labelled apart from its shadow") {
    // One object of two parts: its shadow, cast by a part labelled 2, comes first in the row (port: farther out, to
    // the left); its highlight is labelled 1. Its box, COCO and YOLO say class 1, and so must the legend.
    scratch_dir d;
    const std::vector<io::label_class> classes{{1, "mine"}, {2, "chain"}};
    label_image img{.pings = 1, .samples = 2, .dt_s = 1e-4, .values = {}};
    img.values = {{.kind = sample_class::shadow, .object = 4, .label = 2, .material = 0},
                  {.kind = sample_class::highlight, .object = 4, .label = 1, .material = 0},
                  {.kind = sample_class::seabed, .object = no_object, .label = 0, .material = 0},
                  {.kind = sample_class::seabed, .object = no_object, .label = 0, .material = 0}};
    const auto boxes = io::object_boxes(img, io::box_extent::highlight_and_shadow);
    REQUIRE(boxes.size() == 1u);
    CHECK(boxes[0].class_id == 1u);
    const std::string stem = d.file("parts");
    io::write_label_images(stem, img, classes);
    const auto legend = nlohmann::json::parse(slurp(stem + "_legend.json"))["instance_png"];
    CHECK(legend["5"]["class_id"] == 1);
    CHECK(legend["5"]["class"] == "mine");
}
