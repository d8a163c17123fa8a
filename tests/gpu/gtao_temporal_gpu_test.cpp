// Spatio-temporal GTAO (Jimenez et al. 2016, §4.1) as compute passes (obscura/gpu_temporal.h) against the
// CPU reference ssao::GtaoTemporal and its filters, on lavapipe in CI, with validation on and no message
// allowed.
#include "gpu_test_util.h"
#include "gtao_difference.h"
#include "spirv_edit.h"
#include "ssao/gtao_scenes.h"

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/gtao_temporal_pass.h"
#include "gpu/image_planes.h"
#include "gpu/spirv.h"

#include "obscura/error.h"
#include "obscura/gpu_temporal.h"
#include "obscura/gtao_temporal.h"
#include "obscura/history_packing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

namespace obscura::gpu {
namespace {

using testing::GtaoDifference;
using testing::kBentBound;
using testing::kVisibilityBound;
using testing::pixelDifference;

struct Difference : GtaoDifference {
    int length = 0;  // pixels whose history length differs
};

// Max |a - b| over all pixels and channels; the sizes must agree.
double maxDifference(const Image& a, const Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    if (a.pixels.size() != b.pixels.size()) return 1e30;
    double d = 0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) d = std::max(d, pixelDifference(a, b, i));
    return d;
}

// The CLI's camera path (tools/obscura/gtao_cli.cpp): frame k turns the camera by k / 2 degrees about the
// vertical through its target.
Camera pathCamera(const Camera& base, int k) { return turnedAboutTarget(base, 0.5f * kPi / 180.0f * float(k)); }

// The G-buffers of `frames` frames of a built-in scene along the path, w x h.
std::vector<GBuffer> path(const std::string& scene, int w, int h, int frames) {
    BuiltinScene s = makeBuiltinScene(scene);
    s.camera.width = w;
    s.camera.height = h;
    trace::Tracer tracer(s.scene);
    std::vector<GBuffer> out;
    for (int k = 0; k < frames; ++k) out.push_back(trace::renderGBuffer(tracer, pathCamera(s.camera, k)));
    return out;
}

ssao::GtaoSettings preset(ssao::GtaoQuality quality) {
    ssao::GtaoSettings s;
    ssao::applyQuality(s, quality);
    return s;
}

// Pixels allowed beyond the bounds in a frame, and with a history length that differs. Each accumulation
// step has three comparisons whose outcome rounding can flip where a reprojected tap sits on the edge of
// a test: the depth rejection, the normal rejection and the quarter-footprint threshold; and the
// reconstruction's and upsampling's weights pass the GPU's exp. Lavapipe (measured 2026-11-25, Mesa
// llvmpipe, LLVM 15.0.6): no pixel beyond either bound and no history length that differs, in any frame of
// the runs below (worst visibility 9.3e-5, worst bent-normal component 2.9e-3, on demo), so the tests allow
// it none. Other devices: 0.1% of the pixels.
int allowedBeyond(const Context& context, int pixels, int lavapipe) {
    return context.device().name.rfind("llvmpipe", 0) == 0 ? lavapipe : std::max(lavapipe, pixels / 1000);
}

struct Run {
    const char* scene;
    int width, height;
    ssao::GtaoQuality quality;
    ssao::GtaoSampling sampling = ssao::GtaoSampling::Planar;
};

// Runs the frames through both implementations, compares every frame (visibility, bent normals, history
// length) and prints the worst.
void expectMatch(Context& context, const Run& run, const ssao::GtaoTemporalSettings& t, int frames,
                 int allowedLavapipe, const std::string& mode) {
    const std::vector<GBuffer> gbuffers = path(run.scene, run.width, run.height, frames);
    ssao::GtaoSettings settings = preset(run.quality);
    settings.sampling = run.sampling;
    ssao::GtaoTemporal cpu(settings, t);
    GtaoTemporal gpu(context, settings, t);
    Difference worst;
    Image lastVisibility;
    const int pixels = run.width * run.height;
    const std::string name = std::string(run.scene) + " " + ssao::qualityName(run.quality) +
                             (run.sampling == ssao::GtaoSampling::Planar
                                  ? std::string(" ")
                                  : " " + std::string(ssao::gtaoSamplingName(run.sampling)) + " ") +
                             mode;
    for (int f = 0; f < frames; ++f) {
        const ssao::GtaoResult& c = cpu.frame(gbuffers[std::size_t(f)]);
        const ssao::GtaoResult& g = gpu.frame(gbuffers[std::size_t(f)]);
        ASSERT_EQ(g.visibility.pixels.size(), c.visibility.pixels.size()) << name;
        ASSERT_EQ(g.bentNormal.pixels.size(), c.bentNormal.pixels.size()) << name;
        Difference d{testing::compareGtao(g, c)};
        const Image gpuLength = gpu.historyLength();
        const Image& cpuLength = cpu.historyLength();
        ASSERT_EQ(gpuLength.pixels.size(), cpuLength.pixels.size()) << name;
        for (std::size_t i = 0; i < cpuLength.pixels.size(); ++i)
            d.length += gpuLength.pixels[i] != cpuLength.pixels[i];
        EXPECT_LE(d.visibilityRest, kVisibilityBound) << name << " frame " << f;
        EXPECT_LE(d.bentRest, kBentBound) << name << " frame " << f;
        EXPECT_LE(d.beyond, allowedBeyond(context, pixels, allowedLavapipe)) << name << " frame " << f;
        EXPECT_LE(d.length, allowedBeyond(context, pixels, allowedLavapipe)) << name << " frame " << f;
        worst.visibility = std::max(worst.visibility, d.visibility);
        worst.bent = std::max(worst.bent, d.bent);
        worst.visibilityRest = std::max(worst.visibilityRest, d.visibilityRest);
        worst.bentRest = std::max(worst.bentRest, d.bentRest);
        worst.beyond = std::max(worst.beyond, d.beyond);
        worst.length = std::max(worst.length, d.length);
        lastVisibility = c.visibility;
    }
    EXPECT_EQ(gpu.framesRendered(), cpu.framesRendered());
    // Not vacuous: occluded pixels, and with history, pixels that kept it through every frame.
    // The history length is per element of the history's lattice (the grid's with gridHistory).
    int occluded = 0, accumulated = 0;
    for (float v : lastVisibility.pixels) occluded += v < 0.99f;
    for (float l : cpu.historyLength().pixels) accumulated += l == float(frames);
    EXPECT_GT(occluded, pixels / 50) << name;
    if (t.temporal) {
        EXPECT_GT(accumulated, int(cpu.historyLength().pixelCount() / 4)) << name;
    }
    std::printf("[ measured ] %s %dx%d, %d frames: visibility max %.3g (%.3g within bounds), bent max %.3g (%.3g), "
                "at most %d px beyond and %d px of other history length per frame; %d px occluded, %d px with %d "
                "frames of history; %.3f ms on the GPU\n",
                name.c_str(), run.width, run.height, frames, worst.visibility, worst.visibilityRest, worst.bent,
                worst.bentRest, worst.beyond, worst.length, occluded, accumulated, frames, context.lastPassMs());
}

ssao::GtaoTemporalSettings mode(bool temporal, bool half, bool gridHistory = false) {
    ssao::GtaoTemporalSettings t;
    t.temporal = temporal;
    t.halfResolution = half;
    t.gridHistory = gridHistory;
    return t;
}

// The side-by-side tests' input: 4 frames of the demo path at an odd size, the medium preset.
struct DemoPath {
    static constexpr int w = 97, h = 61;
    std::vector<GBuffer> gbuffers = path("demo", w, h, 4);
    ssao::GtaoSettings settings = preset(ssao::GtaoQuality::Medium);
    std::size_t pixels = std::size_t(w) * std::size_t(h);
};

// Records the frames through two pass objects, both in one submission per frame, and calls compare(f) once
// frame f has run. Every frame's depth stays uploaded and each frame is given the previous one's, which a
// pass object with callerKeepsDepth reads (the others ignore it).
void recordSideBySide(Context::Impl& c, GtaoTemporalPasses& a, GtaoTemporalPasses& b,
                      const std::vector<GBuffer>& gbuffers, const std::function<void(std::size_t)>& compare) {
    std::vector<Buffer> depth;
    for (std::size_t f = 0; f < gbuffers.size(); ++f) {
        depth.push_back(uploadChannels(c, gbuffers[f].depth, 1));
        const Buffer normal = uploadChannels(c, gbuffers[f].normal, 3);
        const GtaoTemporalFrameInputs in{depth[f], normal, gbuffers[f].camera, int(f), f > 0 ? &depth[f - 1] : nullptr};
        c.submit([&](VkCommandBuffer cmd) {
            a.record(cmd, in);
            b.record(cmd, in);
        });
        compare(f);
    }
}

} // namespace

