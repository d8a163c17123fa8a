// `obscura compare`: screen-space AO methods against the ray-traced integral each one estimates, on one
// G-buffer: MAE, RMSE, bias and max error per method, and a side-by-side picture.
#include "ao_options.h"
#include "cli_common.h"
#include "commands.h"
#include "gpu_flags.h"
#include "gtao_cli.h"

#include "obscura/ao_methods.h"
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/metrics.h"
#include "obscura/parallel.h"
#include "obscura/render.h"
#include "obscura/trace.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>

namespace obscura::cli {

namespace {

struct CompareOptions {
    std::string scene = "demo";
    std::string methods = "alchemy";
    std::string output = "compare.png";
    int rays = 256;
    int samples = 0;
    float radius = 0.0f;
    std::string blur = "none";
    std::string blurNormalWeight = "auto";
    int blurRadius = 6;
    float range = 0.5f;
    unsigned seed = 0;
    int threads = 0;
    bool json = false;
    bool quiet = false;
    CameraOptions camera;
    GpuFlags gpu;
    GtaoSliceFlags gtao;
    float gtaoMipRatio = 0.0f;  // eval::MethodOptions::gtaoMipRatio
    std::vector<const CLI::Option*> gtaoFlags;  // ignored, with a warning, when no GTAO method is compared
    std::vector<const CLI::Option*> blurFlags;  // --blur-radius, --blur-normal-weight: ignored with --blur none
};

// A float as JSON's shortest decimal that reads back as the same float (0.01f went out as 0.009999999776482582),
// and a value that is no number (an infinite radius, the noise of too few rays) as null.
nlohmann::json jsonNumber(float v) {
    if (!std::isfinite(v)) return nullptr;
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    return std::strtod(std::string(text, end).c_str(), nullptr);
}

// 3 x 5 glyphs of the legend's labels, one row of 3 bits per line, top first.
const std::map<char, std::array<int, 5>> kGlyphs = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {'+', {0, 2, 7, 2, 0}}, {' ', {0, 0, 0, 0, 0}}, {'e', {7, 4, 7, 4, 7}}};

// A number for the legend and the table: %.3g by default, in the glyphs' characters.
std::string shortNumber(float v, const char* format = "%.3g") {
    char text[32];
    std::snprintf(text, sizeof text, format, double(v));
    return text;
}

void drawText(Image& img, int x0, int y0, const std::string& text, int scale) {
    for (char ch : text) {
        auto it = kGlyphs.find(ch);
        if (it != kGlyphs.end())
            for (int row = 0; row < 5; ++row)
                for (int col = 0; col < 3; ++col)
                    if (it->second[std::size_t(row)] & (4 >> col))
                        for (int sy = 0; sy < scale; ++sy)
                            for (int sx = 0; sx < scale; ++sx) {
                                int x = x0 + col * scale + sx, y = y0 + row * scale + sy;
                                if (x >= 0 && y >= 0 && x < img.width && y < img.height)
                                    for (int c = 0; c < 3; ++c) img.at(x, y, c) = 1.0f;
                            }
        x0 += 4 * scale;
    }
}

void blit(Image& dst, const Image& src, int x0, int y0) {
    for (int y = 0; y < src.height; ++y)
        for (int x = 0; x < src.width; ++x)
            for (int c = 0; c < 3; ++c) dst.at(x0 + x, y0 + y, c) = src.at(x, y, src.channels == 1 ? 0 : c);
}

// Display (sRGB-encoded) grey picture of an AO buffer.
Image aoPicture(const Image& ao) {
    render::ShadeSettings s;
    s.tonemap = render::Tonemap::None;
    Image rgb(ao.width, ao.height, 3);
    for (std::size_t i = 0; i < ao.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) rgb.pixels[3 * i + std::size_t(c)] = ao.pixels[i];
    return render::toDisplay(rgb, s);
}

void run(const CompareOptions& o) {
    checkOutputPath("-o", o.output, {".png"});
    const std::vector<const eval::AoMethod*> methods = eval::parseMethodList(o.methods);
    const bool anyGtao =
        std::any_of(methods.begin(), methods.end(), [](const eval::AoMethod* m) { return m->name.starts_with("gtao"); });
    // An ignored flag is said to be ignored once, and not then refused for its value.
    if (!anyGtao) warnIgnored(o.gtaoFlags, "applies to the gtao methods, and --methods has none");
    if (o.blur == "none") warnIgnored(o.blurFlags, "applies to a blur, and --blur is none");
    if (o.rays < 1 || o.rays > 65536) fail("--rays", "must be in [1, 65536]");
    if (o.samples < 0 || o.samples > 1024) fail("--samples", "must be in [0, 1024] (0: the method's default)");
    if (!(o.radius >= 0.0f && o.radius <= 1e4f)) fail("--radius", "must be in [0, 1e4] m (0: the method's default)");
    if (!(o.range > 0.0f && o.range <= 1.0f)) fail("--range", "must be in (0, 1]");
    if (anyGtao) {
        o.gtao.validate();
        validateGtaoMipRatioOverride(o.gtaoMipRatio);
        if (o.samples > 0 && o.gtao.value.slices != 0)
            fail("--gtao-slices", "sets what --samples sets for GTAO: give one of them");
    }
    eval::MethodOptions mo;
    mo.samples = o.samples;
    if (anyGtao) {
        mo.gtao = o.gtao.value;
        mo.gtaoMipRatio = o.gtaoMipRatio;
    }
    mo.radius = o.radius;
    mo.seed = o.seed;
    if (anyGtao)
        warnGtaoMipRatioUnread(o.gtaoMipRatio,
                               std::any_of(methods.begin(), methods.end(), [](const eval::AoMethod* m) { return m->readsMipRatio; }),
                               "no method of --methods reads it");
    // GTAO takes whole slices of 2 x steps samples, 1 to 64 of them: say so where --samples asked for another count.
    for (const eval::AoMethod* m : methods)
        if (o.samples > 0 && m->samplesPerPixel(mo) != o.samples)
            std::fprintf(stderr, "obscura: warning: --samples %d: %s takes %d samples per pixel (whole slices of 2 x its "
                                 "steps per side, 1 to 64 slices)\n",
                         o.samples, m->name.c_str(), m->samplesPerPixel(mo));
    mo.blur.mode = o.blur == "none" ? ssao::BlurMode::None : o.blur == "2d" ? ssao::BlurMode::TwoD : ssao::BlurMode::Separable;
    if (mo.blur.mode != ssao::BlurMode::None) {
        mo.blur.normalWeight = normalWeightFromFlag(o.blurNormalWeight);
        mo.blur.radius = o.blurRadius;
    }
    try {
        mo.blur.validate();
    } catch (const Error& e) {
        throw Error("--" + std::string(e.what()));  // "--blur-radius: ..."
    }
    o.gpu.validate();
    const std::unique_ptr<gpu::Context> context = o.gpu.open();
    mo.gpu = context.get();

    ThreadLimit limit(o.threads, "--threads");
    LoadedScene loaded = loadSceneArgument(o.scene);
    const Camera camera = o.camera.apply(loaded);
    trace::Tracer tracer(loaded.scene);
    const bool showProgress = progressWanted(o.quiet || o.json);
    GBuffer g;
    {
        Progress p("primary rays", showProgress);
        g = trace::renderGBuffer(tracer, camera, {}, [&](double f) { p(f); });
    }
    // Errors over no pixels are no errors: a view of only sky reported MAE, RMSE and max of 0, which a script
    // reads as exact agreement.
    if (std::none_of(g.depth.pixels.begin(), g.depth.pixels.end(), [](float d) { return d < 1e30f; }))
        fail(loaded.name, "the camera sees no surface, every pixel is sky: nothing to compare (aim it with "
                          "--camera-from and --camera-to)");
    const Image sky = render::proceduralSky();
    const render::SH9 sh = render::projectEnvironment(sky);
    const render::ShadeSettings shading;

    // A reference and its Monte Carlo noise: the RMS over surface pixels of each pixel's standard error, from
    // two nets of its rays (ObscuranceEstimator::estimate; high side). The noise adds to every method's
    // errors (E[RMSE^2] = RMSE^2 of the method + noise^2), so it says how far the figures can be read.
    struct Reference {
        Image ao;
        double noise = 0.0;
    };
    struct Row {
        const eval::AoMethod* method;
        const Reference* reference;
        Image ao;
        eval::ErrorStats stats;
        double ms;
        trace::ObscuranceSettings ref;
    };
    std::vector<Row> rows;
    // References are shared between methods that estimate the same integral.
    std::map<std::tuple<int, float, float, float, float>, Reference> references;
    for (const eval::AoMethod* m : methods) {
        Row r{m, nullptr, {}, {}, 0.0, m->reference(mo, o.rays)};
        r.ref.seed = o.seed;
        auto start = std::chrono::steady_clock::now();
        r.ao = m->compute(g, mo);
        r.ms = 1000.0 * secondsSince(start);
        auto key = std::make_tuple(int(r.ref.falloff), r.ref.radius, r.ref.alchemyU, r.ref.alchemyScale, r.ref.halfDistance);
        auto it = references.find(key);
        if (it == references.end()) {
            checkRayReach(loaded, r.ref.reach(), "--radius");
            Progress p("ray-traced reference", showProgress);
            Reference ref;
            Image standardError;
            ref.ao = trace::ambientObscurance(tracer, g, r.ref, [&](double f) { p(f); }, &standardError);
            double sum = 0.0;
            std::size_t n = 0;
            for (std::size_t i = 0; i < standardError.pixels.size(); ++i)
                if (g.depth.pixels[i] < 1e30f) {
                    sum += double(standardError.pixels[i]) * double(standardError.pixels[i]);
                    ++n;
                }
            ref.noise = std::sqrt(sum / double(n));  // NaN under 8 rays: too few to tell it
            it = references.emplace(key, std::move(ref)).first;
        }
        r.reference = &it->second;
        r.stats = eval::errorStats(r.ao, r.reference->ao, g);
        rows.push_back(std::move(r));
    }

    reportValidation(context.get());
    const char* const falloffNames[] = {"binary", "alchemy", "exponential"};
    nlohmann::json report;
    report["scene"] = loaded.name;
    report["device"] = context ? context->device().name : "CPU";
    report["width"] = camera.width;
    report["height"] = camera.height;
    report["rays"] = o.rays;
    report["seed"] = o.seed;
    report["samples"] = o.samples;
    report["radius"] = jsonNumber(o.radius);
    report["blur"] = {{"mode", o.blur}};
    if (o.blur != "none") {
        report["blur"]["radius"] = o.blurRadius;
        report["blur"]["normal_weight"] = o.blurNormalWeight;
    }
    if (anyGtao && o.gtaoMipRatio > 0.0f) report["gtao_mip_ratio"] = jsonNumber(o.gtaoMipRatio);
    report["surface_pixels"] = rows.front().stats.pixels;
    for (const Row& r : rows) {
        nlohmann::json reference = {{"falloff", falloffNames[int(r.ref.falloff)]},
                                    {"radius", jsonNumber(r.ref.radius)},
                                    {"noise", jsonNumber(float(r.reference->noise))}};
        if (r.ref.falloff == trace::Falloff::Alchemy) {
            reference["u"] = jsonNumber(r.ref.alchemyU);
            reference["scale"] = jsonNumber(r.ref.alchemyScale);
        }
        if (r.ref.falloff == trace::Falloff::Exponential) reference["half_distance"] = jsonNumber(r.ref.halfDistance);
        report["methods"].push_back({{"name", r.method->name},
                                     {"mae", r.stats.mae},
                                     {"rmse", r.stats.rmse},
                                     {"bias", r.stats.bias},
                                     {"max", r.stats.maxError},
                                     {"ms", r.ms},
                                     {"samples_per_pixel", r.method->samplesPerPixel(mo)},
                                     {"reference", reference}});
    }

    // Picture: one row per method: lit frame | method AO | ray-traced AO | signed error; legend below.
    const int w = camera.width, h = camera.height, gap = 4, scale = std::clamp(h / 60, 2, 16);
    const int legendH = 12 * scale + 3 * gap;
    Image sheet(4 * w + 5 * gap, int(rows.size()) * (h + gap) + gap + legendH, 3, 0.12f);
    render::ShadeSettings srgbOnly;
    srgbOnly.tonemap = render::Tonemap::None;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        const int y0 = gap + int(i) * (h + gap);
        blit(sheet, render::toDisplay(render::shade(g, sh, r.ao, sky).color, shading), gap, y0);
        blit(sheet, aoPicture(r.ao), 2 * gap + w, y0);
        blit(sheet, aoPicture(r.reference->ao), 3 * gap + 2 * w, y0);
        // signedErrorImage() is linear light, like the other columns before toDisplay: encode it the same way.
        blit(sheet, render::toDisplay(eval::signedErrorImage(r.ao, r.reference->ao, g, o.range), srgbOnly), 4 * gap + 3 * w, y0);
    }
    // Legend under the error column: the colour ramp from -range (too dark) to +range (too light).
    const int lx = 4 * gap + 3 * w, ly = sheet.height - legendH + gap, lw = w;
    Image ramp(lw, 1, 3);
    for (int x = 0; x < lw; ++x) {
        const Vec3 c = eval::signedErrorColor((2.0f * (float(x) + 0.5f) / float(lw) - 1.0f) * o.range, o.range);
        for (int k = 0; k < 3; ++k) ramp.at(x, 0, k) = c[k];
    }
    ramp = render::toDisplay(ramp, srgbOnly);
    for (int x = 0; x < lw; ++x)
        for (int y = 0; y < 5 * scale; ++y)
            for (int k = 0; k < 3; ++k) sheet.at(lx + x, ly + y, k) = ramp.at(x, 0, k);
    // Three significant digits (0.125 was printed "0.12", 1e-30 as 31 zeros cut at the label's end); the
    // glyphs have an 'e' for small ranges.
    const std::string rangeText = shortNumber(o.range), minus = "-" + rangeText, plus = "+" + rangeText;
    // Glyphs are 4 x scale wide with their space. The labels shrink to fit the ramp and leave out the "0" where
    // it would overlap them; where even the ends cannot fit at scale 1 they run left into the blank area under
    // the reference column, and where the whole sheet is too narrow the table's line carries the range alone.
    const auto width = [](const std::string& t, int k) { return int(t.size()) * 4 * k; };
    int textScale = scale;
    while (textScale > 1 && width(minus + "  " + plus, textScale) > lw) --textScale;
    const int ty = ly + 6 * scale;
    if (width(minus + " 0 " + plus, textScale) <= lw) drawText(sheet, lx + lw / 2 - 2 * textScale, ty, "0", textScale);
    const int ends = width(minus + " " + plus, textScale);
    if (ends <= lx + lw) {
        drawText(sheet, std::min(lx, lx + lw - ends), ty, minus, textScale);
        drawText(sheet, lx + lw - width(plus, textScale), ty, plus, textScale);
    }
    writePng(o.output, sheet);

