// View-space normals rebuilt from linear depth, as ssao::normalsFromDepth (src/ssao/alchemy.cpp) computes
// them: on each axis the neighbour that continues the centre's plane (misfit, the same rule and comments'
// reasoning as there), a cross product of the two differences, turned towards the camera. Sky pixels get 0
// (the G-buffer's sky normal; ssao::prepareGBuffer does the same). One invocation per pixel.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "obscura/depth_prep_constants.h"
#include "prep_layouts.h"

layout(local_size_x = kDepthPrepWorkgroupX, local_size_y = kDepthPrepWorkgroupY, local_size_z = 1) in;

layout(push_constant, std430) uniform Constants { DepthPrepConstants k; };
layout(std430, binding = kRebuildBindingDepth) readonly buffer DepthPlane { float depth[]; };
layout(std430, binding = kRebuildBindingNormal) writeonly buffer NormalPlane { float normal[]; };

const float kInf = 1.0 / 0.0;  // +inf: glslang folds it, as the C++ reference uses INFINITY

float depthAt(int x, int y) { return depth[y * k.width + x]; }
bool usable(int x, int y) { return x >= 0 && y >= 0 && x < k.width && y < k.height && depthAt(x, y) < 1e30; }
// Camera::viewFromPixel at the pixel's centre.
vec3 position(int x, int y) {
    const float d = depthAt(x, y);
    return vec3((float(x) + 0.5) * k.mulX + k.addX, (float(y) + 0.5) * k.mulY + k.addY, -1.0) * d;
}

float misfit(int x, int y, int dx, int dy) {
    if (!usable(x + dx, y + dy)) return kInf;
    const float d0 = depthAt(x, y), d1 = depthAt(x + dx, y + dy);
    if (!usable(x + 2 * dx, y + 2 * dy)) return abs(d1 - d0) / d0;
    const float d2 = depthAt(x + 2 * dx, y + 2 * dy);
    return abs(2.0 / d1 - 1.0 / d2 - 1.0 / d0) * d0;
}

// The CPU's prefer: where one side alone has a second neighbour, it is taken if it continues the centre's plane.
const float kPlaneMisfit = 1e-4;
bool prefer(int x, int y, int dx, int dy) {
    const float a = misfit(x, y, dx, dy), b = misfit(x, y, -dx, -dy);
    const bool longA = usable(x + dx, y + dy) && usable(x + 2 * dx, y + 2 * dy);
    const bool longB = usable(x - dx, y - dy) && usable(x - 2 * dx, y - 2 * dy);
    if (longA != longB && a < kInf && b < kInf) return longA ? a <= kPlaneMisfit : b > kPlaneMisfit;
    return a <= b;
}

void main() {
    const ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= k.width || q.y >= k.height) return;
    const int x = q.x, y = q.y;
    vec3 n = vec3(0.0);
    if (depthAt(x, y) < 1e30) {
        // Scaled by 1/depth before any product, as the CPU's (products of depths near 1e21 overflow float).
        const float scale = 1.0 / max(depthAt(x, y), 1e-30);
        const vec3 unscaled = position(x, y), p = unscaled * scale;
        const bool alongX = usable(x - 1, y) || usable(x + 1, y), alongY = usable(x, y - 1) || usable(x, y + 1);
        const vec3 ddx = !alongX ? vec3(0.0)
                         : (prefer(x, y, 1, 0) ? position(x + 1, y) - unscaled : unscaled - position(x - 1, y)) * scale;
        const vec3 ddy = !alongY ? vec3(0.0)
                         : (prefer(x, y, 0, 1) ? position(x, y + 1) - unscaled : unscaled - position(x, y - 1)) * scale;
        if (alongX && alongY) {
            n = normalize(cross(ddy, ddx));
            if (dot(n, p) > 0.0) n = -n;
        } else if (alongX || alongY) {
            // One axis only: across its tangent, in the plane of the tangent and the view ray (as the CPU's).
            const vec3 t = alongX ? ddx : ddy;
            const vec3 across = t * (dot(p, t) / dot(t, t)) - p;
            n = dot(across, across) > 0.0 ? normalize(across) : -normalize(p);
        } else {
            n = -normalize(p);
        }
    }
    const uint i = uint(y) * uint(k.width) + uint(x);
    normal[3 * i] = n.x;
    normal[3 * i + 1] = n.y;
    normal[3 * i + 2] = n.z;
}
