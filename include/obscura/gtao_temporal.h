// Spatio-temporal GTAO (Jimenez et al. 2016, §4.1): each pixel searches its slices rotated by its place in
// a 4x4 interleave pattern and by one of 6 per-frame rotations; a depth- and normal-aware 4x4
// reconstruction gathers the 16 pattern directions, and an exponential accumulation buffer, reprojected
// from the previous frame with disocclusion rejection, gathers the 6 rotations: 96 directions per slice.
// Also a spatial-only mode (no history) and half-resolution evaluation with depth-aware upsampling, whose
// history is kept at full resolution (the accumulation runs after the upsampling) or, with gridHistory, on
// the half-resolution grid (the accumulation runs before it).
//
// Reprojection is computed from the two cameras and the current depth, which is exact for static scenes
// (moving objects would need the G-buffer's motion vectors). Rejection tests the reprojected depth against
// the previous frame's depth buffer and the world-space normals against each other.
//
// Errors: validate() and GtaoTemporal::frame() throw obscura::Error naming the bad setting or buffer.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/gtao.h"
#include "obscura/image.h"

namespace obscura::ssao {

struct GtaoTemporalSettings {
    bool temporal = true;         // accumulate over frames; false = spatial-only (16 directions per slice)
    bool halfResolution = false;  // evaluate on every other pixel in x and y, then upsample by depth
    float depthSigma = 0.05f;     // reconstruction and upsampling depth tolerance / centre depth, (0, 1]
    float rejectDepth = 0.03f;    // history is rejected where reprojected depth differs by more than this
                                  // fraction of it, (0, 1]
    float rejectNormalCos = 0.9f; // ... or where the normals' cosine is below this, [-1, 1]
    int maxHistory = 24;          // blend weight of the new frame is 1 / min(frames + 1, maxHistory),
                                  // [1, 1024]: 24 = 4 cycles of the 6 rotations
    bool packedHistory = false;   // keep the history as the GPU's packed words (obscura/history_packing.h):
                                  // visibility to 1/65535 and length to 1/32 frame in one word, world
                                  // normal and bent normal octahedral in one word each (with depth, 4
                                  // words per pixel instead of 9 floats);
                                  // the returned visibility is the stored one (with gridHistory,
                                  // upsampled from the stored one)
    bool alternatingWindow = false;  // with temporal: the reconstruction gathers a 4x4 window (each class
                                  // of the pattern once, 16 taps instead of 25) whose place alternates over
                                  // 4 frames, so that the history averages the 5x5 window's weights
                                  // (reconstructInterleaved's windowPhase = reconstructWindowPhase)
    int alternatingWindowSize = 4;  // with alternatingWindow: 4 (the 4x4 windows above) or 2: 2x2 windows
                                  // that each hold the pixel (4 taps), averaging over 4 frames to the 3x3
                                  // tent (obscura/reconstruct_window.h); for half resolution, where it keeps
                                  // the accumulated error (at full resolution it loses some: docs/QUALITY.md)
    bool gridHistory = false;     // with halfResolution: reproject and accumulate on the half-resolution
                                  // grid and upsample the accumulated result, so the history, its reads
                                  // and its writes are a quarter of the full-resolution ones; the
                                  // history planes (and historyLength()) are the grid's size

    void validate() const;        // throws obscura::Error("gtao-<field>: ...")
};

// Depth- and normal-aware gather of the 4x4 interleave: a 5x5 window whose edge rows and columns weigh 1/2,
// so each of the 16 pattern classes has the same spatial weight; taps weigh by ssao::tapWeight (the
// shared cross-bilateral weight). `values` has 1 or 3 channels (3: vectors, renormalised), `depth` and
// `normal` are the grid's own (1 and 3 channels, same size). Sky pixels keep their value.
// windowPhase 0..3 gathers a 4x4 window instead, 4..7 a 2x2 one, every tap at weight 1
// (obscura/reconstruct_window.h says which); -1: the 5x5 window. Throws obscura::Error("reconstruct
// interleaved: ...") for values of another channel count, depth or normal of another size or channel count,
// or a windowPhase outside -1..7.
Image reconstructInterleaved(const Image& values, const Image& depth, const Image& normal, float depthSigma,
                             int windowPhase = -1);
// The windowPhase of frame frameIndex: -1 without alternatingWindow, else 0, 1, 3, 2 in turn, plus 4 for
// alternatingWindowSize 2.
int reconstructWindowPhase(const GtaoTemporalSettings& settings, int frameIndex);
// Throws obscura::Error("reconstruct interleaved: ...") for a windowPhase outside -1..7 (both
// reconstructInterleaved, the CPU's and gpu::reconstructInterleaved, check with it).
void checkReconstructWindowPhase(int windowPhase);
// reconstructInterleaved's checks and messages, window phase included (the CPU's and
// gpu::reconstructInterleaved both check with it).
void checkReconstructInterleavedInputs(const Image& values, const Image& depth, const Image& normal,
                                       int windowPhase);

// Depth-aware upsampling of a half-resolution image (pixel (x, y) taken at full-resolution (2x, 2y)) to the
// G-buffer's size: bilinear weights times the depth weight of each low-resolution tap. `low` has 1 or 3
// channels (3: vectors, renormalised) and the grid's size, ceil(width / 2) x ceil(height / 2); `lowDepth` is
// its depth (1 channel). Sky pixels get 1 (1 channel) or (0, 0, 0). A surface pixel none of whose 4 taps is a
// surface (a feature thinner than the grid's spacing) gets an open surface's values: 1, or its own G-buffer
// normal. Throws obscura::Error("upsample depth-aware: ...") for images of another size or channel count.
Image upsampleDepthAware(const Image& low, const Image& lowDepth, const GBuffer& full, float depthSigma);
// upsampleDepthAware's checks and messages (the CPU's and gpu::upsampleDepthAware both check with it).
void checkUpsampleDepthAwareInputs(const Image& low, const Image& lowDepth, const GBuffer& full);

class GtaoTemporal {
public:
    // Validates both settings (throws obscura::Error).
    GtaoTemporal(const GtaoSettings& settings, const GtaoTemporalSettings& temporal);

    // Computes the next frame from its G-buffer (the camera may move; the size must stay) and returns the
    // accumulated result (visibility and view-space bent normal).
    const GtaoResult& frame(const GBuffer& gbuffer);
    // Frames accumulated per pixel in the last result: 1 where history was rejected or absent. With
    // gridHistory, per grid pixel: ceil(width / 2) x ceil(height / 2), grid pixel (x, y) at pixel (2x, 2y).
    const Image& historyLength() const { return historyLength_; }
    int framesRendered() const { return frame_; }

private:
    GtaoSettings settings_;
    GtaoTemporalSettings temporal_;
    int frame_ = 0;
    GtaoResult result_;
    Image accumulated_;  // with gridHistory, the accumulated visibility on the grid (else the result's is)
    Image bentWorld_;  // accumulated bent normals in world space, so they survive camera motion
    Image historyLength_;
    Camera previousCamera_;
    Image previousDepth_, previousNormalWorld_;  // of the history's lattice: the image, or the grid
};

} // namespace obscura::ssao
