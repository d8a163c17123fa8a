// Vulkan compute: a headless context and the screen-space passes of src/ssao as compute shaders.
//
// Context: Vulkan >= 1.2, no surface, one compute queue. The device is the one at
// ContextSettings::deviceIndex, else the index in the environment variable OBSCURA_GPU_DEVICE, else the
// first discrete GPU, else the first device the loader lists. Validation (VK_LAYER_KHRONOS_validation with
// synchronization validation) is on when ContextSettings::validation is set or OBSCURA_VALIDATION=1; then
// every warning and error message the layer sends is recorded (validationMessages()), so tests can fail on
// any of them.
//
// The passes take the same settings and G-buffers as their CPU references and run the same constants
// function (ssao::alchemyConstants); the kernels differ only in floating-point rounding. Shaders are SPIR-V
// compiled at build time and embedded in the library.
//
// Errors: everything throws obscura::Error with a message naming the device and the problem: no Vulkan
// loader or driver, no device (or none at the index asked for), a device below Vulkan 1.2, validation asked
// for but not installed, device lost, out of device or host memory; and the CPU references' errors for bad
// settings or buffers. The Vulkan library is loaded when the first Context is made, so a program that makes
// none runs without it; it is libvulkan.so.1, or the file OBSCURA_VULKAN_LIBRARY names (a loader carried to a
// machine that lacks one). A request larger than the device's memory heap fails before the driver sees it.
#pragma once

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"
#include "obscura/gbuffer.h"
#include "obscura/gtao.h"
#include "obscura/gtao_half_res.h"
#include "obscura/image.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace obscura::gpu {

struct ContextSettings {
    // Physical device index in the loader's order: [0, deviceCount()); -1 = OBSCURA_GPU_DEVICE, else the
    // first discrete GPU, else device 0.
    int deviceIndex = -1;
    std::string deviceIndexName = "ContextSettings::deviceIndex";  // how errors name it (a CLI: its flag)
    bool validation = false;  // also on when the environment has OBSCURA_VALIDATION=1
    // Keep what the driver says of each compute pipeline it compiles (VK_KHR_pipeline_executable_properties):
    // statistics such as registers per invocation, and with pipelineInternals its internal representations
    // (the driver's intermediate or machine code, as text where it gives text). Where the driver lacks the
    // extension the context works as without them and DeviceInfo::pipelineStatistics says so. Off by default:
    // a driver may compile more slowly or skip its pipeline cache while capturing.
    bool pipelineStatistics = false;
    bool pipelineInternals = false;  // implies pipelineStatistics
};

struct DeviceInfo {
    std::string name;               // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    int index = 0;                  // in the loader's order
    bool discrete = false;
    std::uint32_t apiVersion = 0;   // VK_MAKE_API_VERSION encoding
    std::string driver;             // the driver's name and version, e.g. "llvmpipe Mesa 22.3.6"
    double timestampPeriodNs = 0;   // ns per timestamp tick; 0 when the compute queue has no timestamps
    bool pipelineStatistics = false;  // the context captures pipeline statistics (asked for, and offered)
    std::uint32_t maxImageDimension2D = 0;  // texels a side of the largest 2-D texture (an environment map)
};

// What the driver says of one compiled pipeline (Context::pipelineReports). A compute pipeline usually has
// one executable; the names of executables and statistics are the driver's own, e.g. "Register Count".
struct PipelineStatistic {
    std::string name, description;
    double value = 0;  // booleans as 0 or 1
};
struct PipelineInternal {
    std::string name, description;
    bool text = false;  // data is text (else raw bytes)
    std::string data;
};
struct PipelineExecutable {
    std::string name, description;
    std::uint32_t subgroupSize = 0;  // the subgroup (warp, wave) size it runs with
    std::vector<PipelineStatistic> statistics;
    std::vector<PipelineInternal> internals;  // with ContextSettings::pipelineInternals
};
struct PipelineReport {
    std::string pipeline;  // the shader's name, with its specialization constants as name<a,b>
    std::vector<PipelineExecutable> executables;
    std::string error;  // the driver refused a query: what and why (the executables are then missing)
};

// Number of Vulkan devices; 0 when there is no loader, no driver or no device. Never throws.
int deviceCount();

// Use a Context from one thread at a time; each pass waits for the GPU before it returns.
class Context {
public:
    explicit Context(const ContextSettings& settings = {});
    ~Context();
    Context(Context&&) noexcept;
    Context& operator=(Context&&) noexcept;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& device() const;
    bool validation() const;
    // Every validation message so far ("severity: id: text"), oldest first; empty without validation.
    std::vector<std::string> validationMessages() const;
    // GPU time of the last pass's dispatches, from timestamp queries, ms; -1 when timestamps are missing. A
    // call that submits nothing (a blur of BlurMode::None, an empty G-buffer) leaves the previous value.
    double lastPassMs() const;
    // Every pipeline the context has made so far, by name, with what the driver said of it; empty unless
    // device().pipelineStatistics.
    std::vector<PipelineReport> pipelineReports() const;

