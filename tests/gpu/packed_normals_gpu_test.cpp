// The G-buffer's normals as octahedral words (one 32-bit word per pixel, obscura/history_packing.h's
// packOctahedral; normal_plane.glsl): every pass that reads normals gives, bit for bit on lavapipe, what it
// gives for the words' decoded normals as 3 floats (gpu::unpackNormals), which the other GPU tests hold to
// the CPU reference. So packing the normals changes a frame exactly as much as the 16-bit code moves them
// (within 1e-4 each; GtaoTemporal.OctahedralNormalsKeepTheAccuracy measures what that does to the error). The
// spatio-temporal passes are GpuGtaoTemporal.PackedNormalsGiveTheFrameOfTheirDecodedNormals's; the lighting
// passes (specular occlusion, shading) are here too.
#include "gpu/alchemy_pass.h"
#include "gpu/bilateral_2d_pass.h"
#include "gpu/bilateral_pass.h"
#include "gpu/buffer.h"
#include "gpu/gtao_half_res_pass.h"
#include "gpu/gtao_pass.h"
#include "gpu/gtao_temporal_pass.h"
#include "gpu/image_planes.h"
#include "gpu/shade_pass.h"
#include "gpu/specular_occlusion_pass.h"
#include "gpu_test_util.h"

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"
#include "obscura/gtao.h"
#include "obscura/gtao_half_res.h"
#include "obscura/render.h"
#include "obscura/specular_occlusion.h"

#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

using namespace obscura;
using namespace obscura::gpu;

namespace {

// A built-in scene's G-buffer, and on the device its depth and its normals both ways: the words, and their
// decoding as floats.
struct NormalPlanes {
    GBuffer g;
    Buffer depth, floats, words;
    std::size_t px;
};
NormalPlanes uploadPlanes(Context::Impl& c, const std::string& scene, int w, int h) {
    GBuffer g = gpu::testing::render(scene, w, h);
    const std::vector<std::uint32_t> words = packNormals(g.normal);
    Buffer depth = uploadChannels(c, g.depth, 1);
    Buffer floats = uploadChannels(c, unpackNormals(words, w, h), 3);
    Buffer packed = upload(c, words.data(), words.size() * sizeof(std::uint32_t));
    const std::size_t px = g.depth.pixelCount();
    return {std::move(g), std::move(depth), std::move(floats), std::move(packed), px};
}

// Words of `a` and `b` that differ, and (through occluded) how many of a's are below 0.99, so that a test
// sees it compared something.
int differing(Context::Impl& c, const Buffer& a, const Buffer& b, std::size_t count, int* occluded = nullptr) {
    const std::vector<std::uint32_t> va = downloadWords(c, a, count), vb = downloadWords(c, b, count);
    int n = 0;
    for (std::size_t i = 0; i < count; ++i) {
        n += va[i] != vb[i];
        if (occluded) *occluded += std::bit_cast<float>(va[i]) < 0.99f;
    }
    return n;
}

} // namespace

// Alchemy: the estimator alone and fused with the blur's rows.
TEST(GpuPackedNormals, AlchemyReadsTheWordsAsTheirDecoding) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const NormalPlanes planes = uploadPlanes(c, "demo", 133, 77);
    const GBuffer& g = planes.g;
    const ssao::AlchemyConstants k = ssao::alchemyConstants(ssao::AlchemySettings{}, g.camera);
    const std::vector<float> offsets = alchemySpiralOffsets(k);
    const Buffer spiral = upload(c, offsets.data(), offsets.size() * sizeof(float));
    const SeparableBilateral blur = separableBilateral(ssao::BilateralSettings{}, g.width(), g.height());
    const Buffer logSpatial = upload(c, blur.logSpatial.data(), blur.logSpatial.size() * sizeof(float));
    const std::size_t px = g.depth.pixelCount();
    const Buffer a = deviceFloats(c, px), b = deviceFloats(c, px), scratchA = deviceFloats(c, px),
                 scratchB = deviceFloats(c, px), rowsA = deviceFloats(c, px), rowsB = deviceFloats(c, px);
    c.submit([&](VkCommandBuffer cmd) {
        recordAlchemy(c, cmd, {planes.depth, planes.floats, spiral, a}, k);
        recordAlchemy(c, cmd, {planes.depth, planes.words, spiral, b, true}, k);
        recordAlchemyBlurred(c, cmd, {planes.depth, planes.floats, spiral, planes.depth, logSpatial, scratchA, rowsA},
                             k, blur);
        recordAlchemyBlurred(c, cmd,
                             {planes.depth, planes.words, spiral, planes.depth, logSpatial, scratchB, rowsB, true}, k,
                             blur);
    });
    int occluded = 0;
    EXPECT_EQ(differing(c, a, b, px, &occluded), 0);
    EXPECT_GT(occluded, int(px) / 50);
    EXPECT_EQ(differing(c, rowsA, rowsB, px), 0);
    EXPECT_EQ(gpu::testing::validationReport(context), "");
}

