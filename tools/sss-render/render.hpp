#pragma once
/// \file
/// sss-render's render, one scene from its resolved description to its files, declared for main.cpp: the
/// definition (render_scene.hpp) is compiled once per scalar, in render_float.cpp and render_double.cpp, so the
/// command line and each scalar's simulators build in separate translation units, side by side.

#include "scene_file/scene.hpp"

#include <sss/core/types.hpp>

#include <atomic>
#include <cstddef>
#include <exception>
#include <string>

namespace sss::scene_file {

/// What the command line asks of a scene besides the scene itself.
struct render_request {
    std::string scene_path;      ///< the scene file, for messages
    std::string out_dir = ".";   ///< where the outputs go (created if missing)
    std::size_t first = 0;       ///< the first ping rendered
    std::size_t last = 0;        ///< one past the last
    std::string pings_asked;     ///< the setting that asked for them ("render.pings = N" or "--pings A:B"), for messages
    bool dry_run = false;        ///< print the resolved scene and the coverage problems, render nothing
};

/// Set by SIGINT, SIGTERM or SIGHUP to the signal's number: the render stops and no file is kept. 0: none.
inline std::atomic<int> interrupted{0};
/// Set with `interrupted`: the render's stop flag (sss::render_control::stop), which ends the pings under way at
/// their next along-track column.
inline std::atomic<bool> stop_render{false};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the stop flags are set in a signal handler");

struct interrupted_error : std::exception {
    [[nodiscard]] const char* what() const noexcept override { return "interrupted: no file written"; }
};

/// Renders scene `d` in scalar T (its render.precision) as `r` asks and writes its outputs (or, with
/// r.dry_run, prints the resolved scene); returns the exit status. Errors are exceptions: scene_error with its
/// sentence, the library's sss::error naming the parameter, interrupted_error after SIGINT.
template <Real T> int render_scene(const description& d, const render_request& r);
extern template int render_scene<float>(const description&, const render_request&);
extern template int render_scene<double>(const description&, const render_request&);

} // namespace sss::scene_file
