#include "obscura/error.h"

#include <charconv>

namespace obscura {

namespace {

// The length of the well-formed UTF-8 sequence at text[i] (Unicode 15, table 3-7: no overlong forms, no
// surrogates, nothing past U+10FFFF), or 0 if there is none.
std::size_t utf8Length(const std::string& text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0u; };
    const unsigned lead = byte(0);
    const auto inRange = [&](std::size_t k, unsigned lo, unsigned hi) { return byte(k) >= lo && byte(k) <= hi; };
    if (lead >= 0xC2 && lead <= 0xDF) return inRange(1, 0x80, 0xBF) ? 2 : 0;
    if (lead >= 0xE0 && lead <= 0xEF) {
        const unsigned lo = lead == 0xE0 ? 0xA0 : 0x80, hi = lead == 0xED ? 0x9F : 0xBF;
        return inRange(1, lo, hi) && inRange(2, 0x80, 0xBF) ? 3 : 0;
    }
    if (lead >= 0xF0 && lead <= 0xF4) {
        const unsigned lo = lead == 0xF0 ? 0x90 : 0x80, hi = lead == 0xF4 ? 0x8F : 0xBF;
        return inRange(1, lo, hi) && inRange(2, 0x80, 0xBF) && inRange(3, 0x80, 0xBF) ? 4 : 0;
    }
    return 0;
}

std::string printable(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        const std::size_t n = c >= 0x80 ? utf8Length(text, i) : (c < 0x20 || c == 0x7F ? 0 : 1);
        if (n > 0) {
            out.append(text, i, n);
            i += n;
            continue;
        }
        static const char hex[] = "0123456789abcdef";
        out += "\\x";
        out += hex[c >> 4];
        out += hex[c & 15];
        ++i;
    }
    return out;
}

} // namespace

Error::Error(const std::string& message) : std::runtime_error(printable(message)) {}

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
