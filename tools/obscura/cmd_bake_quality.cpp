// `obscura bench bake-quality`: baked vertices against dense ray tracing at every vertex, and per-vertex
// point sampling with the same ray budget, on built-in scenes refined to a maximum edge length near their objects (instances under 20 m across).
#include "cli_common.h"
#include "commands.h"

#include "obscura/bake_quality.h"
#include "obscura/error.h"
#include "obscura/parallel.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace obscura::cli {

namespace {

struct QualityOptions {
    std::string scenes = "spheres,stairs,demo", distances = "2,300";
    float maxEdge = 0.1f;
    float grading = 1.0f;
    int referenceRays = 4096;
    int rays = 256;
    float creaseAngle = 60.0f;
    int threads = 0;
    bool json = false;
};

// The worst baked vertex as one whitespace-free table field: "x,y,z(baked/reference)".
std::string worst(const bake::QualityChannel& c) {
    char text[128];
    std::snprintf(text, sizeof text, "%.3f,%.3f,%.3f(%.3f/%.3f)", double(c.bakedMaxAt.x), double(c.bakedMaxAt.y),
                  double(c.bakedMaxAt.z), c.bakedMaxValue, c.bakedMaxReference);
    return text;
}

void runQuality(const QualityOptions& o) {
    ThreadLimit limit(o.threads, "--threads");
    if (!(o.maxEdge > 0.0f)) fail("--max-edge", "must be > 0");
    if (!(o.grading >= 0.0f && o.grading <= 100.0f)) fail("--grading", "must be in [0, 100] per m");
    if (o.referenceRays < 1 || o.referenceRays > (1 << 20)) fail("--reference-rays", "must be in [1, 1048576]");
    bake::BakeSettings settings;
    settings.rays = o.rays;
    settings.creaseAngle = o.creaseAngle;
    settings.distances = parseBakeDistances("--distances", o.distances);
    settings.validate();
    // Every name is checked before the table's header: a bad one once failed after the header was printed.
    std::vector<std::string> names;
    std::stringstream in(o.scenes);
    for (std::string name; std::getline(in, name, ',');) names.push_back(name);
    const std::vector<std::string> known = builtinSceneNames();
    for (const std::string& name : names)
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            std::string list;
            for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
            fail("--scenes", "unknown built-in scene '" + name + "' (known: " + list + ")");
        }
    if (names.empty()) fail("--scenes", "no scene given");
    nlohmann::json report;
    if (!o.json)
        std::printf("%-9s %8s %8s %6s %9s %9s %9s %9s %9s %9s %9s %9s %9s %7s %s\n", "scene", "compared", "smooth", "d (m)",
                    "bake MAE", "bake max", "bake smth", "point MAE", "point max", "pt smooth", "J bake", "J point", "J ref",
                    "time s", "bake max at x,y,z (baked/ref)");
    for (const std::string& name : names) {
        BuiltinScene b = makeBuiltinScene(name);
        Scene refined = bake::refineScene(b.scene, o.maxEdge, bake::refinementFocus(b.scene, 20.0f), o.grading);
        bake::QualityResult q = bake::compareWithDense(refined, settings, o.referenceRays);
        for (const bake::QualityChannel& c : q.channels) {
            if (!o.json)
                std::printf("%-9s %8zu %8zu %6g %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f %9.3f %9.3f %9.3f %7.1f %s\n", name.c_str(),
                            q.comparedVertices, q.smoothVertices, c.distance, c.bakedMae, c.bakedMax, c.bakedSmoothMae,
                            c.pointMae, c.pointMax, c.pointSmoothMae, c.bakedJump, c.pointJump, c.referenceJump, q.seconds, worst(c).c_str());
            report["scenes"].push_back({{"scene", name},
                                        {"vertices", q.vertices},
                                        {"compared_vertices", q.comparedVertices},
                                        {"hidden_vertices", q.hiddenVertices},
                                        {"triangles", q.triangles},
                                        {"samples", q.samples},
                                        {"distance_m", c.distance},
                                        {"baked_mae", c.bakedMae},
                                        {"baked_max", c.bakedMax},
                                        {"smooth_vertices", q.smoothVertices},
                                        {"baked_smooth_mae", c.bakedSmoothMae},
                                        {"point_smooth_mae", c.pointSmoothMae},
                                        {"point_mae", c.pointMae},
                                        {"point_max", c.pointMax},
                                        {"gradient_jump_baked", c.bakedJump},
                                        {"gradient_jump_point", c.pointJump},
                                        {"gradient_jump_reference", c.referenceJump},
                                        {"baked_max_at_m", {c.bakedMaxAt.x, c.bakedMaxAt.y, c.bakedMaxAt.z}},
                                        {"baked_max_value", c.bakedMaxValue},
                                        {"baked_max_reference", c.bakedMaxReference},
                                        {"seconds", q.seconds}});
        }
        std::fflush(stdout);  // a long run shows each scene as it finishes
    }
    report["reference_rays"] = o.referenceRays;
    report["rays_per_sample"] = o.rays;
    report["max_edge_m"] = o.maxEdge;
    report["grading_per_m"] = o.grading;
    if (o.json) std::printf("%s\n", report.dump(2).c_str());
}

} // namespace

void addBakeBenchCommands(CLI::App& bench) {
    auto o = std::make_shared<QualityOptions>();
    CLI::App* cmd = bench.add_subcommand(
        "bake-quality", "Baked vertices against dense ray tracing at every vertex (MAE, gradient jump), and point sampling");
    cmd->add_option("--scenes", o->scenes, "Comma-separated built-in scenes")->capture_default_str();
    cmd->add_option("--distances", o->distances, "Half distances d in m")->capture_default_str();
    cmd->add_option("--max-edge", o->maxEdge, "Refine triangles to this edge length, m")->capture_default_str();
    cmd->add_option("--grading", o->grading, "Edge length grows by this factor per m from the objects (floors far away stay coarse), [0, 100]")
        ->capture_default_str();
    cmd->add_option("--reference-rays", o->referenceRays, "Rays per vertex of the dense reference, [1, 1048576]")->capture_default_str();
    cmd->add_option("--rays", o->rays, "Rays per bake sample and per point-sampled vertex, [1, 65536]")->capture_default_str();
    cmd->add_option("--crease-angle", o->creaseAngle, "Bake's crease angle, degrees, [0, 180]")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--json", o->json, "Print JSON instead of a table");
    cmd->callback([o] { runQuality(*o); });
}

} // namespace obscura::cli
