// What the two glTF writers share (gltf_writer.cpp from scratch, gltf_attribute_writer.cpp into a copy of a
// file): the output's kind, the attributes' check and the checked, atomic write.
#pragma once

#include "obscura/gltf_writer.h"

#include <functional>
#include <ostream>
#include <string>

namespace obscura {

// True for .glb, false for .gltf; any other extension is an error naming `path`.
bool gltfOutputIsBinary(const std::string& path);

// Throws obscura::Error naming `path` unless `a` (if given) has one value per vertex of each instance's mesh.
void checkInstanceAttributes(const Scene& scene, const InstanceAttributes* a, const std::string& path);

// Writes `path` through a temporary file that `write` fills, renamed into place once the stream reports every
// byte written: tinygltf never checks its writes, and a full disk left a truncated file behind exit status 0.
void writeGltfFile(const std::string& path, const std::function<void(std::ostream&)>& write);

} // namespace obscura
