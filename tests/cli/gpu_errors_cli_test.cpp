// What `--gpu` says on a machine where the GPU path cannot run: no Vulkan loader, no driver. Each is one
// line naming the problem, a non-zero exit and no output file, whether or not this machine has a device
// (the environment hides it from the child process).
#include "cli_harness.h"
#include "scoped_env.h"

#include <memory>
#include <string>
#include <vector>

namespace {

class GpuErrorsCli : public obscura::clitest::CliTest {
protected:
    // The inputs of `obscura ao`, rendered on the CPU.
    std::string aoInputs() {
        const obscura::clitest::CliResult r =
            obscura::clitest::runCli("render demo --size 32x24 -q --ao none -o " + path("f.png") + " --aov-dir " + path("aov"));
        EXPECT_EQ(r.code, 0) << r.out;
        return "ao --depth " + path("aov/depth.exr") + " --normal " + path("aov/normal.exr") + " --camera " +
               path("aov/camera.json");
    }
    // Sets an environment variable for the children run in this test; the old value comes back after it.
    void setEnv(const char* name, const std::string& value) {
        env_.push_back(std::make_unique<obscura::testutil::ScopedEnv>(name, value));
    }
    void TearDown() override {
        while (!env_.empty()) env_.pop_back();  // the last set first
        CliTest::TearDown();
    }

private:
    std::vector<std::unique_ptr<obscura::testutil::ScopedEnv>> env_;
};

TEST_F(GpuErrorsCli, NoLoader) {
    const std::string in = aoInputs();
    setEnv("OBSCURA_VULKAN_LIBRARY", path("missing/libvulkan.so.1"));
    expectFailure(in + " --gpu -o " + path("gpu.exr"), {"no Vulkan loader", "OBSCURA_VULKAN_LIBRARY"});
}

TEST_F(GpuErrorsCli, NoDriver) {
    const std::string in = aoInputs();
    // The loader reads its driver list from these (VK_ICD_FILENAMES before loader 1.3.207, VK_DRIVER_FILES
    // after); a list naming only a missing file leaves it no driver.
    setEnv("VK_ICD_FILENAMES", path("missing_icd.json"));
    setEnv("VK_DRIVER_FILES", path("missing_icd.json"));
    expectFailure(in + " --gpu -o " + path("gpu.exr"), {"no Vulkan 1.2 driver", "mesa-vulkan-drivers"});
}

} // namespace
