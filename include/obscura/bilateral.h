// Depth- and normal-aware (cross-bilateral) blur of a screen-space AO buffer, for any AO method that
// writes one value per G-buffer pixel.
//
// Two filters, as the sources give them:
//  - Separable: McGuire et al. 2011, "The Alchemy Screen-Space Ambient Obscurance Algorithm", Fig. 6 and
//    Table 1: two 1-D cross-bilateral passes (horizontal then vertical), 13 taps by default, weighted by
//    "camera-space proximity" (§2): spatial Gaussian x exp(-dd^2 / 2 sigma_d^2).
//  - TwoD: "Where Corners Stay Dark" (Alchemy SSAO in an IBL renderer): a (2 radius + 1)^2 window with
//    weight = spatial Gaussian x max(0, N . Ni) x exp(-dd^2 / 2 sigma_d^2).
// The normal factor is a setting of both (NormalWeight): by default each filter weighs as its source does.
// With the same weights the separable filter is the cheap approximation of the 2-D one.
//
// The depth tolerance sigma_d is relative to the centre pixel's depth (sigma_d = depthSigma * d), so one
// setting works for a 10 cm figurine and a 100 m courtyard. Sky pixels (depth +inf) never contribute
// and keep their input value. Each output is the weighted sum divided by the sum of weights, so a constant
// image comes out unchanged bit for bit up to rounding, whatever the edges.
//
// Errors: validate() and bilateralFilter() throw obscura::Error for bad settings or mismatched buffers.
// The per-pixel functions (tapWeight) are hot paths and check nothing.
#pragma once

#include "obscura/gbuffer.h"
#include "obscura/image.h"

#include <cmath>
#include <vector>

namespace obscura::ssao {

enum class BlurMode {
    None,       // no filtering: the raw estimate
    Separable,  // two 1-D passes (the paper)
    TwoD,       // one square 2-D pass (the chapter)
};

enum class NormalWeight { Auto, On, Off };

// The largest blur radius the filters accept (BilateralSettings::radius); the GPU blur's shared-memory lines
// are sized for it (gpu::kBilateralMaxRadius, which static_asserts that it holds this many).
inline constexpr int kMaxBlurRadius = 32;

struct BilateralSettings {
    BlurMode mode = BlurMode::Separable;
    // Taps on each side of the centre: 2 radius + 1 taps per axis; [1, kMaxBlurRadius]. 6 gives the paper's
    // 13 taps.
    int radius = 6;
    // sigma_d / centre depth: unitless, [1e-6, 10]. 0.05 lets a 5% depth change through at weight 0.6 and
    // stops a 20% step (weight 3e-4), so surfaces at a silhouette do not bleed into each other.
    float depthSigma = 0.05f;
    // Multiply each tap by max(0, N . Ni), which keeps the blur from crossing creases at equal depth. Auto:
    // off for Separable (the paper weighs by depth alone, and the normals make that pass about 1.6x slower),
    // on for TwoD (the chapter's weight). docs/QUALITY.md measures both; docs/PERFORMANCE.md times both.
    NormalWeight normalWeight = NormalWeight::Auto;

    bool usesNormals() const {
        return normalWeight == NormalWeight::On || (normalWeight == NormalWeight::Auto && mode == BlurMode::TwoD);
    }
    void validate() const;  // throws obscura::Error naming the bad field
};

// The half kernel w[0..radius] of a Gaussian with sigma = radius / 2 (the kernel edge sits at exp(-2)),
// normalised so that the full symmetric kernel w[0] + 2 (w[1] + ... + w[radius]) is 1: the centre tap
// counts once and every other tap twice (the chapter's off-by-one). Computed in double; the float sum of
// the full kernel is 1 within a few ulps. radius in [1, kMaxBlurRadius] (asserted).
std::vector<float> gaussianHalfKernel(int radius);

// Weight of a tap (the definition; the filter's vectorised loops evaluate the same expression with a
// polynomial exp, relative error < 2e-5 in the 2-D filter, < 8e-5 in the separable one) with spatial weight `spatial` at depth di, normal ni, relative to a centre at depth d
// (finite) with normal n. invTwoSigmaD2 = 1 / (2 (depthSigma d)^2). Sky taps (di = +inf) weigh 0.
inline float tapWeight(float spatial, float d, Vec3 n, float di, Vec3 ni, float invTwoSigmaD2, bool useNormal) {
    float dd = di - d;
    float w = spatial * std::exp(-dd * dd * invTwoSigmaD2);
    if (useNormal) w *= std::fmax(0.0f, dot(n, ni));
    return w;
}

// One 1-D pass along x (axis 0) or y (axis 1). `ao` has 1 channel and the G-buffer's size. The separable
// filter runs both passes fused over tiles (src/ssao/bilateral_separable.cpp) with the same arithmetic, so
// bilateralPass(bilateralPass(ao, 0), 1) gives the same bits as it.
Image bilateralPass(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings, int axis);

// The square (2 radius + 1)^2 filter of the chapter.
Image bilateral2D(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings);

// Validates settings and that `ao` is 1 channel of the G-buffer's size with depth and normal present;
// throws obscura::Error otherwise. What every filter here (and its GPU pass) checks first.
void checkBilateralInputs(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings);

// Filters by settings.mode (None returns a copy). Validates settings and that `ao` is 1 channel of the
// G-buffer's size with depth and normal present; throws obscura::Error otherwise. Deterministic: the same
// bits for any number of threads.
Image bilateralFilter(const Image& ao, const GBuffer& gbuffer, const BilateralSettings& settings);

} // namespace obscura::ssao
