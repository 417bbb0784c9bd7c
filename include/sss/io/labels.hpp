#pragma once
/// \file
/// Ground-truth labels as files that detection and segmentation tools read: one box per object in COCO JSON and
/// YOLO text, and label images (PNG) with a JSON legend. Input: a label_image (labels/ground_truth.hpp).
///
/// Boxes are in pixels of the image the labels share (column = waterfall column, row = ping), from the top-left
/// corner of the top-left pixel; a box covers whole pixels. An object's box encloses its highlight samples
/// (`box_extent::highlight`) or its highlight and its shadow (`box_extent::highlight_and_shadow`); an object
/// with no highlight sample in the image gets no box.
/// - COCO ("Common Objects in Context" data format, cocodataset.org, Lin et al., 2014, ECCV): `images`
///   [{id, file_name, width, height}], `categories` [{id, name, supercategory}], `annotations` [{id, image_id,
///   category_id, bbox [x, y, width, height], area, iscrowd 0, segmentation}]; segmentation is the object's
///   mask as uncompressed run-length encoding {counts, size [height, width]}, runs down the columns
///   (column-major) starting with a run of zeros, as pycocotools reads it; area is the mask's pixel count.
///   Category ids are the scene's class ids.
/// - YOLO (Ultralytics "YOLO format"): one line per object, `index x_centre y_centre width height`, normalised
///   by the image's width and height; index is the position of the object's class in `classes` (0-based), and
///   `yolo_classes_txt` lists the names in that order. An image with no object has an empty file.
/// - Label images: an 8-bit PNG of sample_class values (0 no coverage, 1 water column, 2 seabed, 3 highlight,
///   4 shadow, 5 seabed shadow), a 16-bit PNG of instance values (object id + 1 on its highlight and shadow,
///   0 elsewhere), and a JSON legend of both: every instance value in the image, a shadow-only object's (which
///   has no box) included.

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/io/detail/atomic_file.hpp"
#include "sss/io/detail/bytes.hpp"
#include "sss/io/detail/json.hpp"
#include "sss/io/png.hpp"
#include "sss/labels/ground_truth.hpp"

namespace sss::io {

enum class box_extent : std::uint8_t { highlight, highlight_and_shadow };

/// A class of objects: the id its hits carry (hit::label) and its name.
struct label_class {
    std::uint32_t id = 0;
    std::string name;
};

/// One object's box and mask size, in pixels.
struct object_box {
    std::uint32_t object = no_object;
    std::uint32_t class_id = 0;
    std::size_t x = 0, y = 0, width = 0, height = 0; ///< columns [x, x + width), rows [y, y + height)
    std::size_t area = 0;                           ///< pixels of its mask (highlight, and shadow if chosen)
};

/// True when sample `l` belongs to object `id`'s mask for `e`.
[[nodiscard]] inline bool in_mask(const sample_label& l, std::uint32_t id, box_extent e) noexcept {
    return l.object == id && (l.kind == sample_class::highlight || (e == box_extent::highlight_and_shadow && l.kind == sample_class::shadow));
}

/// Throws invalid_parameter ("label_image.values") unless img holds pings x width() samples.
inline void check_label_image(const label_image& img) {
    const bool fits = img.samples <= (std::size_t(-1) / 2) && (img.pings == 0 || img.width() <= std::size_t(-1) / img.pings);
    sss::require(fits && img.values.size() == img.pings * img.width(), "label_image.values", [&] {
        return "must hold pings x 2 x samples = " + std::to_string(img.pings) + " x " + std::to_string(img.width()) +
               " labels, got " + std::to_string(img.values.size());
    });
}

/// Throws invalid_parameter ("label_class.name") unless every name is non-empty, well-formed UTF-8 and free of
/// control characters: a name is one line of a YOLO class list and one string of a JSON file, and a newline in
/// one would shift every later class's index; and ("label_class.id") where two classes share an id.
inline void check_class_names(std::span<const label_class> classes) {
    for (const label_class& c : classes) {
        const bool control = std::any_of(c.name.begin(), c.name.end(), [](char ch) {
            const auto u = static_cast<unsigned char>(ch);
            return u < 0x20 || u == 0x7f;
        });
        sss::require(!c.name.empty() && !control && sss::detail::valid_utf8(c.name), "label_class.name", [&] {
            return "of class " + std::to_string(c.id) +
                   " must be non-empty UTF-8 text without control characters (it is one line of a class list)";
        });
    }
    // One name per id: COCO's categories, YOLO's list and the legend would each pick a different one.
    std::vector<std::size_t> by_id(classes.size());
    for (std::size_t i = 0; i < by_id.size(); ++i) by_id[i] = i;
    std::stable_sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return classes[a].id < classes[b].id; });
    for (std::size_t i = 1; i < by_id.size(); ++i) {
        const label_class &a = classes[by_id[i - 1]], &b = classes[by_id[i]];
        sss::require(a.id != b.id, "label_class.id",
                     [&] { return std::to_string(a.id) + " names two classes, '" + a.name + "' and '" + b.name + "'"; });
    }
}

