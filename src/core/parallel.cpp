// parallelFor on oneTBB.
#include "obscura/parallel.h"

#include "obscura/error.h"

#include <string>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

namespace obscura {

void parallelFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body, std::size_t grain) {
    if (count == 0) return;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain == 0 ? 1 : grain),
                      [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

ThreadLimit::ThreadLimit(int threads, const char* what) {
    // TBB starts as many workers as it is allowed: 2^31 - 1 once ran a command past 9 GB before any work.
    if (threads < 0 || threads > kMaxThreads)
        fail(what, "must be in [0, " + std::to_string(kMaxThreads) + "] (0 = all hardware threads), got " +
                       std::to_string(threads));
    if (threads > 0)
        control_ = new tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
}

ThreadLimit::~ThreadLimit() { delete static_cast<tbb::global_control*>(control_); }

int hardwareThreads() { return tbb::info::default_concurrency(); }

int allowedThreads() {
    return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

} // namespace obscura
