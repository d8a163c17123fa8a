// Camera <-> JSON. Position/target/up/fov are the source of truth; the matrices are written as well so
// other tools can use the file without reimplementing look-at.
#include "obscura/camera_io.h"

#include "obscura/error.h"
#include "obscura/image_io.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>

namespace obscura {

namespace {

nlohmann::json vec(Vec3 v) { return {v.x, v.y, v.z}; }

nlohmann::json rows(const Mat4& m) {
    nlohmann::json r = nlohmann::json::array();
    for (const auto& row : m.m) r.push_back({row[0], row[1], row[2], row[3]});
    return r;
}

// A JSON number as a float: read as the double it is and refused, naming the field and the value as written,
// where no float holds it. get<float>() is a static_cast from double, undefined past the float range (1e39 came
// out inf, and the message spoke of an infinity the file did not hold), and 1e-50 became 0.
float toFloat(const nlohmann::json& value, const std::string& field, const std::string& what) {
    const double d = value.get<double>();
    const double magnitude = std::fabs(d);
    if (magnitude > double(std::numeric_limits<float>::max()) ||
        (magnitude > 0.0 && magnitude < double(std::numeric_limits<float>::min())))
        fail(what, "\"" + field + "\" is " + numberText(d) + ", beyond what a float holds");
    return float(d);
}

Vec3 readVec(const nlohmann::json& j, const char* key, const std::string& what) {
    if (!j.contains(key)) fail(what, std::string("missing \"") + key + "\"");
    const auto& a = j.at(key);
    if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number())
        fail(what, std::string("\"") + key + "\" must be an array of 3 numbers");
    return {toFloat(a[0], key, what), toFloat(a[1], key, what), toFloat(a[2], key, what)};
}

template <class T>
T readNumber(const nlohmann::json& j, const char* key, const std::string& what, T fallback, bool required) {
    if (!j.contains(key)) {
        if (required) fail(what, std::string("missing \"") + key + "\"");
        return fallback;
    }
    if (!j.at(key).is_number()) fail(what, std::string("\"") + key + "\" must be a number");
    if constexpr (std::is_same_v<T, float>)
        return toFloat(j.at(key), key, what);
    else
        return j.at(key).get<T>();
}

// get<int>() wraps an integer beyond int (4294967360 became 64), truncates a fraction (64.9 became 64) and is
// undefined for a double beyond int (1e30), so the value is read as a double and checked first; the range is
// Camera::validate's, checked here too so that the message names the field.
int readPixelCount(const nlohmann::json& j, const char* key, const std::string& what) {
    const double d = readNumber<double>(j, key, what, 0.0, true);
    if (!(d >= 1 && d <= kMaxImageSide && d == std::floor(d)))
        fail(what, std::string("\"") + key + "\" must be a whole number from 1 to " + std::to_string(kMaxImageSide) +
                       ", got " + numberText(d));
    return static_cast<int>(d);
}

} // namespace

std::string cameraToJson(const Camera& c) {
    nlohmann::json j;
    j["position"] = vec(c.position);
    j["target"] = vec(c.target);
    j["up"] = vec(c.up);
    j["fovY"] = c.fovY;
    j["near"] = c.nearZ;
    j["far"] = c.farZ;
    j["width"] = c.width;
    j["height"] = c.height;
    j["viewFromWorld"] = rows(c.viewFromWorld());
    j["clipFromView"] = rows(c.clipFromView());
    return j.dump(2) + "\n";
}

Camera cameraFromJson(const std::string& text, const std::string& what) {
    // The parser stops at a NUL byte: what followed one was never read, nor refused.
    if (text.find('\0') != std::string::npos) fail(what, "not valid JSON: holds a NUL byte");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        // Every syntax error read "not a JSON object"; the parser's own words say where and what
        // ("[json.exception.parse_error.101] parse error at line 3, column 1: syntax error ...", or
        // "[json.exception.out_of_range.406] number overflow parsing '1e999'").
        std::string why = e.what();
        if (const std::size_t at = why.find("] "); at != std::string::npos) why = why.substr(at + 2);
        fail(what, "not valid JSON: " + why);
    }
    if (!j.is_object()) fail(what, "not a JSON object");
    Camera c;
    c.position = readVec(j, "position", what);
    c.target = readVec(j, "target", what);
    if (j.contains("up")) c.up = readVec(j, "up", what);
    c.fovY = readNumber<float>(j, "fovY", what, c.fovY, true);
    c.nearZ = readNumber<float>(j, "near", what, c.nearZ, false);
    c.farZ = readNumber<float>(j, "far", what, c.farZ, false);
    c.width = readPixelCount(j, "width", what);
    c.height = readPixelCount(j, "height", what);
    try {
        c.validate();
    } catch (const Error& e) {
        // Camera::validate speaks as "camera: fov ..."; here the file is named, and its field is fovY.
        std::string why = e.what();
        if (why.starts_with("camera: ")) why = why.substr(8);
        if (why.starts_with("fov ")) why = "fovY " + why.substr(4);
        fail(what, why);
    }
    return c;
}

Camera readCameraJson(const std::string& path) {
    if (!std::filesystem::exists(path)) fail(path, "no such file");
    if (std::filesystem::is_directory(path)) fail(path, "is a directory, not a camera JSON file");
    std::ifstream in(path);
    if (!in) fail(path, "cannot open");
    std::stringstream ss;
    ss << in.rdbuf();
    return cameraFromJson(ss.str(), path);
}

void writeCameraJson(const std::string& path, const Camera& camera) {
    std::string text = cameraToJson(camera);
    writeAtomically(path, [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out.flush()) fail(path, "write failed");
    });
}

} // namespace obscura