    if (o.json) {
        report["image"] = o.output;
        std::printf("%s\n", report.dump(2).c_str());
        return;
    }
    std::printf("obscura compare: scene %s, %dx%d, %zu surface pixels, reference %d rays/px, methods on %s; error = "
                "method - ray traced\n\n",
                loaded.name.c_str(), camera.width, camera.height, rows.front().stats.pixels, o.rays,
                context ? context->device().name.c_str() : "the CPU");
    std::printf("%-24s %8s %8s %9s %8s %9s %5s %9s\n", "method", "MAE", "RMSE", "bias", "max", "ms", "spp", "ref noise");
    bool noisy = false;
    for (const Row& r : rows) {
        const double noise = r.reference->noise;
        std::printf("%-24s %8.4f %8.4f %+9.4f %8.4f %9.1f %5d %9s\n", r.method->name.c_str(), r.stats.mae, r.stats.rmse,
                    r.stats.bias, r.stats.maxError, r.ms, r.method->samplesPerPixel(mo),
                    std::isfinite(noise) ? shortNumber(float(noise), "%.4f").c_str() : "-");
        noisy = noisy || !std::isfinite(noise) || noise > 0.5 * r.stats.rmse;
    }
    if (noisy)
        std::printf("\nref noise: the reference's own RMS standard error, part of each RMSE; where it is over half of "
                    "one (or unknown, under 8 rays), raise --rays before reading that row's figures\n");
    std::printf("\nwrote %s: rows = methods; columns = lit frame, method AO, ray-traced AO, signed error "
                "(blue: too dark, red: too light, +-%s)\n",
                o.output.c_str(), rangeText.c_str());
}

} // namespace