/// The boxes of the objects with a highlight in the image, in increasing object id; its class is the label of the
/// object's first highlight sample (by ping, then column). One pass over the image for the objects and one for
/// their boxes, whatever their number.
[[nodiscard]] inline std::vector<object_box> object_boxes(const label_image& img, box_extent e) {
    check_label_image(img);
    std::vector<object_box> boxes;
    std::unordered_map<std::uint32_t, std::size_t> index; // object id -> its box
    for (const sample_label& l : img.values)
        if (l.kind == sample_class::highlight && index.emplace(l.object, boxes.size()).second)
            boxes.push_back(object_box{l.object, l.label, 0, 0, 0, 0, 0});
    if (boxes.empty()) return boxes;
    struct extent {
        std::size_t x0, y0, xe = 0, ye = 0;
    };
    std::vector<extent> ext(boxes.size(), extent{img.width(), img.pings});
    for (std::size_t r = 0; r < img.pings; ++r)
        for (std::size_t c = 0; c < img.width(); ++c) {
            const sample_label& l = img.at(r, c);
            if (l.kind != sample_class::highlight && !(e == box_extent::highlight_and_shadow && l.kind == sample_class::shadow))
                continue;
            const auto it = index.find(l.object);
            if (it == index.end()) continue; // a shadow of an object with no highlight in the image
            extent& x = ext[it->second];
            x.x0 = std::min(x.x0, c);
            x.y0 = std::min(x.y0, r);
            x.xe = std::max(x.xe, c + 1);
            x.ye = std::max(x.ye, r + 1);
            ++boxes[it->second].area;
        }
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        boxes[i].x = ext[i].x0;
        boxes[i].y = ext[i].y0;
        boxes[i].width = ext[i].xe - ext[i].x0;
        boxes[i].height = ext[i].ye - ext[i].y0;
    }
    std::sort(boxes.begin(), boxes.end(), [](const object_box& a, const object_box& b) { return a.object < b.object; });
    return boxes;
}

/// One image of a COCO set: its file name and its labels.
struct coco_image {
    std::string file_name;
    const label_image* labels = nullptr;
};

/// The COCO JSON text of a set of images (ids 1, 2, ... in order; annotation ids 1, 2, ... over the set).
/// `classes` names the categories; a class id met in the labels but not listed is named "class_<id>".
[[nodiscard]] inline std::string coco_json(std::span<const coco_image> images, std::span<const label_class> classes, box_extent e) {
    check_class_names(classes);
    std::vector<label_class> cats(classes.begin(), classes.end());
    std::vector<std::vector<object_box>> boxes;
    for (const coco_image& im : images) {
        sss::require(im.labels != nullptr, "coco_image.labels", "must point to a label image");
        sss::require(sss::detail::valid_utf8(im.file_name), "coco_image.file_name", [&] {
            return "must be UTF-8 text (JSON holds no other), got a name of " + std::to_string(im.file_name.size()) + " bytes";
        });
        boxes.push_back(object_boxes(*im.labels, e));
        for (const object_box& b : boxes.back())
            if (std::none_of(cats.begin(), cats.end(), [&](const label_class& c) { return c.id == b.class_id; }))
                cats.push_back({b.class_id, "class_" + std::to_string(b.class_id)});
    }
    sss::detail::json_writer j;
    j.begin_object();
    j.key("info").begin_object().member("description", "sss simulated sidescan ground truth").end_object();
    j.key("images").begin_array();
    for (std::size_t i = 0; i < images.size(); ++i) {
        j.newline().begin_object().member("id", i + 1).member("file_name", images[i].file_name);
        j.member("width", images[i].labels->width()).member("height", images[i].labels->pings).end_object();
    }
    j.end_array().newline().key("categories").begin_array();
    for (const label_class& c : cats)
        j.newline().begin_object().member("id", c.id).member("name", c.name).member("supercategory", "object").end_object();
    j.end_array().newline().key("annotations").begin_array();
    std::size_t next_id = 1;
    for (std::size_t i = 0; i < images.size(); ++i) {
        const label_image& img = *images[i].labels;
        for (const object_box& b : boxes[i]) {
            j.newline().begin_object().member("id", next_id++).member("image_id", i + 1).member("category_id", b.class_id);
            j.key("bbox").begin_array().value(b.x).value(b.y).value(b.width).value(b.height).end_array();
            j.member("area", b.area).member("iscrowd", 0);
            j.key("segmentation").begin_object().key("counts").begin_array();
            // Runs down the columns; no mask pixel lies outside the box, so only the box's pixels are looked at.
            bool inside = false;
            std::size_t run = 0;
            const auto add = [&](bool mask, std::size_t count) {
                if (count == 0) return;
                if (mask != inside) {
                    j.value(run);
                    run = 0;
                    inside = mask;
                }
                run += count;
            };
            add(false, b.x * img.pings);
            for (std::size_t c = b.x; c < b.x + b.width; ++c) {
                add(false, b.y);
                for (std::size_t r = b.y; r < b.y + b.height; ++r) add(in_mask(img.at(r, c), b.object, e), 1);
                add(false, img.pings - b.y - b.height);
            }
            add(false, (img.width() - b.x - b.width) * img.pings);
            j.value(run).end_array();
            j.key("size").begin_array().value(img.pings).value(img.width()).end_array().end_object();
            j.member("sss_object_id", b.object).end_object();
        }
    }
    j.end_array().newline().end_object().newline();
    return j.str();
}

