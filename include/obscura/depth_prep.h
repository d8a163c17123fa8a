// Depth and normal preparation: an engine's depth buffer and normals turned into the G-buffer the
// screen-space passes read (linear view depth, +inf for sky; unit view-space normals, 0 for sky).
//
// Engines keep the hardware depth of a perspective projection, not linear depth: Vulkan's [0, 1] range with
// near at 0 (standard) or at 1 (reversed Z, often with an infinite far plane). The camera's nearZ and farZ
// are the projection's planes. Normals come as view- or world-space vectors, signed or stored as
// n * 0.5 + 0.5 in an unsigned-normalised target, or not at all (rebuilt from depth, as
// ssao::normalsFromDepth does). Decoded normals are renormalised, since 8- or 10-bit storage shortens them.
//
// Errors: prepareGBuffer throws obscura::Error naming `what` and the first bad pixel for a depth outside
// [0, 1] or NaN, a non-finite or zero-length normal on a surface pixel, and a size or channel mismatch.
#pragma once

#include "obscura/camera.h"
#include "obscura/depth_prep_constants.h"
#include "obscura/gbuffer.h"
#include "obscura/image.h"

#include <string>

namespace obscura::ssao {

enum class DepthConvention { Standard, Reversed, ReversedInfinite };
enum class NormalSource { View, World, FromDepth };

struct DepthPrepSettings {
    DepthConvention depth = DepthConvention::Reversed;
    NormalSource normals = NormalSource::World;
    bool unormNormals = false;  // normals stored as n * 0.5 + 0.5
};

// The settings and the camera (size, planes, pose, field of view) as the kernels' constants.
DepthPrepConstants depthPrepConstants(const DepthPrepSettings& settings, const Camera& camera);

// The checks prepareGBuffer makes, for the GPU pass that shares them: deviceDepth 1 channel and normals 3 or
// 4 channels (unused unless the settings read them; the 4th is ignored), both of the camera's size.
void checkDepthPrepInputs(const Image& deviceDepth, const Image& normals, const Camera& camera,
                          const DepthPrepSettings& settings, const std::string& what);

// Throws obscura::Error("<what>: the normal at pixel (x, y) is not a finite non-zero vector") unless `n`, a
// normal as the preparation writes it, is a unit vector: a zero, non-finite or overflowing input normalizes to
// zero or NaN ((1e30, 1e30, 0): 1 / sqrt(inf) = 0), which a finiteness test alone let through. The CPU and
// GPU passes both check with it.
void checkPreparedNormal(Vec3 n, int x, int y, const std::string& what);

// The G-buffer (depth and normal; no albedo) of `camera` from the engine's buffers. `normals` may be empty
// with NormalSource::FromDepth.
GBuffer prepareGBuffer(const Image& deviceDepth, const Image& normals, const Camera& camera,
                       const DepthPrepSettings& settings, const std::string& what = "depth buffer");

// The inverse, for tests and tools that play an engine: the device depth of linear depth d under the
// convention (sky and depth beyond the far plane give the cleared value).
float deviceDepthFromLinear(float d, const DepthPrepConstants& k);

} // namespace obscura::ssao
