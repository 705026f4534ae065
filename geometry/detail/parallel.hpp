#pragma once
// Parallel loops over index ranges. Every loop body writes only to the slots of its own
// indices, so results do not depend on the number of threads or on scheduling.

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "geometry/work_progress.hpp"

namespace geotex::detail {

/// True when one thread is allowed (a tbb::global_control, e.g. geotex -j1): the loops below
/// then run on the calling thread and never enter TBB, which would otherwise start its
/// worker pool anyway; where no thread can be created (a tight ulimit -v) TBB ends the
/// process from inside (std::terminate), with no chance to report the error.
inline bool serial() {
    return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) <= 1;
}

/// Sorts `values` ascending, in parallel unless one thread is allowed. The sorted sequence is
/// the same for any thread count when values that compare equal have the same bits (no -0.0
/// beside 0.0).
template <class T>
void parallel_sort(std::vector<T>& values) {
    if (serial())
        std::sort(values.begin(), values.end());
    else
        tbb::parallel_sort(values.begin(), values.end());
}

/// Calls body(i) for i in [0, n), in parallel chunks of at least `grain` indices.
/// Both loops tell a live WorkProgressScope how far they are (work_progress.hpp).
template <class Body>
void parallel_for(int n, Body&& body, int grain = 1024) {
    if (n <= 0) return;
    LoopMeter meter(n);
    if (serial()) {
        for (int i = 0; i < n; ++i) {
            body(i);
            if ((i & 4095) == 4095) meter.add(4096);
        }
        meter.add(n & 4095);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, n, grain), [&](const tbb::blocked_range<int>& r) {
        for (int i = r.begin(); i != r.end(); ++i) body(i);
        meter.add(static_cast<long long>(r.size()));
    });
}

/// Calls body(i, workspace) with a per-thread workspace made by `make` (reused across the
/// indices one thread handles; it must hold no result, only scratch buffers).
template <class Make, class Body>
void parallel_for_with(int n, Make&& make, Body&& body, int grain = 256) {
    if (n <= 0) return;
    LoopMeter meter(n);
    if (serial()) {
        auto ws = make();
        for (int i = 0; i < n; ++i) {
            body(i, ws);
            if ((i & 4095) == 4095) meter.add(4096);
        }
        meter.add(n & 4095);
        return;
    }
    using Workspace = decltype(make());
    tbb::enumerable_thread_specific<Workspace> workspaces(make);
    tbb::parallel_for(tbb::blocked_range<int>(0, n, grain), [&](const tbb::blocked_range<int>& r) {
        Workspace& ws = workspaces.local();
        for (int i = r.begin(); i != r.end(); ++i) body(i, ws);
        meter.add(static_cast<long long>(r.size()));
    });
}

/// Runs f and g, in parallel when a thread is free. Each must write only its own results.
template <class F, class G>
void parallel_invoke(F&& f, G&& g) {
    if (serial()) {
        f();
        g();
        return;
    }
    tbb::parallel_invoke(std::forward<F>(f), std::forward<G>(g));
}

}  // namespace geotex::detail
