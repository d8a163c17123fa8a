// Built-in scenes: small, exact test geometry with known ambient occlusion, and a furnished demo room.
#pragma once

#include "obscura/camera.h"
#include "obscura/scene.h"

#include <string>
#include <vector>

namespace obscura {

struct BuiltinScene {
    std::string name;
    std::string description;   // one line
    Scene scene;
    Camera camera;             // default view; width/height 1280x720
};

// Names in display order; "demo" is the default scene of the CLI.
std::vector<std::string> builtinSceneNames();
std::string builtinSceneDescription(const std::string& name);
bool isBuiltinScene(const std::string& name);
// Throws obscura::Error for an unknown name.
BuiltinScene makeBuiltinScene(const std::string& name);

// Dimensions of the closed-form scenes, shared by the builders and the tests.
namespace builtin {
constexpr float kWellRadius = 1.0f;      // `well`: radius a, m
constexpr float kWellDepth = 2.0f;       // `well`: depth h, m
constexpr int kWellSegments = 256;       // polygon sides of the well's wall
constexpr float kCeilingHeight = 1.0f;   // `ceiling`: h, m
constexpr float kPlaneHalfSize = 1000.0f;  // half extent of the "infinite" planes, m
constexpr int kCabinetSlats = 30;
} // namespace builtin

// A deterministic large scene for scale tests: terrain, buildings with interiors and scattered props, `triangles`
// triangles in total to within 11 (at least kMinLevelTriangles). The area grows with the budget (a half-width of
// 0.88 sqrt(triangles) m, at least 60 m) so the density stays one of a town: buildings 2 m apart or more, seated
// on the terrain, props in the open. The seed places buildings and props; the terrain is the same for every seed.
Scene generateLevel(std::size_t triangles, std::uint32_t seed = 1);
// The budgets generateLevel is meant for; the CLI's --triangles are held to them (parseLevelTriangles).
constexpr long long kMinLevelTriangles = 4000, kMaxLevelTriangles = 200000000;
// The largest budget whose level fits a .glb (32-bit length): the level's file holds about 27.1 bytes a triangle
// (1.8 M triangles: 48 762 800 bytes, measured 2026-11-28 on the generator as it is), so 4 GiB is about 1.58e8.
constexpr long long kMaxGlbLevelTriangles = 150000000;

} // namespace obscura
