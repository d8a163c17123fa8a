// Built-in scenes: closed-form test geometry (plane, corner, well, ceiling), contact cases (stairs,
// spheres, the slatted cabinet of the Alchemy IBL chapter) and a furnished demo room.
#include "obscura/builtin_scenes.h"

#include "obscura/error.h"
#include "obscura/mesh_builder.h"
#include "obscura/sampling.h"

#include <cmath>
#include <functional>

namespace obscura {

namespace {

using build::addBox;
using build::addQuad;
using build::addSphere;

Mesh named(const char* name, Vec3 color) {
    Mesh m;
    m.name = name;
    m.baseColor = color;
    return m;
}

Mesh floorPlane(float half, Vec3 color = {0.7f, 0.7f, 0.7f}) {
    Mesh m = named("floor", color);
    addQuad(m, {-half, 0, half}, {half, 0, half}, {half, 0, -half}, {-half, 0, -half});
    return m;
}

Camera view(Vec3 from, Vec3 to, float fov = 60.0f, Vec3 up = {0, 1, 0}) {
    Camera c;
    c.position = from;
    c.target = to;
    c.up = up;
    c.fovY = fov;
    return c;
}

// A cabinet whose front is `slats` vertical slats with gaps between them, standing on y = 0, centred on x = 0,
// its back at z = -depth/2. The slat mesh is instanced once per slat.
void addCabinet(Scene& scene, const Mat4& worldFromCabinet, int slats) {
    const float width = 1.2f, height = 1.0f, depth = 0.5f, board = 0.03f;
    Mesh body = named("cabinet", {0.45f, 0.3f, 0.18f});
    addBox(body, {-width / 2, 0, -depth / 2}, {width / 2, board, depth / 2});                     // bottom
    addBox(body, {-width / 2, height - board, -depth / 2}, {width / 2, height, depth / 2});       // top
    addBox(body, {-width / 2, board, -depth / 2}, {-width / 2 + board, height - board, depth / 2});  // sides
    addBox(body, {width / 2 - board, board, -depth / 2}, {width / 2, height - board, depth / 2});
    addBox(body, {-width / 2 + board, board, -depth / 2}, {width / 2 - board, height - board, -depth / 2 + board});
    scene.add(std::move(body), worldFromCabinet);

    const float inner = width - 2 * board;
    const float pitch = inner / float(slats);
    const float slatWidth = pitch * 0.6f;  // 40% gaps: the recesses the chapter's AO darkens
    Mesh slat = named("slat", {0.55f, 0.38f, 0.22f});
    addBox(slat, {-slatWidth / 2, board, -0.01f}, {slatWidth / 2, height - board, 0.01f});
    scene.meshes.push_back(std::move(slat));
    auto slatMesh = std::uint32_t(scene.meshes.size() - 1);
    for (int i = 0; i < slats; ++i) {
        float x = -inner / 2 + pitch * (float(i) + 0.5f);
        scene.instances.push_back({slatMesh, worldFromCabinet * Mat4::translation({x, 0, depth / 2 - 0.02f}),
                                   "slat " + std::to_string(i)});
    }
}

void addStairs(Mesh& m, Vec3 origin, int steps, float rise, float run, float width) {
    for (int i = 0; i < steps; ++i)
        addBox(m, origin + Vec3{0, 0, -run * float(i + 1)}, origin + Vec3{width, rise * float(i + 1), -run * float(i)});
}

BuiltinScene plane() {
    BuiltinScene s{"plane", "an open ground plane: no occlusion anywhere (AO = 1)", {}, {}};
    s.scene.add(floorPlane(builtin::kPlaneHalfSize));
    s.camera = view({0, 3, 6}, {0, 0, 0});
    return s;
}

BuiltinScene corner() {
    BuiltinScene s{"corner", "floor and two walls meeting at the origin (walls 20 m wide, 10 m high)", {}, {}};
    const float size = 20.0f, height = 10.0f;
    Mesh m = named("corner", {0.75f, 0.72f, 0.68f});
    addQuad(m, {0, 0, size}, {size, 0, size}, {size, 0, 0}, {0, 0, 0});             // floor, +Y
    addQuad(m, {0, 0, 0}, {0, height, 0}, {0, height, size}, {0, 0, size});         // wall x = 0, +X
    addQuad(m, {0, 0, 0}, {size, 0, 0}, {size, height, 0}, {0, height, 0});         // wall z = 0, +Z
    s.scene.add(std::move(m));
    s.camera = view({4, 4, 4}, {0.5f, 0, 0.5f});
    return s;
}

BuiltinScene well() {
    BuiltinScene s{"well", "a round well of radius 1 m and depth 2 m sunk in an open floor", {}, {}};
    const float a = builtin::kWellRadius, h = builtin::kWellDepth;
    const int n = builtin::kWellSegments;
    Mesh floor = named("floor", {0.7f, 0.7f, 0.7f});
    build::addPlaneWithHole(floor, 0.0f, builtin::kPlaneHalfSize, a, n);
    s.scene.add(std::move(floor));
    Mesh wall = named("well", {0.6f, 0.55f, 0.5f});
    build::addCylinderSide(wall, {0, 0, 0}, a, -h, 0.0f, n, true);
    build::addDisk(wall, {0, -h, 0}, a, n);
    s.scene.add(std::move(wall));
    s.camera = view({0, 5, 2.5f}, {0, -1, 0});
    return s;
}

BuiltinScene stairs() {
    BuiltinScene s{"stairs", "a flight of 8 steps (0.2 m rise, 0.3 m run) on a floor", {}, {}};
    s.scene.add(floorPlane(50.0f));
    Mesh m = named("stairs", {0.6f, 0.6f, 0.62f});
    addStairs(m, {-1, 0, 1.2f}, 8, 0.2f, 0.3f, 2.0f);
    s.scene.add(std::move(m));
    s.camera = view({3.5f, 3, 3.5f}, {0, 0.6f, 0});
    return s;
}

BuiltinScene spheres() {
    BuiltinScene s{"spheres", "five spheres resting on a floor: contact shadows", {}, {}};
    s.scene.add(floorPlane(50.0f));
    Mesh unit = named("sphere", {0.8f, 0.25f, 0.2f});
    addSphere(unit, {0, 0, 0}, 1.0f, 64, 32);
    s.scene.meshes.push_back(std::move(unit));
    const float radii[5] = {0.5f, 0.3f, 0.2f, 0.4f, 0.15f};
    const float xs[5] = {-1.2f, -0.2f, 0.5f, 1.4f, 0.1f};
    const float zs[5] = {0.0f, 0.6f, -0.3f, 0.4f, 1.1f};
    for (int i = 0; i < 5; ++i)
        s.scene.instances.push_back({1, Mat4::translation({xs[i], radii[i], zs[i]}) * Mat4::scale(Vec3(radii[i])),
                                     "sphere " + std::to_string(i)});
    s.camera = view({0, 2.2f, 4}, {0, 0.2f, 0});
    return s;
}

BuiltinScene cabinet() {
    BuiltinScene s{"cabinet", "a slatted cabinet, 30 parallel slats, on a floor against a wall", {}, {}};
    s.scene.add(floorPlane(50.0f));
    Mesh wall = named("wall", {0.8f, 0.78f, 0.74f});
    addQuad(wall, {-5, 0, -0.3f}, {5, 0, -0.3f}, {5, 4, -0.3f}, {-5, 4, -0.3f});
    s.scene.add(std::move(wall));
    addCabinet(s.scene, Mat4::translation({0, 0, -0.04f}), builtin::kCabinetSlats);
    s.camera = view({0.6f, 1.3f, 2.2f}, {0, 0.5f, 0});
    return s;
}

BuiltinScene ceiling() {
    BuiltinScene s{"ceiling", "a floor under a parallel ceiling 1 m above it", {}, {}};
    const float half = builtin::kPlaneHalfSize, h = builtin::kCeilingHeight;
    s.scene.add(floorPlane(half));
    Mesh top = named("ceiling", {0.8f, 0.8f, 0.8f});
    addQuad(top, {-half, h, -half}, {half, h, -half}, {half, h, half}, {-half, h, half});  // faces -Y
    s.scene.add(std::move(top));
    s.camera = view({0, 0.5f, 0}, {0, 0.2f, -4});
    return s;
}

BuiltinScene demo() {
    BuiltinScene s{"demo", "a furnished room: cabinet, table, spheres, stairs and a shelf", {}, {}};
    const float w = 4.0f, d = 4.0f, h = 3.0f;
    s.scene.add(floorPlane(w, {0.55f, 0.4f, 0.28f}));
    Mesh walls = named("walls", {0.82f, 0.8f, 0.76f});
    addQuad(walls, {-w, 0, -d}, {w, 0, -d}, {w, h, -d}, {-w, h, -d});  // back, +Z
    addQuad(walls, {-w, 0, d}, {-w, 0, -d}, {-w, h, -d}, {-w, h, d});  // left, +X
    addQuad(walls, {w, 0, -d}, {w, 0, d}, {w, h, d}, {w, h, -d});      // right, -X
    s.scene.add(std::move(walls));

    addCabinet(s.scene, Mat4::translation({-1.6f, 0, -d + 0.26f}), builtin::kCabinetSlats);

    Mesh table = named("table", {0.35f, 0.22f, 0.12f});
    addBox(table, {-0.8f, 0.72f, -0.5f}, {0.8f, 0.77f, 0.5f});
    for (float x : {-0.74f, 0.68f})
        for (float z : {-0.44f, 0.38f}) addBox(table, {x, 0, z}, {x + 0.06f, 0.72f, z + 0.06f});
    s.scene.add(std::move(table), Mat4::translation({0.6f, 0, -0.6f}));

    Mesh ball = named("ball", {0.75f, 0.2f, 0.15f});
    addSphere(ball, {0, 0, 0}, 1.0f, 48, 24);
    s.scene.meshes.push_back(std::move(ball));
    auto ballMesh = std::uint32_t(s.scene.meshes.size() - 1);
    const Vec3 balls[4] = {{0.3f, 0.77f + 0.15f, -0.6f}, {0.95f, 0.77f + 0.1f, -0.4f}, {-0.6f, 0.35f, 1.0f},
                           {0.2f, 0.22f, 1.5f}};
    const float radii[4] = {0.15f, 0.1f, 0.35f, 0.22f};
    for (int i = 0; i < 4; ++i)
        s.scene.instances.push_back({ballMesh, Mat4::translation(balls[i]) * Mat4::scale(Vec3(radii[i])),
                                     "ball " + std::to_string(i)});

    Mesh steps = named("stairs", {0.62f, 0.62f, 0.66f});
    addStairs(steps, {2.6f, 0, -0.5f}, 8, 0.2f, 0.3f, 1.4f);
    s.scene.add(std::move(steps));

    Mesh shelf = named("shelf", {0.7f, 0.68f, 0.6f});
    addBox(shelf, {-3.9f, 1.6f, -1.5f}, {-3.6f, 1.64f, 0.5f});
    for (int i = 0; i < 6; ++i) addBox(shelf, {-3.85f, 1.64f, -1.4f + 0.3f * float(i)}, {-3.65f, 1.94f, -1.3f + 0.3f * float(i)});
    s.scene.add(std::move(shelf));

    s.camera = view({0.4f, 2.0f, 5.5f}, {-0.2f, 0.7f, -1.0f}, 60.0f);
    return s;
}

struct Entry {
    const char* name;
    BuiltinScene (*make)();
};

const Entry kScenes[] = {{"demo", demo},     {"plane", plane},     {"corner", corner},   {"well", well},
                         {"stairs", stairs}, {"spheres", spheres}, {"cabinet", cabinet}, {"ceiling", ceiling}};

} // namespace

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const Entry& e : kScenes) names.emplace_back(e.name);
    return names;
}

bool isBuiltinScene(const std::string& name) {
    for (const Entry& e : kScenes)
        if (name == e.name) return true;
    return false;
}

std::string builtinSceneDescription(const std::string& name) { return makeBuiltinScene(name).description; }

BuiltinScene makeBuiltinScene(const std::string& name) {
    for (const Entry& e : kScenes)
        if (name == e.name) {
            BuiltinScene s = e.make();
            sanitizeScene(s.scene, name);
            return s;
        }
    std::string known;
    for (const Entry& e : kScenes) known += (known.empty() ? "" : ", ") + std::string(e.name);
    fail(name, "no such built-in scene (known: " + known + ")");
}

} // namespace obscura
