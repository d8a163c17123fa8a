// Input the public GPU functions once took without a word, or crashed on, where their CPU twins answer: an
// image past the device's storage-buffer range, a depth of another channel count in the benchmark, 0x0
// G-buffers, a low-resolution image that is not the G-buffer's grid, 4-channel normals in the reconstruction,
// depths so small that the blur's depth scale is infinite, and device indices out of range. On lavapipe with
// validation on; each test failed before its fix (a validation error, a crash, no error, or a difference of 0.68).
#include "gpu_test_util.h"
#include "scoped_env.h"

#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gpu_bench.h"
#include "obscura/gpu_lighting.h"
#include "obscura/gpu_temporal.h"
#include "obscura/gtao_temporal.h"
#include "obscura/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura::gpu {
namespace {

// A w x h view of a plane facing the camera 5 m away, albedo 0.5.
GBuffer facingPlane(int w, int h) {
    GBuffer g = testing::render("plane", 1, 1);
    g.camera.width = w;
    g.camera.height = h;
    g.depth = Image(w, h, 1, 5.0f);
    g.normal = Image(w, h, 3);
    g.albedo = Image(w, h, 3, 0.5f);
    for (std::size_t i = 0; i < g.depth.pixelCount(); ++i) g.normal.pixels[3 * i + 2] = 1.0f;
    return g;
}

} // namespace

// 4096x2736 normals are 134,479,872 bytes, past lavapipe's maxStorageBufferRange of 134,217,728: bound whole,
// they gave VUID-VkWriteDescriptorSet-descriptorType-00333 (a device may read a truncated buffer). A device
// with a larger range shades it; one without refuses it, naming the limit. Either way no validation message.
TEST(GpuInputs, ABufferPastTheStorageBufferRangeIsRefused) {
    OBSCURA_GPU_CONTEXT(context);
    const std::size_t before = context.validationMessages().size();
    const std::string m = testing::errorMessage([&] { shade(context, facingPlane(4096, 2736), {}, Image(), Image()); });
    if (m != "no error") {
        EXPECT_NE(m.find("maxStorageBufferRange"), std::string::npos) << m;
    }
    EXPECT_EQ(context.validationMessages().size(), before) << testing::validationReport(context);
    // The context still works after the refusal.
    const render::Frame small = shade(context, facingPlane(8, 4), {}, Image(), Image());
    EXPECT_EQ(small.color.width, 8);
    EXPECT_EQ(testing::validationReport(context), "");
}

