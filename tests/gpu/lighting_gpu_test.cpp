// The post-processing passes as compute passes (src/gpu/shaders/multibounce.comp, specular_occlusion.comp,
// shade.comp) against their CPU references (ssao::multiBounce, ssao::computeSpecularOcclusion, render::shade
// and the CLI's multi-bounce composite), on lavapipe in CI, with validation on and no message allowed.
#include "gpu_test_util.h"

#include "gpu/compute_pipeline.h"
#include "gpu/spirv.h"
#include "gpu/shaders/layouts.h"
#include "gpu/specular_occlusion_pass.h"

#include "obscura/gpu_lighting.h"
#include "obscura/gtao.h"
#include "obscura/multibounce.h"
#include "obscura/render.h"
#include "obscura/specular_occlusion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <vector>

namespace obscura::gpu {

namespace {

struct Case {
    const char* scene;
    int w, h;
};
// Three built-in scenes, one at an odd size; small, so each test stays within a few seconds on lavapipe.
constexpr Case kCases[] = {{"demo", 333, 197}, {"stairs", 160, 96}, {"well", 128, 80}};

double maxAbsDifference(const Image& a, const Image& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0;
    for (std::size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
        worst = std::max(worst, std::fabs(double(a.pixels[i]) - double(b.pixels[i])));
    return worst;
}

// max |a - b| / max(|b|, floor): colours span decades (the sun in the sky), so an absolute bound would be
// loose on dark pixels and tight on bright ones; the floor keeps black pixels from dividing by 0.
double maxRelativeDifference(const Image& a, const Image& b, double floor = 1e-2) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0;
    for (std::size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
        worst = std::max(worst, std::fabs(double(a.pixels[i]) - double(b.pixels[i])) /
                                    std::max(std::fabs(double(b.pixels[i])), floor));
    return worst;
}

// The CLI's multi-bounce image (cli::renderGtaoFrames in gtao_cli.cpp): G(A, albedo) per channel, sky 1.
Image cpuMultiBounce(const GBuffer& g, const Image& visibility) {
    Image out(g.width(), g.height(), 3, 1.0f);
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            if (g.isSky(x, y)) continue;
            const Vec3 albedo{g.albedo.at(x, y, 0), g.albedo.at(x, y, 1), g.albedo.at(x, y, 2)};
            const Vec3 m = ssao::multiBounce(visibility.at(x, y), albedo);
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = m[c];
        }
    return out;
}

// The CLI's shadeGtao with multi-bounce: render::shade without AO, surface colours times G per channel.
render::Frame cpuShadeMultiBounce(const GBuffer& g, const render::SH9& sh, const Image& mb, const Image& env) {
    render::Frame frame = render::shade(g, sh, Image(), env);
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            if (g.isSky(x, y)) continue;
            for (int c = 0; c < 3; ++c) frame.color.at(x, y, c) *= mb.at(x, y, c);
        }
    return frame;
}

ssao::GtaoResult gtao(const GBuffer& g) {
    ssao::GtaoSettings s;
    s.sliceCount = 2;  // the passes under test only need plausible AO and bent normals
    return ssao::computeGtao(g, s);
}

} // namespace

