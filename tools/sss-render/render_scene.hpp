#pragma once
/// \file
/// The definition of sss-render's render (render.hpp), included only by render_float.cpp and render_double.cpp:
/// the scene's world and simulator of scalar T, the render with its progress, and the files the scene asks for,
/// each written under a temporary name and renamed only when every one of them is complete.

#include "render.hpp"
#include "scene_file/build.hpp"
#include "scene_file/coverage.hpp"
#include "scene_file/write.hpp"

#include <sss/core/render_control.hpp>
#include <sss/io/detail/atomic_file.hpp>
#include <sss/io/labels.hpp>
#include <sss/io/npy.hpp>
#include <sss/io/png.hpp>
#include <sss/io/xtf.hpp>
#include <sss/labels/ground_truth.hpp>
#include <sss/receiver/ground_range.hpp>
#include <sss/receiver/quantise.hpp>
#include <sss/receiver/time_sampler.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/file.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <limits>
#include <span>
#include <string>
#include <thread>
#include <signal.h>
#include <unistd.h>
#include <vector>

/// The signals that stop a render: SIGINT, SIGTERM, SIGHUP.
inline constexpr int sss_render_stop_signals[] = {SIGINT, SIGTERM, SIGHUP};

/// One of them: the render stops within the pings under way, at their next along-track column, and writes nothing;
/// a second one, of any of them, ends the process at once (building a large seabed can take long) by the signal's
/// default action, which may leave temporary files.
extern "C" inline void sss_render_on_sigint(int sig) {
    sss::scene_file::interrupted.store(sig);
    sss::scene_file::stop_render.store(true);
    for (const int s : sss_render_stop_signals) std::signal(s, SIG_DFL); // async-signal-safe
}

/// Installs sss_render_on_sigint for the stop signals the process does not ignore: under nohup (SIGHUP ignored) a
/// hangup leaves the render running, as it would without the handler.
inline void sss_render_catch_stop_signals() {
    for (const int sig : sss_render_stop_signals) {
        struct sigaction now {};
        if (sigaction(sig, nullptr, &now) == 0 && now.sa_handler == SIG_IGN) continue;
        std::signal(sig, sss_render_on_sigint);
    }
}

