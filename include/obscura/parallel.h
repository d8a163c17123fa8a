// parallel_for over rows or tiles, on oneTBB.
#pragma once

#include <cstddef>
#include <functional>

namespace obscura {

// Calls body(begin, end) on disjoint sub-ranges covering [0, count), in parallel. Results must not depend
// on how the range is split (write per index), so one thread and many give the same bits.
void parallelFor(std::size_t count, const std::function<void(std::size_t begin, std::size_t end)>& body,
                 std::size_t grain = 1);

// The most threads a ThreadLimit takes: more than the machines this runs on have.
inline constexpr int kMaxThreads = 1024;

// Limits the threads parallelFor uses while the object lives (0 = all hardware threads). Throws
// obscura::Error("<what>: ...") outside [0, kMaxThreads]; a command passes its flag's name.
class ThreadLimit {
public:
    explicit ThreadLimit(int threads, const char* what = "threads");
    ~ThreadLimit();
    ThreadLimit(const ThreadLimit&) = delete;
    ThreadLimit& operator=(const ThreadLimit&) = delete;

private:
    void* control_ = nullptr;
};

int hardwareThreads();

// The threads parallelFor may use now: the innermost live ThreadLimit's, else hardwareThreads(). Libraries with
// thread pools of their own (OpenEXR's) are sized by it, so --threads bounds them too.
int allowedThreads();

} // namespace obscura
