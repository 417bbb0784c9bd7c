// simulator::render on a persistent pool: every ping is rendered once whatever the threads, progress reaches every
// count in order, and cancelling stops the render with render_cancelled and leaves simulator and pool reusable; a
// stop flag set during a ping ends it at its next column.

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sss/sss.hpp>

#include "../support/rough_scenes.hpp"

namespace {

using sim_t = sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>,
                             sss::beam::ideal_fan<float>, sss::motion::perturbed<float>>;

sim_t make_sim() {
    sss::motion::perturbed_params<float> m;
    m.roll_deg = {3.0f, 4.0f, 0.0f};
    return sim_t({}, {}, {}, sss::motion::perturbed<float>{m});
}

} // namespace

TEST_CASE("a pool loop calls every index exactly once, however uneven the work and the thread count") {
    sss::thread_pool pool(3);
    for (unsigned threads : {1u, 2u, 3u, 5u}) {
        std::vector<std::atomic<int>> calls(200);
        pool.for_each(
            calls.size(),
            [&](std::size_t i) {
                if (i % 17 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
                calls[i].fetch_add(1);
            },
            threads);
        for (const auto& c : calls) REQUIRE(c.load() == 1);
    }
}

TEST_CASE("a pool loop rethrows the first failure and the pool runs the next loop in full") {
    sss::thread_pool pool(2);
    std::atomic<int> after{0};
    CHECK_THROWS_AS(pool.for_each(100,
                                  [&](std::size_t i) {
                                      if (i == 10) throw std::runtime_error("ping 10");
                                  }),
                    std::runtime_error);
    pool.for_each(50, [&](std::size_t) { after.fetch_add(1); });
    CHECK(after.load() == 50);
}

TEST_CASE("a loop started inside a loop of the same pool runs on its thread instead of waiting for itself") {
    sss::thread_pool pool(2);
    std::vector<std::atomic<int>> calls(8 * 8);
    pool.for_each(8, [&](std::size_t i) { pool.for_each(8, [&](std::size_t j) { calls[i * 8 + j].fetch_add(1); }); });
    for (const auto& c : calls) CHECK(c.load() == 1);
}

TEST_CASE("render on a pool gives the same waterfall for any thread count, and progress counts every ping in order") {
    const sim_t sim = make_sim();
    const sss::scene::flat_seabed<float> seabed;
    sss::thread_pool pool(2);
    const auto one = sim.render(seabed, 0, 9, sss::render_control{.threads = 1});
    for (unsigned threads : {2u, 3u, 4u}) {
        std::vector<std::size_t> seen;
        const auto w = sim.render(seabed, 0, 9,
                                  sss::render_control{.threads = threads,
                                                      .pool = &pool,
                                                      .progress = [&](const sss::render_progress& p) {
                                                          REQUIRE(p.total == 9);
                                                          seen.push_back(p.done);
                                                          return true;
                                                      }});
        CHECK(w.values == one.values);
        REQUIRE(seen.size() == 10);
        for (std::size_t i = 0; i < seen.size(); ++i) CHECK(seen[i] == i);
    }
}

TEST_CASE("returning false from progress cancels: render_cancelled says how far it got, and the next render is whole") {
    const sim_t sim = make_sim();
    const sss::scene::flat_seabed<float> seabed;
    sss::thread_pool pool(2);
    for (std::size_t stop_at : {std::size_t(0), std::size_t(3)}) {
        std::size_t last = 0;
        try {
            (void)sim.render(seabed, 0, 12,
                             sss::render_control{.threads = 2, .pool = &pool, .progress = [&](const sss::render_progress& p) {
                                                     last = p.done;
                                                     return p.done < stop_at;
                                                 }});
            FAIL("render was not cancelled");
        } catch (const sss::render_cancelled& e) {
            CHECK(e.done() == stop_at);
            CHECK(e.total() == 12);
            CHECK(last == stop_at); // no call after the one that cancelled
        }
    }
    const auto again = sim.render(seabed, 0, 12, sss::render_control{.threads = 2, .pool = &pool});
    const auto ref = sim.render(seabed, 0, 12, 1);
    CHECK(again.values == ref.values);
}

namespace {

// A flat seabed that counts the rays it is asked about and sets `stop` when the count reaches `stop_at`.
class stopping_seabed {
public:
    using value_type = float;
    stopping_seabed(std::atomic<bool>& stop, std::size_t stop_at) : stop_(&stop), stop_at_(stop_at) {}
    [[nodiscard]] std::optional<sss::hit<float>> intersect(const sss::ray<float>& r, float t_max_m) const {
        if (++count_ == stop_at_) stop_->store(true);
        return seabed_.intersect(r, t_max_m);
    }
    [[nodiscard]] float seabed_height_m(float x, float y) const { return seabed_.seabed_height_m(x, y); }
    [[nodiscard]] float top_m() const { return seabed_.top_m(); }
    [[nodiscard]] std::size_t count() const noexcept { return count_; }

private:
    sss::scene::flat_seabed<float> seabed_{};
    std::atomic<bool>* stop_;
    std::size_t stop_at_;
    mutable std::size_t count_ = 0;
};

} // namespace

TEST_CASE("a stop flag set during a ping ends it at the next column: render_cancelled counts no ping done") {
    const sim_t sim = make_sim();
    std::atomic<bool> stop{false};
    stopping_seabed whole(stop, 0);
    (void)sim.ping(whole, 0);
    const std::size_t per_ping = whole.count();
    REQUIRE(per_ping > 1000);
    stop.store(false);
    sss::thread_pool pool(1);
    stopping_seabed halfway(stop, per_ping / 2);
    try {
        (void)sim.render(halfway, 0, 4, sss::render_control{.threads = 1, .pool = &pool, .stop = &stop});
        FAIL("render was not stopped");
    } catch (const sss::render_cancelled& e) {
        CHECK(e.done() == 0);
        CHECK(e.total() == 4);
    }
    // Set halfway through the first ping, the flag let at most a column's rays more be traced (16 columns a ping),
    // where finishing the ping would have taken half of its rays.
    CHECK(halfway.count() - per_ping / 2 < per_ping / 8);
    // A flag set before the render: nothing is traced. Cleared: the next render is whole.
    stopping_seabed none(stop, 0);
    CHECK_THROWS_AS((void)sim.render(none, 0, 4, sss::render_control{.threads = 1, .pool = &pool, .stop = &stop}),
                    sss::render_cancelled);
    CHECK(none.count() == 0);
    stop.store(false);
    const sss::scene::flat_seabed<float> seabed;
    CHECK(sim.render(seabed, 0, 4, sss::render_control{.threads = 1, .pool = &pool, .stop = &stop}).values ==
          sim.render(seabed, 0, 4, 1).values);
}

TEST_CASE("under an array whose columns are all traced before any is divided, a stop flag set meanwhile ends the "
          "ping at the next column, and a flag cleared again before the ping unwinds still cancels the render") {
    using array_sim = sss::simulator<sss::scattering::lambertian<double>, sss::propagation::straight<double>,
                                     sss::beam::planar_array<double>, sss::motion::straight_line<double>>;
    sss::beam::planar_array_params<double> ap;
    ap.frequency_hz = 100e3;
    const array_sim sim({}, {}, sss::beam::planar_array<double>(ap), {}, sss_test::rough_receiver());
    // Rippled relief: the columns' echoes differ sample by sample, so every column of a side is traced and held
    // before the first is divided, and the echoes reach the observer only then.
    const auto ripples = sss_test::ripple_field<double>();
    std::size_t whole = 0;
    (void)sim.ping(ripples, 0, [&](sss::side, const auto&) { ++whole; });
    REQUIRE(whole > 1000);
    sss::thread_pool pool(1);
    std::atomic<bool> stop{false};
    std::size_t after = 0;
    try {
        sss::run_pings(4, sss::render_control{.threads = 1, .pool = &pool, .stop = &stop}, [&](std::size_t i) {
            (void)sim.ping(ripples, i, [&](sss::side, const auto&) {
                if (!stop.exchange(true)) return;
                ++after;
            });
        });
        FAIL("render was not stopped");
    } catch (const sss::render_cancelled& e) {
        CHECK(e.done() == 0);
    }
    CHECK(after < whole / 4); // set at the first echo of the first side: at most a column's echoes more
    // A flag set during ping 2 and cleared as it unwinds: ping 2 stopped, so the render is cancelled after 2.
    stop.store(false);
    struct clear_on_exit {
        std::atomic<bool>& flag;
        bool armed;
        ~clear_on_exit() {
            if (armed) flag.store(false);
        }
    };
    try {
        sss::run_pings(4, sss::render_control{.threads = 1, .pool = &pool, .stop = &stop}, [&](std::size_t i) {
            const clear_on_exit clear{stop, i == 2};
            (void)sim.ping(ripples, i, [&](sss::side, const auto&) {
                if (i == 2) stop.store(true);
            });
        });
        FAIL("render was not cancelled");
    } catch (const sss::render_cancelled& e) {
        CHECK(e.done() == 2);
    }
}

TEST_CASE("a loop nested through another pool's loop back into the first pool runs on its thread, not deadlocked") {
    // A's loop starts B's, whose workers start A's again: A's loop lock is held by A's own loop up the chain.
    sss::thread_pool a(2), b(2);
    std::vector<std::atomic<int>> calls(4 * 4 * 4);
    a.for_each(4, [&](std::size_t i) {
        b.for_each(4, [&](std::size_t j) {
            a.for_each(4, [&](std::size_t k) { calls[(i * 4 + j) * 4 + k].fetch_add(1); });
        });
    });
    for (const auto& c : calls) CHECK(c.load() == 1);
}

TEST_CASE("a progress callback that throws ends the render with its error and is not called again") {
    const sim_t sim = make_sim();
    const sss::scene::flat_seabed<float> seabed;
    sss::thread_pool pool(2);
    std::atomic<int> calls_after{0};
    std::atomic<bool> thrown{false};
    try {
        (void)sim.render(seabed, 0, 24,
                         sss::render_control{.threads = 2, .pool = &pool, .progress = [&](const sss::render_progress& p) {
                                                 if (thrown.load()) calls_after.fetch_add(1);
                                                 if (p.done == 3) {
                                                     thrown.store(true);
                                                     throw std::runtime_error("display closed");
                                                 }
                                                 return true;
                                             }});
        FAIL("no exception");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()) == "display closed");
    }
    CHECK(calls_after.load() == 0);
    // The pool and the simulator render whole afterwards.
    CHECK(sim.render(seabed, 0, 6, sss::render_control{.threads = 2, .pool = &pool}).values == sim.render(seabed, 0, 6, 1).values);
}