namespace sss::scene_file {

// The seabed's synthesis is float in both scalars (make_seabed): compiled once, in render_float.cpp.
extern template sss::seabed::composite_seabed<float> synthesise_seabed<float>(const description&);

namespace detail {

/// Progress on stderr: a redrawn bar on a terminal, a plain line per tenth otherwise.
class progress {
public:
    explicit progress(std::size_t total) : total_(total), tty_(isatty(STDERR_FILENO) != 0), t0_(clock::now()) {}
    void update(std::size_t done) {
        const double s = std::chrono::duration<double>(clock::now() - t0_).count();
        const double rate = s > 0 ? double(done) / s : 0.0;
        const double eta = rate > 0 ? double(total_ - done) / rate : 0.0;
        if (tty_) {
            const std::size_t width = 30, fill = total_ ? done * width / total_ : width;
            std::fprintf(stderr, "\r[%s%s] %zu/%zu pings  %.1f pings/s  ETA %.0f s ", std::string(fill, '#').c_str(),
                         std::string(width - fill, '.').c_str(), done, total_, rate, eta);
            if (done == total_) std::fputc('\n', stderr);
        } else {
            const std::size_t tenth = total_ ? done * 10 / total_ : 10;
            if (tenth == last_tenth_ && done != total_) return;
            last_tenth_ = tenth;
            std::fprintf(stderr, "sss-render: %zu/%zu pings, %.1f pings/s, ETA %.0f s\n", done, total_, rate, eta);
        }
        std::fflush(stderr);
    }

private:
    using clock = std::chrono::steady_clock;
    std::size_t total_;
    bool tty_;
    clock::time_point t0_;
    std::size_t last_tenth_ = std::size_t(-1);
};

/// Pings [first, first + count) in one render, with their labels into *labels unless it is null (one trace for
/// both: sss::render_labelled); its progress callback draws the bar, and Ctrl-C stops the render within the pings
/// under way (render_control::stop; nothing is kept).
template <class Sim, Real T>
sss::waterfall<T> render(const Sim& sim, const world<T>& w, std::size_t first, std::size_t count, unsigned threads,
                         sss::label_image* labels) {
    progress bar(count);
    const sss::render_control control{.threads = threads,
                                      .progress = [&bar](const sss::render_progress& p) {
                                          bar.update(p.done);
                                          return interrupted.load() == 0;
                                      },
                                      .stop = &stop_render};
    try {
        if (labels == nullptr) return sim.render(w, first, count, control);
        auto both = sss::render_labelled(sim, w, first, count, control);
        *labels = std::move(both.labels);
        return std::move(both.image);
    } catch (const sss::render_cancelled&) {
        throw interrupted_error{};
    }
}

/// The files being written: each under a temporary name until `commit` renames them all. The temporary names, and
/// the names old files are kept under while they are replaced, end in a suffix of this run's own
/// (`.NAME.partial-` and `.NAME.replaced-` + 16 hexadecimal digits), so that two runs writing to one directory at
/// once never share one.
class output_set {
public:
    explicit output_set(std::filesystem::path dir) : dir_(std::move(dir)), run_(sss::detail::temporary_suffix()) {}
    ~output_set() {
        for (const auto& [tmp, final] : files_) std::filesystem::remove(tmp, ignored_);
    }
    /// The temporary path to write `name` to.
    std::string add(const std::string& name) {
        std::string tmp_name = ".";
        tmp_name += name;
        tmp_name += ".partial-";
        tmp_name += run_;
        const auto tmp = dir_ / tmp_name;
        files_.emplace_back(tmp, dir_ / name);
        return tmp.string();
    }
    /// A writer that appends suffixes to a stem: each `stem + suffix` is one file.
    std::string add_stem(const std::string& stem, std::initializer_list<const char*> suffixes) {
        std::string tmp = ".";
        tmp += stem;
        tmp += ".partial-";
        tmp += run_;
        for (const char* s : suffixes) files_.emplace_back(dir_ / (tmp + s), dir_ / (stem + s));
        return (dir_ / tmp).string();
    }
    /// The final name of the output a writer's file belongs to: `path` is a temporary name `add` or `add_stem` gave,
    /// or one of a stem's files; empty if none.
    [[nodiscard]] std::string final_name_of(const std::string& path) const {
        const std::filesystem::path p(path);
        for (const auto& [tmp, final] : files_)
            if (tmp == p) return final.string();
        return {};
    }
    /// Before the render: no final name is an existing directory or names two outputs, and every temporary name
    /// (with the writer's own ".tmp-" and 16 hexadecimal digits) fits the directory's file names.
    void check() const {
        check_final_names();
        const long most = pathconf(dir_.c_str(), _PC_NAME_MAX);
        const std::size_t name_max = most > 0 ? std::size_t(most) : 255;
        for (const auto& [tmp, final] : files_) {
            const std::size_t longest = tmp.filename().string().size() + 21;
            if (longest > name_max)
                throw scene_error("output.stem: " + final.filename().string() + " is written under a temporary name of " +
                                  std::to_string(longest) + " bytes, more than the " + std::to_string(name_max) +
                                  " that file names in " + dir_.string() + " hold: choose a shorter stem");
        }
    }
    /// Renames every file to its final name. Before the first rename, every final name is checked again: none may be
    /// an existing directory or name two outputs. Each old file is kept under a second name (a hard link, else a copy)
    /// before the new one is renamed over it, so that every name holds a whole file at every moment; a rename that
    /// fails (a file the system will not let go of) puts the old files back, so that none of the new ones is kept.
    std::vector<std::string> commit() {
        if (interrupted.load()) throw interrupted_error{};
        check_final_names();
        std::vector<std::pair<std::filesystem::path, std::filesystem::path>> kept; // (final name, its old file's copy)
        std::vector<std::filesystem::path> renamed;                                  // final names holding a new file
        const auto drop_kept = [&] {
            std::error_code ignored;
            for (const auto& k : kept) std::filesystem::remove(k.second, ignored);
        };
        const auto undo = [&](const std::filesystem::path& failed, const std::error_code& why) {
            bool restored = true;
            std::error_code e;
            const auto old_of = [&](const std::filesystem::path& f) {
                const auto k = std::find_if(kept.begin(), kept.end(), [&](const auto& x) { return x.first == f; });
                return k == kept.end() ? std::filesystem::path() : k->second;
            };
            for (const auto& f : renamed) { // the old file back over the new one, or the new one removed
                const auto old = old_of(f);
                if (old.empty()) std::filesystem::remove(f, e);
                else std::filesystem::rename(old, f, e);
                restored = restored && !e;
            }
            for (const auto& [final, old] : kept) // the copies of old files not replaced yet
                if (std::find(renamed.begin(), renamed.end(), final) == renamed.end()) std::filesystem::remove(old, e);
            return scene_error(failed.string() + ": cannot be replaced (" + why.message() + "): no output written, " +
                               (restored ? std::string("the old files kept")
                                         : std::string("and not every old file could be put back (see the .replaced-* files)")));
        };
        std::error_code ec;
        for (const auto& [tmp, final] : files_) {
            if (!std::filesystem::exists(final, ec)) continue;
            std::string kept_name = ".";
            kept_name += final.filename().string();
            kept_name += ".replaced-";
            kept_name += run_;
            const auto old = final.parent_path() / kept_name;
            std::filesystem::remove(old, ec);
            std::filesystem::create_hard_link(final, old, ec);
            if (ec) std::filesystem::copy_file(final, old, std::filesystem::copy_options::overwrite_existing, ec);
            if (ec) {
                drop_kept();
                throw scene_error(final.string() + ": cannot keep the old file while it is replaced (" + ec.message() +
                                  "): no output written");
            }
            kept.emplace_back(final, old);
        }
        std::vector<std::string> names;
        for (const auto& [tmp, final] : files_) {
            std::filesystem::rename(tmp, final, ec);
            if (ec) throw undo(final, ec);
            renamed.push_back(final);
            names.push_back(final.string());
        }
        // The renames on the disk too: each directory once.
        std::vector<std::filesystem::path> synced;
        for (const std::string& n : names) {
            const std::filesystem::path dir = std::filesystem::path(n).parent_path();
            if (std::find(synced.begin(), synced.end(), dir) != synced.end()) continue;
            synced.push_back(dir);
            sss::detail::sync_directory_of(n);
        }
        drop_kept();
        files_.clear();
        return names;
    }

private:
    /// No final name is an existing directory or names two outputs.
    void check_final_names() const {
        for (std::size_t i = 0; i < files_.size(); ++i) {
            const auto& final = files_[i].second;
            std::error_code ec;
            if (std::filesystem::is_directory(final, ec))
                throw scene_error(final.string() + ": an output would replace this directory: remove it or choose "
                                                   "another output.stem or -o");
            for (std::size_t j = 0; j < i; ++j)
                if (files_[j].second == final)
                    throw scene_error(final.string() + ": two outputs would have this name: choose another output.stem");
        }
    }

