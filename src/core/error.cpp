#include "obscura/error.h"

#include <charconv>

namespace obscura {

void fail(const std::string& what, const std::string& problem) {
    if (what.empty()) throw Error(problem);
    std::string message;
    message.reserve(what.size() + 2 + problem.size());
    message.append(what).append(": ").append(problem);
    throw Error(message);
}

namespace {
template <class T> std::string shortestText(T value) {
    char text[64];
    // Without a format, to_chars writes the shortest form that parses back to the same value.
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, value);
    return std::string(text, r.ptr);
}
} // namespace

std::string numberText(float value) { return shortestText(value); }
std::string numberText(double value) { return shortestText(value); }

} // namespace obscura