/// The YOLO text of one image (see the file comment). Throws invalid_parameter for a class id not in `classes`.
[[nodiscard]] inline std::string yolo_txt(const label_image& img, std::span<const label_class> classes, box_extent e) {
    std::string out;
    const double w = double(img.width()), h = double(img.pings);
    for (const object_box& b : object_boxes(img, e)) {
        const auto it = std::find_if(classes.begin(), classes.end(), [&](const label_class& c) { return c.id == b.class_id; });
        sss::require(it != classes.end(), "classes", "names no class " + std::to_string(b.class_id) + " (object " + std::to_string(b.object) + ")");
        // Eight decimals, with a '.' whatever the C locale (std::to_chars does not read it).
        out += std::to_string(static_cast<std::size_t>(it - classes.begin()));
        for (const double v : {(double(b.x) + 0.5 * double(b.width)) / w, (double(b.y) + 0.5 * double(b.height)) / h,
                               double(b.width) / w, double(b.height) / h}) {
            char buf[64];
            const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 8);
            out += ' ';
            out.append(buf, r.ptr);
        }
        out += '\n';
    }
    return out;
}

/// The class names, one per line, in YOLO index order.
[[nodiscard]] inline std::string yolo_classes_txt(std::span<const label_class> classes) {
    check_class_names(classes);
    std::string out;
    for (const label_class& c : classes) out += c.name + "\n";
    return out;
}

/// Writes a COCO JSON file, a YOLO text file or a class list (through a temporary renamed when complete).
inline void write_text(const std::string& path, const std::string& text) { sss::detail::write_file_atomically(path, text); }

/// The sample_class of every pixel (8 bits) and the instance value (object id + 1 on highlight and shadow, 16 bits).
[[nodiscard]] inline std::vector<std::uint8_t> class_pixels(const label_image& img) {
    std::vector<std::uint8_t> out(img.values.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(img.values[i].kind);
    return out;
}
[[nodiscard]] inline std::vector<std::uint16_t> instance_pixels(const label_image& img) {
    std::vector<std::uint16_t> out(img.values.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const sample_label& l = img.values[i];
        if (l.kind != sample_class::highlight && l.kind != sample_class::shadow) continue;
        sss::require(l.object < 65535u, "label_image", "object id " + std::to_string(l.object) + " does not fit a 16-bit instance image");
        out[i] = static_cast<std::uint16_t>(l.object + 1);
    }
    return out;
}

/// Writes `<stem>_class.png`, `<stem>_instance.png` and `<stem>_legend.json` (see the file comment).
/// The three are written together (detail::commit_together): a failure writing any of them leaves the old ones as
/// they were.
inline void write_label_images(const std::string& stem, const label_image& img, std::span<const label_class> classes) {
    check_label_image(img);
    check_class_names(classes);
    detail::check_png_image(stem + "_class.png", img.width(), img.pings, img.width() * img.pings);
    const auto cls = sss::detail::encode_png_grey<std::uint8_t>(img.width(), img.pings, class_pixels(img));
    const auto inst = sss::detail::encode_png_grey<std::uint16_t>(img.width(), img.pings, instance_pixels(img));
    sss::detail::json_writer j;
    j.begin_object().key("class_png").begin_object();
    j.member("0", "no_coverage").member("1", "water_column").member("2", "seabed").member("3", "highlight").member("4", "shadow")
        .member("5", "seabed_shadow");
    j.end_object().key("instance_png").begin_object().member("0", "none");
    // Every value of the instance image: an object whose shadow alone is in the image (its highlight beyond the
    // swath, or nearer than the first return in ground range) has pixels too, though it has no box. An object's class
    // is its box's (its first highlight sample's), as in COCO and YOLO; a shadow-only object's, its first shadow
    // sample's (a shadow carries the label of the part that casts it, which may differ from the highlight's).
    std::map<std::uint32_t, std::uint32_t> objects; // object id -> its class
    for (const object_box& b : object_boxes(img, box_extent::highlight)) objects.emplace(b.object, b.class_id);
    for (const sample_label& l : img.values)
        if (l.kind == sample_class::shadow) objects.emplace(l.object, l.label);
    for (const auto& [object, class_id] : objects) {
        std::string name = "class_" + std::to_string(class_id);
        for (const label_class& c : classes)
            if (c.id == class_id) name = c.name;
        j.key(std::to_string(object + 1)).begin_object().member("object_id", object).member("class_id", class_id);
        j.member("class", name).end_object();
    }
    j.end_object().end_object().newline();
    sss::detail::atomic_file class_png(stem + "_class.png"), instance_png(stem + "_instance.png"),
        legend(stem + "_legend.json");
    class_png.write(cls.data(), cls.size());
    instance_png.write(inst.data(), inst.size());
    legend.write(j.str());
    sss::detail::commit_together(class_png, instance_png, legend);
}

} // namespace sss::io