    std::filesystem::path dir_;
    std::string run_; // this run's suffix of its temporary and kept names
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;
    std::error_code ignored_;
};

/// Power compensated for spreading (r^3) and absorption, as a sidescan's TVG shows it.
template <Real T> std::vector<double> compensated(const sss::waterfall<T>& w, double c_mps, double absorption_db_per_km) {
    std::vector<double> gain(w.samples), shown(w.values.size());
    for (std::size_t k = 0; k < w.samples; ++k) {
        const double r = (double(k) + 0.5) * w.dt_s * 0.5 * c_mps;
        gain[k] = r * r * r * std::pow(10.0, 2.0 * absorption_db_per_km * r / 1e4);
    }
    for (std::size_t p = 0; p < w.pings; ++p)
        for (std::size_t c = 0; c < w.width(); ++c) {
            const std::size_t k = c < w.samples ? w.samples - 1 - c : c - w.samples;
            shown[p * w.width() + c] = double(w.at(p, c)) * gain[k];
        }
    return shown;
}

/// The level shown white: the 99.5th percentile of the positive values (dB), so that a few highlights or
/// speckle peaks do not darken the whole image.
inline double white_level_db(const std::vector<double>& v) {
    std::vector<double> positive;
    for (double x : v)
        if (x > 0 && std::isfinite(x)) positive.push_back(x);
    if (positive.empty()) return 0.0;
    const auto at = positive.begin() + std::ptrdiff_t(double(positive.size() - 1) * 0.995);
    std::nth_element(positive.begin(), at, positive.end());
    return 10.0 * std::log10(*at);
}

/// This machine's memory (bytes); 0 where it cannot tell.
inline double physical_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
}

/// What a run would hold in memory at once, roughly (bytes), by part.
struct memory_estimate {
    double samples = 0; ///< per line
    double threads = 0; ///< rendering pings at once
    double seabed = 0;  ///< the synthesised seabed with its pyramid and synthesis buffers
    double image = 0;   ///< the image with its labels, and the PNG's bytes
    double ground = 0;  ///< the ground-range image
    double working = 0; ///< the pings' working memory, every thread's together
    [[nodiscard]] double total() const noexcept { return seabed + image + ground + working; }
};

/// The memory of a run of `count` pings of scene d (memory_estimate).
template <Real T> [[nodiscard]] memory_estimate estimate_memory(const description& d, std::size_t count) {
    memory_estimate m;
    m.samples = std::ceil(2.0 * d.sensor.max_range_m / d.sea.sound_speed_mps * d.sensor.sample_rate_hz);
    const double values = double(count) * 2.0 * m.samples;
    const bool labels = d.out.coco || d.out.yolo || d.out.label_images;
    // A generated seabed: its heights and pyramid (2.5 values a cell); with regions, their synthesis's working
    // rasters too (the blend's sums in double, the textures' fields and spectra: about 40 bytes a cell, measured at
    // 2048^2 with two regions).
    const double per_cell = 2.5 * double(sizeof(T)) + (d.bed.regions.empty() ? 0.0 : 40.0);
    m.seabed = d.bed.file.empty() ? per_cell * double(d.bed.nx) * double(d.bed.ny) : 0.0;
    m.image = values * (double(sizeof(T)) + (labels ? double(sizeof(sss::sample_label)) : 0.0) +
                        (d.out.png || d.out.ground_range ? 9.0 : 0.0));
    m.ground = d.out.ground_range ? double(count) * 2.0 * std::ceil(d.sensor.max_range_m / d.out.ground_range_cell_m) *
                                        (9.0 + (labels ? double(sizeof(sss::sample_label)) : 0.0))
                                  : 0.0;
    // A ping's working memory (measured with sss-render at 0.07 to 0.5 M samples a line): the simulator's time
    // sampler (time_sampler::memory_bytes: its sub-bins' moments, and for a long pulse its kernels' spectra) and line
    // stage (about 24 bytes a sample); each thread's copy of the sampler with its render's transform, its labels' sums
    // (about 130 bytes a sample) and its rays' echoes and paths (about 40 MiB a thread once the columns reach their
    // ray cap, less before).
    m.threads = std::min(double(count), d.run.threads > 0 ? double(d.run.threads)
                                                          : double(std::max(1u, std::thread::hardware_concurrency())));
    const auto sampler = sss::time_sampler::memory_bytes(static_cast<std::size_t>(m.samples), 1.0 / d.sensor.sample_rate_hz,
                                                         receiver_of(d).pulse);
    const double rays = std::min(40.0 * double(1 << 20), 300.0 * m.samples * std::max(1.0, d.run.rays_per_sample));
    m.working = sampler.per_copy + sampler.shared + 24.0 * m.samples +
                m.threads * (sampler.per_copy + sampler.per_render + (labels ? 130.0 : 0.0) * m.samples + rays);
    return m;
}

/// A scene error naming the keys that set each part of the run's memory (estimate_memory) where the whole exceeds
/// the machine's memory, before anything is built.
template <Real T> void check_memory(const description& d, const render_request& r, std::size_t count) {
    const double total = physical_memory_bytes();
    if (!(total > 0)) return;
    const memory_estimate m = estimate_memory<T>(d, count);
    if (m.total() <= total) return;
    const auto gib = [](double b) { return detail::fmt(std::round(b / double(1 << 30) * 10.0) / 10.0) + " GiB"; };
    throw scene_error(r.scene_path + ": the run needs about " + gib(m.total()) + " of memory, more than this machine's " +
                      gib(total) + ": the seabed " + gib(m.seabed) + " (seabed.nx x seabed.ny), the image " + gib(m.image) +
                      " (" + std::to_string(count) + " pings from " + r.pings_asked + " x 2 x " + detail::fmt(m.samples) +
                      " samples from sonar.max_range_m and sonar.sample_rate_hz)" +
                      (d.out.ground_range ? ", the ground-range image " + gib(m.ground) + " (output.ground_range_cell_m)"
                                          : std::string()) +
                      ", the pings' working memory " + gib(m.working) + " (" + detail::fmt(m.threads) +
                      " threads from render.threads, each with lines of " + detail::fmt(m.samples) + " samples)");
}

/// The class list of YOLO's files in directory `dir`, one name per index: the names its classes.txt already lists, in
/// their order, then this scene's class names it does not list. Each name stands for this scene's first class of that
/// name (`ours`; classes of one name share its index), or for none (id 0, which no object has). Other scenes' label
/// files in the directory keep their indices, and this scene's take the same ones for the same names. A UTF-8 byte
/// order mark and blank lines at the end are dropped, CRLF line ends read as LF (the list is written with LF). A
/// classes.txt that cannot be read, or is not a class list, is a scene error.
inline std::vector<sss::io::label_class> yolo_classes(const std::filesystem::path& dir, const std::vector<sss::io::label_class>& ours) {
    const auto path = dir / "classes.txt";
    std::error_code ec;
    std::vector<sss::io::label_class> out;
    auto id_of = [&](const std::string& name) {
        const auto found = std::find_if(ours.begin(), ours.end(), [&](const auto& c) { return c.name == name; });
        return found == ours.end() ? 0u : found->id;
    };
    if (std::filesystem::exists(path, ec)) {
        std::ifstream in(path, std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!in.good() && !in.eof()) throw scene_error(path.string() + ": cannot be read: it holds the class list of the YOLO files beside it");
        if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
        std::vector<std::string> lines;
        for (std::size_t at = 0; at < text.size();) {
            const std::size_t nl = text.find('\n', at);
            std::string name = text.substr(at, nl == std::string::npos ? std::string::npos : nl - at);
            at = nl == std::string::npos ? text.size() : nl + 1;
            if (!name.empty() && name.back() == '\r') name.pop_back();
            lines.push_back(std::move(name));
        }
        while (!lines.empty() && lines.back().empty()) lines.pop_back();
        for (std::size_t i = 0; i < lines.size(); ++i) {
            out.push_back({id_of(lines[i]), lines[i]});
            try {
                sss::io::check_class_names(std::span<const sss::io::label_class>(&out.back(), 1));
            } catch (const sss::error&) {
                throw scene_error(path.string() + ":" + std::to_string(i + 1) + ": is not a class name (one per line, non-empty "
                                  "UTF-8 text): yolo = true adds this scene's classes to this list; remove the file or "
                                  "render into another directory (-o)");
            }
        }
    }
    for (const auto& c : ours)
        if (std::none_of(out.begin(), out.end(), [&](const auto& k) { return k.name == c.name; })) out.push_back({c.id, c.name});
    return out;
}

/// The label image with every object's class id replaced by the first id in `classes` of the same name, so that
/// classes of one name take one YOLO index; nullopt where no two classes share a name (the labels stand as they are).
inline std::optional<sss::label_image> one_id_per_name(const sss::label_image& labels, const std::vector<sss::io::label_class>& classes) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> to; // (id, the first id of its name)
    for (const auto& c : classes) {
        const auto first = std::find_if(classes.begin(), classes.end(), [&](const auto& k) { return k.name == c.name; });
        if (first->id != c.id) to.emplace_back(c.id, first->id);
    }
    if (to.empty()) return std::nullopt;
    sss::label_image out = labels;
    for (auto& l : out.values)
        for (const auto& [id, first] : to)
            if (l.label == id) l.label = first;
    return out;
}

