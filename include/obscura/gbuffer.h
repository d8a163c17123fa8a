// The geometry buffer every screen-space method reads (docs/FORMATS.md, "Spaces and units").
//
// Per pixel: linear view depth (m, positive along -Z; +infinity where no surface is seen), the view-space
// unit normal (zero where no surface), linear albedo, and optionally screen-space motion. Each is a
// separate image (structure of arrays), all of the camera's size.
#pragma once

#include "obscura/camera.h"
#include "obscura/image.h"

namespace obscura {

struct GBuffer {
    Camera camera;   // the camera the buffers were made with; width/height are the buffers' size
    Image depth;     // 1 channel: linear view depth, m; +inf for sky
    Image normal;    // 3 channels: view-space unit normal; (0,0,0) for sky
    Image albedo;    // 3 channels: linear base colour in [0,1]; (0,0,0) for sky
    Image motion;    // optional, 2 channels: pixel offset to the previous frame; empty when absent

    int width() const { return camera.width; }
    int height() const { return camera.height; }
    bool isSky(int x, int y) const { return !(depth.at(x, y) < 1e30f); }
    // View-space position of pixel (x, y)'s centre. Sky pixels give a point at infinity.
    Vec3 viewPosition(int x, int y) const {
        return camera.viewFromPixel(float(x) + 0.5f, float(y) + 0.5f, depth.at(x, y));
    }
    Vec3 viewNormal(int x, int y) const {
        return {normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2)};
    }

    // Checks that every buffer present matches the camera's size and channel count, and that depths
    // are positive or +inf and normals finite; throws obscura::Error naming `what` (e.g. a file) if not.
    void validate(const std::string& what) const;
    // validate() in two parts, for a pass that scans its pixels where it reads them anyway: the sizes and
    // channel counts (throws), and whether every pixel of rows [y0, y1) x columns [x0, x1) has a valid
    // depth and normal (branch-free; validate() then names the first bad pixel).
    void validateShape(const std::string& what) const;
    // validateShape's checks of the depth (1 channel) and normal (3) alone, at any size, 0x0 included: for a
    // pass that reads only those two and answers an empty G-buffer with empty images.
    void validateDepthNormalShape(const std::string& what) const;
    bool pixelsValid(int x0, int x1, int y0, int y1) const;
    // validate()'s scan of the depths and normals alone (in parallel; throws naming the first bad pixel), for a
    // caller that has checked the sizes its own way.
    void validatePixels(const std::string& what) const;
};

// One pixel's test of pixelsValid, for kernels that check the pixels they load: depth > 0 (+inf for sky;
// false for NaN, zero, negative) and a finite normal n[0..2]. Branch-free: x - x is 0 for finite x, NaN
// otherwise.
inline bool pixelValid(float depth, const float* n) {
    return (depth > 0.0f) & ((n[0] - n[0]) == 0.0f) & ((n[1] - n[1]) == 0.0f) & ((n[2] - n[2]) == 0.0f);
}

} // namespace obscura
