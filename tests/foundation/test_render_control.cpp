// simulator::render on a persistent pool: every ping is rendered once whatever the threads, progress reaches every
// count in order, and cancelling stops the render with render_cancelled and leaves simulator and pool reusable.

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <thread>
#include <vector>

#include <sss/sss.hpp>

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
