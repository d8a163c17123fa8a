#include "obscura/error.h"

namespace obscura {

void fail(const std::string& what, const std::string& problem) {
    if (what.empty()) throw Error(problem);
    std::string message;
    message.reserve(what.size() + 2 + problem.size());
    message.append(what).append(": ").append(problem);
    throw Error(message);
}

} // namespace obscura
