// The depth MIP chain of GtaoSampling::Mip and PlanarMip (after XeGTAO's depth prefilter, Intel 2021): coarse
// levels of inverse depth, each texel the mean of its four children, or sky if any of them is (obscura/gtao_mips.h
// holds the filter, the sizes and the layout, shared with gtao_mips.comp).
#include "obscura/gtao.h"

#include <algorithm>
#include <cassert>
#include <cstddef>

namespace obscura::ssao {

float GtaoDepthMips::at(int level, int x, int y) const {
    return texels[std::size_t(offset[level]) + std::size_t(y) * std::size_t(levelWidth[level]) + std::size_t(x)];
}

GtaoDepthMips buildGtaoDepthMips(const Image& depth, int levels) {
    assert(depth.width >= 1 && depth.height >= 1 && levels >= 0 && levels <= GTAO_MAX_MIP_LEVELS);
    GtaoDepthMips m;
    m.width = depth.width;
    m.height = depth.height;
    m.levels = levels;
    m.texels.assign(std::size_t(gtaoMipOffset(m.width, m.height, levels + 1)), 0.0f);
    for (int level = 1; level <= levels; ++level) {
        m.offset[level] = gtaoMipOffset(m.width, m.height, level);
        m.levelWidth[level] = gtaoMipSize(m.width, level);
    }
    for (int level = 1; level <= levels; ++level) {
        const int childWidth = gtaoMipSize(m.width, level - 1), childHeight = gtaoMipSize(m.height, level - 1);
        const int w = m.levelWidth[level], h = gtaoMipSize(m.height, level);
        float* out = m.texels.data() + m.offset[level];
        // Level 0 is the depth buffer: its inverse, 0 for sky (1 / +inf is 0; 1e30 and beyond count as sky).
        auto child = [&](int x, int y) {
            if (level > 1) return m.at(level - 1, x, y);
            const float d = depth.at(x, y);
            return d < 1e30f ? 1.0f / d : 0.0f;
        };
        for (int y = 0; y < h; ++y) {
            const int y0 = 2 * y, y1 = std::min(2 * y + 1, childHeight - 1);
            for (int x = 0; x < w; ++x) {
                const int x0 = 2 * x, x1 = std::min(2 * x + 1, childWidth - 1);
                out[std::size_t(y) * std::size_t(w) + std::size_t(x)] =
                    gtaoMipFilter(child(x0, y0), child(x1, y0), child(x0, y1), child(x1, y1));
            }
        }
    }
    return m;
}

} // namespace obscura::ssao
