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
///
/// `run_pings` is that loop on its own, for renders that build more than a waterfall from each ping (labels beside
/// the image: labels/ground_truth.hpp, render_labelled) and keep render's contract.

#include <cstddef>
#include <functional>
#include <mutex>
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

/// Calls work(i) for every i in [0, count) as simulator::render calls its pings (the file comment): on control's
/// pool and threads, one i at a time per thread, with control's progress and cancellation; throws render_cancelled
/// when the callback cancels, and rethrows the first exception work throws. work(i) must write only what belongs
/// to i (calls for different i overlap).
template <class Work> void run_pings(std::size_t count, const render_control& control, Work&& work) {
    const auto& progress = control.progress;
    if (progress && !progress(render_progress{0, count})) throw render_cancelled(0, count);
    std::mutex report_lock;
    std::size_t done = 0;
    bool cancelled = false;
    thread_pool& pool = control.pool != nullptr ? *control.pool : shared_thread_pool();
    pool.for_each(
        count,
        [&](std::size_t i) {
            work(i);
            if (!progress) return;
            const std::lock_guard<std::mutex> hold(report_lock);
            if (cancelled) return; // finished after the cancellation: dropped
            ++done;
            if (!progress(render_progress{done, count})) {
                cancelled = true;
                throw render_cancelled(done, count); // for_each hands out no further ping
            }
        },
        control.threads);
}

} // namespace sss