// A first spatio-temporal frame that failed (its 4096x2736 normals past lavapipe's storage-buffer range) left
// passes of its size behind: the next frame, 16x8, skipped the size check and came back 4096x2736, of stale
// device memory (max |GPU - CPU| 1 over its 16x8 pixels). On a device that shades the large frame, the 16x8
// one is refused as a change of size, as on the CPU.
TEST(GpuInputs, ATemporalFrameThatFailedLeavesNothingBehind) {
    OBSCURA_GPU_CONTEXT(context);
    ssao::GtaoSettings s;
    s.sliceCount = 1;
    s.stepsPerSide = 1;
    ssao::GtaoTemporalSettings t;
    t.packedHistory = true;
    GtaoTemporal temporal(context, s, t, GtaoOutputs::Visibility);
    const std::string big = testing::errorMessage([&] { temporal.frame(facingPlane(4096, 2736)); });
    const GBuffer small = facingPlane(16, 8);
    if (big == "no error") {
        EXPECT_EQ(testing::errorMessage([&] { temporal.frame(small); }),
                  "gtao temporal: frame size changed from 4096x2736 to 16x8");
    } else {
        EXPECT_NE(big.find("maxStorageBufferRange"), std::string::npos) << big;
        EXPECT_EQ(temporal.framesRendered(), 0);
        ssao::GtaoTemporal cpu(s, t);
        const Image expected = cpu.frame(small).visibility;
        const Image got = temporal.frame(small).visibility;
        ASSERT_EQ(got.width, 16);
        ASSERT_EQ(got.height, 8);
        double worst = 0;
        for (std::size_t i = 0; i < got.pixels.size(); ++i)
            worst = std::max(worst, std::fabs(double(got.pixels[i]) - double(expected.pixels[i])));
        EXPECT_LT(worst, 1e-4);
        EXPECT_EQ(temporal.historyLength().width, 16);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// A 0x0 G-buffer: the CPU's GtaoTemporal answers empty images and counts the frame, the GPU's threw "G-buffer
// is empty"; gpu::multiBounce refused 0x0 inputs that match, saying they did not.
TEST(GpuInputs, AnEmptyTemporalFrameAndMultiBounceAnswerAsTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer e = facingPlane(0, 0);
    GtaoTemporal temporal(context, ssao::GtaoSettings{}, ssao::GtaoTemporalSettings{});
    ssao::GtaoTemporal cpu(ssao::GtaoSettings{}, ssao::GtaoTemporalSettings{});
    const ssao::GtaoResult& r = temporal.frame(e);
    const ssao::GtaoResult& rc = cpu.frame(e);
    EXPECT_EQ(r.visibility.width, rc.visibility.width);
    EXPECT_EQ(r.visibility.channels, rc.visibility.channels);
    EXPECT_EQ(r.bentNormal.channels, rc.bentNormal.channels);
    EXPECT_EQ(temporal.framesRendered(), cpu.framesRendered());
    testing::expectSameError([&] { cpu.frame(facingPlane(4, 4)); }, [&] { temporal.frame(facingPlane(4, 4)); });
    EXPECT_EQ(multiBounce(context, e, Image(0, 0, 1)).width, 0);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The separable blur's row pass dispatches a workgroup per row: for a 1x70000 image that is past every
// device's maxComputeWorkGroupCount of 65535 (VUID-vkCmdDispatch-groupCountY-00387). Refused by name, with no
// validation message; a device with a larger count blurs it as the CPU does.
TEST(GpuInputs, AGroupCountPastTheDeviceLimitIsRefused) {
    OBSCURA_GPU_CONTEXT(context);
    const std::size_t before = context.validationMessages().size();
    const GBuffer tall = facingPlane(1, 70000);
    ssao::BilateralSettings blur;
    blur.mode = ssao::BlurMode::Separable;
    const Image ao(1, 70000, 1, 0.5f);
    const std::string m = testing::errorMessage([&] { bilateralFilter(context, ao, tall, blur); });
    if (m != "no error") {
        EXPECT_NE(m.find("maxComputeWorkGroupCount"), std::string::npos) << m;
    }
    EXPECT_EQ(context.validationMessages().size(), before) << testing::validationReport(context);
    EXPECT_EQ(testing::validationReport(context), "");
}

// A depth of 0 channels crashed in the upload; 2 channels were read as one.
TEST(GpuInputs, TheBenchmarkRefusesADepthOfAnotherChannelCount) {
    OBSCURA_GPU_CONTEXT(context);
    GpuBenchSettings s;
    s.frames = 1;
    s.warmup = 0;
    for (int channels : {0, 2}) {
        GBuffer g = testing::render("demo", 16, 12);
        g.depth = Image(16, 12, channels, 2.0f);
        EXPECT_THROW(benchGpuCase(context, "gtao", {g}, s), Error) << channels << " channels";
    }
}

// render::shade and ssao::computeSpecularOcclusion return empty images for a 0x0 G-buffer; the GPU made
// buffers of 0 bytes (VUID-VkBufferCreateInfo-size-00912 and others).
TEST(GpuInputs, AZeroSizeGBufferGivesEmptyImagesAsOnTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer e = facingPlane(0, 0);
    const render::Frame f = shade(context, e, {}, Image(), Image());
    EXPECT_EQ(f.color.width, 0);
    EXPECT_EQ(f.color.height, 0);
    const Image so =
        specularOcclusion(context, e, Image(0, 0, 1), Image(0, 0, 3), ssao::SpecularOcclusionMode::Cone, 0.5f);
    EXPECT_EQ(so.width, 0);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The GPU upsampled a low-resolution image of any size (its taps clamped to it, so a 3x3 image was stretched
// over a 16x12 frame); the CPU's check and message now stand for both.
TEST(GpuInputs, TheUpsamplingRefusesAnImageThatIsNotTheGrid) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("demo", 16, 12);
    testing::expectSameError([&] { ssao::upsampleDepthAware(Image(3, 3, 1), Image(3, 3, 1, 2.0f), g, 0.05f); },
                             [&] { upsampleDepthAware(context, Image(3, 3, 1), Image(3, 3, 1, 2.0f), g, 0.05f); });
    EXPECT_EQ(testing::errorMessage([&] { upsampleDepthAware(context, Image(3, 3, 1), Image(3, 3, 1, 2.0f), g, 0.05f); }),
              "upsample depth-aware: values are 3x3x1 but the grid of a 16x12 G-buffer is 8x6");
    const GBuffer e = facingPlane(0, 0);
    testing::expectSameError([&] { ssao::upsampleDepthAware(Image(1, 1, 1), Image(1, 1, 1, 2.0f), e, 0.05f); },
                             [&] { upsampleDepthAware(context, Image(1, 1, 1), Image(1, 1, 1, 2.0f), e, 0.05f); });
    EXPECT_EQ(testing::validationReport(context), "");
}

// The GPU's reconstruction once kept its own copy of the CPU's checks, which had drifted: it took 4-channel
// normals (the CPU refuses them) and its message named neither image's shape. Both check with the CPU's now.
TEST(GpuInputs, TheReconstructionRefusesWhatTheCpuRefuses) {
    OBSCURA_GPU_CONTEXT(context);
    const Image values(4, 4, 1, 0.5f), depth(4, 4, 1, 2.0f), normal4(4, 4, 4, 0.5f), normal3(4, 4, 3, 0.5f);
    testing::expectSameError([&] { ssao::reconstructInterleaved(values, depth, normal4, 0.05f); },
                             [&] { reconstructInterleaved(context, values, depth, normal4, 0.05f); });
    EXPECT_EQ(testing::errorMessage([&] { reconstructInterleaved(context, values, depth, normal4, 0.05f); }),
              "reconstruct interleaved: depth (1 channel) and normal (3 channels) must match the 4x4 values, not "
              "4x4x1 and 4x4x4");
    testing::expectSameError([&] { ssao::reconstructInterleaved(values, Image(4, 3, 1, 2.0f), normal3, 0.05f); },
                             [&] { reconstructInterleaved(context, values, Image(4, 3, 1, 2.0f), normal3, 0.05f); });
    testing::expectSameError([&] { ssao::reconstructInterleaved(values, depth, normal3, 0.05f, 8); },
                             [&] { reconstructInterleaved(context, values, depth, normal3, 0.05f, 8); });
    EXPECT_EQ(testing::validationReport(context), "");
}

// Depths below about 1e-19 m pass the G-buffer's checks but make the blur's c = depthScale / d^2 infinite: the
// GPU's weights are NaN and it keeps the input, the CPU's separable blur gave weights of 2^-125 (0 with
// flush-to-zero). Both keep the input now: within the blur's usual 2e-3 (the difference was 0.68).
TEST(GpuInputs, TheBlurKeepsTheInputAtDepthsTooSmallForItsScale) {
    OBSCURA_GPU_CONTEXT(context);
    GBuffer g = testing::render("demo", 24, 16);
    int tiny = 0;
    for (std::size_t i = 0; i < g.depth.pixels.size(); i += 5)
        if (g.depth.pixels[i] < 1e30f) {
            g.depth.pixels[i] = 1e-20f;
            ++tiny;
        }
    ASSERT_GT(tiny, 20);
    Image ao(24, 16, 1);
    for (std::size_t i = 0; i < ao.pixels.size(); ++i) ao.pixels[i] = 0.25f + 0.5f * float(i % 7) / 7.0f;
    const ssao::BilateralSettings s;
    const Image cpu = ssao::bilateralFilter(ao, g, s), gpu = bilateralFilter(context, ao, g, s);
    for (std::size_t i = 0; i < cpu.pixels.size(); ++i) ASSERT_NEAR(cpu.pixels[i], gpu.pixels[i], 2e-3f) << i;
    EXPECT_EQ(testing::validationReport(context), "");
}

// deviceIndex -2 opened device 0; OBSCURA_GPU_DEVICE equal to the device count was called "not a device index".
TEST(GpuInputs, DeviceIndicesOutOfRangeAreNamed) {
    if (deviceCount() == 0) GTEST_SKIP() << "no Vulkan device";
    ContextSettings s;
    s.deviceIndex = -2;
    EXPECT_NE(testing::errorMessage([&] { Context c(s); }).find("-2"), std::string::npos);
    const std::string n = std::to_string(deviceCount());
    testutil::ScopedEnv env("OBSCURA_GPU_DEVICE", n);
    const std::string m = testing::errorMessage([] { Context c; });
    EXPECT_NE(m.find("device " + n + " asked for"), std::string::npos) << m;
}

} // namespace obscura::gpu
