// Flags of the Alchemy AO settings and of the cross-bilateral blur (see ao_options.h).
#include "ao_options.h"

#include "cli_common.h"

#include "obscura/error.h"

#include <CLI/CLI.hpp>

#include <cmath>

namespace obscura::cli {

ssao::NormalWeight normalWeightFromFlag(const std::string& value) {
    return value == "on" ? ssao::NormalWeight::On : value == "off" ? ssao::NormalWeight::Off : ssao::NormalWeight::Auto;
}

const char* const kNormalWeightHelp = "Also weigh blur taps by max(0, N . Ni) so the blur stops at creases: on, off, or "
                                      "auto (off for separable, as the paper; on for 2d, as the chapter)";

void BlurFlags::add(CLI::App& app) {
    app.add_option("--blur", mode,
                   "Cross-bilateral filter of the AO: none, separable (two 1-D passes, the paper) or 2d (the chapter)")
        ->check(CLI::IsMember({"none", "separable", "2d"}))
        ->capture_default_str();
    detailFlags = optionsAddedBy(app, [&] {
        app.add_option("--blur-radius", radius, "Blur taps on each side of the centre, [1, 32] (6: 13 taps)")
            ->capture_default_str();
        app.add_option("--blur-depth-sigma", depthSigma,
                       "Depth tolerance of the blur relative to depth, [1e-6, 10] (0.05: 5% of the pixel's depth)")
            ->capture_default_str();
        app.add_option("--blur-normal-weight", normalWeight, kNormalWeightHelp)
            ->check(CLI::IsMember({"auto", "on", "off"}))
            ->capture_default_str();
    });
}

void BlurFlags::warnUnread() const {
    if (mode == "none") warnIgnored(detailFlags, "applies to a blur, and --blur is none");
}

ssao::BilateralSettings BlurFlags::settings() const {
    ssao::BilateralSettings s;
    s.mode = mode == "none" ? ssao::BlurMode::None : mode == "2d" ? ssao::BlurMode::TwoD : ssao::BlurMode::Separable;
    if (s.mode == ssao::BlurMode::None) return s;  // what warnUnread() calls ignored is not checked either
    s.radius = radius;
    s.depthSigma = depthSigma;
    s.normalWeight = normalWeightFromFlag(normalWeight);
    try {
        s.validate();
    } catch (const Error& e) {
        throw Error("--" + std::string(e.what()));
    }
    return s;
}

void AlchemyFlags::add(CLI::App& app, bool withRadius) {
    app.add_option("--ao-preset", preset,
                   "Alchemy calibration of the IBL chapter: scene (R 0.05, scale 2.0, contrast 3.0) or closeup "
                   "(R 0.08, scale 1.7, contrast 2.2); flags given as well override it")
        ->check(CLI::IsMember({"scene", "closeup"}));
    formulationOption = app.add_option("--ao-formulation", formulation,
                                       "Alchemy estimator: paper (eq. 10) or chapter (c = 0.1 R, bias subtracted)")
                            ->check(CLI::IsMember({"paper", "chapter"}))
                            ->capture_default_str();
    if (withRadius)
        radiusOption = app.add_option("--ao-radius", radius,
                                      "Radius r in meters, (0, 1e4]: Alchemy's r (default 0.5, or the preset's), or the "
                                      "GTAO methods' (default 1)");
    intensityOption = app.add_option("--ao-intensity", intensity, "Alchemy intensity: sigma (paper) or scale (chapter)")
                          ->capture_default_str();
    contrastOption = app.add_option("--ao-contrast", contrast, "Alchemy contrast k, [0.01, 100]")->capture_default_str();
    biasOption = app.add_option("--ao-bias", bias, "Alchemy bias in meters: beta (paper, times depth) or bias (chapter)")
                     ->capture_default_str();
    samplesOption = app.add_option("--ao-samples", samples, "Alchemy samples per pixel, [1, 1024]")->capture_default_str();
    app.add_option("--ao-guard-band", guardBand,
                   "Pixels of extra G-buffer on each side so occluders just off screen count, [0, 1024]")
        ->capture_default_str();
    app.add_option("--ao-max-radius-px", maxRadiusPixels,
                   "Largest screen radius of the Alchemy sample disc in pixels, [1, 4096]")
        ->capture_default_str();
    app.add_option("--ao-lod-radius-px", lodRadiusPixels,
                   "Fewer samples with distance: pixels whose disc is smaller than this many px get proportionally "
                   "fewer samples (at least 1/4), [0, 4096]; 0 = off")
        ->capture_default_str();
    app.add_flag("--ao-normals-from-depth", normalsFromDepth, "Rebuild normals from depth instead of the G-buffer's");
}

ssao::AlchemySettings AlchemyFlags::settings(const std::string& radiusText) const {
    ssao::AlchemySettings s;
    if (!preset.empty()) s = ssao::alchemyPreset(preset);
    if (formulationOption && formulationOption->count() > 0)
        s.formulation = formulation == "chapter" ? ssao::AlchemyFormulation::Chapter : ssao::AlchemyFormulation::Paper;
    if (!radiusText.empty()) {
        float r = parseRadius("--ao-radius", radiusText);
        if (!std::isfinite(r)) fail("--ao-radius", "must be finite for alchemy");
        s.radius = r;
    } else if (radiusOption && radiusOption->count() > 0) {
        s.radius = radius;
    }
    if (intensityOption && intensityOption->count() > 0) s.intensity = intensity;
    if (contrastOption && contrastOption->count() > 0) s.contrast = contrast;
    if (biasOption && biasOption->count() > 0) s.bias = bias;
    if (samplesOption && samplesOption->count() > 0) s.samples = samples;
    s.guardBand = guardBand;
    s.maxRadiusPixels = maxRadiusPixels;
    s.lodRadiusPixels = lodRadiusPixels;
    s.normalsFromDepth = normalsFromDepth;
    s.seed = seed;
    try {
        s.validate();
    } catch (const Error& e) {
        throw Error("--ao-" + std::string(e.what()));
    }
    return s;
}

} // namespace obscura::cli
