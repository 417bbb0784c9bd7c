#pragma once
/// \file
/// How simulator::render runs: on which pool and how many threads, and a progress callback that can cancel.
///
/// Progress. `progress` is called once before the first ping with done = 0, then once after each finished ping
/// with done counting the finished pings (1, 2, ..., total in that order, whatever the threads): calls never
/// overlap, and come from whichever thread finished the ping, so the callback should be quick (a progress bar
/// redraw). Returning false cancels the render.
///
/// Cancellation. No ping starts after the callback returned false; pings already under way on other threads
/// finish and are dropped; then render throws render_cancelled, whose done() is the `done` of the call that
/// returned false. Nothing else changes: the simulator and the pool are ready for the next render, and render
/// returns no partial waterfall.

#include <cstddef>
#include <functional>
#include <string>

#include "sss/core/error.hpp"
#include "sss/core/thread_pool.hpp"

namespace sss {

/// Where a render stands.
struct render_progress {
    std::size_t done = 0;  ///< pings finished
    std::size_t total = 0; ///< pings asked for
};

/// Settings of simulator::render.
struct render_control {
    unsigned threads = 0;        ///< threads, the caller's included (0: the pool's size)
    thread_pool* pool = nullptr; ///< the pool to run on (nullptr: shared_thread_pool())
    std::function<bool(const render_progress&)> progress{}; ///< see the file comment; false cancels
};

/// Thrown by simulator::render when its progress callback returned false.
class render_cancelled : public error {
public:
    render_cancelled(std::size_t done, std::size_t total)
        : error("sss: render cancelled after " + std::to_string(done) + " of " + std::to_string(total) + " pings"),
          done_(done), total_(total) {}
    /// Pings finished when the callback asked to cancel.
    [[nodiscard]] std::size_t done() const noexcept { return done_; }
    /// Pings the render was asked for.
    [[nodiscard]] std::size_t total() const noexcept { return total_; }

private:
    std::size_t done_;
    std::size_t total_;
};

} // namespace sss