// The blurs where they weigh taps by the normals: the separable one in two dispatches and tiled, and the 2-D one.
TEST(GpuPackedNormals, BlursWeighByTheDecodedNormals) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const NormalPlanes planes = uploadPlanes(c, "stairs", 97, 63);
    const GBuffer& g = planes.g;
    const std::size_t px = planes.px;
    Image ao(g.width(), g.height(), 1);
    std::uint32_t state = 99u;
    for (float& v : ao.pixels) {
        state = state * 1664525u + 1013904223u;
        v = float(state >> 8) / float(1u << 24);
    }
    const Buffer input = uploadChannels(c, ao, 1);
    ssao::BilateralSettings s;
    s.normalWeight = ssao::NormalWeight::On;
    s.radius = 4;
    const SeparableBilateral f = separableBilateral(s, g.width(), g.height());
    ASSERT_EQ(f.constants.useNormal, 1);
    const Buffer logSpatial = upload(c, f.logSpatial.data(), f.logSpatial.size() * sizeof(float));
    const std::vector<float> kernel = ssao::gaussianHalfKernel(s.radius);
    const Buffer kernelBuffer = upload(c, kernel.data(), kernel.size() * sizeof(float));
    for (const int variant : {0, 1, 2}) {  // two dispatches, tiled, 2-D
        const Buffer a = deviceFloats(c, px), b = deviceFloats(c, px), scratch = deviceFloats(c, px);
        c.submit([&](VkCommandBuffer cmd) {
            for (const bool packed : {false, true}) {
                const Buffer& normal = packed ? planes.words : planes.floats;
                const Buffer& out = packed ? b : a;
                if (variant == 2)
                    recordBilateral2D(c, cmd, {planes.depth, normal, kernelBuffer, input, out, packed}, f.constants);
                else
                    recordSeparableBilateral(c, cmd, {planes.depth, normal, logSpatial, input, scratch, out, packed}, f,
                                             variant == 1 ? BlurDispatch::Tiled : BlurDispatch::TwoPasses);
                computeBarrier(cmd);  // the second run reuses the scratch buffer
            }
        });
        EXPECT_EQ(differing(c, a, b, px), 0) << variant;
        // Not the input: the blur ran.
        const std::vector<std::uint32_t> blurred = downloadWords(c, a, px);
        int changed = 0;
        for (std::size_t i = 0; i < px; ++i) changed += std::bit_cast<float>(blurred[i]) != ao.pixels[i];
        EXPECT_GT(changed, int(px) / 4) << variant;
    }
    EXPECT_EQ(gpu::testing::validationReport(context), "");
}

