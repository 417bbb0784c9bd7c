#pragma once
/// \file
/// How simulator::render runs: on which pool and how many threads, and a progress callback that can cancel.
///
/// Progress. `progress` is called once before the first ping with done = 0, then once after each finished ping
/// with done counting the finished pings (1, 2, ..., total in that order, whatever the threads): calls never
/// overlap, and come from whichever thread finished the ping, so the callback should be quick (a progress bar
/// redraw). Returning false cancels the render.
///
/// Cancellation. No ping starts after the callback returned false; pings already under way on other threads stop
/// at their next along-track column and are dropped; then render throws render_cancelled, whose done() is the
/// `done` of the call that returned false. Nothing else changes: the simulator and the pool are ready for the next
/// render, and render returns no partial waterfall.
///
/// Stopping from outside. `stop`, where given, is a flag another thread (or a signal handler: a lock-free atomic
/// may be set there) sets to stop the render without waiting for a ping to finish: no ping starts after it is
/// set, pings under way stop at their next along-track column (a column takes milliseconds, where a ping of a
/// dense or wide-beam render can take seconds), and render throws render_cancelled, whose done() counts the pings
/// finished before. The flag is only read.
///
/// `run_pings` is that loop on its own, for renders that build more than a waterfall from each ping (labels beside
/// the image: labels/ground_truth.hpp, render_labelled) and keep render's contract.

#include <atomic>
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
    const std::atomic<bool>* stop = nullptr; ///< set: the render stops (file comment); nullptr: never
};

/// Thrown by simulator::render when its progress callback returned false or its stop flag was set.
class render_cancelled : public error {
public:
    render_cancelled(std::size_t done, std::size_t total)
        : error("sss: render cancelled after " + std::to_string(done) + " of " + std::to_string(total) + " pings"),
          done_(done), total_(total) {}
    /// Pings finished when the callback asked to cancel, or before the render stopped.
    [[nodiscard]] std::size_t done() const noexcept { return done_; }
    /// Pings the render was asked for.
    [[nodiscard]] std::size_t total() const noexcept { return total_; }

private:
    std::size_t done_;
    std::size_t total_;
};

namespace detail {

/// Thrown by a trace (simulator.hpp, between along-track columns) when the render its ping belongs to is stopped;
/// run_pings turns it into render_cancelled. Never seen outside.
struct ping_stopped {};

/// The flags that stop the ping this thread traces for run_pings: the render's own (set when progress cancels)
/// and render_control::stop. Null outside run_pings: a ping traced on its own never stops.
struct ping_stop_flags {
    const std::atomic<bool>* cancelled = nullptr;
    const std::atomic<bool>* stop = nullptr;
};
inline thread_local ping_stop_flags current_ping_stop{};

/// True when the render whose ping this thread traces is stopped or cancelled.
[[nodiscard]] inline bool ping_stop_requested() noexcept {
    const ping_stop_flags& f = current_ping_stop;
    return (f.cancelled != nullptr && f.cancelled->load(std::memory_order_relaxed)) ||
           (f.stop != nullptr && f.stop->load(std::memory_order_relaxed));
}

/// Between along-track columns: throws ping_stopped when the render is stopped.
inline void ping_stop_point() {
    if (ping_stop_requested()) [[unlikely]] throw ping_stopped{};
}

/// Sets this thread's ping stop flags for its lifetime, and puts back the ones before (a loop within a loop).
class ping_stop_scope {
public:
    explicit ping_stop_scope(ping_stop_flags f) noexcept : before_(current_ping_stop) { current_ping_stop = f; }
    ~ping_stop_scope() { current_ping_stop = before_; }
    ping_stop_scope(const ping_stop_scope&) = delete;
    ping_stop_scope& operator=(const ping_stop_scope&) = delete;

private:
    ping_stop_flags before_;
};

} // namespace detail

/// Calls work(i) for every i in [0, count) as simulator::render calls its pings (the file comment): on control's
/// pool and threads, one i at a time per thread, with control's progress, cancellation and stop; throws
/// render_cancelled when the callback cancels or the stop flag is set, and rethrows the first exception work or the
/// callback throws (then the pings under way stop at their next column, and the callback is not called again).
/// work(i) must write only what belongs to i (calls for different i overlap); a simulator's traces within it stop
/// between columns when the render is stopped, by throwing detail::ping_stopped, which work must let pass (a
/// catch (...) in it that does not rethrow would count a stopped ping as done).
template <class Work> void run_pings(std::size_t count, const render_control& control, Work&& work) {
    const auto& progress = control.progress;
    const auto stop_set = [&] { return control.stop != nullptr && control.stop->load(std::memory_order_relaxed); };
    if (stop_set() || (progress && !progress(render_progress{0, count}))) throw render_cancelled(0, count);
    std::mutex report_lock;
    std::size_t done = 0;
    bool cancelled = false;
    std::atomic<bool> cancel_flag{false}; // cancelled, for the pings under way
    thread_pool& pool = control.pool != nullptr ? *control.pool : shared_thread_pool();
    // The render stopped from outside: no further ping (for_each hands out none after an exception).
    const auto stopped = [&]() -> render_cancelled {
        const std::lock_guard<std::mutex> hold(report_lock);
        cancelled = true;
        cancel_flag.store(true, std::memory_order_relaxed);
        return render_cancelled(done, count);
    };
    pool.for_each(
        count,
        [&](std::size_t i) {
            if (stop_set()) throw stopped();
            if (cancel_flag.load(std::memory_order_relaxed)) return; // cancelled: dropped
            try {
                const detail::ping_stop_scope scope({&cancel_flag, control.stop});
                work(i);
            } catch (const detail::ping_stopped&) {
                if (cancel_flag.load(std::memory_order_relaxed)) return; // cancelled or failed elsewhere: dropped
                throw stopped(); // stopped by the flag (even if it was cleared since)
            } catch (...) { // a failed ping: the render fails with its error, the pings under way stop, none reports
                {
                    const std::lock_guard<std::mutex> hold(report_lock);
                    cancelled = true;
                }
                cancel_flag.store(true, std::memory_order_relaxed);
                throw;
            }
            const std::lock_guard<std::mutex> hold(report_lock);
            if (cancelled) return; // finished after the cancellation: dropped
            ++done;
            bool go_on = true;
            if (progress) {
                try {
                    go_on = progress(render_progress{done, count});
                } catch (...) { // a callback that throws ends the render as one that returns false, with its error
                    cancelled = true;
                    cancel_flag.store(true, std::memory_order_relaxed);
                    throw;
                }
            }
            if (!go_on) {
                cancelled = true;
                cancel_flag.store(true, std::memory_order_relaxed);
                throw render_cancelled(done, count); // for_each hands out no further ping
            }
        },
        control.threads);
}

} // namespace sss