// G(A, rho) is a cubic evaluated in float on both sides; the GPU may fuse its multiply-adds. Measured on
// lavapipe (2026-11-23, LLVM 15.0.6): max 0 (bit-equal) on all three cases. Bound 1e-6, for GPUs that fuse.
TEST(GpuLighting, MultiBounceMatchesTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    for (const Case& c : kCases) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const Image visibility = gtao(g).visibility;
        const Image gpu = multiBounce(context, g, visibility);
        const double worst = maxAbsDifference(gpu, cpuMultiBounce(g, visibility));
        std::printf("[ measured ] multibounce %s %dx%d: max %.3g, %.3f ms on the GPU\n", c.scene, c.w, c.h, worst,
                    context.lastPassMs());
        EXPECT_LE(worst, 1e-6) << c.scene;
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// S differs from the CPU's through the GPU's atan, sin, cos and exp on the cone angles, and a table lookup moves
// with its slope times the angle's error; the slopes are steepest at low roughness. The angles were acos of
// cosines, whose rounding near 1 acos magnifies (3.5e-4 rad): measured on lavapipe (2026-11-23, LLVM 15.0.6),
// max over the three scenes at roughness 0.25 and 0.7: lut4 3.6e-4, lut3 3.8e-4, cone 6.7e-4, and, with
// roughness 0 and 0.05 added (2026-11-28), lut4 2.65e-3 at roughness 0, past the bound. As atan of sine and
// cosine (2026-11-28): lut4 4.9e-5, lut3 5.1e-5 (both at roughness 0, demo 333x197), cone 5.8e-4 (roughness
// 0.7). Bound 2e-3 (the AO bound).
// The hardware-filtered lookup (printed beside it at roughness 0.25, -1 where not run) measured the same
// figures to 3 digits on lavapipe, which filters float textures with float weights; GPUs quantise the
// sub-texel weight to subTexelPrecisionBits (8 on most, 4 the Vulkan minimum), and neighbouring table nodes
// differ by up to 1.0 (alpha_v and beta at roughness 0, a step; measured from SpecularOcclusionTable::node),
// so the quantisation alone can reach 1 / 2^9 = 2e-3 at 8 bits and 3e-2 at 4. Hence the public pass
// interpolates texelFetch'd nodes itself.
TEST(GpuLighting, SpecularOcclusionMatchesTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    using Mode = ssao::SpecularOcclusionMode;
    for (const Case& c : kCases) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const ssao::GtaoResult ao = gtao(g);
        for (const auto& [name, mode] : {std::pair{"lut4", Mode::Lut4}, std::pair{"lut3", Mode::Lut3},
                                         std::pair{"cone", Mode::Cone}}) {
            for (const float roughness : {0.0f, 0.05f, 0.25f, 0.7f}) {
                const Image cpu = ssao::computeSpecularOcclusion(g, ao.visibility, ao.bentNormal, mode, roughness);
                const Image gpu = specularOcclusion(context, g, ao.visibility, ao.bentNormal, mode, roughness);
                const double worst = maxAbsDifference(gpu, cpu);
                const double ms = context.lastPassMs();
                double hardware = -1;
                if (mode != Mode::Cone && roughness < 0.5f)  // the rougher lobe's table is smoother
                    hardware = maxAbsDifference(specularOcclusionWith(context, g, ao.visibility, ao.bentNormal, mode,
                                                                      roughness, kSpecularLookupHardware),
                                                cpu);
                std::printf("[ measured ] specular %s %s %dx%d roughness %.2f: max %.3g (hardware filter %.3g), "
                            "%.3f ms on the GPU\n",
                            name, c.scene, c.w, c.h, double(roughness), worst, hardware, ms);
                EXPECT_LE(worst, 2e-3) << c.scene << " " << name << " " << roughness;
            }
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// A G-buffer whose columns see a surface ever closer to grazing: pixel (x, y) has the normal at
// theta_o = thetaO[x] from its view direction, turned about the view by an angle that changes with y. AO 1
// with b = n there (`open`), and AO 0 (`closed`).
struct GrazingViews {
    GBuffer g;
    Image open, closed, bent;
    std::vector<float> thetaO;
};
GrazingViews grazingViews() {
    GrazingViews v;
    v.thetaO = {0.0f, 1.2f, 1.45f, 1.52f, 1.54f, 1.55f, 1.56f, 1.565f, 1.568f, 1.569f, 1.5705f};
    const int w = int(v.thetaO.size()), h = 6;
    Camera cam;
    cam.position = {0, 0, 0};
    cam.target = {0, 0, -1};
    cam.width = w;
    cam.height = h;
    v.g.camera = cam;
    v.g.depth = Image(w, h, 1, 2.0f);
    v.g.normal = Image(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Vec3 view = normalize(-v.g.viewPosition(x, y));
            const Vec3 t1 = normalize(cross(view, Vec3{0, 1, 0})), t2 = cross(view, t1);
            const float turn = float(y), theta = v.thetaO[std::size_t(x)];
            const Vec3 across = t1 * std::cos(turn) + t2 * std::sin(turn);
            const Vec3 n = normalize(view * std::cos(theta) + across * std::sin(theta));
            for (int c = 0; c < 3; ++c) v.g.normal.at(x, y, c) = n[c];
        }
    v.open = Image(w, h, 1, 1.0f);
    v.closed = Image(w, h, 1, 0.0f);
    v.bent = v.g.normal;
    return v;
}

// The shader's own lookups at the CPU's edge cases (tests/ssao/specular_occlusion_test.cpp): the 4-D table's
// beta axis holds b = n at a node for every theta_o, so an unoccluded surface stays 1 (QUALITY.md: within 2e-3)
// up to theta_o = 89.98 degrees; AO 0 gives below 1e-3 in every mode, a mirror's cone included; and the cone
// near a mirror keeps its digits: the shader's float form against the CPU's double, where both take alpha_v
// and beta from float atan (of sine and cosine), whose ulps S multiplies by up to 1 / alpha_s (470 at roughness
// 0.001). Measured on lavapipe (2026-11-28, LLVM 15.0.6): max 4.5e-5 (2.6e-4 while the angles were acos of
// cosines); bound 1e-3 (the textbook form was off by up to 0.99).
TEST(GpuLighting, SpecularOcclusionAtGrazingViewsAndNearMirrors) {
    OBSCURA_GPU_CONTEXT(context);
    using Mode = ssao::SpecularOcclusionMode;
    const GrazingViews v = grazingViews();
    for (float roughness : {0.0f, 0.003f, 0.2f, 0.5f, 1.0f}) {
        for (Mode mode : {Mode::Lut4, Mode::Lut3}) {
            const Image s = specularOcclusion(context, v.g, v.open, v.bent, mode, roughness);
            for (int y = 0; y < v.g.height(); ++y)
                for (int x = 0; x < v.g.width(); ++x)
                    EXPECT_GE(s.at(x, y), 1.0f - 2e-3f) << "mode " << int(mode) << " r " << roughness << " theta_o "
                                                         << v.thetaO[std::size_t(x)] << " row " << y;
        }
        for (Mode mode : {Mode::Lut4, Mode::Lut3, Mode::Cone}) {
            const Image s = specularOcclusion(context, v.g, v.closed, v.bent, mode, roughness);
            for (float value : s.pixels) EXPECT_LT(value, 1e-3f) << "mode " << int(mode) << " r " << roughness;
        }
    }
    // Near a mirror: AO whose cone's edge sweeps across the reflection direction (b = n, so beta = theta_o).
    Image ao(v.g.width(), v.g.height(), 1);
    for (int y = 0; y < v.g.height(); ++y)
        for (int x = 0; x < v.g.width(); ++x) {
            const float alphaV = std::min(v.thetaO[std::size_t(x)] + 0.004f * float(y - 3), 1.5f);
            ao.at(x, y) = 1.0f - std::cos(alphaV) * std::cos(alphaV);  // eq. 17
        }
    double worst = 0.0;
    for (float roughness : {0.001f, 0.003f, 0.01f}) {
        const Image gpu = specularOcclusion(context, v.g, ao, v.bent, Mode::Cone, roughness);
        const Image cpu = ssao::computeSpecularOcclusion(v.g, ao, v.bent, Mode::Cone, roughness);
        worst = std::max(worst, maxAbsDifference(gpu, cpu));
    }
    std::printf("[ measured ] specular cone near a mirror: max |GPU - CPU| %.3g\n", worst);
    EXPECT_LE(worst, 1e-3);
    EXPECT_EQ(testing::validationReport(context), "");
}

// Colours: the irradiance sums its nine terms in float instead of double, and the sky's equirect
// coordinates go through the GPU's atan; relative to the CPU's value (floor 1e-2). Measured on lavapipe
// (2026-11-23, LLVM 15.0.6): colour max relative 1.6e-5 (stairs 160x96, a sky pixel: the environment
// lookup), 3.4e-7 without an environment; lighting 3.4e-7. Bound 1e-4 relative (an AO-scale 2e-3 on a
// colour of 1 would be 20 times looser).
TEST(GpuLighting, ShadeMatchesTheCpu) {
    OBSCURA_GPU_CONTEXT(context);
    const Image sky = render::proceduralSky(64, 32);
    const render::SH9 sh = render::projectEnvironment(sky);
    for (const Case& c : kCases) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const Image visibility = gtao(g).visibility;
        const Image mb = cpuMultiBounce(g, visibility);
        struct Variant {
            const char* name;
            render::Frame gpu, cpu;
        };
        Variant variants[] = {
            {"ao", shade(context, g, sh, visibility, sky), render::shade(g, sh, visibility, sky)},
            {"no ao, no environment", shade(context, g, sh, Image(), Image()), render::shade(g, sh, Image(), Image())},
            {"multibounce", shadeMultiBounce(context, g, sh, mb, sky), cpuShadeMultiBounce(g, sh, mb, sky)},
        };
        for (const Variant& v : variants) {
            const double color = maxRelativeDifference(v.gpu.color, v.cpu.color);
            const double lighting = maxRelativeDifference(v.gpu.lighting, v.cpu.lighting);
            std::printf("[ measured ] shade %s %s %dx%d: color max relative %.3g, lighting %.3g\n", v.name, c.scene,
                        c.w, c.h, color, lighting);
            EXPECT_LE(color, 1e-4) << c.scene << " " << v.name;
            EXPECT_LE(lighting, 1e-4) << c.scene << " " << v.name;
        }
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// Where the two kernels' inputs are degenerate they still agree: a sky pixel looking straight up (atan(0, 0),
// undefined in GLSL, picked another texel of the top row: 0.4 on the CPU, 8 on the GPU, for a 7x5 map of
// distinct texels) and a surface pixel with a zero normal (GLSL's normalize(0) gave black; the CPU lights it with
// the environment's mean, the SH's constant term).
TEST(GpuLighting, ShadeAgreesAtThePoleAndOnAZeroNormal) {
    OBSCURA_GPU_CONTEXT(context);
    Image environment(7, 5, 3);
    for (std::size_t i = 0; i < environment.pixels.size(); ++i) environment.pixels[i] = 0.2f * float(1 + i % 41);
    const render::SH9 sh = render::projectEnvironment(environment);
    GBuffer g;
    g.camera.position = {0, 1, 0};
    g.camera.target = {0, 5, 0};
    g.camera.up = {0, 0, -1};
    g.camera.width = 33;
    g.camera.height = 17;
    g.depth = Image(33, 17, 1, std::numeric_limits<float>::infinity());
    g.normal = Image(33, 17, 3, 0.0f);
    g.albedo = Image(33, 17, 3, 0.0f);
    g.depth.at(3, 3) = 2.0f;  // a surface pixel whose normal is zero
    for (int c = 0; c < 3; ++c) g.albedo.at(3, 3, c) = 0.5f;
    const render::Frame cpu = render::shade(g, sh, Image(), environment);
    const render::Frame gpu = shade(context, g, sh, Image(), environment);
    for (const auto& [x, y] : {std::pair{16, 8}, std::pair{3, 3}}) {
        for (int c = 0; c < 3; ++c) {
            const float want = cpu.color.at(x, y, c);
            EXPECT_GT(want, 0.0f) << x << "," << y;
            EXPECT_NEAR(gpu.color.at(x, y, c), want, 1e-4f * want) << x << "," << y << " channel " << c;
        }
    }
    EXPECT_LE(maxRelativeDifference(gpu.color, cpu.color), 1e-4);
    EXPECT_EQ(testing::validationReport(context), "");
}

// The CPU references' checks with their messages; the multi-bounce pass, whose CPU function checks nothing,
// has its own.
TEST(GpuLighting, RejectsBadInputAsTheCpuDoes) {
    OBSCURA_GPU_CONTEXT(context);
    using Mode = ssao::SpecularOcclusionMode;
    const GBuffer g = testing::render("corner", 24, 16);
    const Image ao(24, 16, 1, 0.5f), bent(24, 16, 3, 0.0f), small(8, 8, 1, 0.5f), sky = render::proceduralSky(16, 8);
    const render::SH9 sh = render::projectEnvironment(sky);
    testing::expectSameError([&] { ssao::computeSpecularOcclusion(g, ao, bent, Mode::Lut4, 1.5f); },
                             [&] { specularOcclusion(context, g, ao, bent, Mode::Lut4, 1.5f); });
    testing::expectSameError([&] { ssao::computeSpecularOcclusion(g, small, bent, Mode::Cone, 0.5f); },
                             [&] { specularOcclusion(context, g, small, bent, Mode::Cone, 0.5f); });
    testing::expectSameError([&] { render::shade(g, sh, small, sky); }, [&] { shade(context, g, sh, small, sky); });
    testing::expectSameError([&] { render::shade(g, sh, ao, Image(4, 4, 2)); },
                             [&] { shade(context, g, sh, ao, Image(4, 4, 2)); });
    EXPECT_THROW(multiBounce(context, g, small), Error);
    EXPECT_THROW(shadeMultiBounce(context, g, sh, ao, sky), Error);  // 1 channel where 3 are needed
    EXPECT_EQ(testing::validationReport(context), "");
}

// The reflection tells sampled images from storage buffers and counts specialization constants, and a
// pipeline whose host side binds otherwise is refused before any Vulkan object is made.
TEST(GpuLighting, PipelinesCheckBindingKindsAndSpecializations) {
    OBSCURA_GPU_CONTEXT(context);
    using K = BindingKind;
    const SpirvLayout shadeLayout = reflect(shaders::shade);
    ASSERT_EQ(shadeLayout.kinds.size(), std::size_t(kShadeBindingCount));
    EXPECT_EQ(shadeLayout.kinds[kShadeBindingEnvironment], K::SampledImage);
    EXPECT_EQ(shadeLayout.kinds[kShadeBindingColor], K::StorageBuffer);
    EXPECT_EQ(shadeLayout.specConstants, 1);
    EXPECT_EQ(reflect(shaders::specular_occlusion).specConstants, 3);
    EXPECT_EQ(reflect(shaders::gtao).kinds, std::vector<K>(kGtaoBindingCount, K::StorageBuffer));

    Context::Impl& c = context.impl();
    const std::string storage = testing::errorMessage([&] {
        ComputePipeline(c, shaders::shade, "shade", kShadeBindingCount, kShadePushConstantBytes, kLightingWorkgroupX,
                        kLightingWorkgroupY);
    });
    EXPECT_NE(storage.find("binding 5 is not a storage buffer"), std::string::npos) << storage;
    std::vector<K> kinds(kSpecularBindingCount, K::StorageBuffer);
    kinds[kSpecularBindingTable] = K::SampledImage;
    const std::string spec = testing::errorMessage([&] {
        ComputePipeline(c, shaders::specular_occlusion, "specular_occlusion", kinds, kSpecularPushConstantBytes,
                        kLightingWorkgroupX, kLightingWorkgroupY, {kSpecularModeCone});
    });
    EXPECT_NE(spec.find("declares 3 specialization constants, the host sets 1"), std::string::npos) << spec;
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
