// The GTAO compute pass (src/gpu/shaders/gtao.comp) against the CPU reference ssao::computeGtao, on
// lavapipe in CI, with validation on and no message allowed.
#include "gpu_test_util.h"

#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gtao.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace obscura::gpu {
namespace {

constexpr double kVisibilityBound = 2e-3;
constexpr double kBentBound = 1e-2;

struct Difference {
    double visibility = 0;      // max |GPU - CPU| over all pixels
    double bent = 0;            // max over all pixels and bent-normal components
    double visibilityRest = 0;  // the same over the pixels within both bounds
    double bentRest = 0;
    int beyond = 0;             // pixels beyond either bound
    int occluded = 0;           // CPU pixels below 0.99: the comparison is not vacuous
};

Difference compare(const ssao::GtaoResult& gpu, const ssao::GtaoResult& cpu) {
    Difference d;
    for (std::size_t i = 0; i < cpu.visibility.pixels.size(); ++i) {
        const double dv = std::fabs(double(gpu.visibility.pixels[i]) - double(cpu.visibility.pixels[i]));
        double db = 0;
        for (std::size_t j = 3 * i; j < 3 * i + 3; ++j)
            db = std::max(db, std::fabs(double(gpu.bentNormal.pixels[j]) - double(cpu.bentNormal.pixels[j])));
        d.visibility = std::max(d.visibility, dv);
        d.bent = std::max(d.bent, db);
        if (dv > kVisibilityBound || db > kBentBound) {
            ++d.beyond;
        } else {
            d.visibilityRest = std::max(d.visibilityRest, dv);
            d.bentRest = std::max(d.bentRest, db);
        }
        d.occluded += cpu.visibility.pixels[i] < 0.99f;
    }
    return d;
}

// Runs both kernels on the constants, prints the differences and checks them against the bounds; at most
// `beyondPerMille` per mille of the pixels may exceed them.
void expectMatch(Context& context, const GBuffer& g, const ssao::GtaoConstants& k, const std::string& name,
                 int beyondPerMille) {
    const ssao::GtaoResult gpu = computeGtao(context, g, k);
    const ssao::GtaoResult cpu = ssao::computeGtao(g, k);
    ASSERT_EQ(gpu.visibility.pixels.size(), cpu.visibility.pixels.size()) << name;
    ASSERT_EQ(gpu.bentNormal.pixels.size(), cpu.bentNormal.pixels.size()) << name;
    const Difference d = compare(gpu, cpu);
    const int pixels = k.width * k.height;
    std::printf("[ measured ] %s %dx%d: visibility max %.3g (%.3g within bounds), bent max %.3g (%.3g), "
                "%d px beyond, %d occluded, %.3f ms on the GPU\n",
                name.c_str(), k.width, k.height, d.visibility, d.visibilityRest, d.bent, d.bentRest, d.beyond,
                d.occluded, context.lastPassMs());
    EXPECT_LE(d.visibilityRest, kVisibilityBound) << name;
    EXPECT_LE(d.bentRest, kBentBound) << name;
    EXPECT_LE(d.beyond * 1000, beyondPerMille * pixels) << name;
    EXPECT_GT(d.occluded, pixels / 50) << name;
}

ssao::GtaoSettings preset(ssao::GtaoQuality quality) {
    ssao::GtaoSettings s;
    ssao::applyQuality(s, quality);
    return s;
}

} // namespace

TEST(GpuGtao, MatchesTheCpuReferenceOnScenesAndPresets) {
    OBSCURA_GPU_CONTEXT(context);
    struct Case {
        const char* scene;
        int w, h;
        ssao::GtaoQuality quality;
    };
    for (const Case& c : {Case{"demo", 333, 197, ssao::GtaoQuality::High}, Case{"well", 160, 96, ssao::GtaoQuality::Low},
                          Case{"well", 160, 96, ssao::GtaoQuality::Ultra}, Case{"stairs", 128, 80, ssao::GtaoQuality::High},
                          Case{"corner", 96, 64, ssao::GtaoQuality::Ultra}}) {
        const GBuffer g = testing::render(c.scene, c.w, c.h);
        const ssao::GtaoConstants k = ssao::gtaoConstants(preset(c.quality), g.camera);
        expectMatch(context, g, k, std::string(c.scene) + " " + ssao::qualityName(c.quality), 1);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

TEST(GpuGtao, MatchesTheCpuReferenceWithEveryOption) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("stairs", 181, 123);
    const GBuffer well = testing::render("well", 120, 90);
    const ssao::GtaoSettings high = preset(ssao::GtaoQuality::High);
    ssao::GtaoSettings uniform = high;
    uniform.weighting = ssao::GtaoWeighting::Uniform;
    ssao::GtaoSettings heuristic = high;
    heuristic.thickness = ssao::GtaoThickness::Heuristic;
    ssao::GtaoSettings bitmask = high;
    bitmask.thickness = ssao::GtaoThickness::Bitmask;
    ssao::GtaoSettings drop = high;
    drop.beyondRadius = ssao::GtaoBeyondRadius::Drop;
    ssao::GtaoSettings jitter = high;
    jitter.jitter = true;
    ssao::GtaoSettings falloff = high;
    falloff.falloffStart = 0.5f;
    falloff.stepPower = 2.0f;
    falloff.radius = 0.7f;
    for (const auto& [name, s] :
         {std::pair{"uniform", uniform}, std::pair{"heuristic thickness", heuristic},
          std::pair{"bitmask thickness", bitmask}, std::pair{"beyond radius drop", drop}, std::pair{"jitter", jitter},
          std::pair{"falloff 0.5, step power 2", falloff}}) {
        expectMatch(context, g, ssao::gtaoConstants(s, g.camera, 3), std::string("stairs ") + name, 1);
        expectMatch(context, well, ssao::gtaoConstants(s, well.camera, 3), std::string("well ") + name, 1);
    }
    for (int frame : {0, 4, 11}) {
        const std::string name = "interleaved frame " + std::to_string(frame);
        expectMatch(context, g, ssao::gtaoConstants(preset(ssao::GtaoQuality::Low), g.camera, frame, true),
                    "stairs " + name, 1);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

// The same validation and messages as ssao::computeGtao.
TEST(GpuGtao, RejectsBadInputAsTheCpuPassDoes) {
    OBSCURA_GPU_CONTEXT(context);
    const GBuffer g = testing::render("plane", 16, 16);
    ssao::GtaoSettings radius;
    radius.radius = -1;
    ssao::GtaoSettings slices;
    slices.sliceCount = 65;
    for (const ssao::GtaoSettings& s : {radius, slices}) {
        const std::string cpu = testing::errorMessage([&] { ssao::computeGtao(g, s); });
        EXPECT_NE(cpu, "no error");
        EXPECT_EQ(testing::errorMessage([&] { computeGtao(context, g, s); }), cpu);
    }
    GBuffer small = g;
    small.normal = Image(8, 8, 3);
    GBuffer twoChannels = g;
    twoChannels.normal = Image(16, 16, 2);
    const ssao::GtaoConstants k = ssao::gtaoConstants(ssao::GtaoSettings{}, g.camera);
    ssao::GtaoConstants wider = k;
    wider.width = 17;
    for (const auto& [buffer, constants] : {std::pair{small, k}, std::pair{twoChannels, k}, std::pair{g, wider}}) {
        const std::string cpu = testing::errorMessage([&] { ssao::computeGtao(buffer, constants); });
        EXPECT_NE(cpu, "no error");
        EXPECT_EQ(testing::errorMessage([&] { computeGtao(context, buffer, constants); }), cpu);
    }
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace obscura::gpu