// The reconstruction and the upsampling alone, on the CPU's own raw interleaved GTAO (so both get the same
// input bits): 1 and 3 channels, an even and an odd size. Measured on lavapipe (2026-11-25), max over
// channels: at most 3.6e-7 (reconstruction) and 2.4e-7 (upsampling); the filters differ only by the GPU's exp.
TEST(GpuGtaoTemporal, FiltersMatchTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    for (const auto& [scene, w, h] : {std::tuple{"demo", 333, 197}, std::tuple{"stairs", 96, 64}}) {
        const GBuffer g = testing::render(scene, w, h);
        const ssao::GtaoResult raw =
            ssao::computeGtao(g, ssao::gtaoConstants(preset(ssao::GtaoQuality::Low), g.camera, 2, true));
        const float sigma = ssao::GtaoTemporalSettings{}.depthSigma;
        const double visibility =
            maxDifference(reconstructInterleaved(context, raw.visibility, g.depth, g.normal, sigma),
                          ssao::reconstructInterleaved(raw.visibility, g.depth, g.normal, sigma));
        const double bent = maxDifference(reconstructInterleaved(context, raw.bentNormal, g.depth, g.normal, sigma),
                                          ssao::reconstructInterleaved(raw.bentNormal, g.depth, g.normal, sigma));

        // A half-resolution grid as the CPU frame makes it: pixel (x, y) from (2x, 2y).
        const int gw = (w + 1) / 2, gh = (h + 1) / 2;
        Image lowVisibility(gw, gh, 1), lowBent(gw, gh, 3), lowDepth(gw, gh, 1);
        for (int y = 0; y < gh; ++y)
            for (int x = 0; x < gw; ++x) {
                lowVisibility.at(x, y) = raw.visibility.at(2 * x, 2 * y);
                for (int c = 0; c < 3; ++c) lowBent.at(x, y, c) = raw.bentNormal.at(2 * x, 2 * y, c);
                lowDepth.at(x, y) = g.depth.at(2 * x, 2 * y);
            }
        const double upVisibility = maxDifference(upsampleDepthAware(context, lowVisibility, lowDepth, g, sigma),
                                                  ssao::upsampleDepthAware(lowVisibility, lowDepth, g, sigma));
        const double upBent = maxDifference(upsampleDepthAware(context, lowBent, lowDepth, g, sigma),
                                            ssao::upsampleDepthAware(lowBent, lowDepth, g, sigma));
        std::printf("[ measured ] %s %dx%d: reconstruction %.3g / %.3g, upsampling %.3g / %.3g (visibility / bent)\n",
                    scene, w, h, visibility, bent, upVisibility, upBent);
        EXPECT_LE(visibility, kVisibilityBound) << scene;
        EXPECT_LE(bent, kBentBound) << scene;
        EXPECT_LE(upVisibility, kVisibilityBound) << scene;
        EXPECT_LE(upBent, kBentBound) << scene;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// Spatial only (no history): the interleaved GTAO pass, the reconstruction and, at half resolution, the
// upsampling. Two frames along the path, so the second shows that nothing of the first is kept.
TEST(GpuGtaoTemporal, SpatialOnlyMatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    for (bool half : {false, true}) {
        const std::string m = half ? "spatial, half resolution" : "spatial";
        expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::High}, mode(false, half), 2, 0, m);
        expectMatch(context, {"well", 96, 64, ssao::GtaoQuality::Low}, mode(false, half), 2, 0, m);
        expectMatch(context, {"stairs", 96, 64, ssao::GtaoQuality::Medium}, mode(false, half), 2, 0, m);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// Accumulation over 5 frames of a camera turning 0.5 degree per frame about its target: reprojection,
// rejection, the running mean and the world-space bent normals.
TEST(GpuGtaoTemporal, TemporalMatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    for (bool half : {false, true}) {
        const std::string m = half ? "temporal, half resolution" : "temporal";
        expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::Medium}, mode(true, half), 5, 0, m);
        expectMatch(context, {"well", 96, 64, ssao::GtaoQuality::Low}, mode(true, half), 5, 0, m);
        expectMatch(context, {"stairs", 96, 64, ssao::GtaoQuality::High}, mode(true, half), 5, 0, m);
        expectMatch(context, {"corner", 96, 64, ssao::GtaoQuality::Low}, mode(true, half), 5, 0, m);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// Mip sampling (GtaoSampling::Mip and PlanarMip): each frame makes the depth MIP chain of its own depth
// before the GTAO pass, at both resolutions (the chain is of the full-resolution depth either way).
TEST(GpuGtaoTemporal, MipSamplingMatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    for (bool half : {false, true}) {
        const std::string m = half ? "temporal, half resolution" : "temporal";
        expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::High, ssao::GtaoSampling::Mip}, mode(true, half),
                    3, 0, m);
        expectMatch(context, {"stairs", 96, 64, ssao::GtaoQuality::Medium, ssao::GtaoSampling::PlanarMip},
                    mode(true, half), 3, 0, m);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The packed history (GtaoTemporalSettings::packedHistory): both sides decode the same words, so the bounds
// and counts are those of the float history. Also at half resolution, and without bent normals.
TEST(GpuGtaoTemporal, PackedHistoryMatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    for (bool half : {false, true}) {
        ssao::GtaoTemporalSettings t = mode(true, half);
        t.packedHistory = true;
        const std::string m = half ? "temporal, packed history, half resolution" : "temporal, packed history";
        expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::Medium}, t, 5, 0, m);
        expectMatch(context, {"stairs", 96, 64, ssao::GtaoQuality::High}, t, 5, 0, m);
        expectMatch(context, {"corner", 96, 64, ssao::GtaoQuality::Low}, t, 5, 0, m);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The grid's history (GtaoTemporalSettings::gridHistory, kTemporalSpecHistoryStep 2): the accumulation
// reconstructs and accumulates each grid pixel, and the upsampling (with kUpsampleSpecPackedLow when packed)
// brings the result to full resolution. With and without history, floats and packed words.
TEST(GpuGtaoTemporal, GridHistoryMatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::High}, mode(false, true, true), 2, 0,
                "spatial, grid history");
    for (bool packed : {false, true}) {
        ssao::GtaoTemporalSettings t = mode(true, true, true);
        t.packedHistory = packed;
        const std::string m = packed ? "temporal, packed grid history" : "temporal, grid history";
        expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::Medium}, t, 5, 0, m);
        expectMatch(context, {"well", 96, 64, ssao::GtaoQuality::Low}, t, 5, 0, m);
        expectMatch(context, {"stairs", 97, 63, ssao::GtaoQuality::High}, t, 5, 0, m);
        expectMatch(context, {"corner", 96, 64, ssao::GtaoQuality::Low, ssao::GtaoSampling::PlanarMip}, t, 3, 0, m);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The alternating 4x4 and 2x2 windows (GtaoTemporalSettings::alternatingWindow, alternatingWindowSize, one
// pipeline per phase): where the accumulation reconstructs (full resolution, the grid's history) and in the
// reconstruction's own pass (half resolution with the history at full resolution). 5 frames, so that every
// phase runs and one twice.
TEST(GpuGtaoTemporal, AlternatingWindowMatchesTheCpuReference) {
    OBSCURA_GPU_CONTEXT(context);
    for (const int size : {4, 2})
        for (const auto& [half, grid] : {std::pair{false, false}, std::pair{true, false}, std::pair{true, true}}) {
            ssao::GtaoTemporalSettings t = mode(true, half, grid);
            t.alternatingWindow = true;
            t.alternatingWindowSize = size;
            t.packedHistory = grid;
            const std::string m = "temporal, alternating " + std::to_string(size) + "x" + std::to_string(size) +
                                  " windows" + (grid ? ", packed grid history" : half ? ", half resolution" : "");
            expectMatch(context, {"demo", 333, 197, ssao::GtaoQuality::Medium}, t, 5, 0, m);
            expectMatch(context, {"stairs", 97, 63, ssao::GtaoQuality::High}, t, 5, 0, m);
        }
    // The filter alone, each phase, on the CPU's own raw values (both get the same input bits).
    const GBuffer g = testing::render("demo", 133, 77);
    const ssao::GtaoResult raw =
        ssao::computeGtao(g, ssao::gtaoConstants(preset(ssao::GtaoQuality::Low), g.camera, 2, true));
    for (int phase = 0; phase < 8; ++phase) {
        const double d = maxDifference(reconstructInterleaved(context, raw.visibility, g.depth, g.normal, 0.05f, phase),
                                       ssao::reconstructInterleaved(raw.visibility, g.depth, g.normal, 0.05f, phase));
        EXPECT_LE(d, kVisibilityBound) << phase;
    }
    EXPECT_THROW(reconstructInterleaved(context, raw.visibility, g.depth, g.normal, 0.05f, 8), Error);
    // The passes validate the window's size, which the phase would otherwise take for 4.
    ssao::GtaoTemporalSettings three = mode(true, true, true);
    three.alternatingWindow = true;
    three.alternatingWindowSize = 3;
    EXPECT_THROW(GtaoTemporalPasses(context.impl(), preset(ssao::GtaoQuality::Low), three, 16, 8), Error);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The benchmark's path: frames recorded back to back on resident buffers in one submission (the barrier at
// the start of each frame orders them), with a mark after each stage, give the bits of GtaoTemporal's
// frame-per-submission path. Also with mip sampling, whose chain each frame rewrites after the previous
// frame's GTAO pass read it.
TEST(GpuGtaoTemporal, RecordsFramesOnResidentBuffers) {
    OBSCURA_GPU_CONTEXT(context);
    const std::vector<GBuffer> gbuffers = path("stairs", 96, 64, 3);
    using ssao::GtaoSampling;
    struct Case {
        GtaoSampling sampling;
        bool half, grid;
        int window = 0;  // alternating windows of this side, a pipeline per phase in one submission; 0: none
    };
    for (const auto& [sampling, half, grid, window] :
         {Case{GtaoSampling::Planar, false, false}, Case{GtaoSampling::Planar, true, false},
          Case{GtaoSampling::Mip, false, false}, Case{GtaoSampling::Mip, true, false},
          Case{GtaoSampling::Planar, true, true}, Case{GtaoSampling::Mip, true, true},
          Case{GtaoSampling::Planar, false, false, 4}, Case{GtaoSampling::Planar, true, false, 4},
          Case{GtaoSampling::Planar, true, true, 4}, Case{GtaoSampling::Planar, true, true, 2}}) {
        ssao::GtaoSettings settings = preset(ssao::GtaoQuality::Low);
        settings.sampling = sampling;
        Context::Impl& c = context.impl();
        ssao::GtaoTemporalSettings t = mode(true, half, grid);
        t.alternatingWindow = window > 0;
        t.alternatingWindowSize = window == 2 ? 2 : 4;
        GtaoTemporalPasses passes(c, settings, t, 96, 64);
        std::vector<Buffer> depth, normal;
        for (const GBuffer& g : gbuffers) {
            depth.push_back(uploadChannels(c, g.depth, 1));
            normal.push_back(uploadChannels(c, g.normal, 3));
        }
        std::string stages;
        c.submit([&](VkCommandBuffer cmd) {
            for (std::size_t f = 0; f < gbuffers.size(); ++f)
                passes.record(cmd, {depth[f], normal[f], gbuffers[f].camera, int(f)},
                              [&](const char* stage) { stages += std::string(stage) + " "; });
        });
        // At full resolution the accumulation reconstructs its own pixel; at half it upsamples its own pixel,
        // and with the grid's history it reconstructs its grid pixel and the upsampling follows.
        const std::string frame = std::string(sampling == GtaoSampling::Mip ? "mips " : "") +
                                  (grid ? "gtao temporal upsample " : half ? "gtao denoise temporal " : "gtao temporal ");
        EXPECT_EQ(stages, frame + frame + frame);
        EXPECT_EQ(passes.framesRecorded(), 3);
        ssao::GtaoResult r{Image(96, 64, 1), Image(96, 64, 3)};
        download(c, passes.visibility(), r.visibility.pixels.data(), r.visibility.pixels.size() * sizeof(float));
        download(c, passes.bentNormal(), r.bentNormal.pixels.data(), r.bentNormal.pixels.size() * sizeof(float));
        GtaoTemporal reference(context, settings, t);
        ssao::GtaoResult expected;
        for (const GBuffer& g : gbuffers) expected = reference.frame(g);
        EXPECT_EQ(r.visibility.pixels, expected.visibility.pixels);
        EXPECT_EQ(r.bentNormal.pixels, expected.bentNormal.pixels);
        // Not trivial: more than 20 floats per pixel, or 10 with the grid's history (a quarter of the history).
        EXPECT_GT(passes.bytesPerFrame(), std::size_t(96 * 64 * 4 * (grid ? 10 : 20)));
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The spatial mode writes the history planes and reads none (temporal_pixel.glsl returns before its loads): its
// frame moves the temporal one's bytes less the history's 9 floats (depth, world normal, visibility, world bent
// normal, length) per element of the lattice. bench --gpu counted them for gtao-spatial too (148 B a pixel at
// full resolution for 112).
TEST(GpuGtaoTemporal, TheSpatialModeIsNotChargedForHistoryReads) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const int w = 37, h = 23;
    const ssao::GtaoSettings settings = preset(ssao::GtaoQuality::Medium);
    for (const auto& [half, grid] : {std::pair{false, false}, std::pair{true, false}, std::pair{true, true}}) {
        const GtaoTemporalPasses spatial(c, settings, mode(false, half, grid), w, h);
        const GtaoTemporalPasses temporal(c, settings, mode(true, half, grid), w, h);
        const std::size_t lattice = grid ? std::size_t((w + 1) / 2) * std::size_t((h + 1) / 2) : std::size_t(w) * std::size_t(h);
        EXPECT_EQ(temporal.bytesPerFrame() - spatial.bytesPerFrame(), 9 * sizeof(float) * lattice)
            << "half " << half << " grid " << grid;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// Packed normals (GtaoTemporalVariant::packedNormals, one octahedral word per pixel): the frame is, bit for
// bit, the frame of the words' decoded normals (unpackNormals) read as floats, in each mode, with bent normals
// and with the alternating windows, over 4 frames of the path; so it is the CPU reference's frame of those
// normals to the bounds the tests above hold the float path to. The decoded normals are within 1e-4 of the
// G-buffer's, and each normal read moves 2 words fewer.
TEST(GpuGtaoTemporal, PackedNormalsGiveTheFrameOfTheirDecodedNormals) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const DemoPath in;
    const auto& [gbuffers, settings, pixels] = in;
    const int w = DemoPath::w, h = DemoPath::h;
    for (const auto& [half, grid, window] : {std::tuple{false, false, 0}, std::tuple{true, false, 4},
                                             std::tuple{true, true, 2}}) {
        ssao::GtaoTemporalSettings t = mode(true, half, grid);
        t.alternatingWindow = window > 0;
        t.alternatingWindowSize = window == 2 ? 2 : 4;
        GtaoTemporalPasses floats(c, settings, t, w, h);
        GtaoTemporalPasses words(c, settings, t, w, h, {.packedNormals = true});
        int differing = 0;
        double normalError = 0;
        for (std::size_t f = 0; f < gbuffers.size(); ++f) {
            const GBuffer& g = gbuffers[f];
            const std::vector<std::uint32_t> packed = packNormals(g.normal);
            const Image decoded = unpackNormals(packed, w, h);
            for (std::size_t i = 0; i < pixels; ++i)
                if (g.depth.pixels[i] < 1e30f)
                    for (int k = 0; k < 3; ++k)
                        normalError = std::max(normalError, double(std::fabs(decoded.pixels[3 * i + k] -
                                                                             g.normal.pixels[3 * i + k])));
            const Buffer depth = uploadChannels(c, g.depth, 1);
            const Buffer wordPlane = upload(c, packed.data(), packed.size() * sizeof(std::uint32_t));
            const Buffer floatPlane = uploadChannels(c, decoded, 3);
            c.submit([&](VkCommandBuffer cmd) {
                floats.record(cmd, {depth, floatPlane, g.camera, int(f)});
                words.record(cmd, {depth, wordPlane, g.camera, int(f)});
            });
            for (const auto& [a, b, count] :
                 {std::tuple{&floats.visibility(), &words.visibility(), pixels},
                  std::tuple{&floats.bentNormal(), &words.bentNormal(), 3 * pixels}}) {
                const std::vector<std::uint32_t> va = downloadWords(c, *a, count), vb = downloadWords(c, *b, count);
                for (std::size_t i = 0; i < count; ++i) differing += va[i] != vb[i];
            }
        }
        const std::string name = grid ? "grid history" : half ? "half resolution" : "full resolution";
        EXPECT_EQ(differing, 0) << name;
        EXPECT_LE(normalError, 1e-4) << name;
        EXPECT_GT(normalError, 0.0) << name;  // the words are not the floats: the test sees the decoding
        // 8 bytes fewer per normal read: the GTAO pass's per grid pixel, the reconstruction's pass's per grid
        // pixel and channel set (half resolution, history at full resolution), the accumulation's per element
        // of its lattice.
        const std::size_t gridPixels = std::size_t((w + 1) / 2) * std::size_t((h + 1) / 2);
        const std::size_t evaluated = half ? gridPixels : pixels;
        const std::size_t reads = evaluated + (half && !grid ? 2 * gridPixels : 0) + (grid ? gridPixels : pixels);
        EXPECT_EQ(floats.bytesPerFrame() - words.bytesPerFrame(), 8 * reads) << name;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The visibility as unorm16 pairs (GtaoTemporalVariant::packedOutput, with the grid's history): each pixel's
// half-word is the float frame's visibility rounded to 1/65535 (ssao::packUnorm16), at an odd width whose rows
// end in a half-filled word, over 4 frames of the path, with the float and the packed history (whose words the
// upsampling then decodes too); the output plane shrinks to (w + 1) / 2 words a row. Without the grid's
// history there is no upsampling to write it, and the passes refuse it.
TEST(GpuGtaoTemporal, PackedOutputIsTheVisibilityInSixteenBits) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const DemoPath in;
    const auto& [gbuffers, settings, pixels] = in;
    const int w = DemoPath::w, h = DemoPath::h;
    const std::size_t rowWords = std::size_t(upsamplePackedRowWords(w));
    for (const bool packedHistory : {false, true}) {
        ssao::GtaoTemporalSettings t = mode(true, true, true);
        t.packedHistory = packedHistory;
        GtaoTemporalPasses floats(c, settings, t, w, h, {.bentNormals = false});
        GtaoTemporalPasses words(c, settings, t, w, h, {.bentNormals = false, .packedOutput = true});
        int differing = 0, occluded = 0;
        recordSideBySide(c, floats, words, gbuffers, [&](std::size_t) {
            const std::vector<std::uint32_t> f = downloadWords(c, floats.visibility(), pixels);
            const std::vector<std::uint32_t> p = downloadWords(c, words.visibility(), rowWords * std::size_t(h));
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const float v = std::bit_cast<float>(f[std::size_t(y) * std::size_t(w) + std::size_t(x)]);
                    const std::uint32_t word = p[std::size_t(y) * rowWords + std::size_t(x / 2)];
                    differing += (x % 2 == 0 ? word & 0xffffu : word >> 16) != ssao::packUnorm16(v);
                    occluded += v < 0.99f;
                }
            // w is odd: each row's last word holds one pixel.
            for (int y = 0; y < h; ++y) differing += (p[std::size_t(y) * rowWords + rowWords - 1] >> 16) != 0;
        });
        EXPECT_EQ(differing, 0) << packedHistory;
        EXPECT_GT(occluded, int(pixels) / 50);
        // The same through the decoder.
        const std::size_t packedWords = rowWords * std::size_t(h);
        const Image decoded = unpackVisibilityPairs(downloadWords(c, words.visibility(), packedWords), w, h);
        const std::vector<std::uint32_t> f = downloadWords(c, floats.visibility(), pixels);
        double worst = 0;
        for (std::size_t i = 0; i < pixels; ++i)
            worst = std::max(worst, std::fabs(double(decoded.pixels[i]) - double(std::bit_cast<float>(f[i]))));
        EXPECT_LE(worst, 0.5 / 65535 + 1e-7) << packedHistory;
        EXPECT_EQ(floats.bytesPerFrame() - words.bytesPerFrame(), 4 * (pixels - rowWords * std::size_t(h)));
    }
    EXPECT_THROW(GtaoTemporalPasses(c, settings, mode(true, true, false), w, h, {.packedOutput = true}), Error);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The fused pass (GtaoTemporalVariant::fused: GTAO, reconstruction and accumulation on the grid in one
// dispatch) against the three dispatches, 4 frames of the path at an odd size (97x61: a 49x31 grid, more than
// one workgroup each way with every window) through every window (5x5, the alternating 4x4 and 2x2 ones),
// with and without bent normals, float and packed history, the history's depth copy and the caller's, float
// and packed normals, and the medium preset's planar samples, planar-nearest ones and the depth MIP chain's
// (whose pass runs before the fused one). Each fused value is
// the same arithmetic on the same inputs, so on lavapipe every word of the output, the history and the bent
// normals is the same; a device whose compiler contracts a multiply-add in one shader and not in the other
// may round differently, within the CPU comparison's bounds. Then the same frames recorded in one
// submission, which reads each frame's temporal constants from its own element of the ring.
TEST(GpuGtaoTemporal, FusedPassGivesTheFrameOfTheThreeDispatches) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const bool lavapipe = context.device().name.rfind("llvmpipe", 0) == 0;
    DemoPath in;
    const int w = DemoPath::w, h = DemoPath::h;
    const std::size_t pixels = in.pixels, grid = std::size_t((w + 1) / 2) * std::size_t((h + 1) / 2);
    struct Case {
        int window;  // 5, 4 or 2 (alternating)
        bool bent, packedHistory, callerKeepsDepth, packedNormals;
        ssao::GtaoSampling sampling;
    };
    const ssao::GtaoSampling planar = ssao::GtaoSampling::Planar, nearest = ssao::GtaoSampling::PlanarNearest;
    for (const Case& k : {Case{5, true, false, false, false, planar}, Case{4, true, true, true, false, planar},
                          Case{2, true, false, true, true, nearest}, Case{2, false, true, true, true, nearest},
                          Case{4, false, false, false, true, nearest}, Case{5, false, true, true, false, nearest},
                          Case{2, false, true, true, true, ssao::GtaoSampling::Mip}}) {
        ssao::GtaoTemporalSettings t = mode(true, true, true);
        t.packedHistory = k.packedHistory;
        t.alternatingWindow = k.window != 5;
        t.alternatingWindowSize = k.window == 2 ? 2 : 4;
        ssao::GtaoSettings settings = in.settings;
        settings.sampling = k.sampling;
        const GtaoTemporalVariant variant{k.bent, k.callerKeepsDepth, k.packedNormals};
        GtaoTemporalVariant fusedVariant = variant;
        fusedVariant.fused = true;
        const std::string name = std::to_string(k.window) + "x" + std::to_string(k.window) +
                                 (k.bent ? " bent" : " ao") + (k.packedHistory ? " packed" : " float") +
                                 (k.callerKeepsDepth ? " caller-depth" : " copy") +
                                 (k.packedNormals ? " words" : " normals") + " " + ssao::gtaoSamplingName(k.sampling);
        GtaoTemporalPasses passes(c, settings, t, w, h, variant), fused(c, settings, t, w, h, fusedVariant);
        EXPECT_LT(fused.bytesPerFrame(), passes.bytesPerFrame()) << name;
        // The outputs as words: the visibility, the history's visibility plane and the view bent normals.
        const auto outputs = [&](const GtaoTemporalPasses& p) {
            std::vector<std::uint32_t> words = downloadWords(c, p.visibility(), pixels);
            const std::vector<std::uint32_t> history = downloadWords(c, p.historyVisibility(), grid);
            words.insert(words.end(), history.begin(), history.end());
            if (k.bent) {
                const std::vector<std::uint32_t> b = downloadWords(c, p.bentNormal(), 3 * pixels);
                words.insert(words.end(), b.begin(), b.end());
            }
            return words;
        };
        const auto compare = [&](const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b,
                                 const std::string& when) {
            ASSERT_EQ(a.size(), b.size());
            int differing = 0;
            double worst = 0;
            for (std::size_t i = 0; i < a.size(); ++i) {
                differing += a[i] != b[i];
                // Packed history words are not floats; their visibility is what the upsampled plane shows.
                if (i < pixels || i >= pixels + grid || !k.packedHistory)
                    worst = std::max(worst, std::fabs(double(std::bit_cast<float>(a[i])) -
                                                      double(std::bit_cast<float>(b[i]))));
            }
            if (lavapipe) {
                EXPECT_EQ(differing, 0) << name << when;
            }
            EXPECT_LE(worst, kVisibilityBound) << name << when;
        };
        int occluded = 0;
        std::vector<Buffer> depth, normal;
        for (std::size_t f = 0; f < in.gbuffers.size(); ++f) {
            depth.push_back(uploadChannels(c, in.gbuffers[f].depth, 1));
            normal.push_back(uploadNormals(c, in.gbuffers[f].normal, k.packedNormals));
        }
        const auto inputs = [&](std::size_t f) {
            return GtaoTemporalFrameInputs{depth[f], normal[f], in.gbuffers[f].camera, int(f),
                                           f > 0 ? &depth[f - 1] : nullptr};
        };
        for (std::size_t f = 0; f < in.gbuffers.size(); ++f) {
            c.submit([&](VkCommandBuffer cmd) {
                passes.record(cmd, inputs(f));
                fused.record(cmd, inputs(f));
            });
            const std::vector<std::uint32_t> a = outputs(passes), b = outputs(fused);
            compare(a, b, " frame " + std::to_string(f));
            for (std::size_t i = 0; i < pixels; ++i) occluded += std::bit_cast<float>(a[i]) < 0.99f;
        }
        EXPECT_GT(occluded, int(pixels) / 50) << name;
        // Every frame in one submission, through fresh pass objects.
        GtaoTemporalPasses passes1(c, settings, t, w, h, variant), fused1(c, settings, t, w, h, fusedVariant);
        c.submit([&](VkCommandBuffer cmd) {
            for (std::size_t f = 0; f < in.gbuffers.size(); ++f) {
                passes1.record(cmd, inputs(f));
                fused1.record(cmd, inputs(f));
            }
        });
        compare(outputs(passes1), outputs(fused1), " in one submission");
        // And the same frame as the one-per-submission objects gave.
        compare(outputs(passes), outputs(fused1), " one submission against one per frame");
    }
    // Without the grid's history (at half resolution, or at full resolution, which has none) there is nothing
    // to fuse; the settings themselves are valid, so the error is the fused pass's.
    for (const ssao::GtaoTemporalSettings& t : {mode(true, true, false), mode(true, false, false)}) {
        try {
            GtaoTemporalPasses refused(c, in.settings, t, w, h, {.fused = true});
            ADD_FAILURE() << "the fused pass ran without the grid's history";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("the fused pass needs the grid's history"), std::string::npos)
                << e.what();
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The fused pass dispatches by the workgroup its module declares (a candidate may try another). One no wider than
// the reconstruction window accumulates no grid pixel: it is refused in one line naming the shader. A 4 x 4 module
// under the 5 x 5 window once divided the dispatch by zero (SIGFPE); a 3 x 3 one asked for 4294967290 workgroups.
TEST(GpuGtaoTemporal, FusedRefusesAWorkgroupNarrowerThanItsWindow) {
    const std::vector<std::uint32_t> embedded(shaders::gtao_temporal_fused.words,
                                              shaders::gtao_temporal_fused.words + shaders::gtao_temporal_fused.count);
    const DemoPath in;
    const int w = DemoPath::w, h = DemoPath::h;
    for (const auto& [x, y] : {std::pair{4u, 4u}, std::pair{16u, 3u}}) {
        testing::ContextWithModule other("gtao_temporal_fused", testing::withWorkgroupSize(embedded, x, y));
        Context::Impl& c = other.context().impl();
        GtaoTemporalPasses fused(c, in.settings, mode(true, true, true), w, h, {.fused = true});
        Buffer depth = uploadChannels(c, in.gbuffers[0].depth, 1), normal = uploadNormals(c, in.gbuffers[0].normal, false);
        const std::string refused = testing::errorMessage([&] {
            c.submit([&](VkCommandBuffer cmd) {
                fused.record(cmd, GtaoTemporalFrameInputs{depth, normal, in.gbuffers[0].camera, 0, nullptr});
            });
        });
        EXPECT_NE(refused.find("shader gtao_temporal_fused: has workgroups of " + std::to_string(x) + "x" +
                               std::to_string(y) + ": the 5x5 reconstruction window needs at least 5 invocations a side"),
                  std::string::npos)
            << refused;
        EXPECT_EQ(testing::validationReport(other.context()), "");
    }
}

// The public gpu::GtaoTemporal with its formats (GtaoTemporalFormats): with packedNormals it uploads the
// words and gives, bit for bit, the frame of the same object fed the words' decoded normals; with packedOutput
// each visibility is the float frame's rounded to 1/65535 (ssao::packUnorm16); both together, the frame of
// the decoded normals so rounded. Four frames of the path, with the bent normal and without, at half
// resolution with the grid's history and the 2x2 windows (the spatio-temporal target's configuration).
TEST(GpuGtaoTemporal, PublicFormatsGiveTheFrameOfTheirRounding) {
    OBSCURA_GPU_CONTEXT(context);
    const DemoPath in;
    const auto& [gbuffers, settings, pixels] = in;
    const int w = DemoPath::w, h = DemoPath::h;
    ssao::GtaoTemporalSettings t = mode(true, true, true);
    t.packedHistory = true;
    t.alternatingWindow = true;
    t.alternatingWindowSize = 2;
    for (const GtaoOutputs outputs : {GtaoOutputs::VisibilityAndBentNormal, GtaoOutputs::Visibility}) {
        GtaoTemporal floats(context, settings, t, outputs), decodedFloats(context, settings, t, outputs);
        GtaoTemporal words(context, settings, t, outputs, {.packedNormals = true});
        GtaoTemporal sixteen(context, settings, t, outputs, {.packedOutput = true});
        GtaoTemporal both(context, settings, t, outputs, {.packedNormals = true, .packedOutput = true});
        int differing = 0, rounded = 0, occluded = 0, fromFloats = 0;
        for (const GBuffer& g : gbuffers) {
            GBuffer decoded = g;
            decoded.normal = unpackNormals(packNormals(g.normal), w, h);
            const ssao::GtaoResult f = floats.frame(g), d = decodedFloats.frame(decoded), p = words.frame(g);
            const ssao::GtaoResult s = sixteen.frame(g), b = both.frame(g);
            for (std::size_t i = 0; i < pixels; ++i) {
                differing += std::bit_cast<std::uint32_t>(p.visibility.pixels[i]) !=
                             std::bit_cast<std::uint32_t>(d.visibility.pixels[i]);
                const float r = ssao::unpackUnorm16(ssao::packUnorm16(f.visibility.pixels[i]));
                const float rd = ssao::unpackUnorm16(ssao::packUnorm16(d.visibility.pixels[i]));
                differing += s.visibility.pixels[i] != r;
                differing += b.visibility.pixels[i] != rd;
                rounded += s.visibility.pixels[i] != f.visibility.pixels[i];
                fromFloats += p.visibility.pixels[i] != f.visibility.pixels[i];
                occluded += f.visibility.pixels[i] < 0.99f;
            }
            EXPECT_EQ(p.bentNormal.pixels, d.bentNormal.pixels);
            EXPECT_EQ(s.bentNormal.pixels, f.bentNormal.pixels);  // the 16 bits are the visibility's alone
            EXPECT_EQ(p.bentNormal.empty(), outputs == GtaoOutputs::Visibility);
        }
        EXPECT_EQ(differing, 0);
        EXPECT_GT(rounded, 0);     // the rounding is there to see
        EXPECT_GT(fromFloats, 0);  // and so is the decoding: the words' frame is not the floats'
        EXPECT_GT(occluded, int(pixels) / 50);
        EXPECT_EQ(words.historyLength().pixels, decodedFloats.historyLength().pixels);
    }
    ssao::GtaoTemporalSettings full = mode(true, true, false);
    EXPECT_THROW(GtaoTemporal(context, settings, full, GtaoOutputs::Visibility, {.packedOutput = true}), Error);
    EXPECT_EQ(testing::validationReport(context), "");
}

// Visibility alone (no bent normal computed, filtered or accumulated, kGtaoSpecBentNormal and
// kTemporalSpecBentNormal 0) gives the full frame's visibility and history length bit for bit: the
// bent normal feeds neither. Four frames of the path, so the history is read and written, at both
// resolutions; the full frames are checked against the CPU reference by the tests above.
TEST(GpuGtaoTemporal, VisibilityOnlyGivesTheSameVisibility) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const DemoPath in;
    const auto& [gbuffers, settings, pixels] = in;
    const int w = DemoPath::w, h = DemoPath::h;
    for (const auto& [half, packed, grid] : {std::tuple{false, false, false}, std::tuple{true, false, false},
                                             std::tuple{false, true, false}, std::tuple{true, false, true},
                                             std::tuple{true, true, true}}) {
        ssao::GtaoTemporalSettings t = mode(true, half, grid);
        t.packedHistory = packed;  // then the history's visibility plane holds visibility and length in one word
        GtaoTemporalPasses full(c, settings, t, w, h);
        GtaoTemporalPasses aoOnly(c, settings, t, w, h, {.bentNormals = false});
        const std::size_t lattice = std::size_t(full.historyWidth()) * std::size_t(full.historyHeight());
        int differing = 0, occluded = 0;
        recordSideBySide(c, full, aoOnly, gbuffers, [&](std::size_t f) {
            const std::vector<std::uint32_t> a = downloadWords(c, full.visibility(), pixels);
            const std::vector<std::uint32_t> b = downloadWords(c, aoOnly.visibility(), pixels);
            const auto lengths = [&](const GtaoTemporalPasses& p) {
                return downloadWords(c, packed ? p.historyVisibility() : p.historyLength(), lattice);
            };
            const std::vector<std::uint32_t> la = lengths(full), lb = lengths(aoOnly);
            for (std::size_t i = 0; i < pixels; ++i) {
                differing += a[i] != b[i];
                const float v = full.visibilityPacked() ? ssao::unpackVisibility(a[i]) : std::bit_cast<float>(a[i]);
                occluded += f + 1 == gbuffers.size() && v < 0.99f;
            }
            for (std::size_t i = 0; i < lattice; ++i) differing += la[i] != lb[i];
        });
        const std::string name = std::string(grid ? "grid history" : half ? "half resolution" : "full resolution") +
                                 (packed ? ", packed" : "");
        EXPECT_EQ(differing, 0) << name;
        EXPECT_GT(occluded, w * h / 50);  // not vacuous: there is occlusion to agree on
        // The bent normal's planes are gone from the traffic: per pixel 3 history floats in, 3 out (packed, a
        // word each) and 3 view floats out; per grid pixel 3 raw floats written and read, and at half
        // resolution the bent reconstruction's 10 (a grid pixel is a quarter of a pixel, a bit more at odd
        // sizes).
        const double saved = double(full.bytesPerFrame() - aoOnly.bytesPerFrame()) / (double(w) * h * sizeof(float));
        std::printf("[ measured ] visibility only, %s: %zu -> %zu bytes per frame (%.2f floats per pixel less)\n",
                    name.c_str(), full.bytesPerFrame(), aoOnly.bytesPerFrame(), saved);
        const double history = packed ? 1 + 1 + 3 : 3 + 3 + 3;  // packed: one word in, one out
        // With the grid's history: per pixel 3 view floats out and the full depth that the bent normals'
        // upsampling reads; per grid pixel the raw 3 written and read, the grid's view bent normal 3 written
        // and read by its upsampling with the grid's depth (1), and the history's in and out.
        const double gridSaved = 4 + (3 + 3 + 3 + 3 + 1 + (packed ? 2 : 6)) / 4.0;
        EXPECT_NEAR(saved, grid ? gridSaved : history + (half ? (3 + 3 + 10) / 4.0 : 3 + 3), 0.2) << name;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The previous frame's depth from the caller instead of a copy in the history (kTemporalSpecDepthCopy 0):
// the same words in every output, frame after frame, with and without the packed history; one plane less.
TEST(GpuGtaoTemporal, CallerKeptDepthGivesTheSameFrames) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    const int w = 90, h = 57;
    const std::vector<GBuffer> gbuffers = path("stairs", w, h, 4);
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    for (const auto& [packed, grid] : {std::pair{false, false}, std::pair{true, false}, std::pair{false, true},
                                       std::pair{true, true}}) {
        ssao::GtaoTemporalSettings t = mode(true, grid, grid);
        t.packedHistory = packed;
        GtaoTemporalPasses copying(c, preset(ssao::GtaoQuality::Medium), t, w, h);
        GtaoTemporalPasses keeping(c, preset(ssao::GtaoQuality::Medium), t, w, h, {.callerKeepsDepth = true});
        // With the grid's history the copy is of the grid's depth; the caller's buffer is read at (2x, 2y).
        const std::size_t lattice = std::size_t(copying.historyWidth()) * std::size_t(copying.historyHeight());
        int differing = 0;
        recordSideBySide(c, copying, keeping, gbuffers, [&](std::size_t) {
            const auto same = [&](const Buffer& a, const Buffer& b, std::size_t count) {
                return downloadWords(c, a, count) == downloadWords(c, b, count);
            };
            differing += !same(copying.visibility(), keeping.visibility(), pixels);
            differing += !same(copying.bentNormal(), keeping.bentNormal(), 3 * pixels);
            differing += !same(copying.historyVisibility(), keeping.historyVisibility(), lattice);
            if (!packed) differing += !same(copying.historyLength(), keeping.historyLength(), lattice);
        });
        EXPECT_EQ(differing, 0) << packed << grid;
        EXPECT_EQ(copying.bytesPerFrame() - keeping.bytesPerFrame(), lattice * sizeof(float)) << packed << grid;
    }
    // A history frame without the previous depth is refused in words before anything is recorded.
    GtaoTemporalPasses keeping(c, preset(ssao::GtaoQuality::Low), mode(true, false), w, h, {.callerKeepsDepth = true});
    const Buffer depth = uploadChannels(c, gbuffers[0].depth, 1);
    const Buffer normal = uploadChannels(c, gbuffers[0].normal, 3);
    c.submit([&](VkCommandBuffer cmd) { keeping.record(cmd, {depth, normal, gbuffers[0].camera, 0}); });
    EXPECT_THROW(c.submit([&](VkCommandBuffer cmd) { keeping.record(cmd, {depth, normal, gbuffers[1].camera, 1}); }),
                 Error);
    EXPECT_EQ(keeping.framesRecorded(), 1);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The public wrapper's AO-only frames (GtaoOutputs::Visibility): the visibility and history length of the
// full frames bit for bit, at both resolutions, and no bent normal. The wrapper reprojects with the previous
// frame's upload (callerKeepsDepth), which the CPU comparisons above check against the reference.
TEST(GpuGtaoTemporal, WrapperWithoutBentNormalsGivesTheSameVisibility) {
    OBSCURA_GPU_CONTEXT(context);
    const int w = 71, h = 45;
    const std::vector<GBuffer> gbuffers = path("stairs", w, h, 3);
    for (bool half : {false, true}) {
        GtaoTemporal full(context, preset(ssao::GtaoQuality::Medium), mode(true, half));
        GtaoTemporal aoOnly(context, preset(ssao::GtaoQuality::Medium), mode(true, half), GtaoOutputs::Visibility);
        int occluded = 0;
        for (const GBuffer& g : gbuffers) {
            const ssao::GtaoResult a = full.frame(g);
            const ssao::GtaoResult& b = aoOnly.frame(g);
            EXPECT_EQ(a.visibility.pixels, b.visibility.pixels) << half;
            EXPECT_EQ(full.historyLength().pixels, aoOnly.historyLength().pixels) << half;
            EXPECT_EQ(a.bentNormal.pixelCount(), std::size_t(w) * std::size_t(h)) << half;
            EXPECT_TRUE(b.bentNormal.empty()) << half;
            occluded = int(std::count_if(b.visibility.pixels.begin(), b.visibility.pixels.end(),
                                         [](float v) { return v < 0.99f; }));
        }
        EXPECT_GT(occluded, w * h / 50) << half;  // not vacuous
        EXPECT_EQ(aoOnly.framesRendered(), 3);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The Context is a movable shell around its state; a GtaoTemporal made on it keeps working when it moves (a struct
// holding both, moved). It kept a pointer to the shell, and the next frame dereferenced the moved-from one.
TEST(GpuGtaoTemporal, KeepsWorkingWhenItsContextMoves) {
    if (deviceCount() == 0) GTEST_SKIP() << "no Vulkan device (install mesa-vulkan-drivers for lavapipe)";
    ContextSettings settings;
    settings.validation = true;
    Context first(settings);
    std::unique_ptr<Context> second;  // declared before the pass, so destroyed after it
    const std::vector<GBuffer> gbuffers = path("stairs", 33, 21, 2);
    GtaoTemporal moving(first, preset(ssao::GtaoQuality::Medium), mode(true, false));
    const ssao::GtaoResult before = moving.frame(gbuffers[0]);
    second = std::make_unique<Context>(std::move(first));
    const ssao::GtaoResult& after = moving.frame(gbuffers[1]);
    EXPECT_EQ(after.visibility.pixelCount(), before.visibility.pixelCount());
    EXPECT_EQ(moving.framesRendered(), 2);
    EXPECT_EQ(testing::validationReport(*second), "");
}

// The same validation and messages as ssao::GtaoTemporal.
TEST(GpuGtaoTemporal, RejectsBadInputAsTheCpuPassDoes) {
    OBSCURA_GPU_CONTEXT(context);
    const ssao::GtaoSettings settings;
    for (const auto& change : std::vector<void (*)(ssao::GtaoTemporalSettings&)>{
             [](auto& t) { t.depthSigma = 0; }, [](auto& t) { t.rejectDepth = 2; },
             [](auto& t) { t.rejectNormalCos = -2; }, [](auto& t) { t.maxHistory = 0; }}) {
        ssao::GtaoTemporalSettings t;
        change(t);
        testing::expectSameError([&] { (void)ssao::GtaoTemporal(settings, t); },
                                 [&] { (void)GtaoTemporal(context, settings, t); });
    }
    ssao::GtaoSettings badRadius;
    badRadius.radius = -1;
    testing::expectSameError([&] { (void)ssao::GtaoTemporal(badRadius, {}); },
                             [&] { (void)GtaoTemporal(context, badRadius, {}); });

    const GBuffer g = testing::render("plane", 16, 16);
    GBuffer small = g;
    small.normal = Image(8, 8, 3);
    GBuffer twoChannels = g;
    twoChannels.normal = Image(16, 16, 2);
    GBuffer nanDepth = g, nanNormal = g;
    nanDepth.depth.at(3, 5) = std::nanf("");
    nanNormal.normal.at(9, 11, 2) = std::nanf("");
    for (const GBuffer& bad : {small, twoChannels, nanDepth, nanNormal}) {
        ssao::GtaoTemporal cpu(settings, {});
        GtaoTemporal gpu(context, settings, {});
        testing::expectSameError([&] { cpu.frame(bad); }, [&] { gpu.frame(bad); });
    }
    {
        GtaoTemporal gpu(context, settings, {});
        const std::string message = testing::errorMessage([&] { gpu.frame(nanDepth); });
        EXPECT_NE(message.find("(3, 5)"), std::string::npos) << message;
        EXPECT_EQ(gpu.framesRendered(), 0);  // nothing ran
    }
    // The size may not change between frames.
    const GBuffer larger = testing::render("plane", 24, 16);
    ssao::GtaoTemporal cpu(settings, {});
    GtaoTemporal gpu(context, settings, {});
    cpu.frame(g);
    gpu.frame(g);
    testing::expectSameError([&] { cpu.frame(larger); }, [&] { gpu.frame(larger); });
    EXPECT_EQ(gpu.framesRendered(), 1);

    // The filters check what the GPU must read safely (the CPU ones check as much, tests/ssao/gtao_temporal_test.cpp).
    EXPECT_THROW(reconstructInterleaved(context, Image(16, 16, 2), g.depth, g.normal, 0.05f), Error);
    EXPECT_THROW(reconstructInterleaved(context, Image(16, 16, 1), g.depth, Image(8, 8, 3), 0.05f), Error);
    EXPECT_THROW(upsampleDepthAware(context, Image(8, 8, 1), Image(4, 4, 1), g, 0.05f), Error);
    EXPECT_THROW(upsampleDepthAware(context, Image(), Image(), g, 0.05f), Error);
    GBuffer noNormals = g;
    noNormals.normal = Image(8, 8, 3);  // the upsampling reads a pixel's own normal where no tap is a surface
    testing::expectSameError([&] { ssao::upsampleDepthAware(Image(8, 8, 3), Image(8, 8, 1), noNormals, 0.05f); },
                             [&] { upsampleDepthAware(context, Image(8, 8, 3), Image(8, 8, 1), noNormals, 0.05f); });
    EXPECT_TRUE(GtaoTemporal(context, settings, {}).historyLength().empty());
    EXPECT_EQ(testing::validationReport(context), "");
}

// A pole one pixel wide against the sky in a column the half-resolution grid never sees
// (test::poleAgainstTheSky, normal (0, 0.6, 0.8)): every upsampling, the filter alone and in each frame that
// runs it, gives its pixels visibility 1 and their own normal as the bent normal, as the CPU does. Before, the
// GPU wrote (0, 0, 0) there (a difference of 0.8). Float normals within 1e-6; packed ones within 1e-4 of the
// CPU's frame of the same floats (the octahedral code's 6.5e-5 rad).
TEST(GpuGtaoTemporal, ThinFeatureAgainstTheSkyKeepsItsNormal) {
    OBSCURA_GPU_CONTEXT(context);
    const Vec3 n{0.0f, 0.6f, 0.8f};
    const GBuffer g = test::poleAgainstTheSky(n);
    const auto expectPole = [&](const ssao::GtaoResult& gpu, const ssao::GtaoResult& cpu, float tolerance,
                                const std::string& name) {
        ASSERT_EQ(gpu.bentNormal.pixels.size(), cpu.bentNormal.pixels.size()) << name;
        for (int y = 0; y < 6; ++y) {
            EXPECT_NEAR(cpu.bentNormal.at(3, y, 1), n.y, 1e-6f) << name << ", row " << y;  // the CPU's own answer
            EXPECT_NEAR(gpu.visibility.at(3, y), cpu.visibility.at(3, y), 1e-6f) << name << ", row " << y;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(gpu.bentNormal.at(3, y, c), cpu.bentNormal.at(3, y, c), tolerance)
                    << name << ", row " << y << ", channel " << c;
        }
    };
    {
        Image lowDepth(3, 3, 1, INFINITY);
        const Image low(3, 3, 3, 0.0f);
        const Image cpu = ssao::upsampleDepthAware(low, lowDepth, g, 0.05f);
        const Image gpu = upsampleDepthAware(context, low, lowDepth, g, 0.05f);
        for (int y = 0; y < 6; ++y)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu.at(3, y, c), cpu.at(3, y, c), 1e-6f) << "filter, row " << y;
        EXPECT_NEAR(cpu.at(3, 2, 2), n.z, 1e-6f);
    }
    const ssao::GtaoSettings settings;
    expectPole(computeGtaoHalfResolution(context, g, settings, {}),
               ssao::computeGtaoHalfResolution(g, settings, {}), 1e-6f, "half resolution");
    struct Case {
        bool gridHistory, packedNormals;
        GtaoTemporalDispatch dispatch;
        const char* name;
    };
    for (const Case& k : {Case{false, false, GtaoTemporalDispatch::Separate, "temporal, history at full resolution"},
                          Case{false, true, GtaoTemporalDispatch::Separate, "the same, packed normals"},
                          Case{true, false, GtaoTemporalDispatch::Separate, "temporal, grid history"},
                          Case{true, true, GtaoTemporalDispatch::Separate, "the same, packed normals"},
                          Case{true, false, GtaoTemporalDispatch::Fused, "temporal, grid history, fused"}}) {
        const ssao::GtaoTemporalSettings t = mode(true, true, k.gridHistory);
        ssao::GtaoTemporal cpu(settings, t);
        GtaoTemporal gpu(context, settings, t, GtaoOutputs::VisibilityAndBentNormal, {k.packedNormals, false},
                         k.dispatch);
        for (int frame = 0; frame < 2; ++frame) {
            const ssao::GtaoResult& want = cpu.frame(g);
            expectPole(gpu.frame(g), want, k.packedNormals ? 1e-4f : 1e-6f,
                       std::string(k.name) + ", frame " + std::to_string(frame));
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