void addCompareCommand(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Screen-space AO methods against the ray-traced integral they estimate: MAE, RMSE, bias, max");
    cmd->add_option("scene", o->scene, "Built-in scene name or a .gltf/.glb/.obj/.ply file")->capture_default_str();
    cmd->add_option("--methods", o->methods, "Comma-separated methods: " + eval::aoMethodNames() + " (at half resolution: --blur filters its grid before the upsampling)")->capture_default_str();
    cmd->add_option("-o,--output", o->output, "Side-by-side PNG")->capture_default_str();
    cmd->add_option("--rays", o->rays, "Rays per pixel of the ray-traced reference, [1, 65536]; its noise is "
                    "reported as 'ref noise' (RMS standard error), and adds to every RMSE")
        ->capture_default_str();
    cmd->add_option("--samples", o->samples, "Samples per pixel of every method (0: each method's default); GTAO takes whole slices of 2 x steps per "
                    "side, 1 to 64, and says so where that is another count")
        ->capture_default_str();
    cmd->add_option("--radius", o->radius, "World radius of every method, m (0: each method's default)")
        ->capture_default_str();
    cmd->add_option("--blur", o->blur, "Filter the methods' AO: none, separable or 2d (the reference is not filtered; gtao-half's grid, before its upsampling)")
        ->check(CLI::IsMember({"none", "separable", "2d"}))
        ->capture_default_str();
    o->blurFlags = optionsAddedBy(*cmd, [&] {
        cmd->add_option("--blur-radius", o->blurRadius, "Taps on each side of the blur's centre, [1, 32] (6: 13 taps)")
            ->capture_default_str();
        cmd->add_option("--blur-normal-weight", o->blurNormalWeight, kNormalWeightHelp)
            ->check(CLI::IsMember({"auto", "on", "off"}))
            ->capture_default_str();
    });
    cmd->add_option("--range", o->range, "Error mapped to full colour in the heat map, (0, 1]")->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the methods and of the reference rays")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress bars");
    o->gtaoFlags = optionsAddedBy(*cmd, [&] {
        o->gtao.add(*cmd, "GTAO methods");
        addGtaoMipRatioOverride(*cmd, o->gtaoMipRatio);
    });
    o->camera.add(*cmd);
    o->gpu.add(*cmd, "the methods (estimators and blur)", "The reference stays ray traced on the CPU.");
    cmd->callback([o] { run(*o); });
}

} // namespace obscura::cli
