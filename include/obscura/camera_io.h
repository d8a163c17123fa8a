// Camera files: the JSON that travels with G-buffers so a user's own buffers can be processed later
// (format in docs/FORMATS.md).
//
// Errors: readCameraJson throws obscura::Error("<path>: <problem>") for a missing, malformed or
// out-of-range file.
#pragma once

#include "obscura/camera.h"

#include <string>

namespace obscura {

std::string cameraToJson(const Camera& camera);
Camera cameraFromJson(const std::string& text, const std::string& what);
Camera readCameraJson(const std::string& path);
void writeCameraJson(const std::string& path, const Camera& camera);

} // namespace obscura
