// Depth and normal preparation against closed forms: each depth convention inverts exactly
// (deviceDepthFromLinear, then prepareGBuffer, gives the linear depth back), world and unorm normals decode
// to the view normals, and the errors name the pixel.
#include "obscura/builtin_scenes.h"
#include "obscura/depth_prep.h"
#include "obscura/alchemy.h"
#include "obscura/error.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace obscura::ssao {
namespace {

GBuffer sceneGBuffer(const std::string& scene, int w, int h) {
    BuiltinScene s = makeBuiltinScene(scene);
    Camera cam = s.camera;
    cam.width = w;
    cam.height = h;
    trace::Tracer tracer(s.scene);
    return trace::renderGBuffer(tracer, cam);
}

// What an engine would hold for this G-buffer: device depth under `settings`, and normals in the settings'
// space and encoding.
struct EngineBuffers {
    Image deviceDepth, normals;
};
EngineBuffers engineBuffers(const GBuffer& g, const DepthPrepSettings& s, int normalChannels = 3) {
    const DepthPrepConstants k = depthPrepConstants(s, g.camera);
    EngineBuffers e{Image(g.width(), g.height(), 1), Image(g.width(), g.height(), normalChannels, 0.0f)};
    const Mat4 worldFromView = g.camera.worldFromView();
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            e.deviceDepth.at(x, y) = deviceDepthFromLinear(g.depth.at(x, y), k);
            Vec3 n = g.viewNormal(x, y);
            if (s.normals == NormalSource::World)
                n = {worldFromView.m[0][0] * n.x + worldFromView.m[0][1] * n.y + worldFromView.m[0][2] * n.z,
                     worldFromView.m[1][0] * n.x + worldFromView.m[1][1] * n.y + worldFromView.m[1][2] * n.z,
                     worldFromView.m[2][0] * n.x + worldFromView.m[2][1] * n.y + worldFromView.m[2][2] * n.z};
            if (s.unormNormals) n = n * 0.5f + Vec3{0.5f, 0.5f, 0.5f};
            for (int c = 0; c < 3; ++c) e.normals.at(x, y, c) = n[c];
        }
    return e;
}

// Relative depth error of the round trip: float z near 1 (standard) holds d / near * 2^-24 of relative
// precision, so the standard convention is bounded by the scene's depth range; the reversed ones keep
// float's own precision (z ~ near / d is small, where floats are dense).
TEST(DepthPrep, EachConventionInvertsAndNormalsDecode) {
    const GBuffer g = sceneGBuffer("demo", 64, 40);
    float maxDepth = 0.0f;
    for (float d : g.depth.pixels)
        if (d < 1e30f) maxDepth = std::max(maxDepth, d);
    struct Case {
        DepthConvention depth;
        NormalSource normals;
        bool unorm;
        int channels;
        float depthTolerance;  // relative
    };
    const float standardTolerance = 4.0f * maxDepth / g.camera.nearZ * std::ldexp(1.0f, -24);
    for (const Case& c : {Case{DepthConvention::Standard, NormalSource::View, false, 3, standardTolerance},
                          Case{DepthConvention::Reversed, NormalSource::World, false, 4, 1e-6f},
                          Case{DepthConvention::ReversedInfinite, NormalSource::World, true, 3, 1e-6f}}) {
        DepthPrepSettings s;
        s.depth = c.depth;
        s.normals = c.normals;
        s.unormNormals = c.unorm;
        const EngineBuffers e = engineBuffers(g, s, c.channels);
        const GBuffer p = prepareGBuffer(e.deviceDepth, e.normals, g.camera, s);
        float depthError = 0.0f, normalError = 0.0f;
        for (int y = 0; y < g.height(); ++y)
            for (int x = 0; x < g.width(); ++x) {
                const float d = g.depth.at(x, y);
                if (!(d < 1e30f)) {
                    ASSERT_FALSE(p.depth.at(x, y) < 1e30f) << x << " " << y;
                    for (int k = 0; k < 3; ++k) ASSERT_EQ(p.normal.at(x, y, k), 0.0f);
                    continue;
                }
                depthError = std::max(depthError, std::fabs(p.depth.at(x, y) - d) / d);
                for (int k = 0; k < 3; ++k)
                    normalError = std::max(normalError, std::fabs(p.normal.at(x, y, k) - g.normal.at(x, y, k)));
            }
        EXPECT_LE(depthError, c.depthTolerance) << int(c.depth);
        EXPECT_LE(normalError, 2e-6f) << int(c.depth);  // a rotation and a renormalisation in float
    }
}

// Rebuilt normals are normalsFromDepth's, with the G-buffer's 0 for sky.
TEST(DepthPrep, NormalsFromDepth) {
    const GBuffer g = sceneGBuffer("stairs", 48, 32);
    DepthPrepSettings s;
    s.normals = NormalSource::FromDepth;
    const EngineBuffers e = engineBuffers(g, s);
    const GBuffer p = prepareGBuffer(e.deviceDepth, Image(), g.camera, s);
    const Image expected = normalsFromDepth(p.depth, g.camera);
    for (std::size_t i = 0; i < p.depth.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k)
            ASSERT_EQ(p.normal.pixels[3 * i + k], p.depth.pixels[i] < 1e30f ? expected.pixels[3 * i + k] : 0.0f) << i;
}

std::string errorOf(const Image& z, const Image& n, const Camera& cam, const DepthPrepSettings& s) {
    try {
        prepareGBuffer(z, n, cam, s, "frame.exr");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(DepthPrep, BadInputsNameTheFileAndPixel) {
    Camera cam;
    cam.width = 8;
    cam.height = 4;
    DepthPrepSettings s;
    Image z(8, 4, 1, 0.5f), n(8, 4, 3, 0.0f);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) n.at(x, y, 1) = 1.0f;
    EXPECT_EQ(errorOf(z, n, cam, s), "no error");
    Image bad = z;
    bad.at(3, 2) = NAN;
    EXPECT_NE(errorOf(bad, n, cam, s).find("frame.exr: depth nan at pixel (3, 2) is outside [0, 1]"), std::string::npos)
        << errorOf(bad, n, cam, s);
    bad.at(3, 2) = 1.5f;
    EXPECT_NE(errorOf(bad, n, cam, s).find("pixel (3, 2)"), std::string::npos);
    Image zeroNormal = n;
    zeroNormal.at(5, 1, 1) = 0.0f;
    EXPECT_NE(errorOf(z, zeroNormal, cam, s).find("normal at pixel (5, 1)"), std::string::npos);
    EXPECT_NE(errorOf(Image(7, 4, 1, 0.5f), n, cam, s).find("depth is 7x4 but the camera is 8x4"), std::string::npos);
    EXPECT_NE(errorOf(z, Image(8, 4, 2, 0.0f), cam, s).find("normals have 2 channels"), std::string::npos);
    s.normals = NormalSource::FromDepth;
    EXPECT_EQ(errorOf(z, Image(), cam, s), "no error");  // no normals needed
}

} // namespace
} // namespace obscura::ssao
