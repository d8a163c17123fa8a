// GTAO at half resolution without a history (Jimenez et al. 2016, §4.1, evaluates GTAO at half resolution;
// here without its temporal accumulation): the kernel runs on every other pixel in x and y (full-resolution
// pixel (2x, 2y) for grid pixel (x, y)), a bilateral blur filters the grid, and a depth-aware upsampling
// brings it back to the G-buffer's size. A quarter of the kernel's work per frame, so it can afford more
// samples per grid pixel: 2 slices of 4 steps rotated by the 4x4 interleave with a 5-tap blur beat the full-
// resolution high preset with its 13-tap blur on every view of docs/QUALITY.md, at 4 horizon samples per
// full-resolution pixel instead of 18.
//
// Errors: validate() and computeGtaoHalfResolution() throw obscura::Error naming the bad setting or buffer.
#pragma once

#include "obscura/bilateral.h"
#include "obscura/gbuffer.h"
#include "obscura/gtao.h"

namespace obscura::ssao {

struct GtaoHalfResolutionSettings {
    // Filters the grid's visibility before the upsampling (its guide: the grid's depth and normals); the
    // bent normals are upsampled unfiltered, as the full-resolution passes leave them. Mode None: no blur.
    BilateralSettings blur{BlurMode::Separable, 2};
    float depthSigma = 0.05f;  // upsampling: depth tolerance / centre depth, (0, 1] (GtaoTemporalSettings')

    void validate() const;  // throws obscura::Error("blur-...: ..." or "gtao-depth-sigma: ...")
};

// The counts this pass was measured with (docs/QUALITY.md) where `counts` gives none: 2 slices, 4 steps per
// side, and the 4x4 interleave unless counts.jitter. Then counts applies as GtaoSliceOverride::apply does.
// What `obscura bench --gpu`'s gtao-half case and the gtao-half method of `compare` and `ao` run.
void applyHalfResolutionCounts(GtaoSettings& settings, const GtaoSliceOverride& counts);

// The grid's G-buffer: depth and normal of full-resolution pixel (2x, 2y) at (x, y), ceil(w / 2) x
// ceil(h / 2), its camera of that size (albedo and motion left empty). The blur's guide.
GBuffer halfResolutionGrid(const GBuffer& gbuffer);

// Visibility and view-space bent normals at the G-buffer's size. The grid pixel (x, y) takes the
// interleave index of (x, y) (with settings.interleave), the jitter hash of (2x, 2y) (with settings.jitter)
// and frameIndex as gtaoConstants does. Validates both settings and the G-buffer's shape.
GtaoResult computeGtaoHalfResolution(const GBuffer& gbuffer, const GtaoSettings& settings,
                                     const GtaoHalfResolutionSettings& half, int frameIndex = 0);

} // namespace obscura::ssao
