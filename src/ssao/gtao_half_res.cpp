// GTAO at half resolution, blurred there and upsampled by depth (include/obscura/gtao_half_res.h; Jimenez
// et al. 2016, §4.1). The GPU twin is gpu::computeGtaoHalfResolution: gtao.comp over the grid, the
// separable blur reading its guide from the full-resolution planes at a stride, upsample_depth_aware.comp.
#include "obscura/gtao_half_res.h"

#include "obscura/error.h"
#include "obscura/gtao_temporal.h"
#include "obscura/parallel.h"

#include <string>

namespace obscura::ssao {

void GtaoHalfResolutionSettings::validate() const {
    blur.validate();
    if (!(depthSigma > 0.0f && depthSigma <= 1.0f)) fail("gtao-depth-sigma", "must be in (0, 1]");
}

void applyHalfResolutionCounts(GtaoSettings& settings, const GtaoSliceOverride& counts) {
    GtaoSliceOverride c = counts;
    if (c.slices == 0) c.slices = 2;
    if (c.steps == 0) c.steps = 4;
    if (!c.jitter) c.interleave = true;
    c.apply(settings);
}

GBuffer halfResolutionGrid(const GBuffer& g) {
    GBuffer grid;
    grid.camera = g.camera;
    grid.camera.width = (g.width() + 1) / 2;
    grid.camera.height = (g.height() + 1) / 2;
    grid.depth = Image(grid.width(), grid.height(), 1);
    grid.normal = Image(grid.width(), grid.height(), 3);
    for (int y = 0; y < grid.height(); ++y)
        for (int x = 0; x < grid.width(); ++x) {
            grid.depth.at(x, y) = g.depth.at(2 * x, 2 * y);
            for (int c = 0; c < 3; ++c) grid.normal.at(x, y, c) = g.normal.at(2 * x, 2 * y, c);
        }
    return grid;
}

GtaoResult computeGtaoHalfResolution(const GBuffer& g, const GtaoSettings& settings,
                                     const GtaoHalfResolutionSettings& half, int frameIndex) {
    settings.validate();
    half.validate();
    const GtaoConstants constants = gtaoConstants(settings, g.camera, frameIndex);
    checkGtaoBuffers(g, constants);
    GtaoResult r;
    if (g.width() < 1 || g.height() < 1) {
        r.visibility = Image(g.width(), g.height(), 1, 1.0f);
        r.bentNormal = Image(g.width(), g.height(), 3, 0.0f);
        return r;
    }
    const GBuffer grid = halfResolutionGrid(g);
    const GtaoDepthMips mips = buildGtaoDepthMips(g.depth, constants.mipLevels);
    Image visibility(grid.width(), grid.height(), 1, 1.0f), bent(grid.width(), grid.height(), 3, 0.0f);
    parallelFor(std::size_t(grid.height()), [&](std::size_t begin, std::size_t end) {
        for (int y = int(begin); y < int(end); ++y)
            for (int x = 0; x < grid.width(); ++x) {
                const GtaoPixel p = gtaoPixel(constants, g, &mips, 2 * x, 2 * y, interleaveIndex(x, y));
                visibility.at(x, y) = p.visibility;
                for (int c = 0; c < 3; ++c) bent.at(x, y, c) = p.bentNormal[c];
            }
    });
    visibility = bilateralFilter(visibility, grid, half.blur);
    r.visibility = upsampleDepthAware(visibility, grid.depth, g, half.depthSigma);
    r.bentNormal = upsampleDepthAware(bent, grid.depth, g, half.depthSigma);
    return r;
}

} // namespace obscura::ssao
