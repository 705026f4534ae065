// Progress of long loops (geometry/work_progress.hpp): what a live scope hears from the
// parallel loops, and that nothing is heard without one or from a short loop.

#include <atomic>
#include <catch2/catch.hpp>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "geometry/detail/parallel.hpp"
#include "geometry/work_progress.hpp"

using namespace geotex;

namespace {

struct Heard {
    std::mutex mutex;
    std::vector<WorkProgress> reports;
    std::atomic<int> inside{0};
    bool overlapped = false;
};

WorkObserver listen(Heard& heard) {
    return [&heard](const WorkProgress& w) {
        if (heard.inside.fetch_add(1) != 0) heard.overlapped = true;
        {
            std::lock_guard<std::mutex> lock(heard.mutex);
            heard.reports.push_back(w);
        }
        heard.inside.fetch_sub(1);
    };
}

}  // namespace

TEST_CASE("WorkProgressScope: a long loop reports how far it is, one call at a time",
          "[progress]") {
    Heard heard;
    const int n = 200000;
    std::vector<double> out(n, 0);
    {
        // No delay and no interval: every finished chunk may report.
        WorkProgressScope scope(listen(heard), 0.0, 0.0, 1000);
        detail::parallel_for(
            n, [&](int i) { out[i] = i * 0.5; }, 1024);
        CHECK_THROWS_AS(WorkProgressScope(listen(heard)), std::logic_error);  // one at a time
    }
    CHECK(out[n - 1] == (n - 1) * 0.5);  // the loop itself is unchanged
    REQUIRE_FALSE(heard.reports.empty());
    CHECK_FALSE(heard.overlapped);
    long long most = 0;
    for (const WorkProgress& w : heard.reports) {
        CHECK(w.total == n);
        CHECK(w.done > 0);
        CHECK(w.done <= n);
        CHECK(w.seconds >= 0);
        most = std::max(most, w.done);
    }
    // The last chunk to finish reports the whole loop done.
    CHECK(most == n);

    // One thread (geotex -j 1): the loop runs on the caller, which reports.
    Heard serial;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        WorkProgressScope scope(listen(serial), 0.0, 0.0, 1000);
        detail::parallel_for(n, [&](int i) { out[i] = i; });
    }
    REQUIRE_FALSE(serial.reports.empty());
    CHECK(serial.reports.back().done == n);
    for (std::size_t k = 1; k < serial.reports.size(); ++k)
        CHECK(serial.reports[k].done > serial.reports[k - 1].done);

    // A second scope may follow the first.
    Heard again;
    {
        WorkProgressScope scope(listen(again), 0.0, 0.0, 1000);
        detail::parallel_for_with(
            n, [] { return 0; }, [&](int i, int&) { out[i] = 1; }, 256);
    }
    CHECK_FALSE(again.reports.empty());
}

TEST_CASE("WorkProgressScope: short loops, early moments and loops without a scope are silent",
          "[progress]") {
    Heard heard;
    std::vector<int> out(5000, 0);
    {
        WorkProgressScope scope(listen(heard), 0.0, 0.0, 10000);  // loops of 10,000 and more
        detail::parallel_for(5000, [&](int i) { out[i] = i; });
    }
    {
        WorkProgressScope scope(listen(heard), 3600.0, 0.0, 1);  // after an hour only
        detail::parallel_for(5000, [&](int i) { out[i] = i; });
    }
    detail::parallel_for(5000, [&](int i) { out[i] = i; });  // no scope
    CHECK(heard.reports.empty());
    CHECK(out[4999] == 4999);
}
