// An environment variable set for a scope: the value it had before, or its absence, comes back when the
// object goes. Tests that set OBSCURA_SHADER_DIR, OBSCURA_VALIDATION or OBSCURA_GPU_DEVICE for a context or a
// child process of their own use it, so that what the whole run was started with (a candidate's shaders
// through OBSCURA_SHADER_DIR, say, over one test process) holds again for the tests after them.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace obscura::testutil {

class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        set(value);
    }
    ~ScopedEnv() {
        if (old_) ::setenv(name_.c_str(), old_->c_str(), 1);
        else ::unsetenv(name_.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

    // Another value for the rest of the scope; the one before the first still comes back at its end.
    void set(const std::string& value) { ::setenv(name_.c_str(), value.c_str(), 1); }

private:
    std::string name_;
    std::optional<std::string> old_;
};

} // namespace obscura::testutil
