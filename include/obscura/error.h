// Errors that come from a user's input or machine.
//
// Two tiers, as everywhere in Obscura: programming errors are assert()s; everything that can fail on
// input or environment (files, parsing, devices, GPU memory) throws obscura::Error, whose message names the
// file or resource and the problem on one line, ready to print as it is. Host memory running out throws
// std::bad_alloc, as the standard library does (the image readers turn it into an Error naming the file;
// the command-line tool reports it as "out of memory").
#pragma once

#include <stdexcept>
#include <string>

namespace obscura {

class Error : public std::runtime_error {
public:
    // The message as given, but for the bytes a terminal or a log would mangle: control characters (a newline
    // among them, which would break the one line) and bytes that are not UTF-8 (a corrupt file's token quoted
    // in the message) are written as \xNN. UTF-8 text, a file name's included, is kept.
    explicit Error(const std::string& message);
};

// Throws Error("<what>: <problem>"), the form every message takes (what = a file path or a flag name).
[[noreturn]] void fail(const std::string& what, const std::string& problem);

// A number as a message shows it: the shortest text that reads back as the same value (0.05, 1e+05, -1, nan,
// inf), where std::to_string prints 0.050000 and 100000.000000.
std::string numberText(float value);
std::string numberText(double value);

} // namespace obscura
