// Order statistics the benches report.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace obscura {

// The middle value, or of an even count the mean of the two middle ones; 0 for none. The benches' one rule
// (the CPU benches once took the upper middle, so 2 repeats' "median" was the slower run).
inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

} // namespace obscura
