// Depth and normal preparation (obscura/depth_prep.h): the reference the GPU passes
// (src/gpu/shaders/prepare_depth.comp, normals_from_depth.comp) are tested against.
#include "obscura/depth_prep.h"

#include "obscura/alchemy.h"
#include "obscura/error.h"
#include "obscura/parallel.h"

#include <cmath>
#include <string>

namespace obscura::ssao {

DepthPrepConstants depthPrepConstants(const DepthPrepSettings& s, const Camera& camera) {
    camera.validate();
    DepthPrepConstants k{};
    k.width = camera.width;
    k.height = camera.height;
    k.normals = s.normals == NormalSource::View ? kNormalsView : s.normals == NormalSource::World ? kNormalsWorld
                                                                                                  : kNormalsFromDepth;
    k.unorm = s.unormNormals ? 1 : 0;
    k.normalChannels = 3;  // prepareGBuffer and the GPU pass set the input's
    const float n = camera.nearZ, f = camera.farZ;
    switch (s.depth) {
    case DepthConvention::Standard: k.a = n * f, k.b = f, k.c = n - f, k.skyZ = 1.0f; break;
    case DepthConvention::Reversed: k.a = n * f, k.b = n, k.c = f - n, k.skyZ = 0.0f; break;
    case DepthConvention::ReversedInfinite: k.a = n, k.b = 0.0f, k.c = 1.0f, k.skyZ = 0.0f; break;
    }
    const Mat4 r = camera.viewFromWorld();
    float* rows[3] = {k.viewFromWorld0, k.viewFromWorld1, k.viewFromWorld2};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rows[i][j] = r.m[i][j];
    const Camera::PixelToView a = camera.viewFromPixelAffine();
    k.mulX = a.mulX, k.addX = a.addX, k.mulY = a.mulY, k.addY = a.addY;
    return k;
}

float deviceDepthFromLinear(float d, const DepthPrepConstants& k) {
    // d = a / (b + c z)  <=>  z = (a / d - b) / c
    if (!(d < 1e30f)) return k.skyZ;
    const float z = (k.a / d - k.b) / k.c;
    return z < 0.0f ? 0.0f : z > 1.0f ? 1.0f : z;
}

void checkDepthPrepInputs(const Image& deviceDepth, const Image& normals, const Camera& camera,
                          const DepthPrepSettings& s, const std::string& what) {
    camera.validate();
    const auto size = [](const Image& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); };
    const std::string cameraSize = std::to_string(camera.width) + "x" + std::to_string(camera.height);
    if (deviceDepth.channels != 1)
        fail(what, "depth has " + std::to_string(deviceDepth.channels) + " channels, needs 1");
    if (deviceDepth.width != camera.width || deviceDepth.height != camera.height)
        fail(what, "depth is " + size(deviceDepth) + " but the camera is " + cameraSize);
    if (s.normals == NormalSource::FromDepth) return;
    if (normals.channels != 3 && normals.channels != 4)
        fail(what, "normals have " + std::to_string(normals.channels) + " channels, need 3 or 4");
    if (normals.width != camera.width || normals.height != camera.height)
        fail(what, "normals are " + size(normals) + " but the camera is " + cameraSize);
}

namespace {

// The normal of one pixel as the kernels compute it: decoded, rotated into view space, renormalised.
Vec3 viewNormal(const float* in, const DepthPrepConstants& k) {
    Vec3 n{in[0], in[1], in[2]};
    if (k.unorm) n = n * 2.0f - Vec3{1, 1, 1};
    if (k.normals == kNormalsWorld)
        n = {k.viewFromWorld0[0] * n.x + k.viewFromWorld0[1] * n.y + k.viewFromWorld0[2] * n.z,
             k.viewFromWorld1[0] * n.x + k.viewFromWorld1[1] * n.y + k.viewFromWorld1[2] * n.z,
             k.viewFromWorld2[0] * n.x + k.viewFromWorld2[1] * n.y + k.viewFromWorld2[2] * n.z};
    return n * (1.0f / std::sqrt(dot(n, n)));
}

} // namespace

void checkPreparedNormal(Vec3 n, int x, int y, const std::string& what) {
    const float l2 = dot(n, n);
    if (!(l2 > 0.5f && l2 < 2.0f))
        fail(what, "the normal at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                       ") is not a finite non-zero vector");
}

GBuffer prepareGBuffer(const Image& deviceDepth, const Image& normals, const Camera& camera, const DepthPrepSettings& s,
                       const std::string& what) {
    checkDepthPrepInputs(deviceDepth, normals, camera, s, what);
    DepthPrepConstants k = depthPrepConstants(s, camera);
    if (s.normals != NormalSource::FromDepth) k.normalChannels = normals.channels;
    GBuffer g;
    g.camera = camera;
    g.depth = Image(k.width, k.height, 1);
    g.normal = Image(k.width, k.height, 3, 0.0f);
    for (int y = 0; y < k.height; ++y)
        for (int x = 0; x < k.width; ++x) {
            const float z = deviceDepth.at(x, y);
            if (!(z >= 0.0f && z <= 1.0f))
                fail(what, "depth " + numberText(z) + " at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                               ") is outside [0, 1]");
            const float d = linearDepthFromDevice(z, k);
            g.depth.at(x, y) = d;
            if (k.normals == kNormalsFromDepth || !(d < 1e30f)) continue;
            const float* in = &normals.pixels[(std::size_t(y) * std::size_t(k.width) + std::size_t(x)) *
                                              std::size_t(k.normalChannels)];
            const Vec3 n = viewNormal(in, k);
            checkPreparedNormal(n, x, y, what);
            for (int c = 0; c < 3; ++c) g.normal.at(x, y, c) = n[c];
        }
    if (k.normals == kNormalsFromDepth) {
        g.normal = normalsFromDepth(g.depth, camera);
        // normalsFromDepth faces sky pixels to the camera; the G-buffer's sky normal is 0.
        for (std::size_t i = 0; i < g.depth.pixels.size(); ++i)
            if (!(g.depth.pixels[i] < 1e30f)) g.normal.pixels[3 * i] = g.normal.pixels[3 * i + 1] = g.normal.pixels[3 * i + 2] = 0.0f;
    }
    return g;
}

} // namespace obscura::ssao