    struct Impl;  // src/gpu/context.h
    Impl& impl() { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

// How the Alchemy passes take the G-buffer's normals, as an engine may keep them (docs/INTEGRATION.md).
struct AlchemyFormats {
    // Uploaded as one octahedral word per pixel (two snorm16, ssao::packOctahedral) instead of 3 floats: the
    // obscurance of the words' decoded normals (within 1e-4 of the floats). Not with normalsFromDepth, whose
    // normals the GPU rebuilds as floats (obscura::Error).
    bool packedNormals = false;
};

// ssao::alchemyAO on the GPU: the same settings, validation, errors and output (raw obscurance, guard band
// cropped, sky 1); equal to ssao::alchemyPixel to within GPU rounding (tests/gpu bound the difference).
// Normals rebuilt from depth (settings.normalsFromDepth) come from the GPU mirror of ssao::normalsFromDepth.
Image alchemyAO(Context& context, const GBuffer& gbuffer, const ssao::AlchemySettings& settings,
                AlchemyFormats formats = {});

// bilateralFilter(alchemyAO(gbuffer, settings), the guard band's inner G-buffer, blur) in two dispatches
// instead of three: the estimator evaluates rows of pixels into shared memory and blurs them there, so its raw
// AO never goes through memory (src/gpu/shaders/alchemy_blur_row.comp). The blur must be BlurMode::Separable
// without the normal weight (obscura::Error otherwise). The same bits as the three dispatches where the device
// rounds both alike (lavapipe); `obscura bench --gpu` times both (cases alchemy and alchemy-fused).
Image alchemyAOBlurred(Context& context, const GBuffer& gbuffer, const ssao::AlchemySettings& settings,
                       const ssao::BilateralSettings& blur, AlchemyFormats formats = {});

// ssao::bilateralFilter on the GPU: BlurMode::Separable as two 1-D passes, BlurMode::TwoD as one square pass
// (src/gpu/bilateral_2d_pass.cpp), BlurMode::None returns a copy; the same settings, validation and errors;
// equal to the CPU filter to within 2e-3 (tests/gpu measure it).
Image bilateralFilter(Context& context, const Image& ao, const GBuffer& gbuffer,
                      const ssao::BilateralSettings& settings);
// The same with BlurMode::Separable's two passes in one dispatch (src/gpu/shaders/bilateral_tiled.comp: rows,
// then columns, of each 32x32 tile from shared memory): the same bits where the device rounds both alike
// (lavapipe). Throws obscura::Error, besides bilateralFilter's errors, for another mode or a radius above
// kTiledBlurMaxRadius (the tile's apron).
inline constexpr int kTiledBlurMaxRadius = 8;
Image bilateralFilterTiled(Context& context, const Image& ao, const GBuffer& gbuffer,
                           const ssao::BilateralSettings& settings);

// ssao::computeGtao on the GPU (src/gpu/shaders/gtao.comp mirrors ssao::gtaoPixel): the same constants or
// settings, validation, errors and output (visibility, sky 1; view-space bent normals, sky 0). Every option
// of the constants is supported; the result differs from the CPU's by the GPU's sin, cos, acos, atan and
// pow (tests/gpu bound it).
//
// GtaoOutputs::Visibility is the AO-only pass (kGtaoSpecBentNormal 0): the same visibility bit for bit, without
// the bent normal's arithmetic and its 12 bytes per pixel; the result's bentNormal is then empty. For a caller
// that shades with visibility alone, as XeGTAO's default does.
enum class GtaoOutputs { VisibilityAndBentNormal, Visibility };
ssao::GtaoResult computeGtao(Context& context, const GBuffer& gbuffer, const ssao::GtaoConstants& constants,
                             GtaoOutputs outputs = GtaoOutputs::VisibilityAndBentNormal);
// Validates the settings, then computeGtao(context, gbuffer, ssao::gtaoConstants(settings, gbuffer.camera)).
ssao::GtaoResult computeGtao(Context& context, const GBuffer& gbuffer, const ssao::GtaoSettings& settings,
                             GtaoOutputs outputs = GtaoOutputs::VisibilityAndBentNormal);

// ssao::computeGtaoHalfResolution on the GPU: gtao.comp over the half-resolution grid, the blur reading its
// guide from the full-resolution planes at a stride (BilateralConstants::guideStep 2), and
// upsample_depth_aware.comp; the same settings, validation, errors and outputs, within the GPU's rounding
// (tests/gpu bound it). GtaoOutputs::Visibility leaves the result's bentNormal empty.
ssao::GtaoResult computeGtaoHalfResolution(Context& context, const GBuffer& gbuffer, const ssao::GtaoSettings& settings,
                                          const ssao::GtaoHalfResolutionSettings& half, int frameIndex = 0,
                                          GtaoOutputs outputs = GtaoOutputs::VisibilityAndBentNormal);

} // namespace obscura::gpu
