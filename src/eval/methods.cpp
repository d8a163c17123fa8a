// The registry of screen-space AO methods (include/obscura/ao_methods.h).
#include "obscura/ao_methods.h"

#include "obscura/alchemy.h"
#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gtao.h"
#include "obscura/gtao_half_res.h"

#include <algorithm>

namespace obscura::eval {

namespace {

ssao::AlchemySettings alchemySettings(ssao::AlchemyFormulation formulation, const MethodOptions& o) {
    ssao::AlchemySettings s;
    s.formulation = formulation;
    if (o.samples > 0) s.samples = o.samples;
    if (o.radius > 0.0f) s.radius = o.radius;
    s.seed = o.seed;
    return s;
}

AoMethod alchemy(const char* name, const char* description, ssao::AlchemyFormulation f) {
    return {name, description,
            [f](const GBuffer& g, const MethodOptions& o) {
                if (o.gpu) return gpu::bilateralFilter(*o.gpu, gpu::alchemyAO(*o.gpu, g, alchemySettings(f, o)), g, o.blur);
                Image raw = ssao::alchemyAO(g, alchemySettings(f, o));
                return ssao::bilateralFilter(raw, g, o.blur);
            },
            [f](const MethodOptions& o, int rays) { return ssao::rayTracedEquivalent(alchemySettings(f, o), rays); },
            [f](const MethodOptions& o) { return alchemySettings(f, o).samples; }};
}

// What every GTAO method takes from the options after its counts: `samples` > 0 sets the slice count to
// samples / (2 x steps per side), the horizon samples per pixel being 2 x slices x steps, unless the override
// sets it; and the MIP distance ratio.
void applySampleOptions(ssao::GtaoSettings& s, const MethodOptions& o) {
    if (o.samples > 0 && o.gtao.slices == 0) s.sliceCount = std::clamp(o.samples / (2 * s.stepsPerSide), 1, 64);
    if (o.gtaoMipRatio > 0.0f) s.mipDistanceRatio = o.gtaoMipRatio;
}

int horizonSamples(const ssao::GtaoSettings& s) { return 2 * s.sliceCount * s.stepsPerSide; }

// GTAO with a preset and the override's counts. Its integral is binary AO of the same radius (default 1 m).
ssao::GtaoSettings gtaoSettings(ssao::GtaoQuality quality, ssao::GtaoSampling sampling, const MethodOptions& o) {
    ssao::GtaoSettings s;
    ssao::applyQuality(s, quality);
    s.sampling = sampling;
    if (o.radius > 0.0f) s.radius = o.radius;
    o.gtao.apply(s);
    applySampleOptions(s, o);
    return s;
}

AoMethod gtao(const char* name, const char* description, ssao::GtaoQuality quality,
             ssao::GtaoSampling sampling = ssao::GtaoSampling::Planar) {
    return {name, description,
            [quality, sampling](const GBuffer& g, const MethodOptions& o) {
                if (o.gpu) {  // AO alone: the method's result is its visibility
                    ssao::GtaoResult r =
                        gpu::computeGtao(*o.gpu, g, gtaoSettings(quality, sampling, o), gpu::GtaoOutputs::Visibility);
                    return gpu::bilateralFilter(*o.gpu, r.visibility, g, o.blur);
                }
                ssao::GtaoResult r = ssao::computeGtao(g, gtaoSettings(quality, sampling, o));
                return ssao::bilateralFilter(r.visibility, g, o.blur);
            },
            [quality, sampling](const MethodOptions& o, int rays) {
                trace::ObscuranceSettings ref;
                ref.falloff = trace::Falloff::Binary;
                ref.radius = gtaoSettings(quality, sampling, o).radius;
                ref.rays = rays;
                return ref;
            },
            [quality, sampling](const MethodOptions& o) { return horizonSamples(gtaoSettings(quality, sampling, o)); },
            ssao::gtaoSamplingReadsMipRatio(sampling)};
}

// GTAO at half resolution (ssao::computeGtaoHalfResolution) with its measured counts unless the override
// gives others; the options' blur filters the grid before the upsampling.
AoMethod gtaoHalf(const char* name, const char* description,
                  ssao::GtaoSampling sampling = ssao::GtaoSampling::Planar) {
    auto settings = [sampling](const MethodOptions& o) {
        ssao::GtaoSettings s;
        s.sampling = sampling;
        if (o.radius > 0.0f) s.radius = o.radius;
        ssao::applyHalfResolutionCounts(s, o.gtao);
        applySampleOptions(s, o);
        return s;
    };
    return {name, description,
            [settings](const GBuffer& g, const MethodOptions& o) {
                ssao::GtaoHalfResolutionSettings half;
                half.blur = o.blur;
                if (o.gpu)
                    return gpu::computeGtaoHalfResolution(*o.gpu, g, settings(o), half, 0, gpu::GtaoOutputs::Visibility)
                        .visibility;
                return ssao::computeGtaoHalfResolution(g, settings(o), half).visibility;
            },
            [settings](const MethodOptions& o, int rays) {
                trace::ObscuranceSettings ref;
                ref.falloff = trace::Falloff::Binary;
                ref.radius = settings(o).radius;
                ref.rays = rays;
                return ref;
            },
            [settings](const MethodOptions& o) { return horizonSamples(settings(o)); }, ssao::gtaoSamplingReadsMipRatio(sampling)};
}

} // namespace

const std::vector<AoMethod>& aoMethods() {
    static const std::vector<AoMethod> methods = {
        alchemy("alchemy", "Alchemy AO, McGuire et al. 2011 eq. 10 (r 0.5 m, sigma 1, k 1, 12 samples)",
                ssao::AlchemyFormulation::Paper),
        alchemy("alchemy-chapter", "Alchemy AO as the IBL chapter writes it (c = 0.1 R, bias subtracted)",
                ssao::AlchemyFormulation::Chapter),
        gtao("gtao", "GTAO, Jimenez et al. 2016, high preset (3 slices x 3 steps per side, r 1 m, binary AO)",
             ssao::GtaoQuality::High),
        gtao("gtao-ultra", "GTAO, ultra preset (9 slices x 3 steps per side, r 1 m, binary AO)", ssao::GtaoQuality::Ultra),
        gtao("gtao-nearest", "GTAO high preset with nearest-pixel horizon samples (1 depth read per sample, as XeGTAO)",
             ssao::GtaoQuality::High, ssao::GtaoSampling::Nearest),
        gtao("gtao-mip", "GTAO high preset with a depth MIP chain: far samples from 4 coarser levels, near ones "
                         "nearest-pixel (as XeGTAO)",
             ssao::GtaoQuality::High, ssao::GtaoSampling::Mip),
        gtao("gtao-planar-mip", "GTAO high preset with a depth MIP chain: far samples from 4 coarser levels, near "
                                "ones planar",
             ssao::GtaoQuality::High, ssao::GtaoSampling::PlanarMip),
        gtao("gtao-planar-nearest", "GTAO high preset with planar horizon samples within 14 pixels and nearest-pixel "
                                    "ones beyond (no chain)",
             ssao::GtaoQuality::High, ssao::GtaoSampling::PlanarNearest),
        gtaoHalf("gtao-half", "GTAO at half resolution (2 slices x 4 steps per side, 4x4 interleave, r 1 m), the "
                              "blur on the grid, depth-aware upsample"),
        gtaoHalf("gtao-half-planar-nearest", "gtao-half with planar horizon samples within 14 pixels and nearest-pixel "
                                             "ones beyond",
                 ssao::GtaoSampling::PlanarNearest),
    };
    return methods;
}

std::string aoMethodNames() {
    std::string names;
    for (const AoMethod& m : aoMethods()) names += (names.empty() ? "" : ", ") + m.name;
    return names;
}

const AoMethod& findAoMethod(const std::string& name, const std::string& flag) {
    for (const AoMethod& m : aoMethods())
        if (m.name == name) return m;
    fail(flag, "unknown AO method '" + name + "' (known: " + aoMethodNames() + ")");
}

std::vector<const AoMethod*> parseMethodList(const std::string& list) {
    std::vector<const AoMethod*> out;
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t end = list.find(',', start);
        if (end == std::string::npos) end = list.size();
        const std::string name = list.substr(start, end - start);
        if (name.empty()) fail("--methods", "empty method name in '" + list + "'");
        const AoMethod* m = &findAoMethod(name);
        if (std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
        start = end + 1;
    }
    return out;
}

} // namespace obscura::eval