// GTAO at full resolution with bent normals, and at half resolution with a normal-weighted 2-D blur on the
// grid.
TEST(GpuPackedNormals, GtaoReadsTheWordsAsTheirDecoding) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const NormalPlanes planes = uploadPlanes(c, "demo", 133, 77);
    const GBuffer& g = planes.g;
    const std::size_t px = planes.px;
    ssao::GtaoSettings settings;
    ssao::applyQuality(settings, ssao::GtaoQuality::Medium);
    const ssao::GtaoConstants k = ssao::gtaoConstants(settings, g.camera);
    const Buffer mips = gtaoDepthMipsBuffer(c, g.width(), g.height(), k.mipLevels);
    const Buffer va = deviceFloats(c, px), vb = deviceFloats(c, px), ba = deviceFloats(c, 3 * px),
                 bb = deviceFloats(c, 3 * px);
    c.submit([&](VkCommandBuffer cmd) {
        recordGtao(c, cmd, {planes.depth, planes.floats, va, ba, mips}, k);
        recordGtao(c, cmd, {planes.depth, planes.words, vb, bb, mips}, k, 1, true, true);
    });
    int occluded = 0;
    EXPECT_EQ(differing(c, va, vb, px, &occluded), 0);
    EXPECT_GT(occluded, int(px) / 50);
    EXPECT_EQ(differing(c, ba, bb, 3 * px), 0);

    ssao::GtaoHalfResolutionSettings half;
    half.blur.mode = ssao::BlurMode::TwoD;  // its normal weight on (Auto)
    ASSERT_TRUE(half.blur.usesNormals());
    GtaoHalfResolutionPasses floats(c, settings, half, g.width(), g.height(), true);
    GtaoHalfResolutionPasses words(c, settings, half, g.width(), g.height(), true, BlurDispatch::TwoPasses, true);
    c.submit([&](VkCommandBuffer cmd) {
        floats.record(cmd, planes.depth, planes.floats, g.camera, 0);
        words.record(cmd, planes.depth, planes.words, g.camera, 0);
    });
    EXPECT_EQ(differing(c, floats.visibility(), words.visibility(), px), 0);
    EXPECT_EQ(differing(c, floats.bentNormal(), words.bentNormal(), 3 * px), 0);
    // The GTAO pass's normals and the blur's guide normals: 8 bytes fewer per grid pixel each.
    const std::size_t grid = std::size_t(floats.gridWidth()) * std::size_t(floats.gridHeight());
    EXPECT_EQ(floats.bytesPerFrame() - words.bytesPerFrame(), 2 * 8 * grid);
    EXPECT_EQ(gpu::testing::validationReport(context), "");
}

// The lighting passes: specular occlusion from the G-buffer's normal (the cone mode reads it beside the bent
// normal) and the shading, whose irradiance and reflection turn on the normal.
TEST(GpuPackedNormals, LightingReadsTheWordsAsTheirDecoding) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const NormalPlanes planes = uploadPlanes(c, "demo", 97, 61);
    const GBuffer& g = planes.g;
    const ssao::GtaoResult ao = ssao::computeGtao(g, ssao::gtaoConstants(ssao::GtaoSettings{}, g.camera));
    const std::size_t pixels = planes.px;
    const Buffer visibility = uploadChannels(c, ao.visibility, 1);
    const Buffer bent = uploadChannels(c, ao.bentNormal, 3);
    using ssao::SpecularOcclusionMode;
    for (const SpecularOcclusionMode mode : {SpecularOcclusionMode::Cone, SpecularOcclusionMode::Lut4}) {
        const Texture table = specularTable(c, mode, TextureFilter::Nearest);
        const SpecularConstants k = specularConstants(g, 0.4f);
        const Buffer a = deviceFloats(c, pixels), b = deviceFloats(c, pixels);
        c.submit([&](VkCommandBuffer cmd) {
            recordSpecularOcclusion(c, cmd, {planes.depth, planes.floats, visibility, bent, table, a}, k, mode,
                                    kSpecularLookupFetch);
            recordSpecularOcclusion(c, cmd, {planes.depth, planes.words, visibility, bent, table, b, true}, k, mode,
                                    kSpecularLookupFetch);
        });
        int occluded = 0;
        EXPECT_EQ(differing(c, a, b, pixels, &occluded), 0) << int(mode);
        EXPECT_GT(occluded, int(pixels) / 50) << int(mode);
    }

    const Image sky = render::proceduralSky(64, 32);
    const std::array<float, 36> terms = irradianceTerms(render::projectEnvironment(sky));
    const Buffer irradiance = upload(c, terms.data(), sizeof terms);
    const Texture environment = environmentTexture(c, sky);
    const Buffer albedo = uploadChannels(c, g.albedo, 3);
    const ShadeConstants k = shadeConstants(g.camera, 1, sky);
    const Buffer colorA = deviceFloats(c, 3 * pixels), colorB = deviceFloats(c, 3 * pixels), lightA = deviceFloats(c, 3 * pixels),
                 lightB = deviceFloats(c, 3 * pixels);
    c.submit([&](VkCommandBuffer cmd) {
        recordShade(c, cmd, {planes.depth, planes.floats, albedo, visibility, irradiance, environment, colorA, lightA},
                    k);
        recordShade(c, cmd,
                    {planes.depth, planes.words, albedo, visibility, irradiance, environment, colorB, lightB, true}, k);
    });
    EXPECT_EQ(differing(c, colorA, colorB, 3 * pixels), 0);
    EXPECT_EQ(differing(c, lightA, lightB, 3 * pixels), 0);
    EXPECT_EQ(gpu::testing::validationReport(context), "");
}
