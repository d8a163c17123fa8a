// The library's entry points against the misuse an integrator may commit: a G-buffer that does not match its
// camera, a scene built by hand and never sanitized, a mesh without normals, a refinement edge of 0. Each once
// read past a buffer's end (ASan) or ran for minutes; each now throws obscura::Error or does the right thing.
#include "obscura/alchemy.h"
#include "obscura/bake.h"
#include "obscura/bake_quality.h"
#include "obscura/builtin_scenes.h"
#include "obscura/error.h"
#include "obscura/trace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

using namespace obscura;

namespace {

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

// A 2 m square on y = 0, two triangles, no normals (Mesh::normals is empty until computed).
Scene bareSquare() {
    Mesh m;
    m.name = "square";
    m.positions = {{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    Scene s;
    s.add(m);
    return s;
}

} // namespace

// The per-pixel overload read the G-buffer without a check: an empty one segfaulted, a depth smaller than its
// camera was read past its end, and a NaN field of view reached Embree's assert (abort).
TEST(LibraryMisuse, AmbientObscuranceChecksTheGBuffer) {
    BuiltinScene plane = makeBuiltinScene("plane");
    trace::Tracer tracer(plane.scene);
    trace::ObscuranceSettings s;
    s.rays = 4;
    GBuffer empty;
    empty.camera = plane.camera;
    EXPECT_NE(messageOf([&] { trace::ambientObscurance(tracer, empty, s); }).find("ambientObscurance"),
              std::string::npos);
    Camera small = plane.camera;
    small.width = 8;
    small.height = 6;
    GBuffer g = trace::renderGBuffer(tracer, small);
    GBuffer shrunk = g;
    shrunk.depth = Image(2, 2, 1, 1.0f);
    EXPECT_NE(messageOf([&] { trace::ambientObscurance(tracer, shrunk, s); }).find("depth"), std::string::npos);
    GBuffer badFov = g;
    badFov.camera.fovY = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(messageOf([&] { trace::ambientObscurance(tracer, badFov, s); }).find("fov"), std::string::npos);
    const Image ao = trace::ambientObscurance(tracer, g, s);
    for (float v : ao.pixels) EXPECT_EQ(v, 1.0f);  // an open plane
}

// Normals rebuilt from depth: where both neighbours' misfits were inf (one side off the image, the other
// overflowing: depths 1e29 and 1e-10 side by side) the pixel off the image was read.
TEST(LibraryMisuse, NormalsFromDepthStayInTheImage) {
    Camera c;
    c.width = 2;
    c.height = 1;
    Image depth(2, 1, 1);
    depth.at(0, 0) = 1e29f;
    depth.at(1, 0) = 1e-10f;
    const Image n = ssao::normalsFromDepth(depth, c);
    for (int x = 0; x < 2; ++x) {
        const float length = std::sqrt(n.at(x, 0, 0) * n.at(x, 0, 0) + n.at(x, 0, 1) * n.at(x, 0, 1) +
                                       n.at(x, 0, 2) * n.at(x, 0, 2));
        EXPECT_NEAR(length, 1.0f, 1e-5f) << x;
    }
    Image three(3, 1, 1, 2.0f);
    three.at(1, 0) = 1e-40f;
    c.width = 3;
    const Image m = ssao::normalsFromDepth(three, c);
    EXPECT_EQ(m.width, 3);
}

// A scene built by hand is checked where the tracer and the bake take it: an instance of a mesh that is not
// there, or an index past the vertices, was read past the buffers' ends.
TEST(LibraryMisuse, TracerAndBakeCheckTheScene) {
    Scene s = bareSquare();
    s.instances[0].mesh = 5;
    EXPECT_NE(messageOf([&] { trace::Tracer t(s); }).find("refers to mesh 5"), std::string::npos);
    Scene index = bareSquare();
    index.meshes[0].indices[4] = 9;
    EXPECT_NE(messageOf([&] { trace::Tracer t(index); }).find("index 9 out of range"), std::string::npos);
    bake::BakeSettings settings;
    settings.rays = 4;
    EXPECT_NE(messageOf([&] { bake::bakeScene(index, settings); }).find("index 9 out of range"), std::string::npos);
}

// compareWithDense read a mesh's normals without a check (a scene without computed normals segfaulted), and a
// refinement edge of 0 or NaN ran 20 s and 1.6 GB into the triangle budget before its message advised a larger
// edge; referenceRays 0 was refused after the whole bake, as "ao-rays".
TEST(LibraryMisuse, BakeQualityChecksItsInputs) {
    const Scene square = bareSquare();
    const Bounds focus = square.bounds();
    for (float edge : {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()})
        EXPECT_NE(messageOf([&] { bake::refineScene(square, edge, focus, 1.0f); }).find("maxEdge must be"),
                  std::string::npos)
            << edge;
    bake::BakeSettings settings;
    settings.rays = 8;
    settings.distances = {2.0f};
    EXPECT_NE(messageOf([&] { bake::compareWithDense(square, settings, 0); }).find("referenceRays"), std::string::npos);
    const bake::QualityResult q = bake::compareWithDense(square, settings, 16);
    ASSERT_EQ(q.channels.size(), 1u);
    EXPECT_NEAR(q.channels[0].bakedMae, 0.0, 1e-6);  // an open square: 1 everywhere, baked and traced
}
