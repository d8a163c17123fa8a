// GTAO at half resolution as compute passes (Jimenez et al. 2016, §4.1): the host side of
// ssao::computeGtaoHalfResolution (src/ssao/gtao_half_res.cpp), with the same checks and messages, the same
// constants, and its three steps as dispatches: gtao.comp over the grid (kGtaoSpecGridStep 2), the blur with
// its guide read from the full-resolution planes at a stride (BilateralConstants::guideStep 2: no grid copy
// of depth and normals), and upsample_depth_aware.comp. Contract in include/obscura/gpu.h.
#include "gpu/gtao_half_res_pass.h"
#include "gpu/bilateral_2d_pass.h"
#include "gpu/bilateral_pass.h"
#include "gpu/gtao_pass.h"
#include "gpu/gtao_temporal_pass.h"
#include "gpu/image_planes.h"

#include "obscura/gpu.h"

namespace obscura::gpu {

namespace {

std::size_t gridPixels(int width, int height) {
    return std::size_t((width + 1) / 2) * std::size_t((height + 1) / 2);
}

} // namespace

GtaoHalfResolutionPasses::GtaoHalfResolutionPasses(Context::Impl& c, const ssao::GtaoSettings& settings,
                                                   const ssao::GtaoHalfResolutionSettings& half, int width,
                                                   int height, bool bentNormals, BlurDispatch blurDispatch,
                                                   bool packedNormals)
    : context_(c), settings_(settings), half_(half), width_(width), height_(height), gridWidth_((width + 1) / 2),
      gridHeight_((height + 1) / 2), bentNormals_(bentNormals), packedNormals_(packedNormals),
      blur_(separableBilateral(half.blur, gridWidth_, gridHeight_)), blurDispatch_(blurDispatch),
      kernel2D_(ssao::gaussianHalfKernel(half.blur.radius)),
      blurWeights_(half.blur.mode == ssao::BlurMode::TwoD
                       ? upload(c, kernel2D_.data(), kernel2D_.size() * sizeof(float))
                       : upload(c, blur_.logSpatial.data(), blur_.logSpatial.size() * sizeof(float))),
      rawVisibility_(deviceFloats(c, gridPixels(width, height))),
      rawBent_(gtaoBentNormalBuffer(c, gridPixels(width, height), bentNormals)),
      scratch_(deviceFloats(c, gridPixels(width, height))), filtered_(deviceFloats(c, gridPixels(width, height))),
      depthMips_(gtaoDepthMipsBuffer(c, width, height, ssao::gtaoDepthMipLevels(settings))),
      visibility_(deviceFloats(c, std::size_t(width) * std::size_t(height))),
      bentView_(deviceFloats(c, bentNormals ? 3 * std::size_t(width) * std::size_t(height) : 4)) {
    blur_.constants.guideStep = 2;
    blur_.constants.guideWidth = width;
}

void GtaoHalfResolutionPasses::record(VkCommandBuffer cmd, const Buffer& depth, const Buffer& normal,
                                      const Camera& camera, int frameIndex,
                                      const std::function<void(const char*)>& mark) {
    Context::Impl& c = context_;
    auto done = [&](const char* stage) {
        if (mark) mark(stage);
    };
    const ssao::GtaoConstants k = ssao::gtaoConstants(settings_, camera, frameIndex);
    if (k.mipLevels > 0) {
        recordGtaoDepthMips(c, cmd, depth, depthMips_, k);
        done("mips");
        computeBarrier(cmd);  // the GTAO pass reads the chain
    }
    recordGtao(c, cmd, {depth, normal, rawVisibility_, rawBent_, depthMips_}, k, 2, bentNormals_, packedNormals_);
    done("gtao");
    computeBarrier(cmd);  // the blur (or the upsampling) reads the grid
    const Buffer* low = &rawVisibility_;
    if (half_.blur.mode == ssao::BlurMode::Separable) {
        recordSeparableBilateral(
            c, cmd, {depth, normal, blurWeights_, rawVisibility_, scratch_, filtered_, packedNormals_}, blur_,
            blurDispatch_);
        low = &filtered_;
    } else if (half_.blur.mode == ssao::BlurMode::TwoD) {
        recordBilateral2D(c, cmd, {depth, normal, blurWeights_, rawVisibility_, filtered_, packedNormals_},
                          blur_.constants);
        low = &filtered_;
    }
    if (low != &rawVisibility_) {
        done("blur");
        computeBarrier(cmd);  // the upsampling reads the blurred grid
    }
    const UpsampleConstants up = upsampleConstants(width_, height_, gridWidth_, gridHeight_, width_, 2, half_.depthSigma);
    recordUpsample(c, cmd, {*low, depth, depth, visibility_, normal}, up, 1);
    if (bentNormals_) recordUpsample(c, cmd, {rawBent_, depth, depth, bentView_, normal, packedNormals_}, up, 3);
    done("upsample");
}

std::size_t GtaoHalfResolutionPasses::bytesPerFrame() const {
    const std::size_t f = sizeof(float);
    const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
    const std::size_t grid = std::size_t(gridWidth_) * std::size_t(gridHeight_);
    const std::size_t b = bentNormals_ ? 3 : 0;  // floats of a bent normal
    const std::size_t n = packedNormals_ ? 1 : 3;  // words of an input normal
    // GTAO: the search reads the whole depth plane, the normals of the grid pixels; writes 1 + b per grid pixel.
    std::size_t bytes = f * (pixels + n * grid + (1 + b) * grid);
    const std::size_t chain = gtaoDepthMipsFloats(width_, height_, ssao::gtaoDepthMipLevels(settings_));
    if (chain > 0) bytes += f * (pixels + 2 * chain);
    // Blur: each pass reads the grid's guide depth (and normals) and values, writes values; 2-D: one pass.
    const std::size_t guide = half_.blur.usesNormals() ? 1 + n : 1;
    const std::size_t blurPasses = half_.blur.mode == ssao::BlurMode::Separable ? blurDispatchCount(blurDispatch_)
                                   : half_.blur.mode == ssao::BlurMode::TwoD   ? 1
                                                                               : 0;
    bytes += f * blurPasses * grid * (guide + 1 + 1);
    // Upsampling: the grid's values and guide depth, the full depth in, the full values out; per channel set.
    bytes += f * ((1 + 1) * grid + 2 * pixels);
    if (b > 0) bytes += f * ((b + 1) * grid + (1 + b) * pixels);
    return bytes;
}

// ---- the public API: upload, one submission, download ----

ssao::GtaoResult computeGtaoHalfResolution(Context& context, const GBuffer& g, const ssao::GtaoSettings& settings,
                                          const ssao::GtaoHalfResolutionSettings& half, int frameIndex,
                                          GtaoOutputs outputs) {
    settings.validate();
    half.validate();
    ssao::checkGtaoBuffers(g, ssao::gtaoConstants(settings, g.camera, frameIndex));  // the CPU's check and message
    const bool bent = outputs == GtaoOutputs::VisibilityAndBentNormal;
    ssao::GtaoResult r;
    r.visibility = Image(g.width(), g.height(), 1, 1.0f);
    if (bent) r.bentNormal = Image(g.width(), g.height(), 3, 0.0f);
    if (g.width() < 1 || g.height() < 1) return r;  // no buffer of 0 bytes
    Context::Impl& c = context.impl();
    const Buffer depth = uploadChannels(c, g.depth, 1);
    const Buffer normal = uploadChannels(c, g.normal, 3);
    GtaoHalfResolutionPasses passes(c, settings, half, g.width(), g.height(), bent);
    c.submit([&](VkCommandBuffer cmd) { passes.record(cmd, depth, normal, g.camera, frameIndex); }, true);
    download(c, passes.visibility(), r.visibility.pixels.data(), r.visibility.pixels.size() * sizeof(float));
    if (bent) download(c, passes.bentNormal(), r.bentNormal.pixels.data(), r.bentNormal.pixels.size() * sizeof(float));
    return r;
}

} // namespace obscura::gpu
