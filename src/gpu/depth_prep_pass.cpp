// Depth and normal preparation as compute passes (src/gpu/shaders/prepare_depth.comp,
// normals_from_depth.comp): the host side of ssao::prepareGBuffer, with its checks and its constants
// (ssao::depthPrepConstants). Contract in include/obscura/gpu_prep.h.
#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"
#include "gpu/depth_prep_pass.h"
#include "gpu/spirv.h"
#include "shaders/prep_layouts.h"

#include "obscura/error.h"
#include "obscura/gpu_prep.h"

#include <cmath>
#include <string>

namespace obscura::gpu {

static_assert(sizeof(ssao::DepthPrepConstants) == kPrepPushConstantBytes,
              "the push constants of the preparation passes are one DepthPrepConstants");

void recordNormalsFromDepth(Context::Impl& c, VkCommandBuffer cmd, const Buffer& depth, const Buffer& normal,
                            const ssao::DepthPrepConstants& k) {
    ComputePipeline& pipeline = c.pipeline("normals_from_depth", shaders::normals_from_depth, kRebuildBindingCount,
                                           kPrepPushConstantBytes, ssao::kDepthPrepWorkgroupX, ssao::kDepthPrepWorkgroupY);
    // In binding order: kRebuildBindingDepth, Normal.
    pipeline.dispatchGrid(cmd, {&depth, &normal}, &k, sizeof k, k.width, k.height);
}

void recordDepthPrep(Context::Impl& c, VkCommandBuffer cmd, const DepthPrepBuffers& b, const ssao::DepthPrepConstants& k) {
    ComputePipeline& pipeline = c.pipeline("prepare_depth", shaders::prepare_depth, kPrepBindingCount,
                                           kPrepPushConstantBytes, ssao::kDepthPrepWorkgroupX, ssao::kDepthPrepWorkgroupY);
    // In binding order: kPrepBindingDeviceDepth, NormalIn, Depth, Normal.
    pipeline.dispatchGrid(cmd, {&b.deviceDepth, &b.normalIn, &b.depth, &b.normal}, &k, sizeof k, k.width, k.height);
    if (k.normals != ssao::kNormalsFromDepth) return;
    computeBarrier(cmd);  // each pixel's normal reads its neighbours' linear depths
    recordNormalsFromDepth(c, cmd, b.depth, b.normal, k);
}

GBuffer prepareGBuffer(Context& context, const Image& deviceDepth, const Image& normals, const Camera& camera,
                       const ssao::DepthPrepSettings& s, const std::string& what) {
    ssao::checkDepthPrepInputs(deviceDepth, normals, camera, s, what);
    // The shader checks nothing: the CPU reference's scan of the depths, with its message.
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x)
            if (const float z = deviceDepth.at(x, y); !(z >= 0.0f && z <= 1.0f))
                fail(what, "depth " + std::to_string(z) + " at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                               ") is outside [0, 1]");
    ssao::DepthPrepConstants k = ssao::depthPrepConstants(s, camera);
    const bool readsNormals = s.normals != ssao::NormalSource::FromDepth;
    if (readsNormals) k.normalChannels = normals.channels;

    Context::Impl& c = context.impl();
    const std::size_t pixels = std::size_t(k.width) * std::size_t(k.height);
    const Buffer zBuffer = upload(c, deviceDepth.pixels.data(), pixels * sizeof(float));
    const Buffer normalIn = readsNormals ? upload(c, normals.pixels.data(), normals.pixels.size() * sizeof(float))
                                         : Buffer(c, sizeof(float), MemoryUse::Device);
    const Buffer depth(c, pixels * sizeof(float), MemoryUse::Device);
    const Buffer normal(c, 3 * pixels * sizeof(float), MemoryUse::Device);
    c.submit([&](VkCommandBuffer cmd) { recordDepthPrep(c, cmd, {zBuffer, normalIn, depth, normal}, k); }, true);
    GBuffer g;
    g.camera = camera;
    g.depth = Image(k.width, k.height, 1);
    g.normal = Image(k.width, k.height, 3);
    download(c, depth, g.depth.pixels.data(), pixels * sizeof(float));
    download(c, normal, g.normal.pixels.data(), 3 * pixels * sizeof(float));
    // Unusable normals are the CPU reference's error too: the pass writes a unit vector for every other.
    if (readsNormals)
        for (std::size_t i = 0; i < pixels; ++i)
            if (g.depth.pixels[i] < 1e30f) {
                const float* n = &g.normal.pixels[3 * i];
                ssao::checkPreparedNormal({n[0], n[1], n[2]}, int(i % std::size_t(k.width)),
                                          int(i / std::size_t(k.width)), what);
            }
    return g;
}

} // namespace obscura::gpu