/// An exclusive lock on a directory (flock), held while its shared class list is read, merged and renamed, so that
/// two runs writing YOLO files into one directory at once each add their classes to the other's.
class directory_lock {
public:
    explicit directory_lock(const std::string& dir) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
        if (fd_ >= 0) ::flock(fd_, LOCK_EX);
    }
    directory_lock(const directory_lock&) = delete;
    directory_lock& operator=(const directory_lock&) = delete;
    ~directory_lock() {
        if (fd_ >= 0) ::close(fd_); // releases the lock
    }

private:
    int fd_;
};

/// The output directory, made if missing, one component at a time as the path is written (`a/../b/c/`: `a`, then
/// `a/../b` if missing, then `a/../b/c`); the ones made are removed again, the last first and each only if empty,
/// unless the run keeps them, so that a failed run leaves no new directory behind.
class output_directory {
public:
    explicit output_directory(const std::string& dir) {
        if (dir.empty()) throw scene_error("-o: the output directory must not be empty");
        try {
            make(dir);
        } catch (...) {
            remove_made();
            throw;
        }
    }
    output_directory(const output_directory&) = delete;
    output_directory& operator=(const output_directory&) = delete;
    ~output_directory() { remove_made(); }
    void keep() noexcept { made_.clear(); }

private:
    void make(const std::string& dir) {
        std::error_code ec;
        std::filesystem::path p;
        for (const auto& part : std::filesystem::path(dir)) {
            p /= part;
            if (part.empty() || part == "." || part == ".." || part == p.root_path()) continue;
            if (std::filesystem::exists(p, ec)) continue;
            const bool made = std::filesystem::create_directory(p, ec);
            if (ec) throw scene_error(dir + ": cannot be the output directory (" + p.string() + ": " + ec.message() + ")");
            if (made) made_.push_back(p); // else another process made it meanwhile
        }
        if (!std::filesystem::is_directory(dir, ec))
            throw scene_error(dir + ": cannot be the output directory (" + (ec ? ec.message() : "not a directory") + ")");
        // Writable: a file made and removed (as root, access() says yes even where the file system says no).
        const std::string probe = (std::filesystem::path(dir) / (".sss-render-probe-" + sss::detail::temporary_suffix())).string();
        const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        if (fd < 0) {
            const std::string why = std::strerror(errno);
            throw scene_error(dir + ": cannot write files in the output directory (" + why + ")");
        }
        ::close(fd);
        std::filesystem::remove(probe, ec);
    }
    void remove_made() noexcept {
        std::error_code ec;
        for (auto p = made_.rbegin(); p != made_.rend(); ++p) // the last made first; one that is not empty stays
            if (!std::filesystem::remove(*p, ec)) break;
        made_.clear();
    }

