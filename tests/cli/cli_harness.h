// What every command-line test needs: run `obscura ARGS` and capture its output and exit code, a scratch
// directory per test process and test, and the check that a failing run printed one line, exited non-zero
// and left nothing behind.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace obscura::clitest {

struct CliResult {
    int code = -1;
    std::string out;  // stdout and stderr together
};

// A file's bytes ("" if it cannot be read): to tell that a failed run left a file as it was.
inline std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

// Runs the obscura binary built with the tests (OBSCURA_CLI) through the shell.
inline CliResult runCli(const std::string& args) {
    const std::string cmd = std::string(OBSCURA_CLI) + " " + args + " 2>&1";
    CliResult r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
    const int status = pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// A fixture with its own empty directory, named by process and test so parallel ctest runs never share one.
class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir = std::filesystem::temp_directory_path() /
              ("obscura_cli_" + std::to_string(getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    void write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path(name), std::ios::binary) << bytes;
    }
    std::size_t entries() const {
        return std::size_t(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}));
    }
    // Runs a command that must fail: one line starting "obscura: error: " and mentioning every needle, exit
    // code `code`, and nothing left in the scratch directory but what was there before.
    void expectFailure(const std::string& args, const std::vector<std::string>& needles, int code = 1) const {
        const std::size_t before = entries();
        const CliResult r = runCli(args);
        EXPECT_EQ(r.code, code) << args << "\n" << r.out;
        EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "not one line: " << r.out;
        EXPECT_EQ(r.out.rfind("obscura: error: ", 0), 0u) << r.out;
        for (const std::string& n : needles)
            EXPECT_NE(r.out.find(n), std::string::npos) << "'" << n << "' not in: " << r.out;
        EXPECT_EQ(entries(), before) << "output or temporary left behind by: " << args;
    }
    std::filesystem::path dir;
};

} // namespace obscura::clitest
