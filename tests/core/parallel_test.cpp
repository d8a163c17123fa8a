// ThreadLimit's range and parallelFor's coverage under it.
#include "obscura/error.h"
#include "obscura/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

namespace obscura {
namespace {

// A negative count was taken as "all threads" and 2^31 - 1 started that many TBB workers (past 9 GB before
// any work); both are refused, naming the range.
TEST(ThreadLimit, RefusesCountsOutsideItsRange) {
    for (int threads : {-1, -2147483647 - 1, kMaxThreads + 1, 2147483647}) {
        try {
            ThreadLimit limit(threads);
            ADD_FAILURE() << threads << " accepted";
        } catch (const Error& e) {
            const std::string expected =
                "threads: must be in [0, 1024] (0 = all hardware threads), got " + std::to_string(threads);
            EXPECT_EQ(std::string(e.what()), expected);
        }
    }
}

TEST(ThreadLimit, EveryIndexOnceWithinTheRange) {
    for (int threads : {0, 1, 3, kMaxThreads}) {
        ThreadLimit limit(threads);
        std::vector<std::atomic<int>> seen(1000);
        parallelFor(seen.size(), [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) ++seen[i];
        });
        for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i].load(), 1) << threads << " threads, index " << i;
    }
}

} // namespace
} // namespace obscura
