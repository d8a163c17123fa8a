// The messages for failures a test cannot provoke on demand on every driver (device lost) and for one it
// can (a buffer larger than the device's memory).
#include "gpu_test_util.h"

#include "gpu/buffer.h"
#include "gpu/check.h"

#include <gtest/gtest.h>

namespace obscura::gpu {
namespace {

TEST(GpuErrors, ResultsInWords) {
    const auto message = [](VkResult r) {
        return testing::errorMessage([&] { check(r, "Test GPU", "waiting for the GTAO pass"); });
    };
    EXPECT_EQ(message(VK_ERROR_DEVICE_LOST),
              "Vulkan device 'Test GPU': waiting for the GTAO pass: device lost (the driver reset the GPU or a shader "
              "faulted); make a new Context (VK_ERROR_DEVICE_LOST)");
    EXPECT_NE(message(VK_ERROR_OUT_OF_DEVICE_MEMORY).find("out of device memory"), std::string::npos);
    EXPECT_NE(message(VK_ERROR_OUT_OF_HOST_MEMORY).find("out of host memory"), std::string::npos);
    EXPECT_EQ(message(VK_SUCCESS), "no error");
    EXPECT_EQ(testing::errorMessage([] { check(VK_ERROR_INITIALIZATION_FAILED, "", "creating the instance"); }),
              "Vulkan: creating the instance: failed (VK_ERROR_INITIALIZATION_FAILED)");
}

// A request beyond the heap fails before the driver sees it, with the device and the sizes named, and the
// context stays usable.
TEST(GpuErrors, OutOfDeviceMemory) {
    Context* context = testing::sharedContext();
    if (!context) GTEST_SKIP() << "no Vulkan device (install mesa-vulkan-drivers for lavapipe)";
    Context::Impl& c = context->impl();
    const std::string m = testing::errorMessage([&] { Buffer(c, VkDeviceSize(1) << 50, MemoryUse::Device); });
    EXPECT_NE(m.find("Vulkan device '" + context->device().name + "'"), std::string::npos) << m;
    EXPECT_NE(m.find("out of device memory"), std::string::npos) << m;
    const float one = 1.0f;
    float back = 0.0f;
    download(c, upload(c, &one, sizeof one), &back, sizeof back);
    EXPECT_EQ(back, 1.0f);
    EXPECT_EQ(testing::validationReport(*context), "");
}

} // namespace
} // namespace obscura::gpu
