// Procedural primitives for the built-in scenes and tests. Every shape is closed or one-sided as stated,
// with outward (or stated) normals and counter-clockwise winding seen from the front.
#pragma once

#include "obscura/scene.h"

namespace obscura::build {

// Quad with corners p0..p3 counter-clockwise seen from the front; flat normal.
void addQuad(Mesh& m, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3);
// Axis-aligned box between lo and hi, outward faces, flat normals.
void addBox(Mesh& m, Vec3 lo, Vec3 hi);
// UV sphere, smooth normals.
void addSphere(Mesh& m, Vec3 center, float radius, int segments = 48, int rings = 24);
// Open cylinder side about +Y from y0 to y1; normals point inward when `inward` (a well's wall).
void addCylinderSide(Mesh& m, Vec3 baseCenter, float radius, float y0, float y1, int segments, bool inward);
// Disk facing +Y (or -Y when `down`).
void addDisk(Mesh& m, Vec3 center, float radius, int segments, bool down = false);
// Square [-half, half]^2 in XZ at height y facing +Y, with a round hole of `radius` at the origin,
// the hole a polygon of `segments` sides matching addCylinderSide.
void addPlaneWithHole(Mesh& m, float y, float half, float radius, int segments);

} // namespace obscura::build