    std::vector<std::filesystem::path> made_;
};

} // namespace detail

template <Real T> int render_scene(const description& d, const render_request& r) {
    const std::size_t count = r.last - r.first;
    detail::check_memory<T>(d, r, count);
    // XTF numbers pings from 1 in 32 bits: ping k is number k + 1.
    if (d.out.xtf && r.last > std::size_t(std::numeric_limits<std::uint32_t>::max()))
        throw scene_error(r.scene_path + ": " + r.pings_asked + ": output.xtf numbers pings in 32 bits: pings up to " +
                          std::to_string(std::numeric_limits<std::uint32_t>::max() - 1) + " only");
    const extent e = d.bed.file.empty() ? extent_of(d) : extent_of(load_seabed<T>(d));
    // The track at the scene's altitude (a trajectory: its own z), for the ping count and the coverage.
    const scene_motion<T> track = motion_of(d, T(d.tow.altitude_m));
    if (const auto beyond = pings_beyond(d, track, r.last, r.pings_asked); !beyond.empty())
        throw scene_error(r.scene_path + ": " + beyond);
    // XTF's dates end with the year 9999, to the hundredth of a second: the last ping's time too.
    if (d.out.xtf) {
        const double last_s = xtf_start_unix_s(d, track, r.last - 1);
        char stamped[64];
        std::snprintf(stamped, sizeof stamped, "%.2f", last_s);
        if (!(last_s < 253402300799.995))
            throw scene_error(r.scene_path + ": output.xtf_start_unix_s: ping " + std::to_string(r.last - 1) + " would be stamped " +
                              stamped + " s, past the end of the year 9999 that XTF's dates hold (" +
                              r.pings_asked + ", motion.ping_interval_s = " + detail::fmt(d.tow.ping_interval_s) + " s)");
        // Its navigation: every ping's place as latitude and longitude, from the UTM zone or the local plane about the
        // origin. Checked here on the first and last pings and a thousand between, so that a track beyond the zone
        // or the pole is refused before the render (and by --dry-run), not after it.
        const std::size_t pings = r.last - r.first, every = std::max<std::size_t>(1, pings / 1000);
        for (std::size_t i = r.first;; i = std::min(r.last - 1, i + every)) {
            const auto q = track.pose_at(i);
            try {
                if (d.out.xtf_utm_zone > 0)
                    (void)sss::io::utm_to_geodetic({.zone = int(d.out.xtf_utm_zone), .south = d.out.xtf_utm_hemisphere == "south"},
                                                   double(q.position.x), double(q.position.y));
                else
                    (void)sss::io::to_geodetic({.latitude_deg = d.out.xtf_origin_latitude_deg,
                                                .longitude_deg = d.out.xtf_origin_longitude_deg},
                                               double(q.position.x), double(q.position.y));
            } catch (const sss::error& failed) {
                throw scene_error(r.scene_path + (d.out.xtf_utm_zone > 0 ? ": output.xtf_utm_zone: " : ": output.xtf_origin_latitude_deg: ") +
                                  "ping " + std::to_string(i) + " at world (" + detail::fmt(double(q.position.x)) + ", " +
                                  detail::fmt(double(q.position.y)) + ") m has no place in XTF's navigation (" +
                                  std::string(sss::message_body(failed)) + ")");
            }
            if (i == r.last - 1) break;
        }
    }
    const auto problems = swath_problems(d, e, track, r.first, count);
    check_sound_speed_file(d);
    for (const auto& p : problems) std::fprintf(stderr, "sss-render: warning: %s: coverage: %s\n", r.scene_path.c_str(), p.c_str());

    // The outputs' names, and the output directory made and checked, before the render rather than after it.
    std::optional<detail::output_directory> out_dir;
    std::optional<detail::output_set> files;
    const std::string& stem = d.out.stem;
    struct temporaries {
        std::string png, ground, npy, json, xtf, coco, yolo, classes, labels, ground_labels;
    } tmp;
    const bool want_labels = d.out.coco || d.out.yolo || d.out.label_images;
    std::vector<sss::io::label_class> classes;
    for (const auto& o : d.objects)
        if (std::none_of(classes.begin(), classes.end(), [&](const auto& c) { return c.id == std::uint32_t(o.class_id); }))
            classes.push_back({std::uint32_t(o.class_id), o.class_name});
    if (!r.dry_run) {
        sss_render_catch_stop_signals(); // a signal from here on removes what the run made
        out_dir.emplace(r.out_dir);
        files.emplace(r.out_dir);
        if (d.out.png) tmp.png = files->add(stem + ".png");
        if (d.out.ground_range) tmp.ground = files->add(stem + "_ground.png");
        if (d.out.npy) {
            tmp.npy = files->add(stem + ".npy");
            tmp.json = files->add(stem + ".json");
        }
        if (d.out.xtf) tmp.xtf = files->add(stem + ".xtf");
        if (d.out.coco) tmp.coco = files->add(stem + "_coco.json");
        if (d.out.yolo) {
            tmp.yolo = files->add(stem + ".txt");
            tmp.classes = files->add("classes.txt");
        }
        if (d.out.label_images) {
            tmp.labels = files->add_stem(stem + "_labels", {"_class.png", "_instance.png", "_legend.json"});
            if (d.out.ground_range)
                tmp.ground_labels = files->add_stem(stem + "_ground_labels", {"_class.png", "_instance.png", "_legend.json"});
        }
        files->check();
        if (d.out.yolo) (void)detail::yolo_classes(r.out_dir, classes); // read again, under a lock, once rendered
        if (interrupted.load()) throw interrupted_error{};
    }

    const auto t0 = std::chrono::steady_clock::now();
    const world<T> w = make_world<T>(d);
    const bool sampled = d.tow.model == "trajectory";
    if (const T z = tow_z(d, w); !sampled && !(z > 0))
        throw scene_error(r.scene_path + ": motion.altitude_m: the towfish's world z (" + detail::fmt(z) +
                          " m) must be > 0: the motion policies keep the towfish above z = 0; "
                          "raise the seabed (mean_height_m) so that it lies above -altitude_m");
    if (const auto below = below_seabed(w, sampled ? track : motion_of(d, tow_z(d, w)), r.first, count); !below.empty())
        throw scene_error(r.scene_path + (sampled ? ": motion.trajectory_file: " : ": motion.altitude_m: ") + below);
    if (const auto in = inside_object(w, sampled ? track : motion_of(d, tow_z(d, w)), r.first, count)) {
        const auto& o = d.objects[in->object];
        const auto p = (sampled ? track : motion_of(d, tow_z(d, w))).pose_at(in->ping).position;
        throw scene_error((o.origin.empty() ? r.scene_path + ": object[" + std::to_string(in->object) + "]" : o.origin) +
                          ": the towfish (at x " + detail::fmt(p.x) + " m, y " + detail::fmt(p.y) + " m, z " + detail::fmt(p.z) +
                          " m) is inside this " + o.type + " at ping " + std::to_string(in->ping) +
                          ": move it off the track, or the track (" +
                          (sampled ? "motion.trajectory_file" : "motion.altitude_m, motion.start_m, motion.heading_deg") +
                          ") off it");
    }
    const auto t1 = std::chrono::steady_clock::now();
    if (r.dry_run) {
        // The simulator built as a render builds it, so that what its policies refuse is found here too.
        with_simulator(d, w, [](const auto&) { return 0; });
        std::fputs(to_toml(d).c_str(), stdout);
        if (std::fflush(stdout) != 0 || std::ferror(stdout))
            throw scene_error("--dry-run: cannot write the resolved scene to standard output");
        return 0;
    }
    std::vector<sss::pose<T>> poses;
    sss::label_image labels;
    const auto image = with_simulator(d, w, [&](const auto& sim) {
        for (std::size_t i = r.first; i < r.last; ++i) poses.push_back(sim.motion().pose_at(i));
        return detail::render(sim, w, r.first, count, unsigned(d.run.threads), want_labels ? &labels : nullptr);
    });
    const auto t2 = std::chrono::steady_clock::now();
    // Not finite, or held at the largest value (the TVG stage saturates rather than overflow).
    const auto overflown = [](T v) { return !std::isfinite(v) || std::abs(v) >= std::numeric_limits<T>::max(); };
    if (const auto bad = std::count_if(image.values.begin(), image.values.end(), overflown); bad > 0)
        throw scene_error(r.scene_path + ": " + std::to_string(bad) + " samples of the render are not finite or saturated: the levels overflow " +
                          (std::is_same_v<T, float> ? "single precision" : "double precision") +
                          "; lower sonar.source_level_db or receiver.tvg_gain_db (or set render.precision = \"double\")");

    // Each ping's altitude above the seabed under the towfish (XTF, ground range), and the ground-range cells per
    // side that cover the slant range (the flat-bottom mapping of the waterfall and of the label images).
    const auto tow_altitudes = [&] {
        std::vector<double> altitude;
        for (const auto& p : poses) altitude.push_back(double(p.position.z - w.seabed().seabed_height_m(p.position.x, p.position.y)));
        return altitude;
    };
    const auto ground_cells = [&] { return std::size_t(std::ceil(d.sensor.max_range_m / d.out.ground_range_cell_m)); };
    // A writer that fails (a full disk, a size limit, a directory made read-only) names its temporary file: the
    // message names the output it was writing instead, and every temporary is removed (output_set).
    const auto output_failed = [&](const sss::file_error& e) {
        const std::string final = files->final_name_of(e.file());
        std::string_view why = sss::message_body(e); // "FILE: why"
        if (why.starts_with(e.file())) why.remove_prefix(std::min(why.size(), why.find(": ", e.file().size()) + 2));
        return scene_error((final.empty() ? e.file() : final) + ": cannot be written (" + std::string(why) +
                           "): no output written");
    };
    std::optional<detail::directory_lock> class_list_lock;
    try {
        if (d.out.png || d.out.ground_range) {
            // With the receiver's TVG the record is already compensated; without it the display compensates.
            sss::waterfall<double> shown{.pings = image.pings, .samples = image.samples, .dt_s = image.dt_s,
                                         .values = d.rx.tvg ? std::vector<double>(image.values.begin(), image.values.end())
                                                            : detail::compensated(image, d.sea.sound_speed_mps, d.sea.absorption_db_per_km)};
            auto grey = [&](const std::vector<double>& v) {
                if (d.out.png_scale == "quantised") {
                    std::vector<double> sorted(v);
                    const auto at = sorted.begin() + std::ptrdiff_t(double(sorted.size() - 1) * 0.95);
                    std::nth_element(sorted.begin(), at, sorted.end());
                    const double ref = *at > 0 ? *at : 1.0;
                    return sss::quantise<std::uint8_t>(std::span<const double>(v), {.gain = sss::quantise_gain(ref, 100.0)});
                }
                return sss::io::to_grey_db<std::uint8_t>(std::span<const double>(v), {.dynamic_range_db = d.out.png_dynamic_range_db,
                                                                                       .top_db = detail::white_level_db(v)});
            };
            if (d.out.png) sss::io::write_png_grey8(tmp.png, image.width(), image.pings, grey(shown.values));
            if (d.out.ground_range) {
                const auto ground = sss::to_ground_range(shown, tow_altitudes(), d.sea.sound_speed_mps, d.out.ground_range_cell_m,
                                                         ground_cells());
                sss::io::write_png_grey8(tmp.ground, ground.width(), ground.pings, grey(ground.values));
            }
        }
        if (d.out.npy) {
            sss::io::write_npy(tmp.npy, image);
            sss::io::write_render_sidecar<T>(tmp.json, image, poses,
                                             {.array_file = stem + ".npy", .sound_speed_mps = d.sea.sound_speed_mps,
                                              .source_level_db = d.sensor.source_level_db,
                                              .receiver_stages = receiver_stage_list(d)});
        }
        if (d.out.xtf) {
            const std::vector<double> altitude = tow_altitudes();
            sss::io::xtf_render_params xp{.start_unix_s = xtf_start_unix_s(d, track, r.first),
                                          .ping_interval_s = d.tow.ping_interval_s, .first_ping_number = std::uint32_t(r.first + 1),
                                          .sound_speed_mps = d.sea.sound_speed_mps,
                                          .origin = {.latitude_deg = d.out.xtf_origin_latitude_deg,
                                                     .longitude_deg = d.out.xtf_origin_longitude_deg}};
            for (std::size_t i = r.first; i < r.last; ++i) xp.row_times_s.push_back(track.time_since_ping0_s(i));
            if (d.out.xtf_utm_zone > 0)
                xp.utm = sss::io::utm_zone{.zone = int(d.out.xtf_utm_zone), .south = d.out.xtf_utm_hemisphere == "south"};
            const auto widths = widths_of(beam_of<T>(d), d.sensor.depression_deg);
            xp.header.port = {.frequency_khz = d.sensor.frequency_hz / 1e3, .horizontal_beam_angle_deg = widths.along_deg,
                              .beam_width_deg = widths.vertical_deg, .tilt_deg = d.sensor.depression_deg};
            xp.header.starboard = xp.header.port;
            xp.header.file_name = stem + ".xtf"; // written under a temporary name, read under this one
            xp.header.tvg_applied = d.rx.tvg;
            sss::io::write_xtf(tmp.xtf, sss::io::make_xtf<T>(image, poses, xp, altitude));
        }
        if (want_labels) {
            const auto box = sss::io::box_extent::highlight_and_shadow;
            if (d.out.coco) {
                const std::vector<sss::io::coco_image> set{{stem + ".png", &labels}};
                sss::io::write_text(tmp.coco, sss::io::coco_json(set, classes, box));
            }
            if (d.out.yolo) {
                // The directory's class list read, merged and renamed under its lock (released when the run returns).
                class_list_lock.emplace(r.out_dir);
                const auto yolo_list = detail::yolo_classes(r.out_dir, classes);
                const auto relabelled = detail::one_id_per_name(labels, classes);
                sss::io::write_text(tmp.yolo, sss::io::yolo_txt(relabelled ? *relabelled : labels, yolo_list, box));
                sss::io::write_text(tmp.classes, sss::io::yolo_classes_txt(yolo_list));
            }
            if (d.out.label_images) {
                sss::io::write_label_images(tmp.labels, labels, classes);
                if (d.out.ground_range) // pixel for pixel with stem_ground.png: the same altitudes, cell and width
                    sss::io::write_label_images(tmp.ground_labels,
                                                sss::ground_range_labels(labels, tow_altitudes(), {.cell_m = d.out.ground_range_cell_m,
                                                                                                      .cells = ground_cells(),
                                                                                                      .sound_speed_mps = d.sea.sound_speed_mps}),
                                                classes);
            }
        }
    } catch (const sss::file_error& e) {
        throw output_failed(e);
    }
    const auto written = files->commit();
    out_dir->keep();
    auto s = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    std::fprintf(stderr, "sss-render: %zu pings x 2 x %zu samples in %.2f s (%.2f ms/ping; scene %.2f s)\n", count,
                 image.samples, s(t1, t2), 1e3 * s(t1, t2) / double(count), s(t0, t1));
    for (const auto& f : written) std::printf("%s\n", f.c_str());
    return 0;
}

} // namespace sss::scene_file
