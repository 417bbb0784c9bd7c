#pragma once
/// \file
/// A persistent pool of worker threads that runs index loops with dynamic scheduling: `for_each(count, f)` calls
/// f(i) once for every i in [0, count), each thread taking the next index as soon as it is free (one shared atomic
/// counter), so uneven items (pings over rough and flat ground, or with and without objects) balance by themselves.
/// The workers are started once and wait between loops, so a loop costs no thread start-up; the calling thread
/// works too. Which thread runs which index varies from run to run: results must not depend on it (each index
/// writes its own output).
///
/// Errors: the first exception thrown by f is rethrown by for_each once every thread has stopped; the other
/// threads take no new index after it. One loop runs at a time per pool (concurrent calls wait their turn); a loop
/// started from inside a loop of the same pool (f calling for_each, directly or through a library call, or through
/// a loop of another pool that f started: A's loop calling B's calling A's) runs on the calling thread alone,
/// rather than waiting for itself.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace sss {

class thread_pool {
public:
    /// A pool that runs loops on up to `threads` threads, the caller's included (0: the hardware's concurrency).
    /// Workers are started lazily, when a loop first asks for them.
    explicit thread_pool(unsigned threads = 0) : size_(resolve(threads)) {}

    thread_pool(const thread_pool&) = delete;
    thread_pool& operator=(const thread_pool&) = delete;

    ~thread_pool() {
        {
            const std::lock_guard<std::mutex> hold(lock_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (auto& t : workers_) t.join();
    }

    /// Threads a loop runs on by default, the caller's included.
    [[nodiscard]] unsigned size() const noexcept { return size_; }

    /// Calls f(i) for every i in [0, count) on up to `threads` threads, the caller's included (0: size();
    /// more than size() starts more workers); returns when all calls have returned. Rethrows f's first exception.
    template <class F> void for_each(std::size_t count, F&& f, unsigned threads = 0) {
        if (count == 0) return;
        unsigned want = threads == 0 ? size_ : threads;
        want = static_cast<unsigned>(std::min<std::size_t>(want, count));
        if (want <= 1 || within(this)) {
            for (std::size_t i = 0; i < count; ++i) f(i);
            return;
        }
        const std::lock_guard<std::mutex> one_loop(loop_lock_);
        job j;
        j.caller = current(); // the loops the caller runs in, for the workers to know too
        j.count = count;
        j.context = &f;
        j.call = [](void* ctx, std::size_t i) { (*static_cast<std::remove_reference_t<F>*>(ctx))(i); };
        {
            std::unique_lock<std::mutex> hold(lock_);
            while (workers_.size() + 1 < want) {
                const std::size_t id = workers_.size();
                workers_.emplace_back([this, id] { worker_loop(id); });
            }
            job_ = &j;
            helpers_ = want - 1;
            busy_ = want - 1;
            ++generation_;
        }
        wake_.notify_all();
        run(j);
        std::unique_lock<std::mutex> hold(lock_);
        done_.wait(hold, [&] { return busy_ == 0; });
        job_ = nullptr;
        hold.unlock();
        if (j.failure) std::rethrow_exception(j.failure);
    }

private:
    /// A loop a thread runs in, and the loops its caller ran in (a chain on the threads' stacks).
    struct loop_chain {
        const thread_pool* pool;
        const loop_chain* caller;
    };

    struct job {
        const loop_chain* caller = nullptr;
        std::size_t count = 0;
        void* context = nullptr;
        void (*call)(void*, std::size_t) = nullptr;
        std::atomic<std::size_t> next{0};
        std::mutex failure_lock;
        std::exception_ptr failure;
    };

    static unsigned resolve(unsigned threads) noexcept {
        return threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
    }

    /// The loops the calling thread runs in (innermost first), through the threads that started them; null outside.
    static const loop_chain*& current() noexcept {
        thread_local const loop_chain* chain = nullptr;
        return chain;
    }
    /// True when the calling thread runs, directly or through the loops that started its own, in a loop of `pool`.
    static bool within(const thread_pool* pool) noexcept {
        for (const loop_chain* c = current(); c != nullptr; c = c->caller)
            if (c->pool == pool) return true;
        return false;
    }

    void run(job& j) const noexcept {
        const loop_chain* const outer = current();
        const loop_chain here{this, j.caller};
        current() = &here;
        struct restore {
            const loop_chain* outer;
            ~restore() { current() = outer; }
        } const back{outer};
        for (;;) {
            const std::size_t i = j.next.fetch_add(1, std::memory_order_relaxed);
            if (i >= j.count) return;
            try {
                j.call(j.context, i);
            } catch (...) {
                const std::lock_guard<std::mutex> hold(j.failure_lock);
                if (!j.failure) j.failure = std::current_exception();
                j.next.store(j.count, std::memory_order_relaxed); // no new index after a failure
            }
        }
    }

    void worker_loop(std::size_t id) {
        std::uint64_t seen = 0;
        std::unique_lock<std::mutex> hold(lock_);
        for (;;) {
            wake_.wait(hold, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
            if (id >= helpers_) continue; // this loop asked for fewer threads
            job* j = job_;
            hold.unlock();
            run(*j);
            hold.lock();
            if (--busy_ == 0) done_.notify_one();
        }
    }

    unsigned size_;
    std::mutex loop_lock_; // one loop at a time
    std::mutex lock_;      // guards everything below
    std::condition_variable wake_, done_;
    std::vector<std::thread> workers_;
    job* job_ = nullptr;
    std::size_t helpers_ = 0, busy_ = 0;
    std::uint64_t generation_ = 0;
    bool stopping_ = false;
};

/// The process-wide pool that simulator::render uses unless given another one: started on first use, its
/// workers wait between loops and end with the program.
[[nodiscard]] inline thread_pool& shared_thread_pool() {
    static thread_pool pool;
    return pool;
}

} // namespace sss
